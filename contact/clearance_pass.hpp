#pragma once
/// \file The clearance pass's shared state (contact_clearance.hpp tells what the pass does):
/// the records of slave nodes with their clearances, the height of a node above a face, and
/// the `Clearance` pass, one stage a file: collecting the records of each view
/// (clearance_records.cpp), moving the nodes and storing the offsets that remain
/// (clearance_moves.cpp). Internal to contact/.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <unordered_map>
#include <vector>

#include "contact/broad_phase.hpp"
#include "contact/closest_point.hpp"
#include "contact/contact_clearance.hpp"

namespace xpl::contact::clearance {

inline std::uint64_t edge_key(Index a, Index b) {
  const auto lo = static_cast<std::uint64_t>(std::min(a, b));
  const auto hi = static_cast<std::uint64_t>(std::max(a, b));
  return (hi << 32) | lo;
}

/// One slave node with its clearance, as the passes see it.
struct Record {
  Index slot = NO_INDEX;
  Index node = NO_INDEX;
  Index view = NO_INDEX;
  Index face = NO_INDEX;  ///< engine face
  Real clearance = 0.0;
  Real sigma = 1.0;       ///< side: +1 above the surface, −1 below (c < 0)
  Real slave_half = 0.0;  ///< half thickness of a shell slave node, m
  Real tolerance = 0.0;   ///< m
  Real gap_before = 0.0;  ///< g as read
  /// The gap wanted above the contact surface on the node's side, m: |c| for a clearance,
  /// −h for an interference distance h.
  Real target_gap = 0.0;
  bool interference = false;  ///< an interference fit (file comment)
  bool adjust = true;         ///< the node is meant to move
  bool held = false;          ///< it cannot move
  OffsetReason reason = OffsetReason::Conflict;
};

/// Height h of `p` above face `face` along its normal at the closest point, the half
/// thickness of a shell master there, and the normal.
struct Height {
  Real h = 0.0;
  Real master_half = 0.0;
  Vec3 normal = Vec3::UnitZ();
  ClosestPoint cp;
};

inline Height height_above(const ContactFace& face, const NodalVectors& position,
                           std::span<const Real> thickness, const Vec3& p) {
  Vec3 corner[4];
  face_corners(face, position, {}, corner);  // the solid face, or the shell's mid-surface
  Height out;
  out.cp = closest_point_on_quad(corner, p);
  out.h = out.cp.gap;
  out.normal = out.cp.normal;
  if (face.shell)
    for (int a = 0; a < 4; ++a)
      out.master_half += 0.5 * out.cp.weights[a] * node_thickness_of(thickness, face.nodes[a]);
  return out;
}

/// Key of a face in the engine's face list: (element, face number).
inline std::uint64_t face_key(Index element, std::uint8_t face) {
  return static_cast<std::uint64_t>(element) * 8 + face;
}

/// What the stages of one clearance pass share: the engine and the configuration, the facet
/// sizes, the engine face of every (element, face), and the records.
class Clearance {
 public:
  Clearance(ContactEngine& engine, NodalVectors& position, std::span<const Real> node_thickness,
            std::span<const std::uint8_t> node_lock, bool adjust_allowed)
      : engine(engine),
        position(position),
        node_thickness(node_thickness),
        node_lock(node_lock),
        adjust_allowed(adjust_allowed),
        record_of(static_cast<std::size_t>(slaves.size()), NO_INDEX) {
    for (Index f = 0; f < static_cast<Index>(faces.size()); ++f)
      face_index.emplace(face_key(faces[f].element, faces[f].face), f);
    engine.probe(position, node_thickness);  // node normals and areas for the facet sizes
    size = slave_facet_sizes(engine, position);
  }

  void collect_view(const ClearanceView& view, Index v, ClearanceReport& report);
  /// Remaining move h* − h of record `r` at the current positions, with the normal it acts
  /// along.
  Real residual(const Record& r, Vec3& normal) const {
    const Height hf =
        height_above(faces[r.face], position, node_thickness, node_point(position, r.node));
    normal = hf.normal;
    const Real target = r.sigma * (r.target_gap + hf.master_half + r.slave_half);
    return target - hf.h;
  }
  void adjust(const ElementTopology& topology, ClearanceReport& report);
  void store_offsets(ClearanceReport& report, std::span<const ClearanceView> views);

  ContactEngine& engine;
  const ContactDomain& domain = engine.domain();
  const SlaveNodes& slaves = domain.slaves();
  const std::vector<ContactFace>& faces = domain.faces();
  NodalVectors& position;
  std::span<const Real> node_thickness;
  std::span<const std::uint8_t> node_lock;
  bool adjust_allowed;
  std::unordered_map<std::uint64_t, Index> face_index;  // (element, face) → engine face
  std::vector<Real> size;                               // facet size per slave slot, m
  std::vector<Record> records;
  std::vector<Index> record_of;  // per slave slot: its record, NO_INDEX when none

 private:
  /// Facet size (m) of engine face f on the configuration as read.
  Real face_size(Index f) const {
    Vec3 corner[4];
    face_corners(faces[f], position, {}, corner);
    return std::sqrt(quad_area(corner));
  }
  /// Facet size (m) at slave slot s against master face f: the mean size of the faces around
  /// it, or for a point node (no face of its own, SPEC C13) the size of f (file comment).
  Real facet(Index s, Index f) const { return slaves.point(s) ? face_size(f) : size[s]; }
  /// Search zone (m) of slave `node` in `view`, with facet size `facet`: how far above and
  /// below the surface.
  void zone(const ClearanceView& view, Index node, Real facet, Real& above, Real& below) const {
    const Index s = slaves.slot(node);
    const Real zone_default = domain.slave_double_sided(s) ? node_thickness_of(node_thickness, node)
                                                           : DEFAULT_ZONE_FRACTION * facet;
    above = std::isnan(view.search_above) ? zone_default : view.search_above;
    below = std::isnan(view.search_below) ? zone_default : view.search_below;
  }
  std::vector<Index> master_faces(const ClearanceView& view, Index v,
                                  ClearanceReport& report) const;
  std::vector<Index> slave_nodes(const ClearanceView& view) const;
  void record_node(const ClearanceView& view, Index v, Index k, Index node,
                   std::span<const Index> master, const BroadPhase& near,
                   std::unordered_map<std::uint64_t, int>& edge_count, ClearanceReport& report);
  Index nearest_master_face(Index node, Index k, std::span<const Index> master,
                            const BroadPhase& near, Height& best_height) const;
  bool on_perimeter(Real facet, const Vec3& p, const ContactFace& bf, const ClosestPoint& cp,
                    std::unordered_map<std::uint64_t, int>& edge_count) const;
};

}  // namespace xpl::contact::clearance
