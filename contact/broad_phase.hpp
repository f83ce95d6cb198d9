#pragma once
/// \file Broad phase of node-to-face contact: candidate faces for every slave node (stage 2).
///
/// Face bounding boxes, with the slab behind the face a node may touch it from and inflated by
/// the search margin, are binned into a uniform grid of
/// buckets over their joint bounding box; a slave node looks only at the faces of the bucket
/// it lies in and keeps those whose inflated box contains it. The list stays valid while no
/// node has moved more than half the margin since the build: a node and a face then close in
/// on each other by at most one margin, so every pair that touches now was within the margin
/// at the build and is in the list (OpenRadioss re-sorts on the same kind of criterion).
///
/// Candidates are stored per slave node in compressed-row form, face indices ascending, so
/// the result does not depend on the number of threads. Storage is reused from build to build:
/// once the arrays have grown to their working size nothing is allocated.

#include <span>
#include <vector>

#include "contact/contact_faces.hpp"

namespace xpl::contact {

/// Bucket grid over inflated face boxes and the candidate faces of each slave node.
class BroadPhase {
 public:
  /// `margin` (m, > 0): how far boxes are inflated on every side. `rebuild_motion` (m, > 0,
  /// ≤ margin/2; default margin/2): how far a node may move before the lists are rebuilt.
  /// A smaller value leaves part of the margin for a contact thickness around the slave node
  /// (a shell's half thickness): pairs within that thickness of touching stay in the lists.
  explicit BroadPhase(Real margin, Real rebuild_motion = 0.0);

  /// Builds the grid and the candidate lists of the slave nodes `slave_nodes` (node indices,
  /// n_slave) against `faces`, on positions (n_nodes × 3, m) with shell node thickness
  /// (n_nodes, m, or empty). `back_depth` (n_faces, m, or empty): how deep behind each face a
  /// node may still touch it; the face's box then also holds the slab of that depth behind
  /// it, so a node that went that deep within one increment (a fast impact) is a candidate
  /// however small the margin. A face is never a candidate of its own corner nodes.
  /// Remembers the positions of every face node and slave node for needs_rebuild().
  /// `scanned` (one per slave node, empty: all): the slave nodes whose candidates are found;
  /// the others get none (a distributed run's process scans the slots it searches).
  /// `binned` (one per face, empty: all): the faces whose corners' rows `position` holds (a
  /// distributed run's ghost faces); only they are binned, the others are candidates of no
  /// node. A scanned node's candidates do not depend on which other faces are binned (the
  /// box test is exact and the grid only narrows which boxes are tested), so they are the
  /// whole build's as long as every face whose box may hold the node is binned.
  void build(std::span<const ContactFace> faces, std::span<const Index> slave_nodes,
             const NodalVectors& position, std::span<const Real> node_thickness,
             std::span<const Real> back_depth = {}, std::span<const char> scanned = {},
             std::span<const char> binned = {});
  /// The box of face `f` as build() bins it (m): its contact surface's corners and the slab
  /// `back_depth` behind it, not yet inflated by the margin (lo, hi: 3 each).
  static void face_box(const ContactFace& face, const NodalVectors& position,
                       std::span<const Real> node_thickness, Real back_depth, Real lo[3],
                       Real hi[3]);

  /// Whether any node tracked at the last build has moved more than the rebuild motion since it
  /// (true before the first build). Parallel max-reduction, no allocation.
  bool needs_rebuild(const NodalVectors& position) const;
  /// The largest squared motion (m²) since the last build of the tracked nodes that
  /// `node_mask` marks (n_nodes; empty: all), 0 before the first build. A distributed run's
  /// processes each take the nodes whose rows they hold and reduce (max is exact), so that
  /// the decision is needs_rebuild()'s on the whole positions, bit for bit.
  Real largest_motion_sq(const NodalVectors& position, std::span<const char> node_mask = {}) const;
  /// The largest squared motion (m²) of the tracked nodes that `node_mask` marks (n_nodes;
  /// empty: all) since the last call that measured them (or the last build), whose positions
  /// it then remembers for the next call; 0 before the first build. A distributed run's
  /// processes each measure the nodes they integrate and reduce (max is exact), as for
  /// largest_motion_sq(). The sum of these over the increments bounds how far any tracked
  /// node has moved since any of them (ContactEngine, sleeping slots).
  Real step_motion_sq(const NodalVectors& position, std::span<const char> node_mask = {});
  /// largest_motion_sq() and step_motion_sq() in one walk over the tracked nodes: returns the
  /// former and puts the latter in `step_sq` (the same bits as the two calls).
  Real motions_sq(const NodalVectors& position, std::span<const char> node_mask, Real& step_sq);
  /// Whether a largest squared motion `max_sq` (m²) calls for a rebuild (after a first build).
  bool exceeds_rebuild_motion(Real max_sq) const {
    return max_sq > m_rebuild_motion * m_rebuild_motion;
  }

  /// Candidate faces of slave slot s (index into the `slave_nodes` of the last build).
  std::span<const Index> candidates(Index s) const {
    return {m_candidates.data() + m_offsets[s],
            static_cast<std::size_t>(m_offsets[s + 1] - m_offsets[s])};
  }
  /// Candidate CSR: slot s has faces m_candidates[offsets[s] .. offsets[s + 1]) (n_slave + 1).
  const std::vector<Index>& offsets() const { return m_offsets; }
  /// Candidate face indices, ascending within each slave node.
  const std::vector<Index>& candidate_faces() const { return m_candidates; }
  Real margin() const { return m_margin; }
  Real rebuild_motion() const { return m_rebuild_motion; }
  /// Number of builds so far.
  long build_count() const { return m_builds; }
  /// Buckets per direction of the last build.
  const std::array<Index, 3>& grid_size() const { return m_dims; }

 private:
  /// Joint box of the inflated face boxes, and the sum of their largest extents (m).
  struct JointBox {
    Real lo[3], hi[3];
    Real extent_sum;
  };
  // The steps of build(), in order.
  JointBox box_faces(std::span<const ContactFace> faces, const NodalVectors& position,
                     std::span<const Real> node_thickness, std::span<const Real> back_depth,
                     std::span<const char> binned);
  void size_grid(const JointBox& joint, Index n_faces);
  void bin_faces(Index n_faces, std::span<const char> binned);
  void find_candidates(std::span<const ContactFace> faces, std::span<const Index> slave_nodes,
                       const NodalVectors& position, std::span<const char> scanned);
  void track_nodes(std::span<const ContactFace> faces, std::span<const Index> slave_nodes,
                   const NodalVectors& position);
  /// Counts the candidate faces of `node` at `p` and, when `out` is not null, writes them there.
  Index scan_bucket(Index node, const Vec3& p, std::span<const ContactFace> faces,
                    Index* out) const;

  Real m_margin;
  Real m_rebuild_motion;
  long m_builds = 0;
  // Grid: origin, bucket size, buckets per direction, bucket -> faces (CSR).
  Vec3 m_origin = Vec3::Zero();
  Vec3 m_top = Vec3::Zero();  ///< the joint box's upper corner (scan_bucket())
  Real m_cell = 1.0;
  std::array<Index, 3> m_dims{0, 0, 0};
  std::vector<Index> m_cell_offsets;
  std::vector<Index> m_cell_faces;
  std::vector<Index> m_cell_fill;
  // Inflated box of each face: lo (n_faces × 3) and hi.
  std::vector<Real> m_box_lo, m_box_hi;
  // Candidates per slave node (CSR).
  std::vector<Index> m_offsets{0};
  std::vector<Index> m_candidates;
  // Nodes whose motion is watched and their positions at the last build (n_tracked × 3).
  std::vector<Index> m_tracked;
  std::vector<Real> m_tracked_position;
  std::vector<Real> m_step_position;  ///< (n_tracked × 3) at the last step_motion_sq()
  std::vector<char> m_is_tracked;
};

}  // namespace xpl::contact
