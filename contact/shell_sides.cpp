// ContactEngine::passed_depth (contact_engine.hpp): whether a node held on one side of a
// shell has passed through it (issue 32 item 4, SPEC C16).
//
// A node pressed on one side of a shell is held there: that element's other side may not take
// it (admissible(), side memory). A node the penalty cannot stop within half the thickness (a
// block's corner between the nodes of a coarse plate) goes behind the mid-surface; once no
// face holds it on its side (it slid onto the next element, deeper than a new touch's limit
// there, or only the wall's other side would take it) and it lies behind the mid-surface of the
// held element or of the elements that continue that wall, over their interior, it has passed
// through, and the run must not go on as if the bodies were where they belong (ContactStage
// ends it). Sweep scenes 116 and 153 ended "completed" that way.
#include <algorithm>
#include <cmath>

#include "contact/closest_point.hpp"
#include "contact/contact_engine.hpp"
#include "contact/contact_options.hpp"

namespace xpl::contact {

namespace {

/// Where shell face f lies for a node held on shell face `held` (unit normal `held_normal`):
/// +1 on the held side of the wall (the held face, or a face of a shell element next to it,
/// sharing a corner, that continues the wall within 45° and faces the same way), −1 on the
/// wall's other side, 0 when f is not part of the held wall (another element, or one folded
/// back over the held one).
int shell_side(const std::vector<ContactFace>& faces, const ContactFace& held,
               const Vec3& held_normal, Index f, const NodalVectors& position) {
  const ContactFace& face = faces[f];
  if (face.element == held.element) return face.face == held.face ? 1 : -1;
  Vec3 shared = Vec3::Zero();
  int n_shared = 0;
  for (Index a : face.nodes)
    for (Index b : held.nodes)
      if (a == b) {
        shared += node_point(position, a);
        ++n_shared;
      }
  if (n_shared == 0) return 0;
  shared /= static_cast<Real>(n_shared);
  Vec3 centre_held = Vec3::Zero(), centre = Vec3::Zero(), corner[4];
  for (int a = 0; a < 4; ++a) {
    corner[a] = node_point(position, face.nodes[a]);
    centre += 0.25 * corner[a];
    centre_held += 0.25 * node_point(position, held.nodes[a]);
  }
  // Folded back over the held element (more than 90°): not the wall's continuation.
  if (!((centre - shared).dot(shared - centre_held) > 0.0)) return 0;
  const Vec3 n = (corner[2] - corner[0]).cross(corner[3] - corner[1]);
  const Real n_len = std::sqrt(n.dot(n));
  if (!(n_len > 0.0)) return 0;
  const Real cosine = n.dot(held_normal) / n_len;
  if (cosine > WALL_COSINE) return 1;
  return cosine < -WALL_COSINE ? -1 : 0;
}

/// The unit normal of shell face `face` (its diagonals' cross product) into `unit`; false where
/// the face has collapsed.
bool unit_normal(const ContactFace& face, const NodalVectors& position, Vec3& unit) {
  Vec3 corner[4];
  face_corners(face, position, {}, corner);
  const Vec3 n = (corner[2] - corner[0]).cross(corner[3] - corner[1]);
  const Real n_len = std::sqrt(n.dot(n));
  if (!(n_len > 0.0)) return false;
  unit = n / n_len;
  return true;
}

}  // namespace

Real ContactEngine::passed_depth(const SlaveView& v, const SlaveTouch& touch,
                                 const NodalVectors& position) const {
  if (v.held == nullptr || !m_updated) return 0.0;
  const Index touched = touch.face;
  const std::vector<ContactFace>& faces = m_domain.faces();
  const ContactFace& held = *v.held;
  // Still held on the same face, or by a solid face: nothing to measure (most held nodes, every
  // increment), before the held face's normal is computed.
  if (touched != NO_INDEX && (!faces[touched].shell || touched == &held - faces.data())) return 0.0;
  Vec3 held_normal;
  if (!unit_normal(held, position, held_normal)) return 0.0;
  // Pressed on another shell face on this wall's side, or on a face that is not part of the
  // wall: held. An open touch holds nothing (sweep scene 6623: a rigid block's corner, pressed
  // 0.27 mm behind a thin plate's mid-surface, slid past its face's edge; the open touch of the
  // next element's corner dropped its side memory and the run completed with it through).
  if (touched != NO_INDEX && touch.gap < 0.0 &&
      shell_side(faces, held, held_normal, touched, position) >= 0)
    return 0.0;
  // Behind the mid-surface of the held face or of the wall's next elements, over its interior.
  Real depth = 0.0;
  const auto behind = [&](Index f) {
    Vec3 corner[4];
    face_corners(faces[f], position, {}, corner);
    const ClosestPoint cp = closest_point_on_quad(corner, v.point);
    if (cp.region == QuadRegion::Interior && cp.gap < 0.0) depth = std::max(depth, -cp.gap);
  };
  behind(static_cast<Index>(&held - faces.data()));
  for (Index f : m_broad.candidates(v.slot))
    if (faces[f].shell && faces[f].element != held.element &&
        shell_side(faces, held, held_normal, f, position) > 0)
      behind(f);
  return depth;
}

void ContactEngine::keep_held_side(const SlaveView& v, const SlaveTouch& held,
                                   const NodalVectors& position, SlaveTouch& best) const {
  // A node pressed into the shell face it is held on, over that face's interior, stays there
  // whatever open touch, or touch of the wall's other side, lies nearer: driven deep at speed,
  // it is nearer to the round edge of the next element than to the face it went into, and an
  // open touch there would drop its side memory, and the other side's would push it on through
  // (sweep scene 5163: a box corner through a plate at 214 m/s, the run "completed").
  if (held.face == NO_INDEX || best.face == held.face) return;
  if (best.face == NO_INDEX || best.gap >= 0.0) {
    best = held;
    return;
  }
  // A touch of the held wall's other side (that face's other side, or the other side of an
  // element continuing the wall).
  const std::vector<ContactFace>& faces = m_domain.faces();
  if (!faces[best.face].shell) return;
  Vec3 held_normal;
  if (unit_normal(*v.held, position, held_normal) &&
      shell_side(faces, *v.held, held_normal, best.face, position) < 0)
    best = held;
}

Real ContactEngine::behind_depth(const SlaveView& v, const SlaveTouch& touch,
                                 std::span<const Real> node_thickness) const {
  if (touch.face == NO_INDEX) return 0.0;
  // Over the face's interior only (beside its edge the gap is a distance, not a depth).
  if (!over_interior(touch)) return 0.0;
  const ContactFace& face = m_domain.faces()[touch.face];
  if (!face.shell) {
    // A solid face: the bodies overlap (beyond a clearance's allowance) by more than half the
    // element behind the face, the depth down to which a new touch is found at all.
    const Real overlap = -touch.gap - v.allowance;
    return overlap > m_domain.face_depth(touch.face) ? overlap : 0.0;
  }
  if (v.held == nullptr || face.element != v.held->element) return 0.0;
  Real half_t = 0.0;
  for (int a = 0; a < 4; ++a)
    half_t += touch.shape[a] * 0.5 * node_thickness_of(node_thickness, face.nodes[a]);
  // The node's own mid-surface against the wall's: the touch's gap is from the wall's side
  // (half its thickness out) less the node's own half thickness.
  const Real from_mid = touch.gap + v.half_t + half_t;
  return from_mid < 0.0 ? -from_mid : 0.0;
}

}  // namespace xpl::contact
