#include "contact/broad_phase.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>
#include <vector>

#include "common/parallel_error.hpp"
#include "contact/parallel_size.hpp"

namespace xpl::contact {

namespace {

/// Upper bound on buckets per face: keeps the grid O(n_faces) however the faces spread out.
constexpr double MAX_BUCKETS_PER_FACE = 4.0;

Index bucket_coordinate(Real x, Real origin, Real cell, Index dim) {
  const auto i = static_cast<Index>(std::floor((x - origin) / cell));
  return std::clamp<Index>(i, 0, dim - 1);
}

/// The largest squared motions of the `tracked` nodes `node_mask` marks (empty: all) since
/// `at_build` (first, when SinceBuild) and since `*at_step` (second, when SinceStep; the
/// positions are then remembered there), in one walk; a max-reduction over the team, exact
/// whatever the order, so one walk gives the bits of two.
template <bool SinceBuild, bool SinceStep>
std::pair<Real, Real> walk_motions(const std::vector<Index>& tracked,
                                   const std::vector<Real>& at_build, std::vector<Real>* at_step,
                                   const NodalVectors& position, std::span<const char> node_mask) {
  const auto n_tracked = static_cast<Index>(tracked.size());
  const bool masked = !node_mask.empty();
  Real build_sq = 0.0, step_sq = 0.0;
  const bool on_team = n_tracked >= PARALLEL_MIN_SLOTS;
#pragma omp parallel for schedule(static) reduction(max : build_sq, step_sq) if (on_team)
  for (Index i = 0; i < n_tracked; ++i) {
    const Index n = tracked[i];
    if (masked && node_mask[n] == 0) continue;
    Real since_build = 0.0, since_step = 0.0;
    for (int d = 0; d < 3; ++d) {
      const Real x = position(n, d);
      if constexpr (SinceBuild) {
        const Real u = x - at_build[3 * i + d];
        since_build += u * u;
      }
      if constexpr (SinceStep) {
        Real& then = (*at_step)[3 * i + d];
        const Real u = x - then;
        since_step += u * u;
        then = x;
      }
    }
    build_sq = std::max(build_sq, since_build);
    step_sq = std::max(step_sq, since_step);
  }
  return {build_sq, step_sq};
}

}  // namespace

BroadPhase::BroadPhase(Real margin, Real rebuild_motion)
    : m_margin(margin), m_rebuild_motion(rebuild_motion > 0.0 ? rebuild_motion : 0.5 * margin) {
  if (!(margin > 0.0)) throw std::invalid_argument("BroadPhase: the search margin must be > 0");
  if (m_rebuild_motion > 0.5 * margin)
    throw std::invalid_argument("BroadPhase: the rebuild motion must not exceed margin/2");
}

void BroadPhase::build(std::span<const ContactFace> faces, std::span<const Index> slave_nodes,
                       const NodalVectors& position, std::span<const Real> node_thickness,
                       std::span<const Real> back_depth, std::span<const char> scanned,
                       std::span<const char> binned) {
  ++m_builds;
  const JointBox joint = box_faces(faces, position, node_thickness, back_depth, binned);
  Index n_binned = static_cast<Index>(faces.size());
  if (!binned.empty())
    n_binned = static_cast<Index>(
        std::count_if(binned.begin(), binned.end(), [](char b) { return b != 0; }));
  size_grid(joint, n_binned);
  bin_faces(static_cast<Index>(faces.size()), binned);
  find_candidates(faces, slave_nodes, position, scanned);
  track_nodes(faces, slave_nodes, position);
}

void BroadPhase::face_box(const ContactFace& face, const NodalVectors& position,
                          std::span<const Real> node_thickness, Real back_depth, Real lo[3],
                          Real hi[3]) {
  Vec3 corner[4];
  face_corners(face, position, node_thickness, corner);
  // The slab behind the face: its corners moved back along the unit normal.
  Vec3 back = Vec3::Zero();
  if (back_depth > 0.0) {
    const Vec3 n = (corner[2] - corner[0]).cross(corner[3] - corner[1]);
    const Real len = std::sqrt(n.dot(n));
    if (len > 0.0) back = -(back_depth / len) * n;
  }
  for (int d = 0; d < 3; ++d) {
    lo[d] = corner[0][d];
    hi[d] = corner[0][d];
    for (int a = 0; a < 4; ++a) {
      lo[d] = std::min({lo[d], corner[a][d], corner[a][d] + back[d]});
      hi[d] = std::max({hi[d], corner[a][d], corner[a][d] + back[d]});
    }
  }
}

/// Inflated face boxes (of the binned faces) and their joint box.
BroadPhase::JointBox BroadPhase::box_faces(std::span<const ContactFace> faces,
                                           const NodalVectors& position,
                                           std::span<const Real> node_thickness,
                                           std::span<const Real> back_depth,
                                           std::span<const char> binned) {
  const auto n_faces = static_cast<Index>(faces.size());
  m_box_lo.resize(3 * static_cast<std::size_t>(n_faces));
  m_box_hi.resize(3 * static_cast<std::size_t>(n_faces));
  Real lo0 = std::numeric_limits<Real>::max(), lo1 = lo0, lo2 = lo0;
  Real hi0 = std::numeric_limits<Real>::lowest(), hi1 = hi0, hi2 = hi0;
  Real extent_sum = 0.0;
#pragma omp parallel for schedule(static) reduction(min : lo0, lo1, lo2) \
    reduction(max : hi0, hi1, hi2) reduction(+ : extent_sum)
  for (Index f = 0; f < n_faces; ++f) {
    if (!binned.empty() && binned[f] == 0) continue;
    Real lo[3], hi[3];
    face_box(faces[f], position, node_thickness, back_depth.empty() ? 0.0 : back_depth[f], lo, hi);
    Real extent = 0.0;
    for (int d = 0; d < 3; ++d) {
      m_box_lo[3 * f + d] = lo[d] - m_margin;
      m_box_hi[3 * f + d] = hi[d] + m_margin;
      extent = std::max(extent, hi[d] - lo[d] + 2.0 * m_margin);
    }
    extent_sum += extent;
    lo0 = std::min(lo0, m_box_lo[3 * f]);
    lo1 = std::min(lo1, m_box_lo[3 * f + 1]);
    lo2 = std::min(lo2, m_box_lo[3 * f + 2]);
    hi0 = std::max(hi0, m_box_hi[3 * f]);
    hi1 = std::max(hi1, m_box_hi[3 * f + 1]);
    hi2 = std::max(hi2, m_box_hi[3 * f + 2]);
  }
  return {{lo0, lo1, lo2}, {hi0, hi1, hi2}, extent_sum};
}

/// Bucket size: the mean box size, grown until the grid has O(n_faces) buckets. The sum may
/// round differently with other thread counts; that moves bucket walls, never the result,
/// which is decided by the exact box test and sorted by face index.
void BroadPhase::size_grid(const JointBox& joint, Index n_faces) {
  m_dims = {0, 0, 0};
  if (n_faces > 0) {
    m_origin = Vec3(joint.lo[0], joint.lo[1], joint.lo[2]);
    m_top = Vec3(joint.hi[0], joint.hi[1], joint.hi[2]);
    const Real span[3] = {joint.hi[0] - joint.lo[0], joint.hi[1] - joint.lo[1],
                          joint.hi[2] - joint.lo[2]};
    m_cell = joint.extent_sum / n_faces;
    const double max_buckets = MAX_BUCKETS_PER_FACE * n_faces + 64.0;
    for (;;) {
      double total = 1.0;
      for (int d = 0; d < 3; ++d) total *= std::max(1.0, std::ceil(span[d] / m_cell));
      if (total <= max_buckets) break;
      m_cell *= std::max(1.01, std::cbrt(total / max_buckets));
    }
    for (int d = 0; d < 3; ++d)
      m_dims[d] = static_cast<Index>(std::max(1.0, std::ceil(span[d] / m_cell)));
  }
}

/// Bucket -> faces by counting sort: faces ascending within each bucket.
void BroadPhase::bin_faces(Index n_faces, std::span<const char> binned) {
  const Index n_cells = m_dims[0] * m_dims[1] * m_dims[2];
  auto for_each_bucket = [&](Index f, auto&& visit) {
    Index a[3], b[3];
    for (int d = 0; d < 3; ++d) {
      a[d] = bucket_coordinate(m_box_lo[3 * f + d], m_origin[d], m_cell, m_dims[d]);
      b[d] = bucket_coordinate(m_box_hi[3 * f + d], m_origin[d], m_cell, m_dims[d]);
    }
    for (Index k = a[2]; k <= b[2]; ++k)
      for (Index j = a[1]; j <= b[1]; ++j)
        for (Index i = a[0]; i <= b[0]; ++i) visit(i + m_dims[0] * (j + m_dims[1] * k));
  };
  const auto skip = [&](Index f) { return !binned.empty() && binned[f] == 0; };
  m_cell_offsets.assign(static_cast<std::size_t>(n_cells) + 1, 0);
  for (Index f = 0; f < n_faces; ++f)
    if (!skip(f)) for_each_bucket(f, [&](Index c) { ++m_cell_offsets[c + 1]; });
  for (Index c = 0; c < n_cells; ++c) m_cell_offsets[c + 1] += m_cell_offsets[c];
  m_cell_faces.resize(static_cast<std::size_t>(m_cell_offsets[n_cells]));
  m_cell_fill.assign(m_cell_offsets.begin(), m_cell_offsets.end() - 1);
  for (Index f = 0; f < n_faces; ++f)
    if (!skip(f)) for_each_bucket(f, [&](Index c) { m_cell_faces[m_cell_fill[c]++] = f; });
}

/// Candidates: count per slave node, prefix sum, fill (both passes parallel, no races).
void BroadPhase::find_candidates(std::span<const ContactFace> faces,
                                 std::span<const Index> slave_nodes, const NodalVectors& position,
                                 std::span<const char> scanned) {
  const auto n_slave = static_cast<Index>(slave_nodes.size());
  m_offsets.resize(static_cast<std::size_t>(n_slave) + 1);
  m_offsets[0] = 0;
  ParallelErrors count_errors;
#pragma omp parallel for schedule(dynamic, 256)
  for (Index s = 0; s < n_slave; ++s)
    count_errors.guard(ParallelSite::BroadPhase, s, [&] {
      const Index n = slave_nodes[s];
      m_offsets[s + 1] = !scanned.empty() && scanned[s] == 0
                             ? 0
                             : scan_bucket(n, Vec3(position(n, 0), position(n, 1), position(n, 2)),
                                           faces, nullptr);
    });
  count_errors.rethrow_if_any();
  for (Index s = 0; s < n_slave; ++s) m_offsets[s + 1] += m_offsets[s];
  m_candidates.resize(static_cast<std::size_t>(m_offsets[n_slave]));
  ParallelErrors fill_errors;
#pragma omp parallel for schedule(dynamic, 256)
  for (Index s = 0; s < n_slave; ++s)
    fill_errors.guard(ParallelSite::BroadPhase, s, [&] {
      if (m_offsets[s + 1] == m_offsets[s]) return;  // none, or not scanned
      const Index n = slave_nodes[s];
      scan_bucket(n, Vec3(position(n, 0), position(n, 1), position(n, 2)), faces,
                  m_candidates.data() + m_offsets[s]);
    });
  fill_errors.rethrow_if_any();
}

/// Nodes to watch: every face corner and every slave node, ascending.
void BroadPhase::track_nodes(std::span<const ContactFace> faces, std::span<const Index> slave_nodes,
                             const NodalVectors& position) {
  const auto n_nodes = static_cast<Index>(position.rows());
  m_is_tracked.assign(static_cast<std::size_t>(n_nodes), 0);
  for (const ContactFace& f : faces)
    for (Index n : f.nodes) m_is_tracked[n] = 1;
  for (Index n : slave_nodes) m_is_tracked[n] = 1;
  m_tracked.clear();
  for (Index n = 0; n < n_nodes; ++n)
    if (m_is_tracked[n]) m_tracked.push_back(n);
  m_tracked_position.resize(3 * m_tracked.size());
  for (std::size_t i = 0; i < m_tracked.size(); ++i)
    for (int d = 0; d < 3; ++d) m_tracked_position[3 * i + d] = position(m_tracked[i], d);
  m_step_position = m_tracked_position;
}

Index BroadPhase::scan_bucket(Index node, const Vec3& p, std::span<const ContactFace> faces,
                              Index* out) const {
  if (m_cell_offsets.size() < 2) return 0;
  // Outside the joint box, outside every box. The exact joint box, not the grid's extent
  // (rounded): every box holding `p` is then found in its bucket whatever the grid (the
  // bucket coordinates are monotonic in x and clamped), so the candidates do not depend on
  // which faces were binned (build()).
  Index cell[3];
  for (int d = 0; d < 3; ++d) {
    if (p[d] < m_origin[d] || p[d] > m_top[d]) return 0;
    cell[d] = bucket_coordinate(p[d], m_origin[d], m_cell, m_dims[d]);
  }
  const Index c = cell[0] + m_dims[0] * (cell[1] + m_dims[1] * cell[2]);
  Index count = 0;
  for (Index k = m_cell_offsets[c]; k < m_cell_offsets[c + 1]; ++k) {
    const Index f = m_cell_faces[k];
    bool inside = true;
    for (int d = 0; d < 3 && inside; ++d)
      inside = p[d] >= m_box_lo[3 * f + d] && p[d] <= m_box_hi[3 * f + d];
    if (!inside) continue;
    const auto& fn = faces[f].nodes;
    if (fn[0] == node || fn[1] == node || fn[2] == node || fn[3] == node) continue;
    if (out) out[count] = f;
    ++count;
  }
  return count;
}

bool BroadPhase::needs_rebuild(const NodalVectors& position) const {
  if (m_builds == 0) return true;
  return exceeds_rebuild_motion(largest_motion_sq(position));
}

Real BroadPhase::largest_motion_sq(const NodalVectors& position,
                                   std::span<const char> node_mask) const {
  return walk_motions<true, false>(m_tracked, m_tracked_position, nullptr, position, node_mask)
      .first;
}

Real BroadPhase::step_motion_sq(const NodalVectors& position, std::span<const char> node_mask) {
  return walk_motions<false, true>(m_tracked, m_tracked_position, &m_step_position, position,
                                   node_mask)
      .second;
}

Real BroadPhase::motions_sq(const NodalVectors& position, std::span<const char> node_mask,
                            Real& step_sq) {
  const auto [largest, step] = walk_motions<true, true>(m_tracked, m_tracked_position,
                                                        &m_step_position, position, node_mask);
  step_sq = step;
  return largest;
}

}  // namespace xpl::contact
