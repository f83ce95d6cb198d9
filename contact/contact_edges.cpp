// ContactEngine::beside_next_face (contact_engine.hpp): whether a node behind a hex face's
// plane but beside its edge belongs to the surface's next face there, or is outside the body.
//
// Used in an engine's first update only (the overclosures of C2-C7). Beyond an edge where the
// surface goes on flat or turns away (convex) the node is the next face's or outside the body,
// however far behind this face's plane: an S4R box's node 5 mm above a slab's top face and
// 10 mm in from its side face was taken 10 mm deep behind the side face (of the top layer's
// element, and of the layers' below) at t = 0, an overclosure that was not there, and its push
// inverted an element (stress sweep scenes 86, 120, 199; 7272, 0.22 mm above the top face and
// 1.5 mm in from the side, within the rim's tolerance). Not later: in the run, admissible()'s
// rule (offset beyond the edge below the penetration) pushes a node beside a convex edge out
// smoothly (a puck's facets over a fold: dropping it there tripled the contact force's peak).
#include <cmath>

#include "contact/closest_point.hpp"
#include "contact/contact_engine.hpp"
#include "contact/contact_options.hpp"

namespace xpl::contact {

bool ContactEngine::beside_next_face(Index f, const Vec3 (&corner)[4], const Vec3& n_f,
                                     const ClosestPoint& cp, const Vec3& point, Real lateral,
                                     const NodalVectors& position,
                                     std::span<const Real> node_thickness) const {
  if (m_domain.faces()[f].shell) return false;
  // In front of the next face by this much, the node is outside the body, not at the edge (a
  // rim node level with the next face's plane to round-off, or pressed a little out of it by
  // Poisson's ratio, still touches this face).
  const Real outside = OUTSIDE_EDGE_FRACTION * m_domain.face_depth(f) / DEPTH_LIMIT_FRACTION;
  // The edge of the closest point, or both edges at its corner.
  const int edges[2] = {cp.feature, cp.region == QuadRegion::Corner ? (cp.feature + 3) % 4 : -1};
  for (const int e : edges) {
    if (e < 0) continue;
    const Index g = m_domain.face_across(f, e);
    if (g == NO_INDEX) continue;
    Vec3 next[4];
    face_corners(m_domain.faces()[g], position, node_thickness, next);
    const Vec3 centre = 0.25 * (next[0] + next[1] + next[2] + next[3]);
    const Vec3 towards = centre - 0.5 * (corner[e] + corner[(e + 1) % 4]);
    const Real rise = towards.dot(n_f) / std::sqrt(towards.dot(towards) * n_f.dot(n_f));
    // Concave: the next face rises in front of this one's plane; a node pushed into the
    // corner is this face's while its offset is below its penetration (admissible()).
    if (rise > CONCAVE_EDGE_SINE) continue;
    // Flat: the node beside the edge lies over the next face, which takes it (level with
    // the edge, within the same distance, both faces keep it: a node over a mesh line).
    if (rise >= -CONCAVE_EDGE_SINE) {
      if (lateral > outside) return true;
      continue;
    }
    // Convex: outside the body in front of the next face's plane; by more than `outside` at
    // the rim, by any amount where the node lies deeper than that behind this face's plane
    // (it is over the next face, not at the edge: sweep scene 7272, an S4R box's node 0.22 mm
    // above a slab's top face and 1.5 mm in from its side face, seeded 1.5 mm deep behind the
    // side face; the push inverted a box element of a 10 m/s impact).
    const Vec3 n_g = (next[2] - next[0]).cross(next[3] - next[1]);
    const Real n_g_len = std::sqrt(n_g.dot(n_g));
    if (!(n_g_len > 0.0)) continue;
    const Real front = (point - centre).dot(n_g) / n_g_len;
    if (front > outside || (front > 0.0 && -cp.gap > outside)) return true;
  }
  return false;
}

}  // namespace xpl::contact
