#include "contact/contact_clearance.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <unordered_map>
#include <utility>

#include "common/parallel_error.hpp"
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

/// Key of a face in the engine's face list: (element, face number).
std::uint64_t face_key(Index element, std::uint8_t face) {
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

/// The clearance pass's moves: every free record off its target moves along the normal of
/// its face by w·(h* − h), until the largest residual stops halving.
class ClearanceMoves final : public AdjustmentMoves {
 public:
  explicit ClearanceMoves(Clearance& pass)
      : m(pass), m_moving(pass.records.size(), 0), m_move(3 * pass.records.size(), 0.0) {}

  void begin_round(int /*round*/) override { m_worst_of_pass.clear(); }

  bool pass(int pass) override {
    const auto n_records = static_cast<Index>(m.records.size());
    bool any = false;
    Real worst = 0.0;
    ParallelErrors errors;
#pragma omp parallel for schedule(static) reduction(|| : any) reduction(max : worst)
    for (Index k = 0; k < n_records; ++k)
      errors.guard(ParallelSite::Clearance, k, [&] {
        const Record& r = m.records[k];
        m_moving[k] = 0;
        if (!r.adjust || r.held) return;
        Vec3 normal;
        const Real delta = m.residual(r, normal);
        if (std::abs(delta) <= r.tolerance) return;
        m_moving[k] = 1;
        any = true;
        worst = std::max(worst, std::abs(delta));
        for (int d = 0; d < 3; ++d) m_move[3 * k + d] = delta * normal[d];
      });
    errors.rethrow_if_any();
    if (!any) return false;
    m_worst_of_pass.push_back(worst);
    if (pass >= 1 && worst > CLEARANCE_CONVERGENCE_RATIO * m_worst_of_pass[pass - 1]) return false;
    for (Index k = 0; k < n_records; ++k) {
      if (!m_moving[k]) continue;
      const Record& r = m.records[k];
      Real w = 1.0;
      for (Index c : m.faces[r.face].nodes) {
        const Index cs = m.slaves.slot(c);
        if (cs != NO_INDEX && m.record_of[cs] != NO_INDEX && m_moving[m.record_of[cs]]) w = 0.5;
      }
      const std::uint8_t lock = m.node_lock.empty() ? 0 : m.node_lock[r.node];
      for (int d = 0; d < 3; ++d)
        if (((lock >> d) & 1u) == 0) m.position(r.node, d) += w * m_move[3 * k + d];
    }
    return true;
  }

  void hold(Index node) override {
    const Index s = m.slaves.slot(node);
    if (s == NO_INDEX || m.record_of[s] == NO_INDEX) return;
    Record& r = m.records[m.record_of[s]];
    if (r.held) return;
    r.held = true;
    r.reason = OffsetReason::Distortion;
  }

 private:
  Clearance& m;
  std::vector<char> m_moving;
  std::vector<Real> m_move;
  std::vector<Real> m_worst_of_pass;
};

/// 2. Adjustment passes (Jacobi) with the distortion check, then the report of every record.
void Clearance::adjust(const ElementTopology& topology, ClearanceReport& report) {
  const bool any_adjust = std::any_of(records.begin(), records.end(),
                                      [](const Record& r) { return r.adjust && !r.held; });
  if (!any_adjust) {
    for (const Record& r : records)
      report.nodes.push_back(
          {r.node, r.view, r.face, r.clearance, r.gap_before, 0.0, Vec3::Zero(), 0.0, r.reason});
    return;
  }
  const NodalVectors original = position;
  std::vector<Index> movable;
  for (const Record& r : records) movable.push_back(r.node);
  ClearanceMoves moves(*this);
  AdjustmentOutcome outcome =
      run_adjustment(topology, original, position, movable, MAX_ADJUSTMENT_PASSES, moves);
  report.passes = outcome.passes;
  report.refused_elements = std::move(outcome.refused_elements);
  report.quality_before = outcome.quality_before;
  report.quality_after = outcome.quality_after;
  for (const Record& r : records) {
    const Vec3 delta = node_point(position, r.node) - node_point(original, r.node);
    const Real distance = delta.norm();
    const Vec3 direction = distance > 0.0 ? Vec3(delta / distance) : Vec3::Zero();
    report.nodes.push_back(
        {r.node, r.view, r.face, r.clearance, r.gap_before, distance, direction, 0.0, r.reason});
  }
}

/// 3. Permanent offsets: the violation that remains, along the node's side; the search is
/// widened for offsets that move a contact surface out.
void Clearance::store_offsets(ClearanceReport& report, std::span<const ClearanceView> views) {
  Real widest = 0.0;
  for (Index k = 0; k < static_cast<Index>(records.size()); ++k) {
    const Record& r = records[k];
    Vec3 normal;
    const Real delta = residual(r, normal);
    ContactConstraint& constraint = engine.constraints()[r.slot];
    if (r.interference) {
      // The overclosure reached, d = σ·δ − target gap (δ = h* − h); what the ramp removes and
      // what stays (file comment).
      const Real reached = r.sigma * delta - r.target_gap;
      const bool at_target = std::abs(delta) <= r.tolerance;
      const Real amount =
          at_target || std::isnan(views[r.view].interference_distance) ? reached : -r.target_gap;
      const Real base = reached - amount;
      engine.set_interference(r.slot, std::max(amount, 0.0), base, views[r.view].ramp_time);
      report.nodes[k].interference = std::max(amount, 0.0);
      report.nodes[k].offset = base;
      if (base != 0.0 && r.adjust && !r.held) report.nodes[k].reason = OffsetReason::Conflict;
      widest = std::max(widest, -base);
      continue;
    }
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
  const Index n_slave = engine.domain().slaves().size();
  report.handled.assign(static_cast<std::size_t>(n_slave), 0);
  if (views.empty() || n_slave == 0) return report;
  Clearance pass(engine, position, node_thickness, node_lock, adjust_allowed);
  for (Index v = 0; v < static_cast<Index>(views.size()); ++v)
    pass.collect_view(views[v], v, report);
  pass.adjust(topology, report);
  pass.store_offsets(report, views);
  report.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return report;
}

}  // namespace xpl::contact
