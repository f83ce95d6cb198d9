#pragma once
/// \file Enhanced assumed-strain hourglass stabilisation of the one-point hex (C3D8R's
/// default, `*SECTION CONTROLS, HOURGLASS=ENHANCED`): the hourglass modes are resisted by the
/// material's own elastic stiffness, in the energy the trilinear element would store if it
/// were enriched with Wilson's incompatible modes, so that it bends like a beam with one
/// element through the thickness. In the spirit of Belytschko–Bindeman (1993) and Puso
/// (2000).
///
/// The derivation (hourglass velocities q̂_α = av_α − L a_α, the strain of the hourglass
/// field, Wilson's modes condensed to the plane-stress energy W_φ = (V/3)[μ|ε_t|² + ½λ̄(tr ε_t)²]
/// of the strain on the plane ⊥ b_φ, and the ξηζ energy W_7): docs/theory/elements.md.
///
/// In the element's frame. Everything is evaluated in an orthonormal frame that follows the
/// element (Gram–Schmidt on the centre tangents a1, a2: e1 ∥ a1, e2 in their plane), with the
/// gradients taken as diagonal there, b_i ≈ c_i e_i (c1 = 1/|a1|, c2 = 1/|a2 − (a2·e1) e1|,
/// c3 = b3·e3: exact on a rectangular element, the shear of a skewed one neglected, as in
/// Belytschko–Bindeman's corotational form). Then each plane φ holds two normal strains and
/// one shear, with local components u_i = e_i·q̂:
///   ξ (plane 2-3): ε22 = c2 q̂4₂, ε33 = c3 q̂6₃, γ23 = c2 q̂4₃ + c3 q̂6₂
///   η (plane 1-3): ε11 = c1 q̂4₁, ε33 = c3 q̂5₃, γ13 = c1 q̂4₃ + c3 q̂5₁
///   ζ (plane 1-2): ε11 = c1 q̂6₁, ε22 = c2 q̂5₂, γ12 = c1 q̂6₂ + c2 q̂5₁
/// and the element keeps the nine plane stresses S (Pa) in its frame, advanced in rate form
/// with the plane-stress moduli (Σ_aa += (2μ + λ̄) ε_a + λ̄ ε_b, Σ_ab += μ γ_ab): objective
/// without a spin term (the frame turns with the element) and invariant under stretch. The
/// generalised forces are Q̂ = ∂W/∂q̂ = (V/3) c·S, e.g. Q̂4 = (V/3)(c1 S_η11, c2 S_ξ22,
/// c2 S_ξ23 + c1 S_η13), and Q̂7 (local, N) advances by (V/9) μ (Σc² + c_i²) q̂7_i dt.
/// The plastic bound and relaxation act on S (hex8r_hourglass.hpp).
/// All functions are templates over the lane type (`Real` or `simd::Vec`).
///

#include "elements/hex/hex8_geometry.hpp"

namespace xpl::elements {

/// Values per element of the enhanced form's state: the nine plane stresses S (Pa: ξ 22, 33,
/// 23; η 11, 33, 13; ζ 11, 22, 12) and the ξηζ resultant Q̂7 (N, 3 local components).
inline constexpr int ENHANCED_STATE = 12;

/// The element frame and its diagonal gradients at one configuration.
template <class T>
struct EnhancedFrame {
  V3<T> e[3];  ///< orthonormal frame, e1 ∥ a1, e2 in the plane of a1 and a2
  T c[3];      ///< |∇ξ_i| along e_i, 1/m
};

/// Frame from the position modes `a` (a1, a2 used), `g3` = ∂V/∂a3 and 1/V.
template <class T>
inline EnhancedFrame<T> enhanced_frame(const V3<T> a[8], const V3<T>& g3, T inv_vol) {
  EnhancedFrame<T> f;
  const T n1 = dot(a[1], a[1]);
  // f2 = |a1|² (a2 − (a2·e1) e1) needs no division; f3 = a1 × f2 has |f3| = |a1| |f2|.
  const V3<T> f2 = n1 * a[2] - dot(a[1], a[2]) * a[1];
  const V3<T> f3 = cross(a[1], f2);
  const T s1 = simd::sqrt(n1), s2 = simd::sqrt(dot(f2, f2));
  const T inv = 1.0 / (s1 * s2);
  const T r1 = s2 * inv, r2 = s1 * inv;
  f.e[0] = r1 * a[1];
  f.e[1] = r2 * f2;
  f.e[2] = inv * f3;
  f.c[0] = r1;
  f.c[1] = n1 * r2;
  f.c[2] = dot(g3, f.e[2]) * inv_vol;
  return f;
}

/// Local components (e_i·q) of the four hourglass velocities q̂4..q̂7.
template <class T>
inline void to_frame(const EnhancedFrame<T>& f, const V3<T> q[4], V3<T> local[4]) {
  for (int m = 0; m < 4; ++m) local[m] = {dot(f.e[0], q[m]), dot(f.e[1], q[m]), dot(f.e[2], q[m])};
}

/// Strain rates of the three planes from the local hourglass velocities `u` (ε22, ε33, γ23 of
/// ξ; ε11, ε33, γ13 of η; ε11, ε22, γ12 of ζ), 1/s.
template <class T>
inline void enhanced_strains(const EnhancedFrame<T>& f, const V3<T> u[4], T eps[9]) {
  const T c1 = f.c[0], c2 = f.c[1], c3 = f.c[2];
  eps[0] = c2 * u[0].y;
  eps[1] = c3 * u[2].z;
  eps[2] = c2 * u[0].z + c3 * u[2].y;
  eps[3] = c1 * u[0].x;
  eps[4] = c3 * u[1].z;
  eps[5] = c1 * u[0].z + c3 * u[1].x;
  eps[6] = c1 * u[2].x;
  eps[7] = c2 * u[1].y;
  eps[8] = c1 * u[2].y + c2 * u[1].x;
}

/// Plane-stress increments of S for the strain increments `eps` (enhanced_strains() times dt):
/// `normal` = 2μ + λ̄ and `lambda_bar` = λ̄ (times κ), `mu` = μ κ, Pa.
template <class T>
inline void enhanced_stress_increment(const T eps[9], T normal, T lambda_bar, T mu, T ds[9]) {
  for (int p = 0; p < 3; ++p) {
    const T a = eps[3 * p], b = eps[3 * p + 1];
    ds[3 * p] = normal * a + lambda_bar * b;
    ds[3 * p + 1] = normal * b + lambda_bar * a;
    ds[3 * p + 2] = mu * eps[3 * p + 2];
  }
}

/// Local generalised forces Q̂4..Q̂6 (N) of the plane stresses S, `v3` = V/3.
template <class T>
inline void enhanced_forces(const EnhancedFrame<T>& f, const T S[9], T v3, V3<T> Q[3]) {
  const T k1 = v3 * f.c[0], k2 = v3 * f.c[1], k3 = v3 * f.c[2];
  Q[0] = {k1 * S[3], k2 * S[0], k2 * S[2] + k1 * S[5]};
  Q[1] = {k3 * S[5] + k2 * S[8], k2 * S[7], k3 * S[4]};
  Q[2] = {k1 * S[6], k3 * S[2] + k1 * S[8], k3 * S[1]};
}

/// Stiffness of the ξηζ mode per local component, (V/9) μ (Σc² + c_i²) (N/m per m/s·s).
template <class T>
inline V3<T> enhanced_mode7_stiffness(const EnhancedFrame<T>& f, T v9_mu) {
  const T c1 = f.c[0] * f.c[0], c2 = f.c[1] * f.c[1], c3 = f.c[2] * f.c[2];
  const T sum = c1 + c2 + c3;
  return {v9_mu * (sum + c1), v9_mu * (sum + c2), v9_mu * (sum + c3)};
}

/// Global vector of local components `l` in frame f.
template <class T>
inline V3<T> from_frame(const EnhancedFrame<T>& f, const V3<T>& l) {
  return l.x * f.e[0] + l.y * f.e[1] + l.z * f.e[2];
}

}  // namespace xpl::elements
