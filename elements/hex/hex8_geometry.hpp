#pragma once
/// \file Geometry of the trilinear 8-node hexahedron in "mode space".
///
/// The position field of a hex is x(ξ,η,ζ) = a0 + a1 ξ + a2 η + a3 ζ + a4 ξη + a5 ηζ + a6 ζξ
/// + a7 ξηζ, with the mode vectors a_k = ⅛ Σ_I Λ_kI x_I, Λ_kI = ±1 the k-th monomial at
/// node I. Everything the one-point element needs is cheap in these modes:
///   V    = 8 ( [a1,a2,a3] + ⅓ ([a1,a4,a6] + [a4,a2,a5] + [a6,a5,a3]) )   (exact)
///   g_k  = ∂V/∂a_k, and b_I = ∂V/∂x_I = ⅛ Σ_k Λ_kI g_k  (Flanagan–Belytschko uniform gradient)
///   Σ_I v_I ⊗ b_I = Σ_k av_k ⊗ g_k                       (av = modes of the velocity)
///   V = ⅓ Σ_k a_k · g_k                                    (V is cubic and homogeneous)
/// The hourglass base vectors Γ of Flanagan–Belytschko are the rows Λ_4..Λ_7.
/// All functions are templates over the lane type: `Real` for one element, `simd::Vec` for
/// a batch of W elements.

#include "common/types.hpp"
#include "elements/parallel/simd.hpp"
#include "elements/vec3.hpp"

namespace xpl::elements {

/// Mode order used below: index 1 ξ, 2 η, 3 ζ, 4 ξη, 5 ηζ, 6 ζξ, 7 ξηζ (0 = mean, unused).
inline constexpr int MODE_COUNT = 8;

/// Natural coordinates of the C3D8R nodes (Abaqus order).
inline constexpr int NODE_XI[8] = {-1, 1, 1, -1, -1, 1, 1, -1};
inline constexpr int NODE_ETA[8] = {-1, -1, 1, 1, -1, -1, 1, 1};
inline constexpr int NODE_ZETA[8] = {-1, -1, -1, -1, 1, 1, 1, 1};

/// Λ_kI: value of mode k's monomial at node I.
constexpr int mode_sign(int k, int node) {
  const int xi = NODE_XI[node], eta = NODE_ETA[node], zeta = NODE_ZETA[node];
  switch (k) {
    case 0:
      return 1;
    case 1:
      return xi;
    case 2:
      return eta;
    case 3:
      return zeta;
    case 4:
      return xi * eta;
    case 5:
      return eta * zeta;
    case 6:
      return zeta * xi;
    default:
      return xi * eta * zeta;
  }
}

/// Modes a_k = ⅛ Σ_I Λ_kI p_I of one nodal component (8 values, Abaqus node order),
/// by a three-stage butterfly (24 additions instead of 56).
template <class T>
inline void to_modes(const T p[8], T a[8]) {
  // Lexicographic corner order c = i + 2j + 4k (i: ξ, j: η, k: ζ bits).
  const T c0 = p[0], c1 = p[1], c2 = p[3], c3 = p[2], c4 = p[4], c5 = p[5], c6 = p[7], c7 = p[6];
  // ξ stage: sums s, differences d.
  const T s0 = c0 + c1, d0 = c1 - c0, s1 = c2 + c3, d1 = c3 - c2;
  const T s2 = c4 + c5, d2 = c5 - c4, s3 = c6 + c7, d3 = c7 - c6;
  // η stage.
  const T ss0 = s0 + s1, sd0 = s1 - s0, ds0 = d0 + d1, dd0 = d1 - d0;
  const T ss1 = s2 + s3, sd1 = s3 - s2, ds1 = d2 + d3, dd1 = d3 - d2;
  // ζ stage.
  const Real q = 0.125;
  a[0] = q * (ss0 + ss1);
  a[1] = q * (ds0 + ds1);
  a[2] = q * (sd0 + sd1);
  a[3] = q * (ss1 - ss0);
  a[4] = q * (dd0 + dd1);
  a[5] = q * (sd1 - sd0);
  a[6] = q * (ds1 - ds0);
  a[7] = q * (dd1 - dd0);
}

/// Inverse of the mode transform without the ⅛: f_I = Σ_k Λ_kI F_k (F[0] included).
template <class T>
inline void from_modes(const T F[8], T f[8]) {
  // ζ stage: (sum-part, diff-part) -> (k=0 value, k=1 value) along ζ.
  const T ss0 = F[0] - F[3], ss1 = F[0] + F[3];
  const T ds0 = F[1] - F[6], ds1 = F[1] + F[6];
  const T sd0 = F[2] - F[5], sd1 = F[2] + F[5];
  const T dd0 = F[4] - F[7], dd1 = F[4] + F[7];
  // η stage.
  const T s0 = ss0 - sd0, s1 = ss0 + sd0, d0 = ds0 - dd0, d1 = ds0 + dd0;
  const T s2 = ss1 - sd1, s3 = ss1 + sd1, d2 = ds1 - dd1, d3 = ds1 + dd1;
  // ξ stage, back to Abaqus node order.
  f[0] = s0 - d0;
  f[1] = s0 + d0;
  f[3] = s1 - d1;
  f[2] = s1 + d1;
  f[4] = s2 - d2;
  f[5] = s2 + d2;
  f[7] = s3 - d3;
  f[6] = s3 + d3;
}

/// Mode vectors of 8 nodal 3-vectors given by components.
template <class T>
inline void to_modes(const T x[8], const T y[8], const T z[8], V3<T> a[8]) {
  T ax[8], ay[8], az[8];
  to_modes(x, ax);
  to_modes(y, ay);
  to_modes(z, az);
  for (int k = 0; k < 8; ++k) a[k] = {ax[k], ay[k], az[k]};
}

/// Volume gradient in mode space g_k = ∂V/∂a_k (k = 1..6; g_0 = g_7 = 0) and the volume.
template <class T>
inline void volume_gradient(const V3<T> a[8], V3<T> g[8], T& volume) {
  const Real third = 1.0 / 3.0;
  g[0] = {T{}, T{}, T{}};
  g[7] = {T{}, T{}, T{}};
  g[1] = 8.0 * (cross(a[2], a[3]) + third * cross(a[4], a[6]));
  g[2] = 8.0 * (cross(a[3], a[1]) + third * cross(a[5], a[4]));
  g[3] = 8.0 * (cross(a[1], a[2]) + third * cross(a[6], a[5]));
  g[4] = (8.0 * third) * (cross(a[6], a[1]) + cross(a[2], a[5]));
  g[5] = (8.0 * third) * (cross(a[4], a[2]) + cross(a[3], a[6]));
  g[6] = (8.0 * third) * (cross(a[1], a[4]) + cross(a[5], a[3]));
  // V is homogeneous of degree 3 in the a_k: V = ⅓ Σ a_k·g_k.
  volume = third * (dot(a[1], g[1]) + dot(a[2], g[2]) + dot(a[3], g[3]) + dot(a[4], g[4]) +
                    dot(a[5], g[5]) + dot(a[6], g[6]));
}

/// Squared area of the largest face (faces approximated by their diagonals' cross product,
/// exact for planar faces).
template <class T>
inline T max_face_area_squared(const V3<T> a[8]) {
  using simd::max;
  auto area2 = [](const V3<T>& u, const V3<T>& v) {
    const V3<T> n = cross(u, v);
    return 16.0 * dot(n, n);
  };
  T m = area2(a[1] - a[6], a[2] - a[5]);        // ζ = −1 (S1)
  m = max(m, area2(a[1] + a[6], a[2] + a[5]));  // ζ = +1 (S2)
  m = max(m, area2(a[1] - a[4], a[3] - a[5]));  // η = −1 (S3)
  m = max(m, area2(a[1] + a[4], a[3] + a[5]));  // η = +1 (S5)
  m = max(m, area2(a[2] - a[4], a[3] - a[6]));  // ξ = −1 (S6)
  m = max(m, area2(a[2] + a[4], a[3] + a[6]));  // ξ = +1 (S4)
  return m;
}

/// A cheap proof that no corner Jacobian of the hex with modes `a` is negative: positive only
/// if σ_min(A) > |Δ| for the centre Jacobian A = [a1, a2, a3] and the change Δ of J from the
/// centre to any corner (its columns ±a4 ± a6 ± a7, ±a4 ± a5 ± a7, ±a5 ± a6 ± a7): then no
/// J between them is singular. With σ_min ≥ 2 det A / |A|²_F and |Δ|²_F ≤ 9 H,
/// H = |a4|² + |a5|² + |a6|² + |a7|², the value 4 det A |det A| − 9 H |A|⁴_F (m⁶) is positive
/// for every element near a parallelepiped; corner_fold() decides the others.
template <class T>
inline T corner_screen(const V3<T> a[8]) {
  const T det = dot(a[1], cross(a[2], a[3]));
  const T size = dot(a[1], a[1]) + dot(a[2], a[2]) + dot(a[3], a[3]);
  const T h = dot(a[4], a[4]) + dot(a[5], a[5]) + dot(a[6], a[6]) + dot(a[7], a[7]);
  return 4.0 * det * simd::abs(det) - 9.0 * h * size * size;
}

/// Fold measure of the 8 corners of a hex with corners `x` (Abaqus order): the smallest over
/// the corners of
///   f = det E |det E| + τ² |e_ξ|² |e_η|² |e_ζ|²,   E = [e_ξ, e_η, e_ζ],
/// e_ξ, e_η, e_ζ the corner's three edges, oriented along +ξ, +η, +ζ (twice the columns of the
/// Jacobian there). f is negative exactly where the corner's scaled Jacobian
/// det E / (|e_ξ| |e_η| |e_ζ|) is below −τ: 1 at a cube's corners, −sin θ where one edge has
/// been pushed through the plane of the other two by θ. No root, no division (m⁶: the sign
/// is what counts); the edge lengths only where a corner is negative at all. Not negative
/// otherwise (the smallest det E then).
template <class T>
inline T corner_fold(const V3<T> x[8], Real tau) {
  using simd::min;
  // Edges by the signs of the other two coordinates, [first][second] with 0 = −1, 1 = +1.
  const V3<T> ex[2][2] = {{x[1] - x[0], x[5] - x[4]}, {x[2] - x[3], x[6] - x[7]}};  // [η][ζ]
  const V3<T> ey[2][2] = {{x[3] - x[0], x[7] - x[4]}, {x[2] - x[1], x[6] - x[5]}};  // [ξ][ζ]
  const V3<T> ez[2][2] = {{x[4] - x[0], x[7] - x[3]}, {x[5] - x[1], x[6] - x[2]}};  // [ξ][η]
  T det[8];
  T smallest{};
  for (int c = 0; c < 8; ++c) {
    const int i = c & 1, j = (c >> 1) & 1, k = c >> 2;  // corner (ξ, η, ζ) sign bits
    det[c] = dot(ex[j][k], cross(ey[i][k], ez[i][j]));
    smallest = c == 0 ? det[c] : min(smallest, det[c]);
  }
  if (!simd::any_negative(smallest)) return smallest;
  T lx[2][2], ly[2][2], lz[2][2];
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) {
      lx[i][j] = (tau * tau) * dot(ex[i][j], ex[i][j]);
      ly[i][j] = dot(ey[i][j], ey[i][j]);
      lz[i][j] = dot(ez[i][j], ez[i][j]);
    }
  for (int c = 0; c < 8; ++c) {
    const int i = c & 1, j = (c >> 1) & 1, k = c >> 2;
    const T f = det[c] * simd::abs(det[c]) + lx[j][k] * ly[i][k] * lz[i][j];
    smallest = c == 0 ? f : min(smallest, f);
  }
  return smallest;
}

/// Volume of one hex given its nodal coordinates (Abaqus order).
inline Real hex8_volume(const Real x[8], const Real y[8], const Real z[8]) {
  V3<Real> a[8], g[8];
  Real volume = 0.0;
  to_modes(x, y, z, a);
  volume_gradient(a, g, volume);
  return volume;
}

}  // namespace xpl::elements
