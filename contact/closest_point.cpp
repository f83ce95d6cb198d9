#include "contact/closest_point.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

namespace xpl::contact {

namespace {

constexpr Real CORNER_XI[4] = {-1.0, 1.0, 1.0, -1.0};
constexpr Real CORNER_ETA[4] = {-1.0, -1.0, 1.0, 1.0};
constexpr int MAX_NEWTON_ITERATIONS = 30;
/// Newton stops when a step moves (ξ, η) by less than this (the coordinates are O(1)).
constexpr Real NEWTON_STEP_TOLERANCE = 1e-13;
/// Warp |a3·n| / √|a1 × a2| (out-of-plane twist over the in-plane half size, n the unit
/// centre normal) above which a face gets Newton starts in its four quadrants as well as at
/// its centre: a 2 % twist.
constexpr Real STRONG_WARP = 0.02;
/// Safety factor of the convexity test (convex_on_square) against rounding.
constexpr Real CONVEX_MARGIN = 2.0;
/// Relative slack of convex_on_square_sharp against rounding (its terms are sums of a few
/// products, each rounded to about 1e-16 of the largest).
constexpr Real CONVEX_SLACK = 1e-9;
/// A boundary point is the minimum over the face only when the distance grows into the face
/// by more than this times |x_ξ| (|x_ξ| + |x_η|) per unit of ξ (and the same in η), so that
/// rounding cannot decide it.
constexpr Real KKT_MARGIN = 1e-8;
constexpr Real START_XI[5] = {0.0, -0.5, 0.5, 0.5, -0.5};
constexpr Real START_ETA[5] = {0.0, -0.5, -0.5, 0.5, 0.5};

Real length(const Vec3& v) {
  return std::sqrt(v.dot(v));
}

/// Coefficients of x = a0 + a1 ξ + a2 η + a3 ξη.
struct Bilinear {
  Vec3 a0, a1, a2, a3;
  explicit Bilinear(const Vec3 x[4])
      : a0(0.25 * (x[0] + x[1] + x[2] + x[3])),
        a1(0.25 * (-x[0] + x[1] + x[2] - x[3])),
        a2(0.25 * (-x[0] - x[1] + x[2] + x[3])),
        a3(0.25 * (x[0] - x[1] + x[2] - x[3])) {}
  Vec3 at(Real xi, Real eta) const { return a0 + xi * a1 + eta * a2 + (xi * eta) * a3; }
};

/// Whether a and b are the same double, bit for bit (−0 and +0 differ).
bool same_bits(Real a, Real b) {
  return std::bit_cast<std::uint64_t>(a) == std::bit_cast<std::uint64_t>(b);
}

/// Stationary point of |x(ξ, η) − p|² strictly inside the square, if Newton started at
/// (xi, eta) finds one.
///
/// An iterate is a function of the one before alone; when one repeats the iterate two steps
/// back bit for bit (the projection bouncing between two points on the boundary, a third of
/// the capped runs on a folding tube), the iteration cycles between them with the step just
/// taken, which was not below the tolerance, and would end at the iteration cap without
/// converging: it stops there at once, with the same answer.
bool newton_interior(const Bilinear& q, const Vec3& p, Real& xi, Real& eta) {
  Real before_xi = std::numeric_limits<Real>::quiet_NaN(), before_eta = before_xi;
  for (int it = 0; it < MAX_NEWTON_ITERATIONS; ++it) {
    const Vec3 r = q.at(xi, eta) - p;
    const Vec3 x_xi = q.a1 + eta * q.a3;
    const Vec3 x_eta = q.a2 + xi * q.a3;
    const Real g0 = r.dot(x_xi), g1 = r.dot(x_eta);
    const Real h00 = x_xi.dot(x_xi), h11 = x_eta.dot(x_eta);
    Real h01 = x_xi.dot(x_eta) + r.dot(q.a3);
    Real det = h00 * h11 - h01 * h01;
    const Real scale = h00 * h11;
    if (!(det > 1e-12 * scale)) {  // exact Hessian not positive definite: Gauss–Newton
      h01 = x_xi.dot(x_eta);
      det = h00 * h11 - h01 * h01;
      if (!(det > 1e-14 * scale)) return false;  // degenerate face
    }
    const Real d_xi = -(h11 * g0 - h01 * g1) / det;
    const Real d_eta = -(h00 * g1 - h01 * g0) / det;
    const Real new_xi = std::clamp(xi + d_xi, -1.0, 1.0);
    const Real new_eta = std::clamp(eta + d_eta, -1.0, 1.0);
    const Real step = std::max(std::abs(new_xi - xi), std::abs(new_eta - eta));
    const Real last_xi = xi, last_eta = eta;
    xi = new_xi;
    eta = new_eta;
    if (step < NEWTON_STEP_TOLERANCE) return std::abs(xi) < 1.0 && std::abs(eta) < 1.0;
    if (same_bits(xi, before_xi) && same_bits(eta, before_eta)) return false;
    before_xi = last_xi;
    before_eta = last_eta;
  }
  return false;
}

/// Whether |x(ξ, η) − p|² is certainly strictly convex on the whole square, so that it has at
/// most one stationary point inside it, its minimum. Half its Hessian is
/// [[x_ξ·x_ξ, x_ξ·x_η + s], [x_ξ·x_η + s, x_η·x_η]] with s = (x − p)·a3 (x_ξξ = x_ηη = 0), whose
/// determinant is |x_ξ × x_η|² − 2 (x_ξ·x_η) s − s². With |ξ|, |η|, |ξη| ≤ 1 on the square,
/// x_ξ × x_η = a1 × a2 + ξ a1 × a3 + η a3 × a2 is at least N = |a1 × a2| − |a1 × a3| − |a2 × a3|
/// long, |x_ξ·x_η| ≤ C = |a1·a2| + |a1·a3| + |a2·a3| + a3·a3 and |s| ≤ σ = |(a0 − p)·a3| +
/// |a1·a3| + |a2·a3| + a3·a3; so N > 0 and N² > 2 C σ + σ² make the determinant positive
/// everywhere (and x_ξ·x_ξ > 0 with it). CONVEX_MARGIN leaves room for rounding.
bool convex_on_square(const Bilinear& q, const Vec3& p) {
  const Real n_min = length(q.a1.cross(q.a2)) - length(q.a1.cross(q.a3)) - length(q.a2.cross(q.a3));
  if (!(n_min > 0.0)) return false;
  const Real twist = std::abs(q.a1.dot(q.a3)) + std::abs(q.a2.dot(q.a3)) + q.a3.dot(q.a3);
  const Real sigma = std::abs((q.a0 - p).dot(q.a3)) + twist;
  const Real c = std::abs(q.a1.dot(q.a2)) + twist;
  return n_min * n_min > CONVEX_MARGIN * (2.0 * c * sigma + sigma * sigma);
}

/// The smallest of |a + t b|² over t ∈ [−1, 1] (m²), by its value at the ends and at the
/// vertex of the parabola.
Real min_square_on_segment(const Vec3& a, const Vec3& b) {
  const Real bb = b.dot(b);
  Real smallest = std::min((a - b).dot(a - b), (a + b).dot(a + b));
  if (bb > 0.0) {
    const Real t = std::clamp(-a.dot(b) / bb, -1.0, 1.0);
    const Vec3 v = a + t * b;
    smallest = std::min(smallest, v.dot(v));
  }
  return smallest;
}

/// A second, sharper test of the same property as convex_on_square: half the Hessian is
/// [[h00(η), h01(ξ, η)], [h01, h11(ξ)]] with h00 = |a1 + η a3|², h11 = |a2 + ξ a3|² and
/// h01 = x_ξ·x_η + s = a1·a2 + (a0 − p)·a3 + 2ξ a1·a3 + 2η a2·a3 + 2ξη a3·a3, bilinear, so
/// its largest magnitude on the square is at a corner. min h00 · min h11 > max h01² makes the
/// determinant positive everywhere. It holds on sheared or strongly twisted faces where the
/// triangle inequalities of convex_on_square give up (a node a few millimetres from a face of
/// a folding tube). The slack CONVEX_SLACK (relative) and the rounding allowance of h01 keep
/// rounding from deciding it.
bool convex_on_square_sharp(const Bilinear& q, const Vec3& p) {
  const Real h00 = min_square_on_segment(q.a1, q.a3);
  const Real h11 = min_square_on_segment(q.a2, q.a3);
  if (!(h00 > 0.0) || !(h11 > 0.0)) return false;
  const Real b0 = q.a1.dot(q.a2) + (q.a0 - p).dot(q.a3);
  const Real b1 = 2.0 * q.a1.dot(q.a3), b2 = 2.0 * q.a2.dot(q.a3), b3 = 2.0 * q.a3.dot(q.a3);
  Real h01 = 0.0;
  for (int k = 0; k < 4; ++k)
    h01 = std::max(h01, std::abs(b0 + CORNER_XI[k] * b1 + CORNER_ETA[k] * b2 +
                                 CORNER_XI[k] * CORNER_ETA[k] * b3));
  const Real len1 = length(q.a1), len2 = length(q.a2), len3 = length(q.a3);
  const Real rounding =
      CONVEX_SLACK * (len1 * len2 + length(q.a0 - p) * len3 + 2.0 * (len1 + len2 + len3) * len3);
  const Real bound = h01 + rounding;
  return (1.0 - CONVEX_SLACK) * h00 * h11 > bound * bound;
}

/// Closest point of segment a → b to p: parameter t ∈ [0, 1].
Real segment_parameter(const Vec3& a, const Vec3& b, const Vec3& p) {
  const Vec3 ab = b - a;
  const Real len_sq = ab.dot(ab);
  if (len_sq <= 0.0) return 0.0;
  return std::clamp((p - a).dot(ab) / len_sq, 0.0, 1.0);
}

/// The closest point of the face's four edges (segments, corners included) to p: the first
/// nearest of them in edge order, in `out` (region Edge or Corner), with its squared distance.
Real nearest_edge_point(const Vec3 corner[4], const Vec3& p, ClosestPoint& out) {
  Real best_sq = std::numeric_limits<Real>::infinity();
  // Edge e runs from corner e to corner e + 1; it is a straight segment of the bilinear face.
  for (int e = 0; e < 4; ++e) {
    const int b = (e + 1) % 4;
    const Real t = segment_parameter(corner[e], corner[b], p);
    const Vec3 c = (1.0 - t) * corner[e] + t * corner[b];
    const Real sq = (p - c).dot(p - c);
    // Strictly closer only: the lower edge number wins ties.
    if (!(sq < best_sq)) continue;
    best_sq = sq;
    out.xi = (1.0 - t) * CORNER_XI[e] + t * CORNER_XI[b];
    out.eta = (1.0 - t) * CORNER_ETA[e] + t * CORNER_ETA[b];
    out.point = c;
    if (t <= 0.0 || t >= 1.0) {
      out.region = QuadRegion::Corner;
      out.feature = t <= 0.0 ? e : b;
    } else {
      out.region = QuadRegion::Edge;
      out.feature = e;
    }
  }
  return best_sq;
}

/// Whether the edge point `e` (nearest_edge_point) is certainly the closest point of the whole
/// face to p, so that no stationary point lies inside it: the squared distance is convex on
/// the square (convex_on_square) and e satisfies the optimality conditions of its minimum over
/// the square with a margin, its gradient pointing out of the square across the edge (both
/// edges at a corner); along its edge it is the minimum already. A strictly convex function
/// whose minimum over the square lies on its boundary has no stationary point inside, and its
/// gradient stays away from zero there, so Newton could not have stopped inside either.
bool edge_point_is_minimum(const Bilinear& q, const Vec3& p, const ClosestPoint& e) {
  if (e.region == QuadRegion::Interior) return false;  // no edge point (not finite)
  // The coordinates held at ±1 (the edge's, or both at a corner) and the free one.
  const int k = e.feature;
  Real bound_xi = 0.0, bound_eta = 0.0;  // ±1 where held, 0 where free
  if (e.region == QuadRegion::Corner) {
    bound_xi = CORNER_XI[k];
    bound_eta = CORNER_ETA[k];
  } else if (k == 0 || k == 2) {
    bound_eta = k == 0 ? -1.0 : 1.0;
  } else {
    bound_xi = k == 1 ? 1.0 : -1.0;
  }
  const Vec3 r = e.point - p;
  const Vec3 x_xi = q.a1 + e.eta * q.a3;
  const Vec3 x_eta = q.a2 + e.xi * q.a3;
  const Real len_xi = length(x_xi), len_eta = length(x_eta);
  const Real scale = KKT_MARGIN * (len_xi + len_eta);
  // Moving into the face (−bound) raises the distance: bound · gradient < −margin.
  if (bound_xi != 0.0 && !(bound_xi * r.dot(x_xi) < -scale * len_xi)) return false;
  if (bound_eta != 0.0 && !(bound_eta * r.dot(x_eta) < -scale * len_eta)) return false;
  return convex_on_square(q, p) || convex_on_square_sharp(q, p);
}

}  // namespace

std::array<Real, 4> quad_shape(Real xi, Real eta) {
  std::array<Real, 4> n;
  for (int a = 0; a < 4; ++a) n[a] = 0.25 * (1.0 + CORNER_XI[a] * xi) * (1.0 + CORNER_ETA[a] * eta);
  return n;
}

Vec3 quad_point(const Vec3 corner[4], Real xi, Real eta) {
  return Bilinear(corner).at(xi, eta);
}

Vec3 quad_normal(const Vec3 corner[4], Real xi, Real eta) {
  const Bilinear q(corner);
  Vec3 n = (q.a1 + eta * q.a3).cross(q.a2 + xi * q.a3);
  Real len = length(n);
  const Vec3 diagonal = (corner[2] - corner[0]).cross(corner[3] - corner[1]);
  const Real diagonal_len = length(diagonal);
  // At a collapsed corner x_ξ × x_η vanishes while the face still has an area.
  if (len <= 1e-10 * diagonal_len) {
    n = diagonal;
    len = diagonal_len;
  }
  return len > 0.0 ? Vec3(n / len) : Vec3::Zero();
}

ClosestPoint closest_point_on_quad(const Vec3 corner[4], const Vec3& p, const QuadStart* warm) {
  const Bilinear q(corner);
  ClosestPoint best;
  Real best_sq = std::numeric_limits<Real>::infinity();
  ClosestPoint edge;
  const Real edge_sq = nearest_edge_point(corner, p, edge);

  // A flat or mildly warped face has one stationary point near the face, found from the
  // centre; a strongly warped one can have several, so it is started from the quadrant
  // centres as well and the nearest stationary point is kept, unless the nearest edge point is
  // certainly the closest point of the face (edge_point_is_minimum; on a flat face the test
  // would cost about what the one start costs).
  const Vec3 centre_normal = q.a1.cross(q.a2);
  const Real normal_len = length(centre_normal);
  const Real warp = std::abs(q.a3.dot(centre_normal)) / (normal_len * std::sqrt(normal_len));
  int starts = !(warp > STRONG_WARP) ? 1 : edge_point_is_minimum(q, p, edge) ? 0 : 5;
  if (starts == 5 && warm != nullptr) {
    // Last increment's point (header): one start instead of five.
    Real xi = warm->xi, eta = warm->eta;
    if (newton_interior(q, p, xi, eta)) {
      const Vec3 c = q.at(xi, eta);
      best_sq = (p - c).dot(p - c);
      best.xi = xi;
      best.eta = eta;
      best.point = c;
      starts = 0;
    } else if (!(std::abs(warm->xi) < 1.0 && std::abs(warm->eta) < 1.0)) {
      starts = 0;
    }
  }
  for (int s = 0; s < starts; ++s) {
    Real xi = START_XI[s], eta = START_ETA[s];
    if (!newton_interior(q, p, xi, eta)) continue;
    const Vec3 c = q.at(xi, eta);
    const Real sq = (p - c).dot(p - c);
    if (!(sq < best_sq)) continue;
    best_sq = sq;
    best.xi = xi;
    best.eta = eta;
    best.point = c;
  }
  // The nearest edge point only when strictly closer: the interior point wins ties.
  if (edge_sq < best_sq) {
    best = edge;
    best_sq = edge_sq;
  }

  best.distance = std::sqrt(best_sq);
  best.weights = quad_shape(best.xi, best.eta);
  const Vec3 face_normal = quad_normal(corner, best.xi, best.eta);
  const Vec3 d = p - best.point;
  const Real along = d.dot(face_normal);
  best.normal = face_normal;
  best.gap = along;
  if (best.region != QuadRegion::Interior && along >= 0.0) {
    // Outside beside an edge or corner: point from c to the node (continuous with n at the
    // edge of the face region). A node on the face itself keeps the face normal.
    const Real size = length(corner[2] - corner[0]) + length(corner[3] - corner[1]);
    if (best.distance > 1e-12 * size) best.normal = d / best.distance;
    best.gap = best.distance;
  }
  return best;
}

}  // namespace xpl::contact
