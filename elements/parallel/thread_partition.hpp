#pragma once
/// \file Per-thread element ranges for one parallel force pass without a barrier per colour.
///
/// Each colour's batches are split into `parts` contiguous ranges; part p computes range p of
/// every colour, one colour after another, with no wait in between. Colours are packed in
/// element order, so range p of each colour covers about the same region of a mesh numbered
/// in space, and the nodes part p touches are mostly its own: there it scatters its forces
/// directly, in colour order, as the one-thread pass does. Only nodes touched by two parts
/// (the boundary between the regions) are not written by the element kernels: their corner
/// forces go to an exchange buffer, and after the single barrier of the pass each boundary
/// node adds its corners in batch order (= colour order). Every node therefore sums the
/// same values in the same order whatever the number of parts: results are bitwise those of
/// one thread.

#include <utility>
#include <vector>

#include "common/parallel_error.hpp"
#include "common/types.hpp"

namespace xpl::elements {

/// Node marks of a partition: not touched by any part yet.
inline constexpr Index UNTOUCHED = -1;
/// Node marks of a partition: touched by two or more parts (a boundary node).
inline constexpr Index SHARED = -2;

/// Batches [first, second) of colour `color` (batches of colour c are [color_batches[c],
/// color_batches[c + 1])) computed by part `part` of `parts`.
inline std::pair<Index, Index> part_batches(const std::vector<Index>& color_batches, int color,
                                            int part, int parts) {
  const Index first = color_batches[color], count = color_batches[color + 1] - first;
  return {first + static_cast<Index>(static_cast<long long>(count) * part / parts),
          first + static_cast<Index>(static_cast<long long>(count) * (part + 1) / parts)};
}

/// Whether a pass of phase `phase` computes batch b: every batch when `phase` < 0, else the
/// batches marked `phase` in `batch_phase` (empty: every batch is of phase 0). Distributed
/// runs compute the batches at the interface between ranks first (phase 0), send their
/// corners, and compute the others (phase 1) while the messages travel (solver/forces/
/// element_set.cpp); each phase keeps the colour and batch order of the whole pass.
inline bool in_phase(const std::vector<unsigned char>& batch_phase, int phase, Index b) {
  return phase < 0 || (batch_phase.empty() ? 0 : int{batch_phase[b]}) == phase;
}

/// Marks in `node_part` (n_nodes; UNTOUCHED, a part, or SHARED) the nodes each part of
/// `parts` touches in a batched block: `conn` [batch][corners][lanes] node indices,
/// `lane_owner` [batch][lanes] (NO_INDEX: padding lane, ignored).
void mark_part_nodes(const std::vector<Index>& conn, const std::vector<Index>& lane_owner,
                     const std::vector<Index>& color_batches, int corners, int lanes, int parts,
                     std::vector<Index>& node_part);

/// The boundary nodes of a partition (SHARED in `node_part`), in node order, and the rank
/// of each node among them.
struct BoundaryNodes {
  std::vector<Index> nodes;  ///< boundary nodes, ascending
  std::vector<Index> rank;   ///< n_nodes: position in `nodes`, or NO_INDEX
  Index size() const { return static_cast<Index>(nodes.size()); }
};

/// Boundary nodes of the marks left by mark_part_nodes() over every block of a pass.
BoundaryNodes boundary_nodes(const std::vector<Index>& node_part);

/// The exchange slots of one batched block: one slot per corner at a boundary node, numbered
/// node by node (boundary rank) and, for one node, in batch order, so that a node's slots are
/// contiguous and in the order its contributions are summed.
class CornerExchange {
 public:
  CornerExchange() = default;
  /// Slots of the corners of `conn` ([batch][corners][lanes], padding lanes per `lane_owner`
  /// skipped) at the nodes `boundary` ranks.
  CornerExchange(const std::vector<Index>& conn, const std::vector<Index>& lane_owner, int corners,
                 int lanes, const BoundaryNodes& boundary);

  /// Slots of batch b ([corners][lanes], NO_INDEX: scatter directly), or nullptr when no
  /// corner of the batch is at a boundary node.
  const Index* batch_slots(Index b) const {
    return m_batch_offset.empty() || m_batch_offset[b] == NO_INDEX ? nullptr
                                                                   : &m_slots[m_batch_offset[b]];
  }
  /// Slots of boundary node k (its rank): [first(k), first(k + 1)).
  Index first(Index k) const { return m_node_start[k]; }
  /// Number of slots.
  Index size() const { return m_node_start.empty() ? 0 : m_node_start.back(); }

 private:
  std::vector<Index> m_batch_offset;  ///< [batch] offset into m_slots, or NO_INDEX
  std::vector<Index> m_slots;         ///< [boundary batch][corners][lanes]
  std::vector<Index> m_node_start;    ///< [boundary rank + 1] CSR over slots
};

}  // namespace xpl::elements

namespace xpl::elements {

/// One force pass over `parts` parts in a single parallel region: `compute_part(p)` for every
/// part (each by one thread, no wait between colours), one barrier, then
/// `add_boundary(k)` for every boundary node k (split between the threads). With one part it
/// runs on the calling thread alone.
template <class ComputePart, class AddBoundary>
void partitioned_pass(int parts, Index n_boundary, ComputePart&& compute_part,
                      AddBoundary&& add_boundary) {
  if (parts <= 1) {
    compute_part(0);
    for (Index k = 0; k < n_boundary; ++k) add_boundary(k);
    return;
  }
  // An exception may not leave the region: kept per loop, rethrown after it.
  ParallelErrors part_errors, boundary_errors;
#pragma omp parallel num_threads(parts)
  {
#pragma omp for schedule(static, 1)
    for (int p = 0; p < parts; ++p)
      part_errors.guard(ParallelSite::ElementForces, p, [&] { compute_part(p); });
#pragma omp for schedule(static) nowait
    for (Index k = 0; k < n_boundary; ++k)
      boundary_errors.guard(ParallelSite::ElementBoundary, k, [&] { add_boundary(k); });
  }
  part_errors.rethrow_if_any();
  boundary_errors.rethrow_if_any();
}

}  // namespace xpl::elements
