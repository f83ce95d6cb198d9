#include "contact/contact_engine.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "common/parallel_error.hpp"
#include "contact/closest_point.hpp"

namespace xpl::contact {

namespace {

/// Default margin: MARGIN_FRACTION × the mean square root of the face areas.
Real mean_face_size(const std::vector<ContactFace>& faces, const NodalVectors& position) {
  if (faces.empty()) return 1.0;
  Real sum = 0.0;
  for (const ContactFace& f : faces) {
    Vec3 corner[4];
    face_corners(f, position, {}, corner);
    sum += std::sqrt(quad_area(corner));
  }
  return sum / static_cast<Real>(faces.size());
}

Real max_thickness(std::span<const Real> thickness) {
  Real t = 0.0;
  for (Real v : thickness)
    if (std::isfinite(v)) t = std::max(t, v);
  return t;
}

/// The broad phase with its search margin (m) and rebuild motion (m): the motion leaves room
/// for half a shell thickness around every slave node.
BroadPhase make_broad_phase(const ContactOptions& options, const std::vector<ContactFace>& faces,
                            const NodalVectors& position, std::span<const Real> node_thickness) {
  Real base =
      options.margin > 0.0 ? options.margin : MARGIN_FRACTION * mean_face_size(faces, position);
  if (!(base > 0.0)) base = FALLBACK_MARGIN;
  const Real half_t = 0.5 * max_thickness(node_thickness);
  return BroadPhase(base + half_t, 0.5 * base);
}

/// Keeps the `kept.size()` nearest of the touches offered (distance `distance`, m) in
/// `kept`, nearest first; `count` is how many it holds.
template <std::size_t N>
void keep_nearest(std::array<SlaveTouch, N>& kept, std::array<Real, N>& kept_distance, int& count,
                  const SlaveTouch& touch, Real distance) {
  int at = count;
  while (at > 0 && distance < kept_distance[at - 1]) --at;
  if (at >= static_cast<int>(N)) return;
  const int last = std::min(count, static_cast<int>(N) - 1);
  for (int k = last; k > at; --k) {
    kept[k] = kept[k - 1];
    kept_distance[k] = kept_distance[k - 1];
  }
  kept[at] = touch;
  kept_distance[at] = distance;
  count = std::min(count + 1, static_cast<int>(N));
}

/// The nearest of the penetrated touches `penetrated` (nearest first) on the other side of
/// the node from `best`: normals more than 120° apart (PINCH_COSINE); none when no such face.
template <std::size_t N>
SlaveTouch opposite_touch(const SlaveTouch& best, const std::array<SlaveTouch, N>& penetrated,
                          int count) {
  for (int k = 0; k < count; ++k)
    if (penetrated[k].face != best.face && penetrated[k].normal.dot(best.normal) < PINCH_COSINE)
      return penetrated[k];
  return SlaveTouch{};
}

/// The nearest of the penetrated touches `penetrated` (nearest first) on a face of another
/// element than `best`'s whose normal is more than 60° from best's (CORNER_COSINE): the other
/// face of a corner a shell node is pressed into; none when no such face.
template <std::size_t N>
SlaveTouch corner_touch(const SlaveTouch& best, const std::array<SlaveTouch, N>& penetrated,
                        int count, const std::vector<ContactFace>& faces) {
  for (int k = 0; k < count; ++k)
    if (faces[penetrated[k].face].element != faces[best.face].element &&
        penetrated[k].normal.dot(best.normal) < CORNER_COSINE)
      return penetrated[k];
  return SlaveTouch{};
}

}  // namespace

ContactEngine::ContactEngine(ContactDomain domain, std::vector<InteractionLaw> laws,
                             ContactOptions options, const NodalVectors& position,
                             std::span<const Real> node_thickness)
    : m_domain(std::move(domain)),
      m_laws(std::move(laws)),
      m_options(options),
      m_broad(make_broad_phase(options, m_domain.faces(), position, node_thickness)) {
  const auto n = static_cast<std::size_t>(m_domain.slaves().size());
  m_constraints.assign(n, ContactConstraint{});
  m_touch.assign(n, SlaveTouch{});
  m_lost_depth.assign(n, 0.0);
  m_second.assign(n, ContactConstraint{});
  m_second_touch.assign(n, SlaveTouch{});
  m_second_force.assign(3 * n, 0.0);
  m_second_normal_force.assign(n, 0.0);
  m_second_dissipation.assign(n, 0.0);
  m_spring.assign(2 * n, Spring{});
  m_normal_force.assign(n, 0.0);
  m_slave_force.assign(3 * n, 0.0);
  m_dissipation.assign(n, 0.0);
  m_stored.assign(n, 0.0);
  m_output_status.assign(n, OutputStatus::Open);
  m_assembly = ForceAssembly(m_domain.slaves().size(), m_domain.pair_count());
  for (const InteractionLaw& law : m_laws)
    m_user_stiffness = m_user_stiffness || law.pressure_slope > 0.0;
  if (m_user_stiffness) {
    m_user_k.assign(2 * n, 0.0);
    m_user_law.assign(2 * n, NO_INDEX);
  }
}

ContactEngine::SlaveView ContactEngine::slave_view(Index s, const NodalVectors& position,
                                                   std::span<const Real> node_thickness) const {
  const std::vector<ContactFace>& faces = m_domain.faces();
  SlaveView v;
  v.slot = s;
  const Index node = m_domain.slaves().nodes()[s];
  v.node = node;
  v.point = node_point(position, node);
  v.normal = m_domain.slaves().normal(s);
  v.double_sided = m_domain.slave_double_sided(s);
  v.free_edge = m_domain.slave_on_free_edge(s);
  v.point_node = m_domain.slave_point(s);
  v.half_t = v.double_sided ? 0.5 * node_thickness_of(node_thickness, node) : 0.0;
  if (v.double_sided) {
    // The nodes of its own elements, once per node rather than once per candidate face.
    for (Index g : m_domain.slaves().faces_of(s))
      for (Index a : faces[g].nodes) {
        if (v.own_count < 0) break;
        bool seen = false;
        for (int k = 0; k < v.own_count; ++k) seen = seen || v.own[k] == a;
        if (seen) continue;
        if (v.own_count == static_cast<int>(v.own.size()))
          v.own_count = -1;  // more than fit: admissible() walks the faces instead
        else
          v.own[v.own_count++] = a;
      }
  }
  const ContactConstraint& before = m_constraints[s];
  if (before.offset_permanent) v.allowance = std::max(before.offset, 0.0);
  // Side memory: a node pressed onto one side of a shell last increment may not be taken by
  // the other side of that shell, however deep it has gone (no pass-through).
  if (before.status == ContactStatus::Closed && before.master_face >= 0 &&
      faces[before.master_face].shell)
    v.held = &faces[before.master_face];
  if (m_updated && before.status == ContactStatus::Closed && before.master_face >= 0 &&
      !faces[before.master_face].shell)
    v.continuing = before.master_face;
  return v;
}

bool ContactEngine::admissible(const SlaveView& v, Index f, const NodalVectors& position,
                               std::span<const Real> node_thickness, SlaveTouch& out,
                               Real& distance) const {
  const std::vector<ContactFace>& faces = m_domain.faces();
  const Index s = v.slot;
  const ContactFace* held = v.held;
  const bool double_sided = v.double_sided;
  // The other side of the shell it is held on: only round the edge (below).
  const bool round_edges = double_sided && m_updated;
  const bool other_side = held != nullptr && faces[f].shell && faces[f].element == held->element &&
                          faces[f].face != held->face;
  if (other_side && !round_edges) return false;
  // A face of the node's own hex (file comment).
  if (faces[f].behind(v.node)) return false;
  // A shell face next to the shell node's own elements continues its own shell (file comment).
  if (double_sided && faces[f].shell) {
    bool own = false;
    if (v.own_count >= 0) {
      for (Index b : faces[f].nodes)
        for (int k = 0; k < v.own_count; ++k) own = own || v.own[k] == b;
    } else {
      for (Index g : m_domain.slaves().faces_of(s))
        for (Index a : faces[g].nodes)
          for (Index b : faces[f].nodes) own = own || a == b;
    }
    if (own) return false;
  }
  Index pair = NO_INDEX;
  const Real w = m_domain.weight(s, f, pair);
  if (w == 0.0) return false;
  Vec3 corner[4];
  face_corners(faces[f], position, node_thickness, corner);
  const Vec3 n_f = (corner[2] - corner[0]).cross(corner[3] - corner[1]);
  const Real n_len = std::sqrt(n_f.dot(n_f));
  if (!(n_len > 0.0)) return false;
  // A shell node is double sided (either orientation), and one on a free edge may touch a
  // face edge-on (a tube end on a plate). A point node has no orientation: any face.
  const Real cosine = v.normal.dot(n_f) / n_len;
  if (!v.point_node && (double_sided ? !v.free_edge && std::abs(cosine) < OPPOSING_COSINE
                                     : cosine > -OPPOSING_COSINE))
    return false;
  const ClosestPoint cp = closest_point_on_quad(corner, v.point);
  if (other_side && cp.region == QuadRegion::Interior) return false;
  const Real half_t = v.half_t;
  Real gap = cp.gap - half_t;
  Vec3 normal = cp.normal;
  Real reach_distance = cp.distance;
  Real depth = m_domain.face_depth(f);
  if (faces[f].shell) {
    Real t = 0.0;
    for (Index c : faces[f].nodes) t += node_thickness_of(node_thickness, c);
    depth = DEPTH_LIMIT_FRACTION * 0.25 * t;  // of the mean thickness
  }
  // Beside a shell face's edge or corner, a shell node touches the wall's round edge (file
  // comment): the points within half the thickness of the mid-surface's edge, each side of
  // the wall owning the half of the round on its side. The gap is the distance to the
  // mid-surface edge less both half thicknesses and the normal points from the edge to the
  // node, so a node coming at the edge side-on (layers crumpled flat on a plate sliding into
  // each other) is pushed back from its first touch, where the gap along the face normal took
  // it in up to a thickness deep at once. Not in an engine's first update, which seeds the
  // overclosures by the rule below (C2-C7).
  if (cp.region != QuadRegion::Interior && round_edges && faces[f].shell) {
    Vec3 mid = Vec3::Zero();
    Real radius = 0.0;
    for (int a = 0; a < 4; ++a) {
      mid += cp.weights[a] * node_point(position, faces[f].nodes[a]);
      radius += cp.weights[a] * 0.5 * node_thickness_of(node_thickness, faces[f].nodes[a]);
    }
    const Vec3 d = v.point - mid;
    const Real reach = std::sqrt(d.dot(d));
    if (!(reach > 0.0)) return false;
    normal = d / reach;
    // The other side's half: this side would follow the node round the edge to the back of
    // the wall, where its gap is a thickness deep at once (energy from nowhere).
    if (normal.dot(n_f) < 0.0) return false;
    gap = reach - radius - half_t;
    reach_distance = std::abs(reach - radius);
  } else if (cp.region != QuadRegion::Interior && gap < 0.0) {
    // Behind the face's plane but beside its edge or corner, the node penetrates the face only
    // while its offset beyond the edge is smaller than its penetration (it is nearer to the
    // face than to clearing it sideways). Farther out the gap "along the face normal" measures
    // nothing real: at a fold it makes a node touch the face of the element next to its own
    // (suddenly, a shell thickness deep), and its force, not the gradient of that gap, turns
    // with the face and does work (energy injection). A node pushed into a concave corner is
    // still caught: for one of the two faces its offset is below its penetration.
    const Real lateral_sq = cp.distance * cp.distance - cp.gap * cp.gap;
    if (lateral_sq > gap * gap) return false;
  }
  const bool kept_side = held != nullptr && faces[f].shell && faces[f].element == held->element;
  if (f == v.continuing) depth *= 2.0;  // contact at speed (file comment)
  if (!kept_side && -gap > depth + half_t + v.allowance) return false;
  out = {f, pair, w, gap, normal, cp.weights, cp.xi, cp.eta};
  distance = reach_distance;
  return true;
}

void ContactEngine::search(const NodalVectors& position, std::span<const Real> node_thickness) {
  const Index n_slave = m_domain.slaves().size();
  ParallelErrors errors;
#pragma omp parallel for schedule(dynamic, 256)
  for (Index s = 0; s < n_slave; ++s)
    errors.guard(ParallelSite::ContactSearch, s, [&] {
      SlaveTouch best;
      SlaveTouch second;
      m_lost_depth[s] = 0.0;
      if (!m_broad.candidates(s).empty() ||
          (m_updated && m_constraints[s].status == ContactStatus::Closed)) {
        Real best_distance = std::numeric_limits<Real>::max();
        SlaveTouch candidate;
        Real distance = 0.0;
        // The nearest penetrated faces, for the touch on the other side (file comment).
        std::array<SlaveTouch, PENETRATED_KEPT> penetrated;
        std::array<Real, PENETRATED_KEPT> penetrated_distance{};
        int n_penetrated = 0;
        int n_seen = 0;
        const SlaveView view = slave_view(s, position, node_thickness);
        const auto consider = [&](Index f) {
          if (!admissible(view, f, position, node_thickness, candidate, distance)) return;
          if (distance < best_distance) {
            best_distance = distance;
            best = candidate;
          }
          if (candidate.gap < 0.0) {
            keep_nearest(penetrated, penetrated_distance, n_penetrated, candidate, distance);
            ++n_seen;
          }
        };
        const std::span<const Index> listed = m_broad.candidates(s);
        for (Index f : listed) consider(f);
        // The face pressed last increment, deeper than the broad phase's slab (contact at speed).
        if (view.continuing != NO_INDEX &&
            !std::binary_search(listed.begin(), listed.end(), view.continuing))
          consider(view.continuing);
        m_lost_depth[s] = best.face == NO_INDEX ? released_depth(view, position) : 0.0;
        // Pinched: penetrating its nearest face and one on its other side. A node outside its
        // nearest face is not pinched, however deep it lies behind a face across its own body
        // (a corner node of a squashed block behind the block's far side).
        const bool pinched = best.face != NO_INDEX && best.gap < 0.0;
        if (pinched) second = opposite_touch(best, penetrated, n_penetrated);
        if (pinched && second.face == NO_INDEX && n_seen > PENETRATED_KEPT) {
          // More penetrated faces than kept (a node under the shared corner of many faces on
          // both sides): look for the other side among all of them.
          Real second_distance = std::numeric_limits<Real>::max();
          for (Index f : m_broad.candidates(s))
            if (admissible(view, f, position, node_thickness, candidate, distance) &&
                candidate.gap < 0.0 && candidate.face != best.face &&
                candidate.normal.dot(best.normal) < PINCH_COSINE && distance < second_distance) {
              second_distance = distance;
              second = candidate;
            }
        }
        if (pinched && second.face == NO_INDEX && view.double_sided && m_updated)
          second = corner_touch(best, penetrated, n_penetrated, m_domain.faces());
      }
      m_touch[s] = best;
      m_second_touch[s] = second;
    });
  errors.rethrow_if_any();
}

Real ContactEngine::released_depth(const SlaveView& v, const NodalVectors& position) const {
  if (v.continuing == NO_INDEX) return 0.0;
  const ContactFace& face = m_domain.faces()[v.continuing];
  Vec3 corner[4];
  face_corners(face, position, {}, corner);
  const ClosestPoint cp = closest_point_on_quad(corner, v.point);
  // Beside the face (its edge or corner), the node has slid off it rather than gone through.
  if (cp.region != QuadRegion::Interior) return 0.0;
  const Real depth = -cp.gap;
  return depth > 2.0 * m_domain.face_depth(v.continuing) + v.allowance ? depth : 0.0;
}

void ContactEngine::widen_search(Real extra) {
  if (!(extra > 0.0)) return;
  m_broad = BroadPhase(m_broad.margin() + extra, m_broad.rebuild_motion());
}

bool ContactEngine::refresh_broad_phase(const NodalVectors& position,
                                        std::span<const Real> node_thickness) {
  SlaveNodes& slaves = m_domain.slaves();
  if (!m_broad.needs_rebuild(position)) return false;
  m_broad.build(m_domain.faces(), slaves.nodes(), position, node_thickness, m_domain.face_depths());
  const Index n_slave = slaves.size();
  m_active_slot.assign(static_cast<std::size_t>(n_slave), 0);
  m_active_face.assign(m_domain.faces().size(), 0);
  for (Index s = 0; s < n_slave; ++s) {
    if (m_broad.candidates(s).empty()) continue;
    m_active_slot[s] = 1;
    for (Index f : slaves.faces_of(s)) m_active_face[f] = 1;
  }
  return true;
}

bool ContactEngine::probe(const NodalVectors& position, std::span<const Real> node_thickness) {
  const bool rebuild = refresh_broad_phase(position, node_thickness);
  m_domain.slaves().update_areas(m_domain.faces(), position);
  search(position, node_thickness);
  return rebuild;
}

std::vector<SlaveTouch> ContactEngine::penetrated_faces(Index s, const NodalVectors& position,
                                                        std::span<const Real> node_thickness,
                                                        Real tolerance) const {
  std::vector<std::pair<Real, SlaveTouch>> found;
  {
    SlaveTouch candidate;
    Real distance = 0.0;
    const SlaveView view = slave_view(s, position, node_thickness);
    for (Index f : m_broad.candidates(s))
      if (admissible(view, f, position, node_thickness, candidate, distance) &&
          candidate.gap < -tolerance)
        found.emplace_back(distance, candidate);
  }
  std::stable_sort(found.begin(), found.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<SlaveTouch> out;
  for (const auto& [d, t] : found) out.push_back(t);
  return out;
}

ContactTotals ContactEngine::update(const NodalVectors& position, const NodalVectors& velocity_half,
                                    Real dt, Real dt_penalty, std::span<const Real> node_thickness,
                                    std::span<const Real> mass, std::span<const Real> inverse_mass,
                                    NodalVectors& force_internal, PhaseTimers& timers) {
  ContactTotals totals;
  SlaveNodes& slaves = m_domain.slaves();
  const std::vector<ContactFace>& faces = m_domain.faces();
  const Index n_slave = slaves.size();
  {
    ScopedTimer timer(timers, Phase::ContactSearch);
    totals.rebuilt = refresh_broad_phase(position, node_thickness);
    // Only the search of a slot with candidates reads its area and normal, and so does a
    // user-stiffness law's spring (same slots); a LINEAR law's increment estimate reads all.
    if (m_user_stiffness)
      slaves.update_areas(faces, position);
    else
      slaves.update_areas(faces, position, m_active_slot, m_active_face);
    search(position, node_thickness);
    for (Index s = 0; s < n_slave; ++s) {
      if (!(m_lost_depth[s] > 0.0)) continue;
      ++totals.lost;
      if (m_lost_depth[s] <= totals.lost_depth) continue;
      const ContactFace& face = faces[m_constraints[s].master_face];
      totals.lost_depth = m_lost_depth[s];
      totals.lost_node = slaves.nodes()[s];
      totals.lost_element = face.element;
      totals.lost_element_depth = 2.0 * m_domain.face_depth(m_constraints[s].master_face);
    }
  }

  ScopedTimer timer(timers, Phase::ContactForce);
  // The springs' memory and stiffness, both sides of every slot.
  ParallelErrors errors;
#pragma omp parallel for schedule(static)
  for (Index s = 0; s < n_slave; ++s)
    errors.guard(ParallelSite::ContactForces, s, [&] {
      ContactConstraint& c = m_constraints[s];
      ContactConstraint& c2 = m_second[s];
      const SlaveTouch& t = m_touch[s];
      const SlaveTouch& t2 = m_second_touch[s];
      // The memory of a side follows its side (file comment): each constraint continues
      // with the touch that looks the way it looked last increment.
      if ((c.master_face != NO_INDEX || c2.master_face != NO_INDEX) && !c.offset_permanent &&
          !c2.offset_permanent) {
        const auto alike = [](const SlaveTouch& now, const ContactConstraint& before) {
          return now.face != NO_INDEX && before.master_face != NO_INDEX
                     ? now.normal.dot(before.normal)
                     : -2.0;
        };
        if (alike(t, c2) + alike(t2, c) > alike(t, c) + alike(t2, c2)) std::swap(c, c2);
      }
      // Interference ramp (set_interference): the offset of this update's step time.
      if (!m_interference.empty() && m_interference[s].amount > 0.0) {
        const Interference& ramp = m_interference[s];
        const Real r = ramp.duration > 0.0 ? std::max(0.0, 1.0 - m_step_time / ramp.duration) : 0.0;
        m_ramp_before[s] = c.offset;
        c.offset = ramp.base + ramp.amount * r;
      }
      prepare_spring(s, c, t, m_spring[2 * s], position, velocity_half, dt, dt_penalty, mass,
                     inverse_mass);
      if (t2.face == NO_INDEX) {
        // No face on the other side is penetrated: that side's offset is spent (C3).
        c2.master_face = NO_INDEX;
        c2.status = ContactStatus::Inactive;
        c2.tangential_force = Vec3::Zero();
        if (!c2.offset_permanent) c2.offset = 0.0;
        c2.stiffness = 0.0;
        m_spring[2 * s + 1].k = 0.0;
        return;
      }
      // A node held with an offset at the start is held on both sides (C3, C6).
      if (!m_updated && c2.master_face == NO_INDEX && c.offset > 0.0)
        c2.offset = std::max(c2.offset, -t2.gap);
      prepare_spring(s, c2, t2, m_spring[2 * s + 1], position, velocity_half, dt, dt_penalty, mass,
                     inverse_mass);
    });
  errors.rethrow_if_any();

  cap_default_springs(dt_penalty, mass, inverse_mass);

#pragma omp parallel for schedule(static)
  for (Index s = 0; s < n_slave; ++s)
    errors.guard(ParallelSite::ContactForces, s, [&] {
      m_dissipation[s] = 0.0;
      m_second_dissipation[s] = 0.0;
      m_stored[s] = 0.0;
      OutputStatus status = OutputStatus::Open;
      if (m_user_stiffness) m_user_k[2 * s] = m_user_k[2 * s + 1] = 0.0;
      const Real fn_before = m_normal_force[s];
      const Vec3 f = spring_force(s, 0, m_constraints[s], m_touch[s], dt, dt_penalty, status);
      if (!m_interference.empty() && m_interference[s].amount > 0.0) {
        // The work of the ramp step on the spring, in the trapezoidal measure of the work the
        // contact forces do on the nodes (ForceAssembly): with F = k (d − d0), ½ k e² grows
        // by ½ (F_n + F_{n+1}) (Δd − Δd0), the nodes' part of which ALLPW books.
        m_ramp_work[s] =
            0.5 * (fn_before + m_spring[2 * s].fn) * (m_ramp_before[s] - m_constraints[s].offset);
      }
      for (int d = 0; d < 3; ++d) m_slave_force[3 * s + d] = f[d];
      m_normal_force[s] = m_spring[2 * s].fn;
      const Vec3 f2 =
          m_second_touch[s].face == NO_INDEX
              ? Vec3::Zero()
              : spring_force(s, 1, m_second[s], m_second_touch[s], dt, dt_penalty, status);
      for (int d = 0; d < 3; ++d) m_second_force[3 * s + d] = f2[d];
      m_second_normal_force[s] = m_spring[2 * s + 1].fn;
      m_output_status[s] = status;
    });
  errors.rethrow_if_any();

  // Assembly, sums and work, in slot order (independent of the thread count).
  m_assembly.assemble(
      slaves, faces, {m_touch, m_slave_force, m_normal_force, m_constraints, m_dissipation},
      {m_second_touch, m_second_force, m_second_normal_force, m_second, m_second_dissipation},
      velocity_half, dt, force_internal, totals);
  for (Index s = 0; s < n_slave; ++s) totals.stored_energy += m_stored[s];
  if (m_ramping > 0) {
    // In slot order; a ramp that has reached zero ends (its offset stays permanent only
    // where a base is left).
    for (Index s = 0; s < n_slave; ++s) {
      Interference& ramp = m_interference[s];
      if (!(ramp.amount > 0.0)) continue;
      totals.interference_work += m_ramp_work[s];
      m_ramp_work[s] = 0.0;
      if (m_step_time < ramp.duration) continue;
      ramp.amount = 0.0;
      m_constraints[s].offset = ramp.base;
      m_constraints[s].offset_permanent = ramp.base != 0.0;
      --m_ramping;
    }
  }
  // A face corner without candidates of its own that carries force: its area and normal
  // (read by the contact output) as the full pass would have made them.
  if (!m_user_stiffness) {
    bool extra = false;
    for (Index s = 0; s < n_slave && !extra; ++s) {
      const Vec3 f = m_assembly.nodal_force(s);
      extra = !m_active_slot[s] && f.dot(f) != 0.0;
    }
    if (extra) {
      m_extra_slot.assign(static_cast<std::size_t>(n_slave), 0);
      m_extra_face.assign(faces.size(), 0);
      for (Index s = 0; s < n_slave; ++s) {
        const Vec3 f = m_assembly.nodal_force(s);
        if (m_active_slot[s] || f.dot(f) == 0.0) continue;
        m_extra_slot[s] = 1;
        for (Index g : slaves.faces_of(s)) m_extra_face[g] = 1;
      }
      slaves.update_areas(faces, position, m_extra_slot, m_extra_face);
    }
  }
  m_updated = true;
  if (m_user_stiffness) {
    m_penalty_sum.reset(static_cast<Index>(mass.size()));
    for (Index s = 0; s < n_slave; ++s)
      for (int side = 0; side < 2; ++side) {
        const SlaveTouch& t = side == 0 ? m_touch[s] : m_second_touch[s];
        const Index j = 2 * s + side;
        if (m_user_k[j] > 0.0)
          m_penalty_sum.add_spring(slaves.nodes()[s], faces[t.face].nodes, t.shape, m_user_k[j],
                                   m_user_law[j], inverse_mass);
      }
    m_penalty_limit = m_penalty_sum.largest(inverse_mass);
  }
  return totals;
}

void ContactEngine::prepare_spring(Index s, ContactConstraint& c, const SlaveTouch& t,
                                   Spring& spring, const NodalVectors& position,
                                   const NodalVectors& velocity_half, Real dt, Real dt_penalty,
                                   std::span<const Real> mass,
                                   std::span<const Real> inverse_mass) const {
  (void)position;
  spring = Spring{};
  if (t.face == NO_INDEX) {
    c.master_face = NO_INDEX;
    c.status = ContactStatus::Inactive;
    c.tangential_force = Vec3::Zero();
    return;
  }
  const SlaveNodes& slaves = m_domain.slaves();
  const Index node = slaves.nodes()[s];
  spring.interaction = m_domain.interaction(s, t.face);
  spring.law =
      spring.interaction != NO_INDEX && spring.interaction < static_cast<Index>(m_laws.size())
          ? m_laws[spring.interaction]
          : InteractionLaw{};
  const ContactFace& face = m_domain.faces()[t.face];
  Vec3 v_rel = node_point(velocity_half, node);
  for (int a = 0; a < 4; ++a) v_rel -= t.shape[a] * node_point(velocity_half, face.nodes[a]);
  spring.v_rel = v_rel;
  // A touch the increment's motion cannot have made starts without force (file comment).
  if (m_updated && !c.offset_permanent)
    c.offset = std::max(c.offset, onset_offset(c, t.face, t.gap, t.normal, v_rel, dt));
  c.gap = t.gap;
  c.normal = t.normal;
  const Real master_mass = master_mass_at_point(t.shape, face.nodes, mass, inverse_mass);
  Real k = penalty_stiffness(spring.law, slaves.areas()[s], mass[node], master_mass, dt_penalty,
                             m_options.penalty_scale);
  k *= t.weight;
  spring.k = k;
  spring.acts = -t.gap - c.offset > 0.0;
}

void ContactEngine::set_interference(Index s, Real amount, Real base, Real duration) {
  const auto n = static_cast<std::size_t>(m_domain.slaves().size());
  if (m_interference.empty()) {
    m_interference.assign(n, Interference{});
    m_ramp_before.assign(n, 0.0);
    m_ramp_work.assign(n, 0.0);
  }
  Interference& ramp = m_interference[s];
  if (!(ramp.amount > 0.0) && amount > 0.0) ++m_ramping;
  if (ramp.amount > 0.0 && !(amount > 0.0)) --m_ramping;
  ramp = {amount, base, duration};
  m_constraints[s].offset = base + amount;
  m_constraints[s].offset_permanent = amount > 0.0 || base != 0.0;
}

void ContactEngine::set_rigid_bodies(std::vector<Index> node_body,
                                     std::vector<std::array<Real, 3>> body_translation_mass) {
  m_node_body = std::move(node_body);
  m_body_mass = std::move(body_translation_mass);
  m_body_row.assign(m_body_mass.size(), {0.0, 0.0, 0.0});
  m_body_factor.assign(m_body_mass.size(), 1.0);
}

void ContactEngine::cap_default_springs(Real dt_penalty, std::span<const Real> mass,
                                        std::span<const Real> inverse_mass) {
  const SlaveNodes& slaves = m_domain.slaves();
  const std::vector<ContactFace>& faces = m_domain.faces();
  const Index n_slave = slaves.size();
  auto touch_of = [&](Index j) -> const SlaveTouch& {
    return j % 2 == 0 ? m_touch[j / 2] : m_second_touch[j / 2];
  };
  auto counted = [&](const Spring& spring) {
    return spring.k > 0.0 && spring.acts && !(spring.law.pressure_slope > 0.0);
  };
  m_default_sum.reset(static_cast<Index>(mass.size()));
  bool any = false;
  for (Index j = 0; j < 2 * n_slave; ++j) {
    const Spring& spring = m_spring[j];
    if (!counted(spring)) continue;
    const SlaveTouch& t = touch_of(j);
    m_default_sum.add_spring(slaves.nodes()[j / 2], faces[t.face].nodes, t.shape, spring.k,
                             NO_INDEX, inverse_mass);
    any = true;
  }
  // The user's penalty scale raises every default spring, and the node budget with them.
  const Real budget =
      DEFAULT_PENALTY_NODE_BUDGET * m_options.penalty_scale / (dt_penalty * dt_penalty);
  // The rigid body a spring pushes (its slave node's or its face's), NO_INDEX: none.
  auto body_of = [&](Index j) {
    if (m_node_body.empty()) return NO_INDEX;
    const Index slave_body = m_node_body[slaves.nodes()[j / 2]];
    if (slave_body != NO_INDEX) return slave_body;
    return m_node_body[faces[touch_of(j).face].nodes[0]];
  };
  if (!m_body_mass.empty()) {
    for (auto& r : m_body_row) r = {0.0, 0.0, 0.0};
    for (Index j = 0; j < 2 * n_slave; ++j) {
      const Spring& spring = m_spring[j];
      if (!counted(spring)) continue;
      const Index b = body_of(j);
      if (b == NO_INDEX) continue;
      const Vec3& n = touch_of(j).normal;
      const Real spread = std::abs(n[0]) + std::abs(n[1]) + std::abs(n[2]);
      for (int d = 0; d < 3; ++d) m_body_row[b][d] += spring.k * std::abs(n[d]) * spread;
    }
    for (std::size_t b = 0; b < m_body_mass.size(); ++b) {
      Real largest = 0.0;
      for (int d = 0; d < 3; ++d)
        if (std::isfinite(m_body_mass[b][d]) && m_body_mass[b][d] > 0.0)
          largest = std::max(largest, m_body_row[b][d] / m_body_mass[b][d]);
      m_body_factor[b] = largest > budget ? budget / largest : 1.0;
    }
  }
  for (Index j = 0; j < 2 * n_slave; ++j) {
    Spring& spring = m_spring[j];
    ContactConstraint& c = j % 2 == 0 ? m_constraints[j / 2] : m_second[j / 2];
    Real factor = 1.0;
    if (any && counted(spring)) {
      const SlaveTouch& t = touch_of(j);
      Real largest = m_default_sum.row(slaves.nodes()[j / 2]) * inverse_mass[slaves.nodes()[j / 2]];
      for (int a = 0; a < 4; ++a)
        if (t.shape[a] > 0.0 && inverse_mass[faces[t.face].nodes[a]] > 0.0)
          largest = std::max(largest, m_default_sum.row(faces[t.face].nodes[a]) *
                                          inverse_mass[faces[t.face].nodes[a]]);
      if (largest > budget) factor = budget / largest;
      if (!m_body_mass.empty()) {
        const Index b = body_of(j);
        if (b != NO_INDEX) factor = std::min(factor, m_body_factor[b]);
      }
    }
    if (factor < 1.0) spring.k *= factor;
    // A default spring whose stiffness changes while loaded (its share of the node's budget,
    // the increment it is tied to as the elements are squashed, the master mass at a sliding
    // point) would hold another energy at the same depth than the motion put in, and give it
    // back as it opens: the offset moves so that the stored energy stays. Both ways, so that
    // the offset depends on the stiffness now, not on the path: a stiffness that goes up and
    // down again leaves it where it was (a softening spring's offset stops at zero).
    const bool user = spring.law.pressure_slope > 0.0;
    if (!user && spring.acts && c.stiffness > 0.0 && spring.k != c.stiffness &&
        !c.offset_permanent) {
      const Real excess = -c.gap - c.offset;
      c.offset = std::max(0.0, -c.gap - std::sqrt(c.stiffness / spring.k) * excess);
    }
    c.stiffness = !user && spring.acts ? spring.k : 0.0;
  }
}

Vec3 ContactEngine::spring_force(Index s, int side, ContactConstraint& c, const SlaveTouch& t,
                                 Real dt, Real dt_penalty, OutputStatus& status) {
  Spring& spring = m_spring[2 * s + side];
  spring.fn = 0.0;
  if (t.face == NO_INDEX) return Vec3::Zero();
  const Real k = spring.k;
  const InteractionLaw& law = spring.law;
  c.master_face = t.face;
  c.xi = t.xi;
  c.eta = t.eta;
  const Real fn = normal_contact_update(c, t.gap, k);
  spring.fn = fn;
  m_stored[s] += penalty_energy(t.gap, c.offset, k);
  Vec3 f = fn * t.normal;
  if (law.pressure_slope > 0.0) {
    // Counted while closed, or when the approach closes it within the look-ahead.
    const Real ahead =
        t.gap + PENALTY_LOOKAHEAD_INCREMENTS * dt_penalty * spring.v_rel.dot(t.normal);
    const bool acts = fn > 0.0 || penalty_force(ahead, c.offset, k) > 0.0;
    m_user_k[2 * s + side] = acts ? k : 0.0;
    m_user_law[2 * s + side] = spring.interaction;
  }
  if (law.friction > 0.0 && dt > 0.0) {
    const FrictionUpdate fr =
        friction_update(c.tangential_force, spring.v_rel, t.normal, fn, law.friction, k, dt);
    c.tangential_force = fr.force;
    (side == 0 ? m_dissipation : m_second_dissipation)[s] = fr.dissipation;
    if (k > 0.0) m_stored[s] += 0.5 * fr.force.dot(fr.force) / k;
    f += fr.force;
    if (fn > 0.0 && status != OutputStatus::Stick)
      status = fr.slipping ? OutputStatus::Slip : OutputStatus::Stick;
  } else {
    c.tangential_force = Vec3::Zero();
    if (fn > 0.0 && status == OutputStatus::Open) status = OutputStatus::Slip;
  }
  return f;
}

PenaltyLimit ContactEngine::estimate_penalty_limit(std::span<const Real> inverse_mass) const {
  PenaltyLimit out;
  if (!m_user_stiffness) return out;
  const SlaveNodes& slaves = m_domain.slaves();
  for (Index s = 0; s < slaves.size(); ++s) {
    if (m_domain.slave_rigid(s)) continue;
    const Index node = slaves.nodes()[s];
    for (Index ia = 0; ia < static_cast<Index>(m_laws.size()); ++ia) {
      if (!(m_laws[ia].pressure_slope > 0.0) || !m_domain.may_use(s, ia)) continue;
      const Real k = linear_penalty_stiffness(m_laws[ia].pressure_slope, slaves.areas()[s]);
      const Real w = 2.0 * k * inverse_mass[node];
      if (w > out.omega_sq) out = {w, node, ia};
    }
  }
  return out;
}

}  // namespace xpl::contact
