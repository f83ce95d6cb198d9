#include "partition/mesh_partition.hpp"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

#include "partition/bisection.hpp"
#include "partition/element_graph.hpp"
#include "partition/exchange_plan.hpp"
#include "partition/metis_graph.hpp"

namespace xpl::partition {

const char* method_name(Method method) {
  switch (method) {
    case Method::Automatic:
      return "automatic";
    case Method::Metis:
      return "METIS";
    case Method::Bisection:
      return "bisection";
  }
  return "unknown";
}

MeshPartition partition_mesh(const PartitionInput& input, int parts, Method method) {
  if (parts < 1) throw std::invalid_argument("partition_mesh: parts must be at least 1");
  if (method == Method::Automatic) method = metis_available() ? Method::Metis : Method::Bisection;
  if (method == Method::Metis && !metis_available())
    throw std::invalid_argument("partition_mesh: this build has no METIS (XPL_MPI=OFF)");
  const Index n_elements = static_cast<Index>(input.element_offsets.size()) - 1;
  const ElementGraph graph = build_element_graph(input);

  MeshPartition p;
  p.parts = parts;
  p.method = method;
  std::vector<int> vertex_part;
  if (parts == 1)
    vertex_part.assign(static_cast<std::size_t>(graph.vertex_count()), 0);
  else if (graph.vertex_count() <= parts) {
    // As many parts as vertices or more: one vertex each (METIS refuses such graphs).
    vertex_part.resize(static_cast<std::size_t>(graph.vertex_count()));
    for (Index v = 0; v < graph.vertex_count(); ++v) vertex_part[v] = static_cast<int>(v);
  } else if (method == Method::Metis)
    vertex_part = metis_parts(graph, parts);
  else
    vertex_part = bisect(graph, parts);

  p.element_part.resize(static_cast<std::size_t>(std::max<Index>(n_elements, 0)));
  for (Index e = 0; e < n_elements; ++e)
    p.element_part[e] = vertex_part[graph.vertex_of_element[e]];

  p.stats.assign(static_cast<std::size_t>(parts), PartStats{});
  for (Index e = 0; e < n_elements; ++e) {
    PartStats& s = p.stats[p.element_part[e]];
    ++s.elements;
    s.weight += input.element_weight.empty() ? 1.0 : input.element_weight[e];
  }
  for (Index v = 0; v + 1 < static_cast<Index>(graph.offsets.size()); ++v)
    for (Index k = graph.offsets[v]; k < graph.offsets[v + 1]; ++k)
      if (graph.neighbours[k] > v) {
        ++p.graph_edges;
        if (vertex_part[v] != vertex_part[graph.neighbours[k]]) ++p.cut_edges;
      }

  std::vector<std::pair<Index, Index>> extra;
  for (const auto& [a, b] : input.extra_edges)
    if (a != b && a >= 0 && b >= 0 && a < n_elements && b < n_elements)
      extra.emplace_back(std::min(a, b), std::max(a, b));
  std::sort(extra.begin(), extra.end());
  extra.erase(std::unique(extra.begin(), extra.end()), extra.end());
  p.extra_pairs = static_cast<long>(extra.size());
  for (const auto& [a, b] : extra)
    if (p.element_part[a] != p.element_part[b]) ++p.cut_extra_pairs;

  // Parts of each node: (node, part) pairs, sorted and unique.
  std::vector<std::pair<Index, int>> uses;
  uses.reserve(input.element_nodes.size());
  for (Index e = 0; e < n_elements; ++e)
    for (Index k = input.element_offsets[e]; k < input.element_offsets[e + 1]; ++k)
      uses.emplace_back(input.element_nodes[k], p.element_part[e]);
  std::sort(uses.begin(), uses.end());
  uses.erase(std::unique(uses.begin(), uses.end()), uses.end());
  p.node_owner.assign(static_cast<std::size_t>(input.node_count), -1);
  for (std::size_t k = 0; k < uses.size();) {
    const Index node = uses[k].first;
    std::size_t end = k;
    while (end < uses.size() && uses[end].first == node) ++end;
    p.node_owner[node] = uses[k].second;  // the lowest part using it
    if (end - k > 1) {
      p.interface_nodes.push_back(node);
      for (std::size_t m = k; m < end; ++m) ++p.stats[uses[m].second].interface_nodes;
    }
    k = end;
  }
  // Nodes no element holds: with their group (a rigid body's reference node), else part 0.
  std::vector<int> group_part;
  for (Index e = 0; e < n_elements; ++e) {
    const Index group = input.element_group.empty() ? NO_INDEX : input.element_group[e];
    if (group == NO_INDEX) continue;
    if (group >= static_cast<Index>(group_part.size()))
      group_part.resize(static_cast<std::size_t>(group) + 1, -1);
    group_part[group] = p.element_part[e];
  }
  for (Index i = 0; i < input.node_count; ++i) {
    if (p.node_owner[i] >= 0) continue;
    const Index group = input.node_group.empty() ? NO_INDEX : input.node_group[i];
    const bool placed = group != NO_INDEX && group < static_cast<Index>(group_part.size()) &&
                        group_part[group] >= 0;
    p.node_owner[i] = placed ? group_part[group] : 0;
  }
  for (Index i = 0; i < input.node_count; ++i) ++p.stats[p.node_owner[i]].owned_nodes;

  if (parts > 1) {
    const ExchangePlan plan = make_exchange_plan(input, p);
    for (int k = 0; k < parts; ++k) {
      PartStats& s = p.stats[k];
      s.neighbours = static_cast<Index>(plan.part[k].neighbours.size());
      s.send_slots = plan.part[k].send_slots();
      for (const NeighbourExchange& x : plan.part[k].neighbours)
        s.shared_nodes += static_cast<Index>(x.nodes.size());
    }
  }

  Real total = 0.0, largest = 0.0;
  for (const PartStats& s : p.stats) {
    total += s.weight;
    largest = std::max(largest, s.weight);
  }
  p.imbalance = total > 0.0 ? largest * parts / total : 1.0;
  return p;
}

std::vector<std::string> partition_report(const MeshPartition& p, double seconds) {
  std::vector<std::string> lines;
  char text[320];
  std::snprintf(text, sizeof text,
                "partition: %d parts by %s in %.3f s: imbalance %.3f (largest part weight / "
                "mean), %zu interface nodes, %ld of %ld graph edges cut, %ld of %ld contact/tie "
                "element pairs across parts",
                p.parts, method_name(p.method), seconds, p.imbalance, p.interface_nodes.size(),
                p.cut_edges, p.graph_edges, p.cut_extra_pairs, p.extra_pairs);
  lines.emplace_back(text);
  for (int k = 0; k < p.parts; ++k) {
    const PartStats& s = p.stats[k];
    std::snprintf(text, sizeof text,
                  "partition: part %d: %d elements (weight %.1f), %d owned nodes, %d interface "
                  "nodes; exchange per increment: %d neighbours, %d shared nodes, %d force "
                  "slots sent (%.1f kB)",
                  k, s.elements, s.weight, s.owned_nodes, s.interface_nodes, s.neighbours,
                  s.shared_nodes, s.send_slots, s.send_slots * 3.0 * sizeof(Real) / 1000.0);
    lines.emplace_back(text);
  }
  return lines;
}

}  // namespace xpl::partition
