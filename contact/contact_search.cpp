// The search half of ContactEngine (contact_engine.hpp): the admissible faces of a slave node
// and the nearest of them (with the touch on its other side), and the probes of the
// start-of-step passes (the lists it walks: contact_lists.cpp).
#include <algorithm>
#include <cmath>
#include <limits>

#include <omp.h>

#include "common/parallel_error.hpp"
#include "contact/closest_point.hpp"
#include "contact/contact_engine.hpp"
#include "contact/parallel_size.hpp"

namespace xpl::contact {

namespace {

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

/// The nearest penetrated touch among `listed` on the other side of a pinched node from `best`
/// (normals within PINCH_COSINE); `touch(f, t, d)` is admissible() of face f for the node.
template <class Touch>
SlaveTouch other_side_among(std::span<const Index> listed, const SlaveTouch& best, Touch&& touch) {
  SlaveTouch second, candidate;
  Real distance = 0.0, second_distance = std::numeric_limits<Real>::max();
  for (Index f : listed)
    if (touch(f, candidate, distance) && candidate.gap < 0.0 && candidate.face != best.face &&
        candidate.normal.dot(best.normal) < PINCH_COSINE && distance < second_distance) {
      second_distance = distance;
      second = candidate;
    }
  return second;
}

}  // namespace

bool ContactEngine::admissible(const SlaveView& v, Index f, const NodalVectors& position,
                               std::span<const Real> node_thickness, SlaveTouch& out,
                               Real& distance, Real nearer_than) const {
  const std::vector<ContactFace>& faces = m_domain.faces();
  const Index s = v.slot;
  const ContactFace* held = v.held;
  const bool double_sided = v.double_sided;
  // The other side of the shell it is held on: only round the edge (below).
  const bool round_edges = double_sided && m_updated;
  const bool other_side = held != nullptr && faces[f].shell && faces[f].element == held->element &&
                          faces[f].face != held->face;
  if (other_side && !round_edges) return false;
  if (!v.listed && never_admissible(v, f)) return false;
  Index pair = NO_INDEX;
  const Real w = m_domain.weight(s, f, pair);
  if (w == 0.0) return false;
  FaceGeometry local;
  FaceGeometry& geometry = face_geometry(f, position, node_thickness, v.faces, local);
  const Vec3(&corner)[4] = geometry.corner;
  const Vec3& n_f = geometry.normal;
  const Real n_len = geometry.normal_len;
  if (!(n_len > 0.0)) return false;
  // A shell node is double sided (either orientation), and one on a free edge may touch a
  // face edge-on (a tube end on a plate). A point node has no orientation: any face.
  const Real cosine = v.normal.dot(n_f) / n_len;
  if (!v.point_node && (double_sided ? !v.free_edge && std::abs(cosine) < OPPOSING_COSINE
                                     : cosine > -OPPOSING_COSINE))
    return false;
  const Real half_t = v.half_t;
  Real depth = faces[f].shell ? geometry.shell_depth : m_domain.face_depth(f);
  const bool kept_side = held != nullptr && faces[f].shell && faces[f].element == held->element;
  if (f == v.continuing) depth *= 2.0;  // contact at speed (file comment)
  // Beside its edges a shell face is round (below): a node there is nearer to it, and touches
  // it sooner, by at most the largest half thickness of its corners.
  const bool round_face = round_edges && faces[f].shell;
  // A node certainly behind the mid-surface of a round face (along the face normal) is on the
  // other side's half of every point of its round edge, which the test below rejects: only
  // the face's interior can hold it, and the other side of its held shell not even that.
  bool behind = false;
  if (round_face || (!kept_side && m_try_skip)) face_bounds(f, geometry);
  if (round_face) {
    behind = behind_mid_surface(geometry.mid_bounds, v.point, geometry.unit);
    if (other_side && behind) return false;
  }
  if (!kept_side && m_try_skip) {
    const Real round = round_face ? geometry.round : 0.0;
    if (out_of_reach(geometry.bounds, geometry.unit, v.point, depth + half_t + v.allowance, half_t,
                     m_broad.margin(), nearer_than, round_face ? &geometry.mid_bounds : nullptr,
                     behind, round))
      return false;
  }
  const QuadStart* start = nullptr;
  if (v.warm != nullptr)
    for (int k = 0; k < v.warm->count && start == nullptr; ++k)
      if (v.warm->kept[k].face == f) start = &v.warm->kept[k].at;
  const ClosestPoint cp = closest_point_on_quad(corner, v.point, start);
  if (v.next != nullptr) v.next->keep(f, cp.xi, cp.eta);
  if (other_side && cp.region == QuadRegion::Interior) return false;
  Real gap = cp.gap - half_t;
  Vec3 normal = cp.normal;
  Real reach_distance = cp.distance;
  // Beside a shell face's edge or corner, a shell node touches the wall's round edge (file
  // comment): the points within half the thickness of the mid-surface's edge, each side of
  // the wall owning the half of the round on its side. The gap is the distance to the
  // mid-surface edge less both half thicknesses and the normal points from the edge to the
  // node, so a node coming at the edge side-on (layers crumpled flat on a plate sliding into
  // each other) is pushed back from its first touch, where the gap along the face normal took
  // it in up to a thickness deep at once. Not in an engine's first update, which seeds the
  // overclosures by the rule below (C2-C7).
  if (cp.region != QuadRegion::Interior && round_face) {
    Vec3 mid = Vec3::Zero();
    Real radius = 0.0;
    for (int a = 0; a < 4; ++a) {
      mid += cp.weights[a] * geometry.mid[a];
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
    // The seeds of an engine's first update: beside a flat or convex edge (contact_edges.cpp).
    if (!m_updated && beside_next_face(f, corner, n_f, cp, v.point, std::sqrt(lateral_sq), position,
                                       node_thickness))
      return false;
  }
  if (!kept_side && -gap > depth + half_t + v.allowance) return false;
  out = {f, pair, w, gap, normal, cp.weights, cp.xi, cp.eta};
  distance = reach_distance;
  return true;
}

ContactEngine::FaceGeometry& ContactEngine::face_geometry(Index f, const NodalVectors& position,
                                                          std::span<const Real> node_thickness,
                                                          FaceCache* cache,
                                                          FaceGeometry& local) const {
  if (cache != nullptr && cache->stamp[f] == cache->current) return cache->geometry[f];
  FaceGeometry& g = cache != nullptr ? cache->geometry[f] : local;
  const ContactFace& face = m_domain.faces()[f];
  face_corners(face, position, node_thickness, g.corner);
  g.bounds_ready = false;
  g.normal = (g.corner[2] - g.corner[0]).cross(g.corner[3] - g.corner[1]);
  g.normal_len = std::sqrt(g.normal.dot(g.normal));
  // The unit normal is read by the reach test (m_try_skip) and a round face's behind test only.
  if (face.shell || m_try_skip) g.unit = g.normal / g.normal_len;
  g.shell_depth = 0.0;
  g.round = 0.0;
  if (face.shell) {
    Real t = 0.0;
    for (Index c : face.nodes) {
      t += node_thickness_of(node_thickness, c);
      g.round = std::max(g.round, 0.5 * node_thickness_of(node_thickness, c));
    }
    g.shell_depth = DEPTH_LIMIT_FRACTION * 0.25 * t;  // of the mean thickness
    for (int a = 0; a < 4; ++a) g.mid[a] = node_point(position, face.nodes[a]);
  }
  if (cache != nullptr) cache->stamp[f] = cache->current;
  return g;
}

void ContactEngine::face_bounds(Index f, FaceGeometry& g) const {
  if (g.bounds_ready) return;
  bound_corners(g.corner, g.unit, g.bounds);
  if (m_domain.faces()[f].shell) bound_corners(g.mid, g.unit, g.mid_bounds);
  g.bounds_ready = true;
}

void ContactEngine::search(const NodalVectors& position, std::span<const Real> node_thickness) {
  const auto n_live = static_cast<Index>(m_sleep.searched.size());
  ParallelErrors errors;
  const bool on_team = static_cast<Index>(m_listed.size()) >= PARALLEL_MIN_CANDIDATES;
  // Each thread works out a face's geometry once for all the slots it searches that list the
  // face (its own cache: no writes shared between threads; the same numbers as per slot).
  const std::size_t n_caches =
      on_team ? static_cast<std::size_t>(std::max(1, omp_get_max_threads())) : 1;
  if (m_face_caches.size() < n_caches) m_face_caches.resize(n_caches);
  const std::size_t n_faces = m_domain.faces().size();
  for (std::size_t t = 0; t < n_caches; ++t) {
    FaceCache& cache = m_face_caches[t];
    if (cache.stamp.size() != n_faces || cache.current == UINT32_MAX) {
      cache.geometry.assign(n_faces, FaceGeometry{});
      cache.stamp.assign(n_faces, 0);
      cache.current = 0;
    }
    ++cache.current;
  }
#pragma omp parallel for schedule(dynamic, 256) if (on_team)
  for (Index k = 0; k < n_live; ++k) {
    const Index s = m_sleep.searched[k];  // this process's (build_visits())
    errors.guard(ParallelSite::ContactSearch, s, [&] {
      SlaveTouch best;
      SlaveTouch second;
      WarmStarts next;
      m_lost_depth[s] = 0.0;
      m_passed_depth[s] = 0.0;
      m_behind_depth[s] = 0.0;
      if (!listed_faces(s).empty() ||
          (m_updated && m_constraints[s].status == ContactStatus::Closed)) {
        Real best_distance = std::numeric_limits<Real>::max();
        SlaveTouch candidate;
        Real distance = 0.0;
        // The nearest penetrated faces, for the touch on the other side (file comment).
        std::array<SlaveTouch, PENETRATED_KEPT> penetrated;
        std::array<Real, PENETRATED_KEPT> penetrated_distance{};
        int n_penetrated = 0;
        int n_seen = 0;
        SlaveView view = slave_view(s, position, node_thickness, false);
        if (m_updated) view.warm = &m_warm[s];
        view.next = &next;
        view.faces = &m_face_caches[static_cast<std::size_t>(omp_get_thread_num())];
        const std::span<const Index> listed = listed_faces(s);
        // The face pressed last increment, when no static rule rejects it (the listed faces
        // have been sifted by never_admissible(); a solid face has no own-shell test).
        const Index continuing =
            view.continuing != NO_INDEX && !never_admissible(view, view.continuing)
                ? view.continuing
                : NO_INDEX;
        // The face of last increment's touch first, when the loop below considers it: its
        // distance bounds that of the nearest face from the start, so that admissible() skips
        // the closest points of the faces beyond it (same result, the loop still takes the
        // faces in order; the touch found here is reused when the loop reaches its face).
        const Index previous = m_constraints[s].master_face;
        SlaveTouch previous_touch;
        Real previous_distance = 0.0;
        bool previous_known = false, previous_admissible = false;
        if (m_try_skip && previous != NO_INDEX &&
            (previous == continuing ||
             std::binary_search(listed.begin(), listed.end(), previous))) {
          previous_known = true;
          previous_admissible = admissible(view, previous, position, node_thickness, previous_touch,
                                           previous_distance);
        }
        const Real bound =
            previous_admissible ? previous_distance : std::numeric_limits<Real>::max();
        SlaveTouch held_touch;  // on the held shell face, pressed in over its interior
        const auto consider = [&](Index f) {
          if (previous_known && f == previous) {
            if (!previous_admissible) return;
            candidate = previous_touch;
            distance = previous_distance;
          } else if (!admissible(view, f, position, node_thickness, candidate, distance,
                                 std::min(best_distance, bound))) {
            return;
          }
          if (distance < best_distance) {
            best_distance = distance;
            best = candidate;
          }
          if (candidate.gap < 0.0) {
            keep_nearest(penetrated, penetrated_distance, n_penetrated, candidate, distance);
            ++n_seen;
            if (view.held == &m_domain.faces()[f] && over_interior(candidate))
              held_touch = candidate;
          }
        };
        for (Index f : listed) consider(f);
        // The face pressed last increment, deeper than the broad phase's slab (contact at speed).
        if (continuing != NO_INDEX && !std::binary_search(listed.begin(), listed.end(), continuing))
          consider(continuing);
        keep_held_side(view, held_touch, position, best);
        m_lost_depth[s] = best.face == NO_INDEX ? released_depth(view, position) : 0.0;
        m_passed_depth[s] = passed_depth(view, best, position);
        m_behind_depth[s] = behind_depth(view, best, node_thickness);
        // Pinched: penetrating its nearest face and one on its other side. A node outside its
        // nearest face is not pinched, however deep it lies behind a face across its own body
        // (a corner node of a squashed block behind the block's far side).
        const bool pinched = best.face != NO_INDEX && best.gap < 0.0;
        if (pinched) second = opposite_touch(best, penetrated, n_penetrated);
        // More penetrated faces than kept (a node under the shared corner of many faces on both
        // sides): look for the other side among all of them.
        if (pinched && second.face == NO_INDEX && n_seen > PENETRATED_KEPT)
          second = other_side_among(listed, best, [&](Index f, SlaveTouch& t, Real& d) {
            return admissible(view, f, position, node_thickness, t, d);
          });
        if (pinched && second.face == NO_INDEX && view.double_sided && m_updated)
          second = corner_touch(best, penetrated, n_penetrated, m_domain.faces());
        if (m_sleep.asleep[s] == 0) record_sleep(view, best, second, position, node_thickness);
      }
      m_touch[s] = best;
      m_second_touch[s] = second;
      if (next.count > 0 || m_warm[s].count > 0) m_warm[s] = next;
    });
  }
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

}  // namespace xpl::contact
