#include "contact/contact_clearance.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <unordered_map>

#include "contact/broad_phase.hpp"
#include "contact/closest_point.hpp"

namespace xpl::contact {

namespace {

using Clock = std::chrono::steady_clock;

std::uint64_t edge_key(Index a, Index b) {
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
  bool adjust = true;     ///< the node is meant to move
  bool held = false;      ///< it cannot move
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

Height height_above(const ContactFace& face, const NodalVectors& position,
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

}  // namespace

const char* clearance_skip_name(ClearanceSkip why) {
  switch (why) {
    case ClearanceSkip::NoValue:
      return "no clearance value at the node or at every corner of its master face";
    case ClearanceSkip::PerimeterEdge:
      return "closest point on a perimeter edge of the master surface";
    case ClearanceSkip::WrongSide:
      return "ADJUST=NO and the node lies on the other side of the shell";
    case ClearanceSkip::NotInDomain:
      return "the contact domain does not let it touch the master surface";
    case ClearanceSkip::Repeated:
      return "an earlier assignment already gave it a clearance";
  }
  return "?";
}

ClearanceReport apply_clearances(ContactEngine& engine, const ElementTopology& topology,
                                 NodalVectors& position, std::span<const Real> node_thickness,
                                 std::span<const std::uint8_t> node_lock,
                                 std::span<const ClearanceView> views, bool adjust_allowed) {
  const auto start = Clock::now();
  ClearanceReport report;
  const ContactDomain& domain = engine.domain();
  const SlaveNodes& slaves = domain.slaves();
  const std::vector<ContactFace>& faces = domain.faces();
  const Index n_slave = slaves.size();
  report.handled.assign(static_cast<std::size_t>(n_slave), 0);
  if (views.empty() || n_slave == 0) return report;

  std::unordered_map<std::uint64_t, Index> face_index;  // (element, face) → engine face
  for (Index f = 0; f < static_cast<Index>(faces.size()); ++f)
    face_index.emplace(static_cast<std::uint64_t>(faces[f].element) * 8 + faces[f].face, f);
  engine.probe(position, node_thickness);  // node normals and areas for the facet sizes
  const std::vector<Real> size = slave_facet_sizes(engine, position);

  // 1. Records: every slave node in a view's search zone, with its nearest master face.
  std::vector<Record> records;
  std::vector<Index> record_of(static_cast<std::size_t>(n_slave), NO_INDEX);
  for (Index v = 0; v < static_cast<Index>(views.size()); ++v) {
    const ClearanceView& view = views[v];
    std::vector<Index> master;
    for (const FaceRef& r : view.master_faces) {
      const auto it = face_index.find(static_cast<std::uint64_t>(r.element) * 8 + r.face);
      if (it == face_index.end())
        report.faces_outside_domain.push_back(v);
      else
        master.push_back(it->second);
    }
    std::sort(master.begin(), master.end());
    master.erase(std::unique(master.begin(), master.end()), master.end());
    // Perimeter of the master surface: edges of one face, and their corners.
    std::unordered_map<std::uint64_t, int> edge_count;
    for (Index f : master)
      for (int a = 0; a < 4; ++a)
        ++edge_count[edge_key(faces[f].nodes[a], faces[f].nodes[(a + 1) % 4])];
    std::vector<Index> slave_nodes;
    for (const FaceRef& r : view.slave_faces) {
      const auto it = face_index.find(static_cast<std::uint64_t>(r.element) * 8 + r.face);
      if (it == face_index.end()) continue;
      for (Index node : faces[it->second].nodes) slave_nodes.push_back(node);
    }
    std::sort(slave_nodes.begin(), slave_nodes.end());
    slave_nodes.erase(std::unique(slave_nodes.begin(), slave_nodes.end()), slave_nodes.end());

    // Search zone of each slave node; candidates from a broad phase over the master faces
    // whose margin covers the widest zone plus the shell half thicknesses (a face whose
    // mid-surface is farther away cannot put the node in its zone).
    auto zone = [&](Index node, Real& above, Real& below) {
      const Index s = slaves.slot(node);
      const Real zone_default = domain.slave_double_sided(s)
                                    ? node_thickness_of(node_thickness, node)
                                    : DEFAULT_ZONE_FRACTION * size[s];
      above = std::isnan(view.search_above) ? zone_default : view.search_above;
      below = std::isnan(view.search_below) ? zone_default : view.search_below;
    };
    slave_nodes.erase(std::remove_if(slave_nodes.begin(), slave_nodes.end(),
                                     [&](Index node) {
                                       const Index s = slaves.slot(node);
                                       return s == NO_INDEX || domain.slave_rigid(s);
                                     }),
                      slave_nodes.end());
    if (master.empty() || slave_nodes.empty()) continue;
    Real reach = 0.0, thickest = 0.0;
    for (Index node : slave_nodes) {
      Real above = 0.0, below = 0.0;
      zone(node, above, below);
      reach = std::max({reach, above, below});
      thickest = std::max(thickest, node_thickness_of(node_thickness, node));
    }
    std::vector<ContactFace> master_faces;
    for (Index f : master) {
      master_faces.push_back(faces[f]);
      for (Index c : faces[f].nodes)
        thickest = std::max(thickest, node_thickness_of(node_thickness, c));
    }
    const Real margin = reach + thickest;
    BroadPhase near(margin > 0.0 ? margin : 1e-300);
    near.build(master_faces, slave_nodes, position, {});

    for (Index k = 0; k < static_cast<Index>(slave_nodes.size()); ++k) {
      const Index node = slave_nodes[k];
      const Index s = slaves.slot(node);
      const Vec3 p = node_point(position, node);
      const Real slave_half =
          domain.slave_double_sided(s) ? 0.5 * node_thickness_of(node_thickness, node) : 0.0;
      Real above = 0.0, below = 0.0;
      zone(node, above, below);
      // Nearest master face (its contact surface: solid face or shell mid-surface).
      Index best = NO_INDEX;
      Height best_height;
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
      if (best == NO_INDEX) continue;
      const Real gap = best_height.h - best_height.master_half - slave_half;
      if (gap > above || gap < -below) continue;  // outside the search zone
      auto skip = [&](ClearanceSkip why) { report.skipped.push_back({node, v, why}); };
      const ClosestPoint& cp = best_height.cp;
      const ContactFace& bf = faces[best];
      // Beside the surface: the closest point is on a perimeter edge or corner and the node
      // lies beyond it (a node right above the edge, as the edge nodes of two matching
      // meshes do, still projects onto the surface).
      Real lateral = 0.0;
      if (cp.region != QuadRegion::Interior) {
        Vec3 corner[4];
        face_corners(bf, position, {}, corner);
        const Vec3 n_face = quad_normal(corner, cp.xi, cp.eta);
        const Vec3 offset = p - cp.point;
        lateral = (offset - offset.dot(n_face) * n_face).norm();
      }
      const bool beside = lateral > PERIMETER_TOLERANCE * size[s];
      if (beside && cp.region == QuadRegion::Edge &&
          edge_count[edge_key(bf.nodes[cp.feature], bf.nodes[(cp.feature + 1) % 4])] == 1) {
        skip(ClearanceSkip::PerimeterEdge);
        continue;
      }
      if (beside && cp.region == QuadRegion::Corner) {
        const Index c = bf.nodes[cp.feature];
        bool perimeter = false;
        for (int a = 0; a < 4; ++a)
          if (bf.nodes[a] == c)
            perimeter = edge_count[edge_key(c, bf.nodes[(a + 1) % 4])] == 1 ||
                        edge_count[edge_key(c, bf.nodes[(a + 3) % 4])] == 1;
        if (perimeter) {
          skip(ClearanceSkip::PerimeterEdge);
          continue;
        }
      }
      Index pair = NO_INDEX;
      if (domain.weight(s, best, pair) == 0.0) {
        skip(ClearanceSkip::NotInDomain);
        continue;
      }
      Real c = view.value;
      if (!view.nodal_values.empty()) {
        c = view.nodal_values[node];
        if (std::isnan(c)) {
          c = 0.0;
          for (int a = 0; a < 4; ++a) c += cp.weights[a] * view.nodal_values[bf.nodes[a]];
        }
        if (std::isnan(c)) {
          skip(ClearanceSkip::NoValue);
          continue;
        }
      }
      const Real sigma = c < 0.0 && bf.shell ? -1.0 : 1.0;
      const bool adjust = view.adjust && adjust_allowed;
      if (!adjust && bf.shell && sigma * best_height.h < 0.0) {
        skip(ClearanceSkip::WrongSide);
        continue;
      }
      if (record_of[s] != NO_INDEX) {
        skip(ClearanceSkip::Repeated);
        continue;
      }
      Record r;
      r.slot = s;
      r.node = node;
      r.view = v;
      r.face = best;
      r.clearance = c;
      r.sigma = sigma;
      r.slave_half = slave_half;
      r.tolerance = OVERCLOSURE_TOLERANCE * size[s];
      r.gap_before = gap;
      r.adjust = adjust;
      const std::uint8_t lock = node_lock.empty() ? 0 : node_lock[node];
      if ((lock & LOCK_RIGID) != 0) {
        r.held = true;
        r.reason = OffsetReason::Rigid;
      }
      for (int d = 0; d < 3 && !r.held; ++d)
        if (((lock >> d) & 1u) != 0 && std::abs(best_height.normal[d]) > LOCK_COMPONENT) {
          r.held = true;
          r.reason = OffsetReason::Boundary;
        }
      record_of[s] = static_cast<Index>(records.size());
      records.push_back(r);
      report.handled[s] = 1;
    }
  }
  const auto n_records = static_cast<Index>(records.size());

  // Remaining move h* − h of record k at `position`, with the normal it acts along.
  auto residual = [&](const Record& r, Vec3& normal) {
    const Height hf =
        height_above(faces[r.face], position, node_thickness, node_point(position, r.node));
    normal = hf.normal;
    const Real target = r.sigma * (std::abs(r.clearance) + hf.master_half + r.slave_half);
    return target - hf.h;
  };

  // 2. Adjustment passes (Jacobi), rounds restarting after a refused distortion.
  const bool any_adjust = std::any_of(records.begin(), records.end(),
                                      [](const Record& r) { return r.adjust && !r.held; });
  if (any_adjust) {
    const NodalVectors original = position;
    std::vector<char> moving(records.size(), 0);
    std::vector<Real> move(3 * records.size(), 0.0);
    for (int round = 0; round < MAX_ADJUSTMENT_ROUNDS; ++round) {
      if (round > 0) position = original;
      report.passes = 0;
      std::vector<Real> worst_of_pass;
      for (int pass = 0; pass < MAX_ADJUSTMENT_PASSES; ++pass) {
        bool any = false;
        Real worst = 0.0;
#pragma omp parallel for schedule(static) reduction(|| : any) reduction(max : worst)
        for (Index k = 0; k < n_records; ++k) {
          const Record& r = records[k];
          moving[k] = 0;
          if (!r.adjust || r.held) continue;
          Vec3 normal;
          const Real delta = residual(r, normal);
          if (std::abs(delta) <= r.tolerance) continue;
          moving[k] = 1;
          any = true;
          worst = std::max(worst, std::abs(delta));
          for (int d = 0; d < 3; ++d) move[3 * k + d] = delta * normal[d];
        }
        if (!any) break;
        worst_of_pass.push_back(worst);
        if (pass >= 1 && worst > CLEARANCE_CONVERGENCE_RATIO * worst_of_pass[pass - 1]) break;
        ++report.passes;
        for (Index k = 0; k < n_records; ++k) {
          if (!moving[k]) continue;
          const Record& r = records[k];
          Real w = 1.0;
          for (Index c : faces[r.face].nodes) {
            const Index cs = slaves.slot(c);
            if (cs != NO_INDEX && record_of[cs] != NO_INDEX && moving[record_of[cs]]) w = 0.5;
          }
          const std::uint8_t lock = node_lock.empty() ? 0 : node_lock[r.node];
          for (int d = 0; d < 3; ++d)
            if (((lock >> d) & 1u) == 0) position(r.node, d) += w * move[3 * k + d];
        }
      }
      std::vector<char> node_moved(static_cast<std::size_t>(position.rows()), 0);
      for (const Record& r : records)
        if ((position.row(r.node) - original.row(r.node)).squaredNorm() > 0.0)
          node_moved[r.node] = 1;
      const std::vector<Index> refused = distorted_elements(
          topology, original, position, node_moved, report.quality_before, report.quality_after);
      if (refused.empty() || round + 1 == MAX_ADJUSTMENT_ROUNDS) break;
      for (Index e : refused) {
        report.refused_elements.push_back(e);
        for (Index k = topology.offsets[e]; k < topology.offsets[e + 1]; ++k) {
          const Index node = topology.nodes[k];
          const Index s = slaves.slot(node);
          if (s == NO_INDEX || record_of[s] == NO_INDEX || !node_moved[node]) continue;
          Record& r = records[record_of[s]];
          if (r.held) continue;
          r.held = true;
          r.reason = OffsetReason::Distortion;
        }
      }
    }
    for (Index k = 0; k < n_records; ++k) {
      const Record& r = records[k];
      const Vec3 delta = node_point(position, r.node) - node_point(original, r.node);
      const Real distance = delta.norm();
      ClearedNode out{r.node,
                      r.view,
                      r.face,
                      r.clearance,
                      r.gap_before,
                      distance,
                      distance > 0.0 ? Vec3(delta / distance) : Vec3::Zero(),
                      0.0,
                      r.reason};
      report.nodes.push_back(out);
    }
  } else {
    for (const Record& r : records)
      report.nodes.push_back(
          {r.node, r.view, r.face, r.clearance, r.gap_before, 0.0, Vec3::Zero(), 0.0, r.reason});
  }

  // 3. Permanent offsets: the violation that remains, along the node's side.
  Real widest = 0.0;
  for (Index k = 0; k < n_records; ++k) {
    const Record& r = records[k];
    Vec3 normal;
    const Real delta = residual(r, normal);
    ContactConstraint& constraint = engine.constraints()[r.slot];
    if (std::abs(delta) <= r.tolerance) {
      constraint.offset = 0.0;
      constraint.offset_permanent = false;
      continue;
    }
    const Real d0 = r.sigma * delta;
    constraint.offset = d0;
    constraint.offset_permanent = true;
    report.nodes[k].offset = d0;
    if (r.adjust && !r.held) report.nodes[k].reason = OffsetReason::Conflict;
    widest = std::max(widest, -d0);
  }
  engine.widen_search(widest);
  engine.probe(position, node_thickness);
  report.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return report;
}

}  // namespace xpl::contact
