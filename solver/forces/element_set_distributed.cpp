// The distributed part of ElementSet (element_set.hpp; issue 37 item 3, distributed_run.hpp):
// the partition of the SIMD batches, this rank's blocks, the exchange of the interface forces
// and the reduction of the batch totals over the ranks.
#include <algorithm>
#include <type_traits>

#include "solver/distributed_run.hpp"
#include "solver/forces/element_set.hpp"
#include "solver/forces/element_set_blocks.hpp"
#include "solver/model_partition.hpp"

namespace xpl {

namespace {

/// Tuple index of each kind (ElementKinds order) and its position in ForcePassOrder.
constexpr int KIND_HEX8R = 0, KIND_HEX8 = 1, KIND_SHELL = 2;
constexpr Index pass_position(int kind) {
  return kind == KIND_HEX8R ? 0 : kind == KIND_SHELL ? 1 : 2;
}
/// Slot sources: kind × 2^29 + the corner slot of its block.
constexpr int SOURCE_SHIFT = 29;

}  // namespace

partition::MeshPartition ElementSet::partition_batches(
    int parts, partition::Method method, std::vector<int>& element_part,
    const std::vector<std::pair<Index, Index>>& node_element_pairs,
    const std::vector<std::pair<Index, Index>>& node_node_pairs) const {
  // Every batch of every block as one "element" of the partition: its lanes' nodes, cost.
  constexpr int W = simd::W;
  std::vector<Index> offsets{0}, nodes, lane_elements{0}, elements;
  std::vector<Real> weight;
  for_each_block([&](const auto& block) {
    const std::vector<Index>& owners = block.lane_owners();
    for (Index b = 0; b < block.batch_count(); ++b) {
      Real cost = 0.0;
      for (int l = 0; l < W; ++l) {
        const Index owner = owners[b * W + l];
        if (owner == NO_INDEX) continue;
        const Index e = block.element_index(owner);
        elements.push_back(e);
        cost += element_cost(m_model, e, false);
        nodes.insert(nodes.end(), m_model.nodes_of(e),
                     m_model.nodes_of(e) + nodes_per_element(m_model.element_types[e]));
      }
      offsets.push_back(static_cast<Index>(nodes.size()));
      lane_elements.push_back(static_cast<Index>(elements.size()));
      weight.push_back(cost);
    }
  });
  // Extra edges: the batch of each pair's node (the first batch holding it) and that of its
  // element (e.g. the t = 0 contact candidate pairs: partners tend to share a part), and the
  // batches of the two nodes of each node pair (a tie's slave and master corners).
  std::vector<std::pair<Index, Index>> extra_edges;
  if (!node_element_pairs.empty() || !node_node_pairs.empty()) {
    std::vector<Index> node_batch(static_cast<std::size_t>(m_model.node_count()), NO_INDEX);
    std::vector<Index> element_batch(static_cast<std::size_t>(m_model.element_count()), NO_INDEX);
    for (std::size_t b = 0; b + 1 < lane_elements.size(); ++b) {
      for (Index k = lane_elements[b]; k < lane_elements[b + 1]; ++k)
        element_batch[elements[k]] = static_cast<Index>(b);
      for (Index k = offsets[b]; k < offsets[b + 1]; ++k)
        if (node_batch[nodes[k]] == NO_INDEX) node_batch[nodes[k]] = static_cast<Index>(b);
    }
    for (const auto& [node, element] : node_element_pairs) {
      const Index a = node_batch[node], b = element_batch[element];
      if (a != NO_INDEX && b != NO_INDEX && a != b) extra_edges.emplace_back(a, b);
    }
    for (const auto& [node, other] : node_node_pairs) {
      const Index a = node_batch[node], b = node_batch[other];
      if (a != NO_INDEX && b != NO_INDEX && a != b) extra_edges.emplace_back(a, b);
    }
    std::sort(extra_edges.begin(), extra_edges.end());
    extra_edges.erase(std::unique(extra_edges.begin(), extra_edges.end()), extra_edges.end());
  }
  partition::PartitionInput input;
  input.node_count = m_model.node_count();
  input.extra_edges = extra_edges;
  input.element_offsets = offsets;
  input.element_nodes = nodes;
  input.element_weight = weight;
  input.coordinates = &m_model.coordinates;
  partition::MeshPartition p = partition::partition_mesh(input, parts, method);
  element_part.assign(static_cast<std::size_t>(m_model.element_count()), 0);
  for (std::size_t b = 0; b + 1 < lane_elements.size(); ++b)
    for (Index k = lane_elements[b]; k < lane_elements[b + 1]; ++k)
      element_part[elements[k]] = p.element_part[b];
  return p;
}

std::vector<Index> ElementSet::element_order() const {
  std::vector<Index> order(static_cast<std::size_t>(m_model.element_count()), NO_INDEX);
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    (
        [&] {
          const auto& block = std::get<I>(m_blocks);
          if (!block) return;
          constexpr int W = simd::W;
          const std::vector<Index>& owners = block->lane_owners();
          for (Index k = 0; k < block->batch_count() * W; ++k)
            if (owners[k] != NO_INDEX)
              order[block->element_index(owners[k])] = (pass_position(I) << 28) + k;
        }(),
        ...);
  }
  (std::make_index_sequence<3>{});
  // Elements of no block (rigid ones) after all others, in element order.
  Index next = Index{3} << 28;
  for (Index& o : order)
    if (o == NO_INDEX) o = next++;
  return order;
}

template <class K>
void ElementSet::distribute_block(std::unique_ptr<K>& block, std::unique_ptr<K>& whole) {
  whole = std::move(block);
  if (!whole) return;
  constexpr int W = simd::W;
  constexpr int kind = std::is_same_v<K, elements::Hex8rBlock>  ? KIND_HEX8R
                       : std::is_same_v<K, elements::Hex8Block> ? KIND_HEX8
                                                                : KIND_SHELL;
  const K& w = *whole;
  const std::vector<Index>& owners = w.lane_owners();
  const std::vector<Index>& colors = w.color_batches();
  std::vector<std::vector<Index>>& rank_batches = m_rank_batches[kind];
  rank_batches.assign(static_cast<std::size_t>(m_run->size()), {});
  std::vector<Index> elements, connectivity;
  std::vector<typename K::Properties> properties;
  elements::BatchLayout layout;
  for (std::size_t c = 0; c + 1 < colors.size(); ++c) {
    for (Index b = colors[c]; b < colors[c + 1]; ++b) {
      const int part = m_run->element_part()[w.element_index(owners[b * W])];
      rank_batches[part].push_back(b);
      if (part != m_run->rank()) continue;
      for (int l = 0; l < W; ++l) {
        const Index owner = owners[b * W + l];
        if (owner == NO_INDEX) {
          layout.lane_owner.push_back(NO_INDEX);
          continue;
        }
        const Index e = w.element_index(owner);
        layout.lane_owner.push_back(static_cast<Index>(elements.size()));
        elements.push_back(e);
        connectivity.insert(connectivity.end(), m_model.nodes_of(e),
                            m_model.nodes_of(e) + K::NODES);
        properties.push_back(KindBinding<K>::properties(m_model, e, mass_factor(e)));
      }
    }
    layout.color_batches.push_back(static_cast<Index>(layout.lane_owner.size() / W));
  }
  if (elements.empty()) return;
  block = std::make_unique<K>(elements, connectivity, properties, m_model.node_count(), &layout);
  if constexpr (requires { block->note_reference_corners(m_model.coordinates); })
    block->note_reference_corners(m_model.coordinates);
}

template <std::size_t... I>
void ElementSet::distribute_blocks(std::index_sequence<I...>) {
  (distribute_block(std::get<I>(m_blocks), std::get<I>(m_whole)), ...);
}

void ElementSet::distribute(DistributedRun& run) {
  m_run = &run;
  // The global estimate on every rank, its stiffness products shared (increment_estimate()):
  // the same iteration on the same whole vectors everywhere; rank 0's eigenvalue and product
  // count are broadcast all the same, so that every rank takes its increment bit for bit.
  m_global.set_distribution(
      true, [&run](Real& lambda, int& products) { run.broadcast_estimate(lambda, products); });
  distribute_blocks(std::make_index_sequence<3>{});
  m_parts = 0;  // the force pass partitions the rank's blocks anew
  m_slot_parts = 0;
  // The whole blocks' batches this rank multiplies in a stiffness product: those with a
  // corner at a node it owns, so that its owned rows get every term, in the one-rank order.
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    (
        [&] {
          const auto& whole = std::get<I>(m_whole);
          std::vector<char>& selected = m_product_batches[I];
          selected.clear();
          if (!whole) return;
          constexpr int W = simd::W;
          const std::vector<Index>& owners = whole->lane_owners();
          selected.assign(static_cast<std::size_t>(whole->batch_count()), 0);
          for (Index b = 0; b < whole->batch_count(); ++b)
            for (int l = 0; l < W && selected[b] == 0; ++l) {
              if (owners[b * W + l] == NO_INDEX) continue;
              const Index e = whole->element_index(owners[b * W + l]);
              for (Index k = m_model.element_offsets[e]; k < m_model.element_offsets[e + 1]; ++k)
                if (run.owns(m_model.element_nodes[k])) selected[b] = 1;
            }
        }(),
        ...);
  }
  (std::make_index_sequence<3>{});
}

void ElementSet::mark_batch_phases(std::vector<Index>& node_part) {
  constexpr int W = simd::W;
  const partition::PartPlan& plan = m_run->plan();
  std::vector<unsigned char> interface(static_cast<std::size_t>(m_model.node_count()), 0);
  for (const Index n : plan.interface_nodes) interface[n] = 1;
  // Bit p set: a batch of phase p touches the node.
  std::vector<unsigned char> touched(interface.size(), 0);
  for_each_block([&](auto& block) {
    using K = std::remove_cvref_t<decltype(block)>;
    const std::vector<Index>& owners = block.lane_owners();
    const auto for_each_node = [&](Index b, auto&& f) {
      for (int l = 0; l < W; ++l) {
        if (owners[b * W + l] == NO_INDEX) continue;
        const Index* nodes = m_model.nodes_of(block.element_index(owners[b * W + l]));
        for (int a = 0; a < K::NODES; ++a) f(nodes[a]);
      }
    };
    std::vector<unsigned char> phase(static_cast<std::size_t>(block.batch_count()), 1);
    for (Index b = 0; b < block.batch_count(); ++b) {
      for_each_node(b, [&](Index n) {
        if (interface[n] != 0) phase[b] = 0;
      });
      for_each_node(b, [&](Index n) { touched[n] |= static_cast<unsigned char>(1 << phase[b]); });
    }
    block.set_batch_phases(std::move(phase));
  });
  for (std::size_t n = 0; n < touched.size(); ++n)
    if (touched[n] == 3 || interface[n] != 0) node_part[n] = elements::SHARED;
}

void ElementSet::send_interface_forces() {
  constexpr int W = simd::W;
  const partition::PartPlan& plan = m_run->plan();
  const int width = m_rotations ? 6 : 3;
  if (m_slot_parts != m_parts) {
    // Where each corner of this rank at a boundary node has its value (the corner slots
    // change with the thread partition).
    m_slot_source.assign(m_model.element_nodes.size(), NO_INDEX);
    [&]<std::size_t... I>(std::index_sequence<I...>) {
      (
          [&] {
            const auto& block = std::get<I>(m_blocks);
            if (!block) return;
            const std::vector<Index>& owners = block->lane_owners();
            for (Index b = 0; b < block->batch_count(); ++b) {
              const Index* slots = block->corner_exchange().batch_slots(b);
              if (slots == nullptr) continue;
              using K = std::remove_cvref_t<decltype(*block)>;
              for (int l = 0; l < W; ++l) {
                if (owners[b * W + l] == NO_INDEX) continue;
                const Index e = block->element_index(owners[b * W + l]);
                for (int a = 0; a < K::NODES; ++a)
                  if (slots[a * W + l] != NO_INDEX)
                    m_slot_source[m_model.element_offsets[e] + a] =
                        (Index{I} << SOURCE_SHIFT) + slots[a * W + l];
              }
            }
          }(),
          ...);
    }
    (std::make_index_sequence<3>{});
    m_slot_parts = m_parts;
  }
  std::vector<std::vector<Real>>& send = m_run->send_buffers();
  for (std::size_t j = 0; j < plan.neighbours.size(); ++j) {
    Real* out = send[j].data();
    for (const Index s : plan.neighbours[j].send)
      for (int c = 0; c < width; ++c) *out++ = slot_value(m_slot_source[s], c);
  }
  m_run->send();
}

Real ElementSet::slot_value(Index source, int c) const {
  const Index slot = source & ((Index{1} << SOURCE_SHIFT) - 1);
  switch (source >> SOURCE_SHIFT) {
    case KIND_HEX8R:
      return c < 3 ? std::get<KIND_HEX8R>(m_blocks)->exchange_values()[3 * slot + c] : 0.0;
    case KIND_HEX8:
      return c < 3 ? std::get<KIND_HEX8>(m_blocks)->exchange_values()[3 * slot + c] : 0.0;
    default:
      return std::get<KIND_SHELL>(m_blocks)->exchange_values()[6 * slot + c];
  }
}

const Real* ElementSet::slot_values(Index source, int& count) const {
  const Index slot = source & ((Index{1} << SOURCE_SHIFT) - 1);
  switch (source >> SOURCE_SHIFT) {
    case KIND_HEX8R:
      count = 3;
      return &std::get<KIND_HEX8R>(m_blocks)->exchange_values()[3 * slot];
    case KIND_HEX8:
      count = 3;
      return &std::get<KIND_HEX8>(m_blocks)->exchange_values()[3 * slot];
    default:
      count = 6;
      return &std::get<KIND_SHELL>(m_blocks)->exchange_values()[6 * slot];
  }
}

void ElementSet::combine_interface_forces() {
  const partition::PartPlan& plan = m_run->plan();
  const int width = m_rotations ? 6 : 3;
  const std::vector<std::vector<Real>>& received = m_run->receive();
  // Each interface node: every contribution, own or received, folded from +0 in the one-rank
  // order (partition::PartPlan::combine), replacing the sum of the rank's own corners.
  // Each component's sum in the same order as slot_value() one at a time, the slot's kind
  // looked up once per slot (a hex slot gives +0 to the moments, as slot_value() does).
  for (std::size_t k = 0; k < plan.interface_nodes.size(); ++k) {
    const Index n = plan.interface_nodes[k];
    Real sum[6] = {};
    for (Index i = plan.combine_start[k]; i < plan.combine_start[k + 1]; ++i) {
      const partition::SlotSource& src = plan.combine[i];
      int count = width;
      const Real* values =
          src.neighbour < 0 ? slot_values(m_slot_source[src.index], count)
                            : &received[src.neighbour][static_cast<std::size_t>(src.index) * width];
      for (int c = 0; c < width; ++c) sum[c] += c < count ? values[c] : 0.0;
    }
    for (int c = 0; c < width; ++c) {
      if (c < 3)
        m_force_internal(n, c) = sum[c];
      else
        m_moment_internal(n, c - 3) = sum[c];
    }
  }
}

void ElementSet::post_totals() {
  // This rank's batch totals, kind after kind, batch after batch (into a buffer kept
  // between increments: 350 kB a rank on the 46³ block at 2 ranks).
  std::vector<Real>& mine = m_totals_mine;
  mine.clear();
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    (
        [&] {
          const auto& block = std::get<I>(m_blocks);
          if (!block) return;
          using K = std::remove_cvref_t<decltype(*block)>;
          Real values[K::BATCH_TOTALS];
          for (Index b = 0; b < block->batch_count(); ++b) {
            block->pack_batch_totals(b, values);
            mine.insert(mine.end(), values, values + K::BATCH_TOTALS);
          }
        }(),
        ...);
  }
  (std::make_index_sequence<3>{});
  // Every rank's count is known: its batches' totals.
  std::vector<int> counts(static_cast<std::size_t>(m_run->size()), 0);
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    (
        [&] {
          const auto& whole = std::get<I>(m_whole);
          if (!whole) return;
          using K = std::remove_cvref_t<decltype(*whole)>;
          for (int r = 0; r < m_run->size(); ++r)
            counts[r] += static_cast<int>(m_rank_batches[I][r].size()) * K::BATCH_TOTALS;
        }(),
        ...);
  }
  (std::make_index_sequence<3>{});
  m_run->post_allgather(mine, counts);
}

void ElementSet::reduce_totals(ElementTotals& totals) {
  const std::vector<Real>& all = m_run->wait_allgather();
  // Into the whole blocks at their batches, then the one-rank reduction of each.
  std::size_t at = 0;
  for (int r = 0; r < m_run->size(); ++r) [&]<std::size_t... I>(std::index_sequence<I...>) {
      (
          [&] {
            auto& whole = std::get<I>(m_whole);
            if (!whole) return;
            using K = std::remove_cvref_t<decltype(*whole)>;
            for (const Index b : m_rank_batches[I][r]) {
              whole->unpack_batch_totals(b, &all[at]);
              at += K::BATCH_TOTALS;
            }
          }(),
          ...);
    }
  (std::make_index_sequence<3>{});
  std::apply(
      [&](const auto&... whole) {
        (
            [&] {
              if (!whole) return;
              typename std::remove_cvref_t<decltype(*whole)>::Totals t;
              whole->add_totals(t);
              totals.add(t);
            }(),
            ...);
      },
      m_whole);
}

}  // namespace xpl
