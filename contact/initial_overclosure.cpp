#include "contact/initial_overclosure.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "contact/closest_point.hpp"

namespace xpl::contact {

namespace {

using Clock = std::chrono::steady_clock;

enum class Role : std::uint8_t { Free, Ignored, Held };

/// Corner measures of element e: hex: the 8 corner Jacobians det[e1 e2 e3] and their scaled
/// values; shell: the 4 corner area vectors along the element normal `normal`. Returns the
/// number of corners (0 for other elements).
int corner_measures(const ElementTopology& topology, Index e, const NodalVectors& x,
                    const Vec3& normal, Real* measure, Real* scaled) {
  const Index* en = topology.nodes.data() + topology.offsets[e];
  if (topology.kinds[e] == ElementKind::Hex) {
    for (int a = 0; a < 8; ++a) {
      const int ring = a < 4 ? 0 : 4;
      const int local = a - ring;
      // Bottom corners: next, previous, up; top corners: previous, next, down (both right
      // handed for a valid element).
      const int first = ring + (a < 4 ? (local + 1) % 4 : (local + 3) % 4);
      const int second = ring + (a < 4 ? (local + 3) % 4 : (local + 1) % 4);
      const int third = a < 4 ? a + 4 : a - 4;
      const Vec3 p = node_point(x, en[a]);
      const Vec3 e1 = node_point(x, en[first]) - p, e2 = node_point(x, en[second]) - p,
                 e3 = node_point(x, en[third]) - p;
      measure[a] = e1.dot(e2.cross(e3));
      const Real lengths = std::sqrt(e1.dot(e1) * e2.dot(e2) * e3.dot(e3));
      scaled[a] = lengths > 0.0 ? measure[a] / lengths : -1.0;
    }
    return 8;
  }
  if (topology.kinds[e] == ElementKind::Shell) {
    for (int a = 0; a < 4; ++a) {
      const Vec3 p = node_point(x, en[a]);
      const Vec3 e1 = node_point(x, en[(a + 1) % 4]) - p, e2 = node_point(x, en[(a + 3) % 4]) - p;
      measure[a] = normal.dot(e1.cross(e2));
      const Real lengths = std::sqrt(e1.dot(e1) * e2.dot(e2));
      scaled[a] = lengths > 0.0 ? measure[a] / lengths : -1.0;
    }
    return 4;
  }
  return 0;
}

Vec3 shell_normal(const ElementTopology& topology, Index e, const NodalVectors& x) {
  const Index* en = topology.nodes.data() + topology.offsets[e];
  const Vec3 n = (node_point(x, en[2]) - node_point(x, en[0]))
                     .cross(node_point(x, en[3]) - node_point(x, en[1]));
  const Real length = std::sqrt(n.dot(n));
  return length > 0.0 ? Vec3(n / length) : Vec3::Zero();
}

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

std::vector<Index> distorted_elements(const ElementTopology& topology, const NodalVectors& original,
                                      const NodalVectors& position,
                                      std::span<const char> node_moved, Real& quality_before,
                                      Real& quality_after) {
  std::vector<Index> refused;
  quality_before = quality_after = 1.0;
  for (Index e = 0; e < topology.element_count(); ++e) {
    const Index* en = topology.nodes.data() + topology.offsets[e];
    const Index count = topology.offsets[e + 1] - topology.offsets[e];
    bool touched = false;
    for (Index k = 0; k < count && !touched; ++k) touched = node_moved[en[k]] != 0;
    if (!touched) continue;
    // A shell's corner areas are measured along its own mean normal in each configuration:
    // rotating a shell element is strain free (an adjustment may tilt it a lot), while a corner
    // folding over its mean plane turns negative.
    const bool shell = topology.kinds[e] == ElementKind::Shell;
    const Vec3 normal_before = shell ? shell_normal(topology, e, original) : Vec3::Zero();
    const Vec3 normal_after = shell ? shell_normal(topology, e, position) : Vec3::Zero();
    Real before[8], after[8], scaled_before[8], scaled_after[8];
    const int corners =
        corner_measures(topology, e, original, normal_before, before, scaled_before);
    corner_measures(topology, e, position, normal_after, after, scaled_after);
    bool refuse = false;
    for (int a = 0; a < corners; ++a) {
      quality_before = std::min(quality_before, scaled_before[a]);
      quality_after = std::min(quality_after, scaled_after[a]);
      refuse = refuse || after[a] < MIN_CORNER_RATIO * before[a];
    }
    if (refuse) refused.push_back(e);
  }
  return refused;
}

const char* offset_reason_name(OffsetReason reason) {
  switch (reason) {
    case OffsetReason::Boundary:
      return "BC";
    case OffsetReason::Rigid:
      return "rigid";
    case OffsetReason::Pinched:
      return "pinched";
    case OffsetReason::Distortion:
      return "distortion";
    case OffsetReason::Conflict:
      return "conflict";
    case OffsetReason::LaterStep:
      return "later step";
    case OffsetReason::Import:
      return "import";
  }
  return "conflict";
}

OverclosureReport resolve_initial_overclosures(ContactEngine& engine,
                                               const ElementTopology& topology,
                                               NodalVectors& position,
                                               std::span<const Real> node_thickness,
                                               std::span<const std::uint8_t> node_lock,
                                               const OverclosureSettings& settings) {
  const auto start = Clock::now();
  OverclosureReport report;
  const ContactDomain& domain = engine.domain();
  const SlaveNodes& slaves = domain.slaves();
  const std::vector<ContactFace>& faces = domain.faces();
  const Index n_slave = slaves.size();
  const auto n = static_cast<std::size_t>(n_slave);

  const std::vector<Real> size = slave_facet_sizes(engine, position);
  auto tolerance = [&](Index s) { return OVERCLOSURE_TOLERANCE * size[s]; };
  auto limit = [&](Index s, Index f) {
    return faces[f].shell ? std::numeric_limits<Real>::max() : settings.depth_fraction * size[s];
  };
  auto penetrates = [&](Index s) {
    if (!settings.exclude.empty() && settings.exclude[s] != 0) return false;
    const SlaveTouch& t = engine.touch(s);
    return t.face != NO_INDEX && t.gap < -tolerance(s);
  };

  // 1. Classification on the mesh as read.
  engine.probe(position, node_thickness);
  std::vector<Role> role(n, Role::Free);
  std::vector<OffsetReason> reason(n, OffsetReason::Conflict);
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
        engine.penetrated_faces(s, position, node_thickness, tolerance(s));
    bool pinched = false;
    for (std::size_t i = 0; i < all.size() && !pinched; ++i)
      for (std::size_t j = i + 1; j < all.size() && !pinched; ++j)
        pinched = all[i].normal.dot(all[j].normal) < PINCH_COSINE;
    const std::uint8_t lock = node_lock.empty() ? 0 : node_lock[node];
    bool bc = false;
    for (int c = 0; c < 3; ++c)
      bc = bc || (((lock >> c) & 1u) != 0 && std::abs(t.normal[c]) > LOCK_COMPONENT);
    if (pinched || (lock & LOCK_RIGID) != 0 || bc) {
      role[s] = Role::Held;
      reason[s] = pinched                    ? OffsetReason::Pinched
                  : (lock & LOCK_RIGID) != 0 ? OffsetReason::Rigid
                                             : OffsetReason::Boundary;
    }
  }

  // 2.–3. Adjustment passes; rounds restart from the mesh as read after a refusal.
  std::vector<Index> first_face(n, NO_INDEX), first_pair(n, NO_INDEX);
  std::vector<Real> first_depth(n, 0.0);
  const bool anything_to_move =
      settings.adjust &&
      std::any_of(role.begin(), role.end(), [](Role r) { return r == Role::Free; }) &&
      report.max_overclosure > 0.0;
  bool moved_any = false;
  if (anything_to_move) {
    const NodalVectors original = position;
    std::vector<char> moving(n, 0);
    std::vector<Real> move(3 * n, 0.0);
    for (int round = 0; round < MAX_ADJUSTMENT_ROUNDS; ++round) {
      if (round > 0) {
        position = original;
        engine.probe(position, node_thickness);
        std::fill(first_face.begin(), first_face.end(), NO_INDEX);
      }
      report.passes = 0;
      for (int pass = 0; pass < settings.max_passes; ++pass) {
        if (pass > 0) engine.probe(position, node_thickness);
        bool any = false;
        for (Index s = 0; s < n_slave; ++s) {
          moving[s] = role[s] == Role::Free && penetrates(s) &&
                      -engine.touch(s).gap <= limit(s, engine.touch(s).face);
          any = any || moving[s];
        }
        if (!any) break;
        ++report.passes;
#pragma omp parallel for schedule(static)
        for (Index s = 0; s < n_slave; ++s) {
          if (!moving[s]) continue;
          const SlaveTouch& t = engine.touch(s);
          // Half when the face moves too in this pass (the other view of a balanced pair).
          Real w = 1.0;
          for (Index c : faces[t.face].nodes) {
            const Index cs = slaves.slot(c);
            if (cs != NO_INDEX && moving[cs]) w = std::min(1.0, t.weight);
          }
          const Vec3 delta = w * (-t.gap) * t.normal;
          // A DOF with a boundary condition does not move at all (its share of the
          // direction is below LOCK_COMPONENT, or the node would be held).
          const std::uint8_t lock = node_lock.empty() ? 0 : node_lock[slaves.nodes()[s]];
          for (int d = 0; d < 3; ++d) move[3 * s + d] = ((lock >> d) & 1u) != 0 ? 0.0 : delta[d];
        }
        for (Index s = 0; s < n_slave; ++s) {
          if (!moving[s]) continue;
          const Index node = slaves.nodes()[s];
          for (int d = 0; d < 3; ++d) position(node, d) += move[3 * s + d];
          if (first_face[s] == NO_INDEX) {
            const SlaveTouch& t = engine.touch(s);
            first_face[s] = t.face;
            first_pair[s] = t.pair;
            first_depth[s] = -t.gap;
          }
        }
      }

      // Safety: no element corner may lose half its volume (area) or invert.
      std::vector<char> node_moved(static_cast<std::size_t>(position.rows()), 0);
      moved_any = false;
      for (Index s = 0; s < n_slave; ++s) {
        const Index node = slaves.nodes()[s];
        if ((position.row(node) - original.row(node)).squaredNorm() > 0.0) {
          node_moved[node] = 1;
          moved_any = true;
        }
      }
      const std::vector<Index> refused = distorted_elements(
          topology, original, position, node_moved, report.quality_before, report.quality_after);
      if (refused.empty() || round + 1 == MAX_ADJUSTMENT_ROUNDS) break;
      for (Index e : refused) {
        report.refused_elements.push_back(e);
        const Index* en = topology.nodes.data() + topology.offsets[e];
        for (Index k = 0; k < topology.offsets[e + 1] - topology.offsets[e]; ++k) {
          const Index s = slaves.slot(en[k]);
          if (s == NO_INDEX || !node_moved[en[k]] || role[s] != Role::Free) continue;
          role[s] = Role::Held;
          reason[s] = OffsetReason::Distortion;
        }
      }
    }
    if (moved_any) engine.probe(position, node_thickness);
    for (Index s = 0; s < n_slave; ++s) {
      const Index node = slaves.nodes()[s];
      const Vec3 delta = node_point(position, node) - node_point(original, node);
      const Real distance = std::sqrt(delta.dot(delta));
      if (!(distance > 0.0)) continue;
      const Index f = first_face[s];
      report.adjusted.push_back({node, f, domain.slave_surface(s, f, first_pair[s]),
                                 domain.master_surface(s, f, first_pair[s]), first_depth[s],
                                 distance, delta / distance});
    }
  }

  // 4. Offsets: what still penetrates.
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

  // Crossed surfaces.
  if (settings.detect_crossed && n_slave > 0) {
    const auto crossed_start = Clock::now();
    std::vector<std::pair<Index, Index>> edges;
    for (const ContactFace& face : faces)
      for (int a = 0; a < 4; ++a) {
        const Index p = face.nodes[a], q = face.nodes[(a + 1) % 4];
        if (domain.slave_rigid(slaves.slot(p)) || domain.slave_rigid(slaves.slot(q))) continue;
        edges.emplace_back(std::min(p, q), std::max(p, q));
      }
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    Real longest = 0.0;
    for (const auto& [p, q] : edges)
      longest = std::max(longest, (node_point(position, p) - node_point(position, q)).norm());
    if (!edges.empty() && longest > 0.0) {
      BroadPhase reach(1.001 * longest);
      reach.build(faces, slaves.nodes(), position, node_thickness);
      const auto n_edges = static_cast<Index>(edges.size());
      std::vector<Index> hit(edges.size(), NO_INDEX);
#pragma omp parallel for schedule(dynamic, 256)
      for (Index k = 0; k < n_edges; ++k) {
        const auto [p, q] = edges[k];
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
          if (segment_meets_triangle(xp, xq, c[0], c[1], c[2]) ||
              segment_meets_triangle(xp, xq, c[0], c[2], c[3])) {
            hit[k] = f;
            break;
          }
        }
      }
      for (Index k = 0; k < n_edges; ++k)
        if (hit[k] != NO_INDEX) report.crossed.push_back({edges[k].first, edges[k].second, hit[k]});
    }
    report.crossed_seconds = std::chrono::duration<double>(Clock::now() - crossed_start).count();
  }
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
