// Lower bounds of the node-to-face distance for the search's reach test (face_bounds.hpp).
#include "contact/face_bounds.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace xpl::contact {

namespace {

/// How far (m, squared) from the node an admissible penetration can lie: a touch admissible()
/// keeps with gap < 0 and −gap ≤ `limit` (depth + half thickness + allowance, m; `half_t` the
/// node's half thickness, m) is at most max(half_t, √(limit² + (limit − half_t)²)) away.
/// Inside the face region, or beside it on the outside, the distance is |gap + half_t| ≤
/// max(half_t, limit − half_t); beside it below the face plane the lateral test bounds the
/// offset beyond the edge by |gap|.
Real penetration_reach_sq(Real limit, Real half_t) {
  return std::max(half_t * half_t, limit * limit + (limit - half_t) * (limit - half_t));
}

}  // namespace

void bound_corners(const Vec3 corner[4], const Vec3& unit, CornerBounds& out) {
  out.extent = 0.0;
  out.scale = 0.0;
  for (int d = 0; d < 3; ++d) {
    out.lo[d] = std::min({corner[0][d], corner[1][d], corner[2][d], corner[3][d]});
    out.hi[d] = std::max({corner[0][d], corner[1][d], corner[2][d], corner[3][d]});
    out.extent = std::max(out.extent, out.hi[d] - out.lo[d]);
    for (int a = 0; a < 4; ++a) out.scale = std::max(out.scale, std::abs(corner[a][d]));
  }
  Real lo = std::numeric_limits<Real>::infinity(), hi = -lo;
  for (int a = 0; a < 4; ++a) {
    const Real h = corner[a].dot(unit);
    lo = std::min(lo, h);
    hi = std::max(hi, h);
  }
  out.along_lo = lo;
  out.along_hi = hi;
}

/// Every point of the face is a convex combination of its corners (the bilinear weights are
/// ≥ 0 and sum to 1 on the square), so it lies in their box and between the planes normal to
/// `unit` (a unit vector) through the lowest and highest of them; the distance to the box and
/// that to the slab between those planes both bound the distance from below. Less a relative
/// slack of 1e-9 for the rounding of the closest point, so that a test against it changes no
/// bit of the search.
Real distance_below(const CornerBounds& b, const Vec3& p, const Vec3& unit) {
  Real out_sq = 0.0, scale = 0.0;
  for (int d = 0; d < 3; ++d) {
    const Real out = std::max({b.lo[d] - p[d], p[d] - b.hi[d], 0.0});
    out_sq += out * out;
    scale = std::max(scale, std::abs(p[d]));
  }
  const Real height = p.dot(unit);
  const Real bound =
      std::max(std::sqrt(out_sq), std::max({b.along_lo - height, height - b.along_hi, 0.0}));
  return bound - 1e-9 * (bound + b.extent) - 1e-12 * scale;
}

/// For every point m of the mid-surface (a convex combination of its corners) then
/// (p − m)·unit < 0.
bool behind_mid_surface(const CornerBounds& mid, const Vec3& p, const Vec3& unit) {
  Real scale = std::max(std::abs(p.dot(unit)), mid.scale);
  for (int d = 0; d < 3; ++d) scale = std::max(scale, std::abs(p[d]));
  return p.dot(unit) < mid.along_lo - 1e-9 * mid.extent - 1e-12 * scale;
}

/// All of the face farther than `nearer_than` (m), so not the nearest, and than any admissible
/// penetration can lie, so not a penetrated one (what the search does with such a face is
/// nothing). `limit` (m): the deepest penetration admissible() keeps (depth + half thickness
/// `half_t` + allowance). Tried only when that reach is shorter than the search `margin` (m):
/// shells, about a thickness against a margin of a third of a face; a solid face's depth
/// reaches beyond it, and the test would only cost. A round face (admissible()) passes its
/// mid-surface bounds `mid` (else null), whether the node is `behind` that mid-surface, and
/// `round` (m), the largest half thickness of its corners.
bool out_of_reach(const CornerBounds& corner, const Vec3& unit, const Vec3& p, Real limit,
                  Real half_t, Real margin, Real nearer_than, const CornerBounds* mid, bool behind,
                  Real round) {
  // How far from the node an admissible penetration can lie: inside the face region, or
  // beside it on a round edge or on the outside, the distance is |gap + half_t| ≤
  // max(half_t, limit − half_t); beside a square edge below the face plane the lateral
  // test bounds the offset beyond the edge by |gap| (penetration_reach_sq).
  const Real reach = mid != nullptr ? std::max(half_t, limit - half_t)
                                    : std::sqrt(penetration_reach_sq(limit, half_t));
  if (!(reach < margin)) return false;
  Real below = distance_below(corner, p, unit);
  if (mid != nullptr && !behind) {
    // Beside the edge the distance is |reach − radius| to the mid-surface point, at least
    // the mid-surface's distance less the largest half thickness of its corners.
    below = std::min(below, distance_below(*mid, p, unit) - round);
  }
  return below > nearer_than && below > reach;
}

}  // namespace xpl::contact
