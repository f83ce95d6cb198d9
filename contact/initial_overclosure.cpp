#include "contact/initial_overclosure.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "common/parallel_error.hpp"
#include "contact/closest_point.hpp"
#include "contact/surface_corners.hpp"

namespace xpl::contact {

namespace {

using Clock = std::chrono::steady_clock;

enum class Role : std::uint8_t { Free, Ignored, Held };

/// Whether segment p→q meets triangle (a, b, c) (Möller–Trumbore, closed triangle).
bool segment_meets_triangle(const Vec3& p, const Vec3& q, const Vec3& a, const Vec3& b,
                            const Vec3& c) {
  constexpr Real EPS = 1e-12;
  const Vec3 d = q - p, e1 = b - a, e2 = c - a;
  const Vec3 h = d.cross(e2);
  const Real det = e1.dot(h);
  if (std::abs(det) <= EPS * std::sqrt(d.dot(d) * e1.dot(e1) * e2.dot(e2))) return false;
  const Vec3 s = p - a;
  const Real u = s.dot(h) / det;
  if (u < -EPS || u > 1.0 + EPS) return false;
  const Vec3 qv = s.cross(e1);
  const Real v = d.dot(qv) / det;
  if (v < -EPS || u + v > 1.0 + EPS) return false;
  const Real t = e2.dot(qv) / det;
  return t >= -EPS && t <= 1.0 + EPS;
}

/// What the stages of one overclosure pass share: the engine and the configuration, the facet
/// size around every slave node, and each node's role (with the reason of a held node).
struct Overclosure {
  ContactEngine& engine;
  const ElementTopology& topology;
  NodalVectors& position;
  std::span<const Real> node_thickness;
  std::span<const std::uint8_t> node_lock;
  const OverclosureSettings& settings;
  const ContactDomain& domain = engine.domain();
  const SlaveNodes& slaves = domain.slaves();
  const std::vector<ContactFace>& faces = domain.faces();
  const Index n_slave = slaves.size();
  const std::vector<Real> size = slave_facet_sizes(engine, position);
  std::vector<Role> role = std::vector<Role>(static_cast<std::size_t>(n_slave), Role::Free);
  std::vector<OffsetReason> reason =
      std::vector<OffsetReason>(static_cast<std::size_t>(n_slave), OffsetReason::Conflict);

  /// Facet size (m) next to slave slot s when it touches face f: the mean size of the faces
  /// around it, or for a point node (no face of its own, SPEC C13) the size of f on the
  /// current geometry.
  Real facet(Index s, Index f) const {
    if (!slaves.point(s)) return size[s];
    Vec3 corner[4];
    face_corners(faces[f], position, {}, corner);
    return std::sqrt(quad_area(corner));
  }
  /// Penetration (m) under which slave slot s touching face f counts as on the surface.
  Real tolerance(Index s, Index f) const { return OVERCLOSURE_TOLERANCE * facet(s, f); }
  /// Deepest penetration of slot s below face f that is adjusted, m.
  Real limit(Index s, Index f) const {
    return faces[f].shell ? std::numeric_limits<Real>::max()
                          : settings.depth_fraction * facet(s, f);
  }
  /// Whether slot s (not excluded) penetrates its nearest face of the last search.
  bool penetrates(Index s) const {
    if (!settings.exclude.empty() && settings.exclude[s] != 0) return false;
    const SlaveTouch& t = engine.touch(s);
    return t.face != NO_INDEX && t.gap < -tolerance(s, t.face);
  }

  void classify(OverclosureReport& report);
  void adjust(OverclosureReport& report);
  void store_offsets(OverclosureReport& report);
  void find_crossed(OverclosureReport& report) const;
  std::vector<std::pair<Index, Index>> slave_edges() const;
  Index crossed_face(Index p, Index q, const BroadPhase& reach,
                     std::span<const std::uint8_t> corners) const;
};

/// 1. Classification on the mesh as read: ignored, pinched, held or free (header comment).
void Overclosure::classify(OverclosureReport& report) {
  engine.probe(position, node_thickness);
  for (Index s = 0; s < n_slave; ++s) {
    if (!penetrates(s)) continue;
    const SlaveTouch& t = engine.touch(s);
    const Real depth = -t.gap;
    report.max_overclosure = std::max(report.max_overclosure, depth);
    const Index node = slaves.nodes()[s];
    if (!settings.adjust) continue;
    if (depth > limit(s, t.face)) {
      role[s] = Role::Ignored;
      report.ignored.push_back({node, t.face, domain.slave_surface(s, t.face, t.pair),
                                domain.master_surface(s, t.face, t.pair), depth, limit(s, t.face)});
      continue;
    }
    const std::vector<SlaveTouch> all =
        engine.penetrated_faces(s, position, node_thickness, tolerance(s, t.face));
    bool pinched = false;
    for (std::size_t i = 0; i < all.size() && !pinched; ++i)
      for (std::size_t j = i + 1; j < all.size() && !pinched; ++j)
        pinched = all[i].normal.dot(all[j].normal) < PINCH_COSINE;
    const std::uint8_t lock = node_lock.empty() ? 0 : node_lock[node];
    const std::optional<OffsetReason> locked = lock_reason(lock, t.normal);
    if (pinched || locked) {
      role[s] = Role::Held;
      reason[s] = pinched ? OffsetReason::Pinched : *locked;
    }
  }
}

/// The overclosure pass's moves: every free node that penetrates its nearest face (within
/// the depth limit) moves along the contact normal by w·d; the search is repeated on the
/// moved geometry before every pass but the first.
class OverclosureMoves final : public AdjustmentMoves {
  Overclosure& m;  // the pass whose nodes move

 public:
  explicit OverclosureMoves(Overclosure& pass)
      : m(pass),
        first_face(static_cast<std::size_t>(pass.n_slave), NO_INDEX),
        first_pair(first_face.size(), NO_INDEX),
        first_depth(first_face.size(), 0.0),
        m_moving(first_face.size(), 0),
        m_move(3 * first_face.size(), 0.0) {}

  void begin_round(int round) override {
    if (round == 0) return;
    m.engine.probe(m.position, m.node_thickness);
    std::fill(first_face.begin(), first_face.end(), NO_INDEX);
  }

  bool pass(int pass) override {
    if (pass > 0) m.engine.probe(m.position, m.node_thickness);
    bool any = false;
    for (Index s = 0; s < m.n_slave; ++s) {
      m_moving[s] = m.role[s] == Role::Free && m.penetrates(s) &&
                    -m.engine.touch(s).gap <= m.limit(s, m.engine.touch(s).face);
      any = any || m_moving[s];
    }
    if (!any) return false;
    const SlaveNodes& slaves = m.slaves;
    ParallelErrors errors;
#pragma omp parallel for schedule(static)
    for (Index s = 0; s < m.n_slave; ++s)
      errors.guard(ParallelSite::Overclosure, s, [&] {
        if (!m_moving[s]) return;
        const SlaveTouch& t = m.engine.touch(s);
        // Half when the face moves too in this pass (the other view of a balanced pair).
        Real w = 1.0;
        for (Index c : m.faces[t.face].nodes) {
          const Index cs = slaves.slot(c);
          if (cs != NO_INDEX && m_moving[cs]) w = std::min(1.0, t.weight);
        }
        const Vec3 delta = w * (-t.gap) * t.normal;
        // A DOF with a boundary condition does not move at all (its share of the direction is
        // below LOCK_COMPONENT, or the node would be held).
        const std::uint8_t lock = m.node_lock.empty() ? 0 : m.node_lock[slaves.nodes()[s]];
        for (int d = 0; d < 3; ++d) m_move[3 * s + d] = ((lock >> d) & 1u) != 0 ? 0.0 : delta[d];
      });
    errors.rethrow_if_any();
    for (Index s = 0; s < m.n_slave; ++s) {
      if (!m_moving[s]) continue;
      const Index node = slaves.nodes()[s];
      for (int d = 0; d < 3; ++d) m.position(node, d) += m_move[3 * s + d];
      if (first_face[s] == NO_INDEX) {
        const SlaveTouch& t = m.engine.touch(s);
        first_face[s] = t.face;
        first_pair[s] = t.pair;
        first_depth[s] = -t.gap;
      }
    }
    return true;
  }

  void hold(Index node) override {
    const Index s = m.slaves.slot(node);
    if (s == NO_INDEX || m.role[s] != Role::Free) return;
    m.role[s] = Role::Held;
    m.reason[s] = OffsetReason::Distortion;
  }

  /// Per slave slot: the face, pair and depth of the first move of the last round.
  std::vector<Index> first_face, first_pair;
  std::vector<Real> first_depth;

 private:
  std::vector<char> m_moving;
  std::vector<Real> m_move;
};

/// 2.–3. Adjustment passes and the distortion check; the moved nodes go to the report.
void Overclosure::adjust(OverclosureReport& report) {
  const bool anything_to_move =
      settings.adjust &&
      std::any_of(role.begin(), role.end(), [](Role r) { return r == Role::Free; }) &&
      report.max_overclosure > 0.0;
  if (!anything_to_move) return;
  const NodalVectors original = position;
  OverclosureMoves moves(*this);
  AdjustmentOutcome outcome =
      run_adjustment(topology, original, position, slaves.nodes(), settings.max_passes, moves);
  report.passes = outcome.passes;
  report.refused_elements = std::move(outcome.refused_elements);
  report.quality_before = outcome.quality_before;
  report.quality_after = outcome.quality_after;
  if (outcome.moved) engine.probe(position, node_thickness);
  for (Index s = 0; s < n_slave; ++s) {
    const Index node = slaves.nodes()[s];
    const Vec3 delta = node_point(position, node) - node_point(original, node);
    const Real distance = std::sqrt(delta.dot(delta));
    if (!(distance > 0.0)) continue;
    const Index f = moves.first_face[s];
    const Index pair = moves.first_pair[s];
    report.adjusted.push_back({node, f, domain.slave_surface(s, f, pair),
                               domain.master_surface(s, f, pair), moves.first_depth[s], distance,
                               delta / distance});
  }
}

/// 4. Offsets: what still penetrates keeps its penetration as d0, with its reason.
void Overclosure::store_offsets(OverclosureReport& report) {
  for (Index s = 0; s < n_slave; ++s) {
    if (role[s] == Role::Ignored || !penetrates(s)) continue;
    const SlaveTouch& t = engine.touch(s);
    const OffsetReason why = !settings.adjust        ? settings.offset_reason
                             : role[s] == Role::Held ? reason[s]
                                                     : OffsetReason::Conflict;
    engine.constraints()[s].offset = -t.gap;
    report.offsets.push_back({slaves.nodes()[s], t.face, domain.slave_surface(s, t.face, t.pair),
                              domain.master_surface(s, t.face, t.pair), -t.gap, why});
  }
}

/// Facet edges between two slave nodes that are not rigid, each once (lower node first), in
/// order.
std::vector<std::pair<Index, Index>> Overclosure::slave_edges() const {
  std::vector<std::pair<Index, Index>> edges;
  for (const ContactFace& face : faces)
    for (int a = 0; a < 4; ++a) {
      const Index p = face.nodes[a], q = face.nodes[(a + 1) % 4];
      if (domain.slave_rigid(slaves.slot(p)) || domain.slave_rigid(slaves.slot(q))) continue;
      edges.emplace_back(std::min(p, q), std::max(p, q));
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  return edges;
}

/// The first candidate face of node p in `reach` that edge p–q passes through with its two
/// nodes on opposite sides (header comment), or NO_INDEX. `corners`: corner_edges() of the faces.
Index Overclosure::crossed_face(Index p, Index q, const BroadPhase& reach,
                                std::span<const std::uint8_t> corners) const {
  const Index sp = slaves.slot(p), sq = slaves.slot(q);
  const Vec3 xp = node_point(position, p), xq = node_point(position, q);
  const Real tol = OVERCLOSURE_TOLERANCE * (xq - xp).norm();
  for (Index f : reach.candidates(sp)) {
    const ContactFace& face = faces[f];
    if (std::find(face.nodes.begin(), face.nodes.end(), q) != face.nodes.end()) continue;
    Index pair = NO_INDEX;
    if (domain.weight(sp, f, pair) == 0.0 && domain.weight(sq, f, pair) == 0.0) continue;
    Vec3 c[4];
    face_corners(face, position, {}, c);  // mid-surface of a shell
    Vec3 normal = (c[2] - c[0]).cross(c[3] - c[1]);
    const Real length = normal.norm();
    if (!(length > 0.0)) continue;
    normal /= length;
    const Vec3 centre = 0.25 * (c[0] + c[1] + c[2] + c[3]);
    const Real gp = normal.dot(xp - centre), gq = normal.dot(xq - centre);
    if (!((gp > tol && gq < -tol) || (gp < -tol && gq > tol))) continue;
    if (!face.shell) {
      // A node within the depth limit below a solid face is the pass's business.
      const Index inside = gp < 0.0 ? sp : sq;
      if (-std::min(gp, gq) <= settings.depth_fraction * size[inside]) continue;
    }
    if (!segment_meets_triangle(xp, xq, c[0], c[1], c[2]) &&
        !segment_meets_triangle(xp, xq, c[0], c[2], c[3]))
      continue;
    // An edge that meets the face near a corner edge of the master surface grazes it (the
    // seed's "corner" case): the corner pokes into the slave facet by at most that distance,
    // a mismatch of the size the adjustment is meant for, with no node on the wrong side.
    const Vec3 meet = xp + (gp / (gp - gq)) * (xq - xp);
    const Real graze = settings.depth_fraction * std::sqrt(quad_area(c));
    bool grazes = false;
    for (int a = 0; a < 4 && !grazes; ++a)
      grazes =
          ((corners[f] >> a) & 1u) != 0 && distance_to_segment(meet, c[a], c[(a + 1) % 4]) <= graze;
    if (!grazes) return f;
  }
  return NO_INDEX;
}

/// Crossed surfaces (C5): the slave facet edges that pass through a master face, found with a
/// broad phase whose margin is the longest edge.
void Overclosure::find_crossed(OverclosureReport& report) const {
  if (!settings.detect_crossed || n_slave == 0) return;
  const auto crossed_start = Clock::now();
  const std::vector<std::pair<Index, Index>> edges = slave_edges();
  Real longest = 0.0;
  for (const auto& [p, q] : edges)
    longest = std::max(longest, (node_point(position, p) - node_point(position, q)).norm());
  if (!edges.empty() && longest > 0.0) {
    BroadPhase reach(1.001 * longest);
    reach.build(faces, slaves.nodes(), position, node_thickness);
    const std::vector<std::uint8_t> corners = corner_edges(faces, position);
    const auto n_edges = static_cast<Index>(edges.size());
    std::vector<Index> hit(edges.size(), NO_INDEX);
    ParallelErrors errors;
#pragma omp parallel for schedule(dynamic, 256)
    for (Index k = 0; k < n_edges; ++k)
      errors.guard(ParallelSite::Overclosure, k,
                   [&] { hit[k] = crossed_face(edges[k].first, edges[k].second, reach, corners); });
    errors.rethrow_if_any();
    for (Index k = 0; k < n_edges; ++k)
      if (hit[k] != NO_INDEX) report.crossed.push_back({edges[k].first, edges[k].second, hit[k]});
  }
  report.crossed_seconds = std::chrono::duration<double>(Clock::now() - crossed_start).count();
}

}  // namespace

std::vector<Real> slave_facet_sizes(const ContactEngine& engine, const NodalVectors& position) {
  const SlaveNodes& slaves = engine.domain().slaves();
  const std::vector<ContactFace>& faces = engine.domain().faces();
  std::vector<Real> size(static_cast<std::size_t>(slaves.size()), 0.0);
  for (Index s = 0; s < slaves.size(); ++s) {
    Real sum = 0.0;
    int count = 0;
    for (Index f : slaves.faces_of(s)) {
      Vec3 corner[4];
      face_corners(faces[f], position, {}, corner);
      sum += std::sqrt(quad_area(corner));
      ++count;
    }
    size[s] = count > 0 ? sum / count : 0.0;
  }
  return size;
}

OverclosureReport resolve_initial_overclosures(ContactEngine& engine,
                                               const ElementTopology& topology,
                                               NodalVectors& position,
                                               std::span<const Real> node_thickness,
                                               std::span<const std::uint8_t> node_lock,
                                               const OverclosureSettings& settings) {
  const auto start = Clock::now();
  OverclosureReport report;
  Overclosure pass{engine, topology, position, node_thickness, node_lock, settings};
  pass.classify(report);
  pass.adjust(report);
  pass.store_offsets(report);
  pass.find_crossed(report);
  report.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return report;
}

void carry_offsets(const ContactEngine& from, ContactEngine& to) {
  const SlaveNodes& old_slaves = from.domain().slaves();
  const SlaveNodes& new_slaves = to.domain().slaves();
  for (Index s = 0; s < new_slaves.size(); ++s) {
    const Index old = old_slaves.slot(new_slaves.nodes()[s]);
    if (old == NO_INDEX) continue;
    to.constraints()[s].offset = from.constraints()[old].offset;
    to.constraints()[s].offset_permanent = from.constraints()[old].offset_permanent;
  }
}

}  // namespace xpl::contact
