#pragma once
/// \file Narrow phase of node-to-face contact: the closest point on a bilinear face (stage 3).
///
/// A face x(ξ, η) = Σ N_I(ξ, η) x_I, (ξ, η) ∈ [−1, 1]², corners I = 0..3 at (−1, −1), (1, −1),
/// (1, 1), (−1, 1), N_I = ¼ (1 + ξ_I ξ)(1 + η_I η). The face normal n(ξ, η) = x_ξ × x_η / |…|
/// points to the outside (ContactFace corner order).
///
/// Contact normal and gap, chosen so that the contact force never jumps:
/// - closest point inside the face: n(ξ, η) and gap = (p − c)·n, which is ±|p − c| there;
/// - closest point on an edge or corner, node outside ((p − c)·n(c) ≥ 0): the direction from c
///   to the node, gap = |p − c|. Inside the face region that direction is n, so the normal
///   turns smoothly around the edge instead of switching between the normals of two faces;
/// - closest point on an edge or corner, node inside ((p − c)·n(c) < 0): n(c) and
///   gap = (p − c)·n(c), so the penetration grows from zero as the node sinks below the
///   face plane beside the face.
/// Where the two edge cases meet (node in the face plane beside an edge) the gap jumps from
/// |p − c| > 0 to 0, both of which mean "no force": the penalty force k·max(0, −gap) is
/// continuous everywhere. The region is reported so that callers can leave out nodes whose
/// closest point is on a perimeter edge (SPEC C9).

#include <array>
#include <cmath>
#include <cstdint>

#include "contact/contact_faces.hpp"

namespace xpl::contact {

/// Where on the face the closest point lies.
enum class QuadRegion : std::uint8_t {
  Interior,  ///< |ξ| < 1 and |η| < 1
  Edge,      ///< on edge `feature` (corner feature → feature + 1), not at its ends
  Corner,    ///< at corner `feature`
};

/// Result of the narrow phase for one point and one face.
struct ClosestPoint {
  Real xi = 0.0, eta = 0.0;       ///< face coordinates of the closest point, in [−1, 1]
  Vec3 point = Vec3::Zero();      ///< closest point c = x(ξ, η), m
  Real distance = 0.0;            ///< |p − c|, m
  Real gap = 0.0;                 ///< signed gap, m: > 0 on the side the normal points to
  Vec3 normal = Vec3::UnitZ();    ///< unit contact normal, from the face towards outside
  std::array<Real, 4> weights{};  ///< N_I(ξ, η): shares of the reaction on the corners
  QuadRegion region = QuadRegion::Interior;
  int feature = -1;  ///< edge or corner number (0..3), −1 in the interior
};

/// Bilinear shape functions N_I(ξ, η), I = 0..3.
std::array<Real, 4> quad_shape(Real xi, Real eta);

/// The point x(ξ, η) of the face with these corners, m.
Vec3 quad_point(const Vec3 corner[4], Real xi, Real eta);

/// Unit normal x_ξ × x_η at (ξ, η); where that vanishes (a collapsed corner) the normal of
/// the diagonals (x2 − x0) × (x3 − x1). Zero for a face collapsed to a line or point.
Vec3 quad_normal(const Vec3 corner[4], Real xi, Real eta);

/// Face coordinates of a Newton start (closest_point_on_quad).
struct QuadStart {
  Real xi = 0.0, eta = 0.0;
};

/// The closest point on the face with corners `corner` (m) to `p` (m).
///
/// Newton on (ξ, η) for the squared distance, exact Hessian when it is positive definite and
/// Gauss–Newton otherwise, iterates projected onto [−1, 1]², started at the centre (and, on a
/// strongly warped face, at the four quadrant centres too). A stationary point strictly
/// inside the square is compared with the closest points of the four straight edges
/// (segments, corners included), and the nearest of them wins; so a projection leaving the
/// square, a non-converged iteration or a warped face far from the point still give the right
/// answer. No allocation; safe to call from any number of threads.
///
/// `warm` (may be null): where the closest point on this face lay last increment for the same
/// node. On a strongly warped face it replaces the five starts by one: Newton from `warm`; an
/// interior stationary point it finds is compared with the edges as above; when it ends on the
/// boundary from a start on the boundary the edges' point is taken (the node stays beside the
/// face); only a start inside the face that fails falls back on the five starts. The
/// stationary point is the one the five starts find on all but a few faces where a fold makes
/// several (contact tests, crash tube), in far fewer Newton iterations; its last bits depend
/// on the start.
ClosestPoint closest_point_on_quad(const Vec3 corner[4], const Vec3& p,
                                   const QuadStart* warm = nullptr);

/// What the contact search found for one slave node: the nearest admissible face and the
/// closest point on it (ContactEngine).
struct SlaveTouch {
  Index face = NO_INDEX;        ///< contact face, NO_INDEX when none is admissible
  Index pair = NO_INDEX;        ///< included pair that allows the touch (per-pair output)
  Real weight = 0.0;            ///< view weight w (½ balanced, 1 one-sided or rigid master)
  Real gap = 0.0;               ///< signed gap, m (negative: penetration); shell nodes less t/2
  Vec3 normal = Vec3::Zero();   ///< unit contact normal, from the face towards the node
  std::array<Real, 4> shape{};  ///< weights N_I of the face corners at the closest point
  Real xi = 0.0, eta = 0.0;     ///< face coordinates of the closest point
};

/// Whether a touch's closest point lies over its face's interior (not beside an edge).
inline bool over_interior(const SlaveTouch& t) {
  return std::abs(t.xi) < 1.0 && std::abs(t.eta) < 1.0;
}

/// Where the closest point of a face lay for a slave node (face, coordinates): last
/// increment's, a Newton start on a strongly warped face (closest_point_on_quad).
struct WarmStart {
  Index face = NO_INDEX;
  QuadStart at;
};

/// The closest points of the first WARM_KEPT faces a slot's search evaluates (ContactEngine).
struct WarmStarts {
  static constexpr int WARM_KEPT = 4;
  std::array<WarmStart, WARM_KEPT> kept{};
  int count = 0;
  /// Keeps face f's closest point (ξ, η) unless f is there already or the list is full.
  void keep(Index f, Real xi, Real eta) {
    for (int k = 0; k < count; ++k)
      if (kept[k].face == f) return;
    if (count < WARM_KEPT) kept[count++] = {f, {xi, eta}};
  }
};

}  // namespace xpl::contact
