#include "elements/parallel/thread_partition.hpp"

namespace xpl::elements {

void mark_part_nodes(const std::vector<Index>& conn, const std::vector<Index>& lane_owner,
                     const std::vector<Index>& color_batches, int corners, int lanes, int parts,
                     std::vector<Index>& node_part) {
  const int n_colors = static_cast<int>(color_batches.size()) - 1;
  for (int p = 0; p < parts; ++p)
    for (int c = 0; c < n_colors; ++c) {
      const auto [first, last] = part_batches(color_batches, c, p, parts);
      for (Index b = first; b < last; ++b)
        for (int l = 0; l < lanes; ++l) {
          if (lane_owner[static_cast<std::size_t>(b) * lanes + l] == NO_INDEX) continue;
          for (int a = 0; a < corners; ++a) {
            Index& mark = node_part[conn[(static_cast<std::size_t>(b) * corners + a) * lanes + l]];
            if (mark == UNTOUCHED)
              mark = p;
            else if (mark != p)
              mark = SHARED;
          }
        }
    }
}

BoundaryNodes boundary_nodes(const std::vector<Index>& node_part) {
  BoundaryNodes b;
  b.rank.assign(node_part.size(), NO_INDEX);
  for (std::size_t i = 0; i < node_part.size(); ++i)
    if (node_part[i] == SHARED) {
      b.rank[i] = b.size();
      b.nodes.push_back(static_cast<Index>(i));
    }
  return b;
}

CornerExchange::CornerExchange(const std::vector<Index>& conn, const std::vector<Index>& lane_owner,
                               int corners, int lanes, const BoundaryNodes& boundary) {
  const auto n_batches = static_cast<Index>(lane_owner.size() / lanes);
  const std::size_t per_batch = static_cast<std::size_t>(corners) * lanes;
  auto rank_of = [&](Index b, int a, int l) -> Index {
    if (lane_owner[static_cast<std::size_t>(b) * lanes + l] == NO_INDEX) return NO_INDEX;
    return boundary.rank[conn[static_cast<std::size_t>(b) * per_batch + a * lanes + l]];
  };
  // Count the corners of each boundary node, then number them in batch order.
  m_node_start.assign(static_cast<std::size_t>(boundary.size()) + 1, 0);
  m_batch_offset.assign(n_batches, NO_INDEX);
  Index boundary_batches = 0;
  for (Index b = 0; b < n_batches; ++b) {
    bool touches = false;
    for (int l = 0; l < lanes; ++l)
      for (int a = 0; a < corners; ++a)
        if (const Index k = rank_of(b, a, l); k != NO_INDEX) {
          ++m_node_start[k + 1];
          touches = true;
        }
    if (touches) m_batch_offset[b] = static_cast<Index>(per_batch) * boundary_batches++;
  }
  if (boundary_batches == 0) {
    // Nothing to exchange: every batch scatters directly.
    m_batch_offset.clear();
    return;
  }
  for (Index k = 0; k < boundary.size(); ++k) m_node_start[k + 1] += m_node_start[k];
  std::vector<Index> fill(m_node_start.begin(), m_node_start.end() - 1);
  m_slots.assign(static_cast<std::size_t>(boundary_batches) * per_batch, NO_INDEX);
  for (Index b = 0; b < n_batches; ++b) {
    if (m_batch_offset[b] == NO_INDEX) continue;
    Index* slots = &m_slots[m_batch_offset[b]];
    // Lane by lane, corner by corner: the order in which the kernels scatter.
    for (int l = 0; l < lanes; ++l)
      for (int a = 0; a < corners; ++a)
        if (const Index k = rank_of(b, a, l); k != NO_INDEX) slots[a * lanes + l] = fill[k]++;
  }
}

}  // namespace xpl::elements
