#pragma once
/// \file Enhanced assumed-strain hourglass stabilisation of the one-point hex (C3D8R's
/// default, `*SECTION CONTROLS, HOURGLASS=ENHANCED`): the hourglass modes are resisted by the
/// material's own elastic stiffness, in the energy the trilinear element would store if it
/// were enriched with Wilson's incompatible modes, so that it bends like a beam with one
/// element through the thickness. In the spirit of Belytschko–Bindeman (1993) and Puso
/// (2000); derived here as follows.
///
/// Hourglass velocity. With the modes a_k of hex8_geometry.hpp and the uniform gradient
/// L = (1/V) Σ_k av_k ⊗ g_k, the hourglass parts of the velocity are
///   q̂_α = av_α − L a_α,   α = 4 (ξη), 5 (ηζ), 6 (ζξ), 7 (ξηζ),
/// zero for every linear field (rigid motions included): the patch test holds on any hex.
/// (Flanagan–Belytschko's q_α = γ_α·v is 8 q̂_α; the resultants Q_α stored and applied are
/// conjugate to q_α, as for their stiffness form.)
///
/// Strain of the hourglass field. Take the centre gradients b_i = ∇ξ_i = g_i / V (exact on a
/// parallelepiped). The gradient of Σ_α q̂_α h_α(ξ) is linear in each natural coordinate φ:
///   G_ξ = q̂4 ⊗ b2 + q̂6 ⊗ b3,  G_η = q̂4 ⊗ b1 + q̂5 ⊗ b3,  G_ζ = q̂5 ⊗ b2 + q̂6 ⊗ b1,
/// plus the bilinear terms of ξηζ. On a parallelepiped ∫φ² dV = V/3, ∫(ηζ)² dV = V/9 and
/// every cross term integrates to zero, so the fully integrated energy is a sum over φ.
///
/// Enhanced strain. Wilson's modes u += Σ_i w_i (1 − ξ_i²) add −2ξ_i w_i ⊗ b_i: a free vector
/// in the column of G_φ along its own b_φ. Condensing it out (minimum energy over w) frees the
/// normal and shear strains on the plane ⊥ b_φ, and what remains is the plane-stress energy
/// of the strain projected on that plane (P = I − n nᵀ, n = b_φ/|b_φ|):
///   W_φ = (V/3) [ μ |ε_t|² + ½ λ̄ (tr ε_t)² ],  ε_t = P sym(G_φ) P,  λ̄ = 2μλ/(λ + 2μ).
/// This removes both the parasitic shear of a bending mode (shear locking: the shear ⊗ b_φ
/// is condensed) and the Poisson over-stiffness (λ̄ ≤ 2μ stays bounded as ν → ½). On a
/// rectangular cantilever one element through the thickness stores exactly E I κ² / 2 per
/// length in pure bending. The energy is positive definite on the nine linear hourglass
/// components (the twist triple q̂4·e3, q̂5·e1, q̂6·e2 is held by the three in-plane shears,
/// whose 3 × 3 system has determinant 2/(a1 a2 a3)).
/// The ξηζ mode (no bending content) keeps the full integral of its strain energy without
/// the bulk term (so that it does not lock):
///   W_7 = (V/9) Σ_i ½ μ (|b_i|² |q̂7|² + (q̂7·b_i)²).
///
/// Forces: with t_j, t_k the other two gradients projected on the plane of φ and
/// ε_t = sym(Pu ⊗ t_j + Pv ⊗ t_k) (u, v the two q̂ of G_φ), ∂W_φ/∂u = (V/3) Σ_φ t_j and
/// ∂W_φ/∂v = (V/3) Σ_φ t_k with the plane stress Σ_φ = 2μ ε_t + λ̄ tr(ε_t) P.
/// All functions are templates over the lane type (`Real` or `simd::Vec`).

#include "elements/hex8_geometry.hpp"

namespace xpl::elements {

/// Geometry of the enhanced stabilisation at one configuration.
template <class T>
struct EnhancedGeometry {
  V3<T> b[3];     ///< centre gradients ∇ξ, ∇η, ∇ζ (g_i / V), 1/m
  V3<T> h[3];     ///< b_i / |b_i|² (the projection P_i x = x − (x·b_i) h_i), m
  V3<T> t[3][2];  ///< for φ = ξ, η, ζ: the two other gradients projected on the plane ⊥ b_φ
  T tt[3][3];     ///< for φ: t0·t0, t1·t1, t0·t1, 1/m²
  T sum_bb;       ///< Σ_i |b_i|², 1/m²
};

/// The two hourglass components (indices into q̂4..q̂7) and the two gradients (j, k) of G_φ,
/// φ = ξ, η, ζ: G_φ = q̂[U] ⊗ b_j + q̂[V] ⊗ b_k.
inline constexpr int ENHANCED_U[3] = {0, 0, 1};
inline constexpr int ENHANCED_V[3] = {2, 1, 2};
inline constexpr int ENHANCED_J[3] = {1, 0, 1};
inline constexpr int ENHANCED_K[3] = {2, 2, 0};

/// Geometry from the volume gradient g (hex8_geometry.hpp, g_1..g_3 used) and 1/V.
template <class T>
inline EnhancedGeometry<T> enhanced_geometry(const V3<T> g[8], T inv_vol) {
  EnhancedGeometry<T> e;
  T bb[3];
  for (int i = 0; i < 3; ++i) {
    e.b[i] = inv_vol * g[1 + i];
    bb[i] = dot(e.b[i], e.b[i]);
  }
  // One division for the three inverses.
  const T inv_all = 1.0 / (bb[0] * bb[1] * bb[2]);
  e.h[0] = (bb[1] * bb[2] * inv_all) * e.b[0];
  e.h[1] = (bb[0] * bb[2] * inv_all) * e.b[1];
  e.h[2] = (bb[0] * bb[1] * inv_all) * e.b[2];
  for (int p = 0; p < 3; ++p) {
    const V3<T>& bj = e.b[ENHANCED_J[p]];
    const V3<T>& bk = e.b[ENHANCED_K[p]];
    e.t[p][0] = bj - dot(bj, e.b[p]) * e.h[p];
    e.t[p][1] = bk - dot(bk, e.b[p]) * e.h[p];
    e.tt[p][0] = dot(e.t[p][0], e.t[p][0]);
    e.tt[p][1] = dot(e.t[p][1], e.t[p][1]);
    e.tt[p][2] = dot(e.t[p][0], e.t[p][1]);
  }
  e.sum_bb = bb[0] + bb[1] + bb[2];
  return e;
}

/// Generalised forces conjugate to the hourglass velocities q̂ (q̂[0..3] = q̂4..q̂7): writes
/// Q̂ = K q̂ with the stiffness of the energies above, where `mu` = (V/3)·μ·c, `lambda_bar` =
/// (V/3)·λ̄·c and `mu7` = (V/9)·μ·c for a common factor c (a rate times dt gives the increment
/// of the resultants; 1/8 converts to Flanagan–Belytschko's Q conjugate to q = 8 q̂).
template <class T>
inline void enhanced_forces(const EnhancedGeometry<T>& e, const V3<T> q[4], T mu, T lambda_bar,
                            T mu7, V3<T> out[4]) {
  for (int m = 0; m < 3; ++m) out[m] = {T{}, T{}, T{}};
  for (int p = 0; p < 3; ++p) {
    const V3<T>& u = q[ENHANCED_U[p]];
    const V3<T>& v = q[ENHANCED_V[p]];
    const V3<T>& tj = e.t[p][0];
    const V3<T>& tk = e.t[p][1];
    const T s_uj = dot(u, tj), s_vk = dot(v, tk), s_vj = dot(v, tj), s_uk = dot(u, tk);
    const T lt = lambda_bar * (s_uj + s_vk);
    // μ P (u tj·tj + v tj·tk) and μ P (u tj·tk + v tk·tk): the 2μ ε_t t terms along u and v.
    V3<T> wu = e.tt[p][0] * u + e.tt[p][2] * v;
    V3<T> wv = e.tt[p][2] * u + e.tt[p][1] * v;
    wu = wu - dot(wu, e.b[p]) * e.h[p];
    wv = wv - dot(wv, e.b[p]) * e.h[p];
    out[ENHANCED_U[p]] = out[ENHANCED_U[p]] + mu * wu + (mu * s_uj + lt) * tj + (mu * s_vj) * tk;
    out[ENHANCED_V[p]] = out[ENHANCED_V[p]] + mu * wv + (mu * s_uk) * tj + (mu * s_vk + lt) * tk;
  }
  const V3<T>& r = q[3];
  out[3] = mu7 * (e.sum_bb * r + dot(r, e.b[0]) * e.b[0] + dot(r, e.b[1]) * e.b[1] +
                  dot(r, e.b[2]) * e.b[2]);
}

}  // namespace xpl::elements
