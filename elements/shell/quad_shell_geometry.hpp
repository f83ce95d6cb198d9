#pragma once
/// \file Corotational geometry of a 4-node shell element with one in-plane point.
///
/// The local frame is built from the diagonals d13 = x3 − x1 and d24 = x4 − x2 (0-based: nodes
/// 0..3): e3 ∥ d13 × d24, e1 bisects the unit diagonals (â − b̂), e2 = e3 × e1. The frame does
/// not depend on which node is called "1" beyond a rotation by 90°, and it follows the
/// element's in-plane spin, so stresses stored in it are corotational.
///
/// Both diagonals lie in the e1–e2 plane, so the one-point derivative operators need only the
/// projected diagonals, and the out-of-plane node positions are exactly z_I = z_h Γ_I with the
/// hourglass pattern Γ = (1, −1, 1, −1) and the warp height z_h = ¼ e3·(x1 − x2 + x3 − x4).
/// With B1 = ∂N/∂x̂ and B2 = ∂N/∂ŷ at the centre:
///   B1 = (b1a, b1b, −b1a, −b1b),  B2 = (b2a, b2b, −b2a, −b2b),
/// so Σ_I B_I u_I = b_a (u_1 − u_3) + b_b (u_2 − u_4) needs only two node differences, and the
/// Flanagan–Belytschko hourglass vector γ_I = Γ_I − (Γ·x̂) B1_I − (Γ·ŷ) B2_I is
///   γ = (1 − s_a, −1 − s_b, 1 + s_a, −1 + s_b).
/// All functions are templates over the lane type (`Real` or `simd::Vec`).

#include "elements/parallel/simd.hpp"
#include "elements/vec3.hpp"

namespace xpl::elements {

/// Geometry of one shell element (or of a batch of them) in its corotational frame.
template <class T>
struct QuadFrame {
  V3<T> e1, e2, e3;  ///< local axes (global components): rows of the rotation to local
  T area;            ///< projected area A = ½ |d13 × d24|, m^2
  T b1a, b1b;        ///< B1 = ∂N/∂x̂ = (b1a, b1b, −b1a, −b1b), 1/m
  T b2a, b2b;        ///< B2 = ∂N/∂ŷ = (b2a, b2b, −b2a, −b2b), 1/m
  T sa, sb;          ///< hourglass vector γ = (1 − sa, −1 − sb, 1 + sa, −1 + sb)
  T hx, hy;          ///< Σ Γ_I x̂_I, Σ Γ_I ŷ_I: 4 × the taper X_h of x = … + X_h ξη, m
  T warp;            ///< z_h: node I lies z_h Γ_I above the projected plane, m
  T diagonal;        ///< longer diagonal, m
};

/// Local frame, area, gradient operator and hourglass vector of the quad with corners p.
template <class T>
inline QuadFrame<T> quad_frame(const V3<T> p[4]) {
  QuadFrame<T> f;
  const V3<T> d13 = p[2] - p[0];
  const V3<T> d24 = p[3] - p[1];
  const V3<T> n = cross(d13, d24);
  const T n_len = simd::sqrt(dot(n, n));
  f.e3 = (1.0 / n_len) * n;
  const T l13 = simd::sqrt(dot(d13, d13));
  const T l24 = simd::sqrt(dot(d24, d24));
  const V3<T> bisector = (1.0 / l13) * d13 - (1.0 / l24) * d24;
  f.e1 = (1.0 / simd::sqrt(dot(bisector, bisector))) * bisector;
  f.e2 = cross(f.e3, f.e1);
  f.area = 0.5 * n_len;
  f.diagonal = simd::max(l13, l24);
  const T inv_2a = 1.0 / n_len;
  // y_2 − y_4 = −e2·d24, y_3 − y_1 = e2·d13, x_4 − x_2 = e1·d24, x_1 − x_3 = −e1·d13.
  f.b1a = -dot(f.e2, d24) * inv_2a;
  f.b1b = dot(f.e2, d13) * inv_2a;
  f.b2a = dot(f.e1, d24) * inv_2a;
  f.b2b = -dot(f.e1, d13) * inv_2a;
  const V3<T> h = p[0] - p[1] + p[2] - p[3];  // Σ Γ_I x_I
  const T gx = dot(f.e1, h), gy = dot(f.e2, h);
  f.hx = gx;
  f.hy = gy;
  f.sa = gx * f.b1a + gy * f.b2a;
  f.sb = gx * f.b1b + gy * f.b2b;
  f.warp = 0.25 * dot(f.e3, h);
  return f;
}

/// The node combinations every one-point quantity of a nodal field u needs:
/// d02 = u_1 − u_3, d13 = u_2 − u_4, hg = Σ Γ_I u_I (0-based names, 1-based in the text).
template <class T>
struct QuadCombos {
  T d02, d13, hg;
};

/// Σ_I B1_I u_I for the combinations of u.
template <class T>
inline T grad_x(const QuadFrame<T>& f, const QuadCombos<T>& u) {
  return f.b1a * u.d02 + f.b1b * u.d13;
}
/// Σ_I B2_I u_I.
template <class T>
inline T grad_y(const QuadFrame<T>& f, const QuadCombos<T>& u) {
  return f.b2a * u.d02 + f.b2b * u.d13;
}
/// Hourglass rate Σ_I γ_I u_I.
template <class T>
inline T hourglass_rate(const QuadFrame<T>& f, const QuadCombos<T>& u) {
  return u.hg - f.sa * u.d02 - f.sb * u.d13;
}

/// Combinations of a nodal vector field, rotated into the local frame of f.
template <class T>
inline void local_combos(const QuadFrame<T>& f, const V3<T> u[4], QuadCombos<T>& x,
                         QuadCombos<T>& y, QuadCombos<T>& z) {
  const V3<T> d02 = u[0] - u[2], d13 = u[1] - u[3];
  const V3<T> hg = u[0] - u[1] + u[2] - u[3];
  x = {dot(f.e1, d02), dot(f.e1, d13), dot(f.e1, hg)};
  y = {dot(f.e2, d02), dot(f.e2, d13), dot(f.e2, hg)};
  z = {dot(f.e3, d02), dot(f.e3, d13), dot(f.e3, hg)};
}

/// Natural coordinates (ξ, η) of the corners, in node order.
inline constexpr Real QUAD_CORNER_XI[4] = {-1.0, 1.0, 1.0, -1.0};
inline constexpr Real QUAD_CORNER_ETA[4] = {-1.0, -1.0, 1.0, 1.0};

/// Jacobian of the bilinear map of the projected quad at each corner: `det`[k] = det J and
/// `columns`[k] = |J_ξ|² |J_η|² (m⁴ each), so that det / √columns is the corner's scaled
/// Jacobian, the sine of its angle (negative: a reflex corner). With x = x0 + ξ a1 + η a2 +
/// ξη h in the element plane, J_ξ = a1 + η h and J_η = a2 + ξ h at a corner, and det J =
/// a1×a2 + ξ a1×h + η h×a2 with a1×a2 = A/4 > 0 in the frame of quad_frame(), whose normal
/// follows the diagonals. A negative corner: that node has crossed the diagonal joining its
/// neighbours, the quad is folded over there (concave, or crossed once its normal has turned
/// over, and its area alone shows neither). From the frame's gradient operator, in the plane:
/// d13 = 2A (−b2b, b1b), d24 = 2A (b2a, −b1a), a1 = ¼(d13 − d24), a2 = ¼(d13 + d24) and
/// h = ¼ (hx, hy).
template <class T>
inline void quad_corner_jacobians(const QuadFrame<T>& f, T det[4], T columns[4]) {
  const T half = 0.5 * f.area;
  const T a1x = -half * (f.b2a + f.b2b), a1y = half * (f.b1a + f.b1b);
  const T a2x = half * (f.b2a - f.b2b), a2y = half * (f.b1b - f.b1a);
  const T hx = 0.25 * f.hx, hy = 0.25 * f.hy;
  for (int k = 0; k < 4; ++k) {
    const Real xi = QUAD_CORNER_XI[k], eta = QUAD_CORNER_ETA[k];
    const T ux = a1x + eta * hx, uy = a1y + eta * hy;  // J_ξ
    const T vx = a2x + xi * hx, vy = a2y + xi * hy;    // J_η
    det[k] = ux * vy - uy * vx;
    columns[k] = (ux * ux + uy * uy) * (vx * vx + vy * vy);
  }
}

/// Angle in degrees between the normals of the two triangles of each diagonal split, the
/// larger of the two splits: 0 for a flat element.
inline Real quad_warp_angle(const V3<Real> p[4]) {
  auto angle = [](const V3<Real>& a, const V3<Real>& b) {
    const Real c = dot(a, b) / std::sqrt(dot(a, a) * dot(b, b));
    return std::acos(c > 1.0 ? 1.0 : (c < -1.0 ? -1.0 : c)) * 180.0 / 3.14159265358979323846;
  };
  const V3<Real> n012 = cross(p[1] - p[0], p[2] - p[0]);
  const V3<Real> n023 = cross(p[2] - p[0], p[3] - p[0]);
  const V3<Real> n123 = cross(p[2] - p[1], p[3] - p[1]);
  const V3<Real> n130 = cross(p[3] - p[1], p[0] - p[1]);
  const Real a = angle(n012, n023), b = angle(n123, n130);
  return a > b ? a : b;
}

}  // namespace xpl::elements
