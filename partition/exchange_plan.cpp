#include "partition/exchange_plan.hpp"

#include <algorithm>
#include <map>
#include <stdexcept>

namespace xpl::partition {

namespace {

/// The element of every slot (n_slots).
std::vector<Index> slot_elements(const PartitionInput& input) {
  const Index n_elements = static_cast<Index>(input.element_offsets.size()) - 1;
  std::vector<Index> element(input.element_nodes.size());
  for (Index e = 0; e < n_elements; ++e)
    for (Index k = input.element_offsets[e]; k < input.element_offsets[e + 1]; ++k) element[k] = e;
  return element;
}

}  // namespace

Index PartPlan::send_slots() const {
  Index n = 0;
  for (const NeighbourExchange& x : neighbours) n += static_cast<Index>(x.send.size());
  return n;
}

SlotOrder make_slot_order(const PartitionInput& input, std::span<const Index> element_rank) {
  const std::vector<Index> element = slot_elements(input);
  const Index n_slots = static_cast<Index>(element.size());
  if (!element_rank.empty() && element_rank.size() + 1 != input.element_offsets.size())
    throw std::invalid_argument("make_slot_order: one rank per element expected");
  SlotOrder order;
  order.node_start.assign(static_cast<std::size_t>(input.node_count) + 1, 0);
  for (Index s = 0; s < n_slots; ++s) ++order.node_start[input.element_nodes[s] + 1];
  for (Index n = 0; n < input.node_count; ++n) order.node_start[n + 1] += order.node_start[n];
  order.slots.resize(static_cast<std::size_t>(n_slots));
  std::vector<Index> fill(order.node_start.begin(), order.node_start.end() - 1);
  for (Index s = 0; s < n_slots; ++s) order.slots[fill[input.element_nodes[s]]++] = s;
  // Slots enter each node in slot order (element, then corner): already the order by
  // element number; with ranks, sort each node's slots by (rank of the element, slot).
  if (!element_rank.empty())
    for (Index n = 0; n < input.node_count; ++n)
      std::sort(order.slots.begin() + order.node_start[n],
                order.slots.begin() + order.node_start[n + 1], [&](Index a, Index b) {
                  const Index ra = element_rank[element[a]], rb = element_rank[element[b]];
                  return ra != rb ? ra < rb : a < b;
                });
  return order;
}

ExchangePlan make_exchange_plan(const PartitionInput& input, const MeshPartition& partition,
                                std::span<const Index> element_rank) {
  const Index n_elements = static_cast<Index>(input.element_offsets.size()) - 1;
  if (static_cast<Index>(partition.element_part.size()) != n_elements ||
      static_cast<Index>(partition.node_owner.size()) != input.node_count)
    throw std::invalid_argument("make_exchange_plan: the partition is not of this input");
  ExchangePlan plan;
  plan.parts = partition.parts;
  plan.order = make_slot_order(input, element_rank);
  plan.part.resize(static_cast<std::size_t>(partition.parts));
  const std::vector<Index> element = slot_elements(input);
  const auto part_of_slot = [&](Index s) { return partition.element_part[element[s]]; };

  // An element of part < 0 is in no part (a rigid body's element: no kernel, no slots).
  for (Index e = 0; e < n_elements; ++e)
    if (partition.element_part[e] >= 0) plan.part[partition.element_part[e]].elements.push_back(e);
  for (Index n = 0; n < input.node_count; ++n)
    plan.part[partition.node_owner[n]].owned.push_back(n);

  // Parts using each node (ascending), then each part's nodes, interface nodes and the
  // nodes it shares with each neighbour.
  std::vector<std::map<int, NeighbourExchange>> neighbours(plan.part.size());
  std::vector<int> users;
  for (Index n = 0; n < input.node_count; ++n) {
    users.clear();
    for (Index k = plan.order.node_start[n]; k < plan.order.node_start[n + 1]; ++k)
      if (part_of_slot(plan.order.slots[k]) >= 0)
        users.push_back(part_of_slot(plan.order.slots[k]));
    std::sort(users.begin(), users.end());
    users.erase(std::unique(users.begin(), users.end()), users.end());
    for (const int p : users) {
      plan.part[p].nodes.push_back(n);
      if (users.size() < 2) continue;
      plan.part[p].interface_nodes.push_back(n);
      for (const int q : users)
        if (q != p) {
          NeighbourExchange& x = neighbours[p][q];
          x.part = q;
          x.nodes.push_back(n);
          for (Index k = plan.order.node_start[n]; k < plan.order.node_start[n + 1]; ++k)
            if (part_of_slot(plan.order.slots[k]) == p) x.send.push_back(plan.order.slots[k]);
        }
    }
  }
  for (std::size_t p = 0; p < plan.part.size(); ++p)
    for (auto& [q, x] : neighbours[p])
      x.receive_count = static_cast<Index>(neighbours[q].at(static_cast<int>(p)).send.size());
  for (std::size_t p = 0; p < plan.part.size(); ++p)
    for (auto& [q, x] : neighbours[p]) plan.part[p].neighbours.push_back(std::move(x));

  // Combine tables: a neighbour's slots arrive node by node (ascending) in the fixed order,
  // the order in which this part meets them walking its interface nodes.
  for (std::size_t p = 0; p < plan.part.size(); ++p) {
    PartPlan& pp = plan.part[p];
    std::vector<int> position(plan.part.size(), -1);
    for (std::size_t j = 0; j < pp.neighbours.size(); ++j)
      position[pp.neighbours[j].part] = static_cast<int>(j);
    std::vector<Index> next(pp.neighbours.size(), 0);
    pp.combine_start.assign(1, 0);
    for (const Index n : pp.interface_nodes) {
      for (Index k = plan.order.node_start[n]; k < plan.order.node_start[n + 1]; ++k) {
        const Index s = plan.order.slots[k];
        const int r = part_of_slot(s);
        if (r < 0) continue;
        if (r == static_cast<int>(p))
          pp.combine.push_back({-1, s});
        else
          pp.combine.push_back({position[r], next[position[r]]++});
      }
      pp.combine_start.push_back(static_cast<Index>(pp.combine.size()));
    }
  }
  return plan;
}

void assemble(const SlotOrder& order, std::span<const Real> slot_values, int width,
              std::span<Real> nodal) {
  for (Index n = 0; n < order.node_count(); ++n)
    for (int c = 0; c < width; ++c) {
      Real sum = 0.0;
      for (Index k = order.node_start[n]; k < order.node_start[n + 1]; ++k)
        sum += slot_values[static_cast<std::size_t>(order.slots[k]) * width + c];
      nodal[static_cast<std::size_t>(n) * width + c] = sum;
    }
}

std::vector<Real> pack(const ExchangePlan& plan, int p, int j, std::span<const Real> slot_values,
                       int width) {
  const std::vector<Index>& send = plan.part[p].neighbours[j].send;
  std::vector<Real> buffer;
  buffer.reserve(send.size() * static_cast<std::size_t>(width));
  for (const Index s : send)
    for (int c = 0; c < width; ++c)
      buffer.push_back(slot_values[static_cast<std::size_t>(s) * width + c]);
  return buffer;
}

void assemble_part(const ExchangePlan& plan, int p, std::span<const Real> slot_values,
                   const std::vector<std::vector<Real>>& received, int width,
                   std::span<Real> nodal) {
  const PartPlan& pp = plan.part[p];
  const SlotOrder& order = plan.order;
  std::size_t k_interface = 0;
  for (const Index n : pp.nodes) {
    Real* out = &nodal[static_cast<std::size_t>(n) * width];
    if (k_interface < pp.interface_nodes.size() && pp.interface_nodes[k_interface] == n) {
      // An interface node: own and received slots, merged in the fixed order.
      const Index first = pp.combine_start[k_interface], last = pp.combine_start[k_interface + 1];
      for (int c = 0; c < width; ++c) {
        Real sum = 0.0;
        for (Index k = first; k < last; ++k) {
          const SlotSource& src = pp.combine[k];
          sum += src.neighbour < 0
                     ? slot_values[static_cast<std::size_t>(src.index) * width + c]
                     : received[src.neighbour][static_cast<std::size_t>(src.index) * width + c];
        }
        out[c] = sum;
      }
      ++k_interface;
      continue;
    }
    // A node of this part alone: its slots are all its own.
    for (int c = 0; c < width; ++c) {
      Real sum = 0.0;
      for (Index k = order.node_start[n]; k < order.node_start[n + 1]; ++k)
        sum += slot_values[static_cast<std::size_t>(order.slots[k]) * width + c];
      out[c] = sum;
    }
  }
}

}  // namespace xpl::partition
