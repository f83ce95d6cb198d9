// Stage 1 of the clearance pass: the records of one view, every slave node in the view's
// search zone with its nearest master face and its clearance, or the reason it is skipped.
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "contact/clearance_pass.hpp"

namespace xpl::contact::clearance {

/// The engine faces of the view's master surface, each once in order; a face outside the
/// contact domain is reported.
std::vector<Index> Clearance::master_faces(const ClearanceView& view, Index v,
                                           ClearanceReport& report) const {
  std::vector<Index> master;
  for (const FaceRef& r : view.master_faces) {
    const auto it = face_index.find(face_key(r.element, r.face));
    if (it == face_index.end())
      report.faces_outside_domain.push_back(v);
    else
      master.push_back(it->second);
  }
  std::sort(master.begin(), master.end());
  master.erase(std::unique(master.begin(), master.end()), master.end());
  return master;
}

/// The nodes of the view's slave surface that may act as (non-rigid) slaves of the domain,
/// each once in order.
std::vector<Index> Clearance::slave_nodes(const ClearanceView& view) const {
  std::vector<Index> nodes;
  for (const FaceRef& r : view.slave_faces) {
    const auto it = face_index.find(face_key(r.element, r.face));
    if (it == face_index.end()) continue;
    for (Index node : faces[it->second].nodes) nodes.push_back(node);
  }
  nodes.insert(nodes.end(), view.slave_nodes.begin(), view.slave_nodes.end());
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  nodes.erase(std::remove_if(nodes.begin(), nodes.end(),
                             [&](Index node) {
                               const Index s = slaves.slot(node);
                               return s == NO_INDEX || domain.slave_rigid(s);
                             }),
              nodes.end());
  return nodes;
}

/// 1. Records of one view: every slave node in the view's search zone, with its nearest master
/// face.
void Clearance::collect_view(const ClearanceView& view, Index v, ClearanceReport& report) {
  const std::vector<Index> master = master_faces(view, v, report);
  // Perimeter of the master surface: edges of one face, and their corners.
  std::unordered_map<std::uint64_t, int> edge_count;
  for (Index f : master)
    for (int a = 0; a < 4; ++a)
      ++edge_count[edge_key(faces[f].nodes[a], faces[f].nodes[(a + 1) % 4])];
  const std::vector<Index> nodes = slave_nodes(view);
  if (master.empty() || nodes.empty()) return;
  // An interference pair is not adjusted by the automatic pass (file comment): none of its
  // slave nodes, recorded or not.
  if (view.interference)
    for (Index node : nodes) report.handled[slaves.slot(node)] = 1;

  // Candidates from a broad phase over the master faces whose margin covers the widest zone
  // plus the shell half thicknesses (a face whose mid-surface is farther away cannot put the
  // node in its zone); a point node's zone is taken with the largest master face.
  Real largest_face = 0.0;
  for (Index f : master) largest_face = std::max(largest_face, face_size(f));
  Real reach = 0.0, thickest = 0.0;
  for (Index node : nodes) {
    const Index s = slaves.slot(node);
    Real above = 0.0, below = 0.0;
    zone(view, node, slaves.point(s) ? largest_face : size[s], above, below);
    reach = std::max({reach, above, below});
    thickest = std::max(thickest, node_thickness_of(node_thickness, node));
  }
  std::vector<ContactFace> near_faces;
  for (Index f : master) {
    near_faces.push_back(faces[f]);
    for (Index c : faces[f].nodes)
      thickest = std::max(thickest, node_thickness_of(node_thickness, c));
  }
  const Real margin = reach + thickest;
  BroadPhase near(margin > 0.0 ? margin : 1e-300);
  near.build(near_faces, nodes, position, {});
  for (Index k = 0; k < static_cast<Index>(nodes.size()); ++k)
    record_node(view, v, k, nodes[k], master, near, edge_count, report);
}

/// Nearest master face of slave `node` (candidate list k of `near`) by its contact surface
/// (solid face or shell mid-surface), with its height; NO_INDEX when none.
Index Clearance::nearest_master_face(Index node, Index k, std::span<const Index> master,
                                     const BroadPhase& near, Height& best_height) const {
  const Vec3 p = node_point(position, node);
  Index best = NO_INDEX;
  Real best_distance = std::numeric_limits<Real>::max();
  for (Index local : near.candidates(k)) {
    const Index f = master[local];
    if (std::find(faces[f].nodes.begin(), faces[f].nodes.end(), node) != faces[f].nodes.end())
      continue;
    const Height hf = height_above(faces[f], position, node_thickness, p);
    if (hf.cp.distance < best_distance) {
      best_distance = hf.cp.distance;
      best = f;
      best_height = hf;
    }
  }
  return best;
}

/// Whether the node of slot s at `p` lies beside the master surface: its closest point `cp` on
/// face `bf` is on a perimeter edge or corner and the node lies beyond it (a node right above
/// the edge, as the edge nodes of two matching meshes do, still projects onto the surface).
bool Clearance::on_perimeter(Real facet, const Vec3& p, const ContactFace& bf,
                             const ClosestPoint& cp,
                             std::unordered_map<std::uint64_t, int>& edge_count) const {
  Real lateral = 0.0;
  if (cp.region != QuadRegion::Interior) {
    Vec3 corner[4];
    face_corners(bf, position, {}, corner);
    const Vec3 n_face = quad_normal(corner, cp.xi, cp.eta);
    const Vec3 offset = p - cp.point;
    lateral = (offset - offset.dot(n_face) * n_face).norm();
  }
  const bool beside = lateral > PERIMETER_TOLERANCE * facet;
  if (beside && cp.region == QuadRegion::Edge &&
      edge_count[edge_key(bf.nodes[cp.feature], bf.nodes[(cp.feature + 1) % 4])] == 1)
    return true;
  if (beside && cp.region == QuadRegion::Corner) {
    const Index c = bf.nodes[cp.feature];
    bool perimeter = false;
    for (int a = 0; a < 4; ++a)
      if (bf.nodes[a] == c)
        perimeter = edge_count[edge_key(c, bf.nodes[(a + 1) % 4])] == 1 ||
                    edge_count[edge_key(c, bf.nodes[(a + 3) % 4])] == 1;
    if (perimeter) return true;
  }
  return false;
}

/// The record of slave `node` (candidate list k of `near`) in view v, when it is in the search
/// zone and gets a clearance; otherwise the reason it is skipped goes to the report.
void Clearance::record_node(const ClearanceView& view, Index v, Index k, Index node,
                            std::span<const Index> master, const BroadPhase& near,
                            std::unordered_map<std::uint64_t, int>& edge_count,
                            ClearanceReport& report) {
  const Index s = slaves.slot(node);
  const Vec3 p = node_point(position, node);
  const Real slave_half =
      domain.slave_double_sided(s) ? 0.5 * node_thickness_of(node_thickness, node) : 0.0;
  Height best_height;
  const Index best = nearest_master_face(node, k, master, near, best_height);
  if (best == NO_INDEX) return;
  const Real facet_size = facet(s, best);
  Real above = 0.0, below = 0.0;
  zone(view, node, facet_size, above, below);
  const Real gap = best_height.h - best_height.master_half - slave_half;
  if (gap > above || gap < -below) return;  // outside the search zone
  auto skip = [&](ClearanceSkip why) { report.skipped.push_back({node, v, why}); };
  // A record joins the pass held where the node's DOFs are locked along the normal.
  auto add_record = [&](Record r) {
    const std::uint8_t lock = node_lock.empty() ? 0 : node_lock[node];
    if (const std::optional<OffsetReason> locked = lock_reason(lock, best_height.normal)) {
      r.held = true;
      r.reason = *locked;
    }
    record_of[s] = static_cast<Index>(records.size());
    records.push_back(r);
    report.handled[s] = 1;
  };
  const ClosestPoint& cp = best_height.cp;
  const ContactFace& bf = faces[best];
  // An overclosed node of an interference fit is resolved wherever it projects: on the rim of
  // a slice (nodes of two matching meshes at the free faces) it is as overclosed as inside.
  if (!view.interference && on_perimeter(facet_size, p, bf, cp, edge_count))
    return skip(ClearanceSkip::PerimeterEdge);
  Index pair = NO_INDEX;
  if (domain.weight(s, best, pair) == 0.0) return skip(ClearanceSkip::NotInDomain);
  if (view.interference) {
    const bool distance = !std::isnan(view.interference_distance);
    if (!distance && !(gap < 0.0)) return;  // not overclosed: nothing to resolve
    if (record_of[s] != NO_INDEX) return skip(ClearanceSkip::Repeated);
    const Real side = bf.shell && best_height.h < 0.0 ? -1.0 : 1.0;
    Record r{s, node, v, best, 0.0, side, slave_half, OVERCLOSURE_TOLERANCE * facet_size, gap};
    r.target_gap = distance ? -view.interference_distance : -gap;
    r.interference = true;
    r.adjust = distance && view.adjust && adjust_allowed;
    add_record(r);
    return;
  }
  Real c = view.value;
  if (!view.nodal_values.empty()) {
    c = view.nodal_values[node];
    if (std::isnan(c)) {
      c = 0.0;
      for (int a = 0; a < 4; ++a) c += cp.weights[a] * view.nodal_values[bf.nodes[a]];
    }
    if (std::isnan(c)) return skip(ClearanceSkip::NoValue);
  }
  const Real sigma = c < 0.0 && bf.shell ? -1.0 : 1.0;
  const bool adjust = view.adjust && adjust_allowed;
  if (!adjust && bf.shell && sigma * best_height.h < 0.0) return skip(ClearanceSkip::WrongSide);
  if (record_of[s] != NO_INDEX) return skip(ClearanceSkip::Repeated);
  Record r{s,   node,        v,     best,  c, sigma, slave_half, OVERCLOSURE_TOLERANCE * facet_size,
           gap, std::abs(c), false, adjust};
  add_record(r);
}

}  // namespace xpl::contact::clearance
