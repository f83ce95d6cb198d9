#pragma once
/// \file The hourglass resultants of one C3D8R batch over one increment, in the two families
/// the block runs (hex8r.cpp): Flanagan–Belytschko's stiffness and viscous forms, and the
/// enhanced assumed-strain stabilisation (hex8r_enhanced.hpp). Both return the resultants Q_α
/// (α = 4..7, conjugate to q_α = γ_α·v = 8 (av_α − L a_α)) that the force assembly applies,
/// the stored resultants for the next increment, and the hourglass power Q·q (W) whose
/// integral is the artificial energy ALLAE.

#include "elements/hex8r_enhanced.hpp"
#include "elements/simd.hpp"

namespace xpl::elements {

/// Lane-wise choice between two 3-vectors.
inline V3<simd::Vec> select3(simd::Mask m, const V3<simd::Vec>& a, const V3<simd::Vec>& b) {
  return {simd::select(m, a.x, b.x), simd::select(m, a.y, b.y), simd::select(m, a.z, b.z)};
}

/// |dev σ|² of a stress in Voigt order (11 22 33 12 13 23), Pa².
inline simd::Vec deviator_norm2(const simd::Vec s[6]) {
  const simd::Vec p = (s[0] + s[1] + s[2]) * (1.0 / 3.0);
  const simd::Vec d0 = s[0] - p, d1 = s[1] - p, d2 = s[2] - p;
  return d0 * d0 + d1 * d1 + d2 * d2 + 2.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]);
}

/// The factor by which a radial return scaled the deviator, |dev σ| / |dev σ_trial|, from the
/// squared norms before (`trial`) and after (`returned`); exactly 1 where nothing yielded.
inline simd::Vec return_factor(simd::Vec trial, simd::Vec returned) {
  const simd::Mask some = trial > 0.0;
  const simd::Vec ratio = returned / simd::max(trial, simd::splat(1e-300));
  return simd::select(some, simd::sqrt(simd::min(ratio, simd::splat(1.0))), simd::splat(1.0));
}

/// One increment of the hourglass resultants of a batch.
struct HourglassStep {
  V3<simd::Vec> stored[4];  ///< resultants kept for the next increment, N
  V3<simd::Vec> force[4];   ///< resultants applied now (stored + viscous part), N
  simd::Vec power;          ///< mean hourglass power over the increment, W
};

/// L a_α / V for the four hourglass modes: `Ln` = Σ_k av_k ⊗ g_k (unscaled uniform gradient on
/// the current geometry), `a` the position modes.
inline V3<simd::Vec> projected_mode(const simd::Vec Ln[3][3], const V3<simd::Vec>& a,
                                    simd::Vec inv_vol) {
  return {(Ln[0][0] * a.x + Ln[0][1] * a.y + Ln[0][2] * a.z) * inv_vol,
          (Ln[1][0] * a.x + Ln[1][1] * a.y + Ln[1][2] * a.z) * inv_vol,
          (Ln[2][0] * a.x + Ln[2][1] * a.y + Ln[2][2] * a.z) * inv_vol};
}

/// Flanagan–Belytschko: stiffness resultants advanced by k_hg dt q (N/m per lane, `k_hg`)
/// from `old`, plus the viscous part c_hg q (N s/m, `c_hg`); the power by the trapezoidal rule.
inline void flanagan_belytschko_step(const V3<simd::Vec> ax[8], const V3<simd::Vec> av[8],
                                     const simd::Vec Ln[3][3], simd::Vec inv_vol, simd::Vec k_hg,
                                     simd::Vec c_hg, Real dt, const V3<simd::Vec> old[4],
                                     HourglassStep& s) {
  s.power = simd::splat(0.0);
  for (int m = 0; m < 4; ++m) {
    const V3<simd::Vec> q = 8.0 * (av[4 + m] - projected_mode(Ln, ax[4 + m], inv_vol));
    s.stored[m] = old[m] + (k_hg * dt) * q;
    s.force[m] = s.stored[m] + c_hg * q;
    s.power += dot(0.5 * (old[m] + s.stored[m]) + c_hg * q, q);
  }
}

/// Amplitude of the linear hourglass stress that carries a section's fully plastic moment:
/// σ_y t²/4 = (κ σ_y) t²/6 with κ = 3/2.
inline constexpr Real HOURGLASS_PLASTIC_AMPLITUDE = 1.5;

/// The plastic bound of the enhanced resultants Q (modes 4..6, Flanagan–Belytschko scaling,
/// N): the plane hourglass stresses Σ_φ they carry, read in the element's axes n_i = b_i/|b_i|
/// as on a rectangular element (Q̂_α = 8 Q_α = (V/3)(Σ_φ t_j + Σ_φ' t_k); the six normal
/// components are one component of Q̂ each, the three in-plane shears solve a 3 × 3 system),
/// are scaled where their von Mises value exceeds `limit` (Pa per lane; +inf: no bound), the
/// change going back along the dual vectors |b_i| a_i. A lane within the bound is untouched.
inline void bound_enhanced(const V3<simd::Vec> ax[8], const EnhancedGeometry<simd::Vec>& e,
                           simd::Vec vol, simd::Vec limit, V3<simd::Vec> Q[3]) {
  using simd::Vec;
  Vec c[3];
  V3<Vec> n[3];
  for (int i = 0; i < 3; ++i) {
    c[i] = simd::sqrt(dot(e.b[i], e.b[i]));
    n[i] = (1.0 / c[i]) * e.b[i];
  }
  const Vec s = 24.0 / vol;  // Σ = 3 Q̂ / (V |b|) with Q̂ = 8 Q
  Vec C[3][3];               // C[α][i] = Q_α·n_i
  for (int m = 0; m < 3; ++m)
    for (int i = 0; i < 3; ++i) C[m][i] = dot(Q[m], n[i]);
  // Normal stresses (mode ξη: x along η (φ = η), y along ξ; ηζ: z along η, y along ζ; ζξ: z
  // along ξ, x along ζ) and the shear triple A = c2 X + c1 Y, B = c3 Y + c2 Z, C = c3 X + c1 Z.
  const Vec eta_xx = s * C[0][0] / c[0], xi_yy = s * C[0][1] / c[1];
  const Vec eta_zz = s * C[1][2] / c[2], zeta_yy = s * C[1][1] / c[1];
  const Vec xi_zz = s * C[2][2] / c[2], zeta_xx = s * C[2][0] / c[0];
  const Vec a = s * C[0][2], b = s * C[1][0], cc = s * C[2][1];
  const Vec x = 0.5 * (c[2] * a - c[0] * b + c[1] * cc) / (c[1] * c[2]);  // Σξ_yz
  const Vec y = 0.5 * (c[2] * a + c[0] * b - c[1] * cc) / (c[0] * c[2]);  // Ση_xz
  const Vec z = 0.5 * (c[0] * b + c[1] * cc - c[2] * a) / (c[0] * c[1]);  // Σζ_xy
  const auto mises2 = [](Vec p, Vec q, Vec t) { return p * p + q * q - p * q + 3.0 * t * t; };
  const Vec m2[3] = {mises2(xi_yy, xi_zz, x), mises2(eta_xx, eta_zz, y),
                     mises2(zeta_xx, zeta_yy, z)};
  const Vec limit2 = limit * limit;
  const simd::Mask over[3] = {m2[0] > limit2, m2[1] > limit2, m2[2] > limit2};
  const simd::Mask any = over[0] | over[1] | over[2];
  if (!simd::any(any)) return;
  Vec f[3];
  for (int p = 0; p < 3; ++p)
    f[p] = simd::select(over[p], limit / simd::sqrt(simd::max(m2[p], limit2)), simd::splat(1.0));
  // New components along n_i (f = 1: unchanged), shears through the triple.
  const Vec xs = f[0] * x, ys = f[1] * y, zs = f[2] * z;
  const Vec inv_s = vol * (1.0 / 24.0);
  const Vec D[3][3] = {
      {(f[1] - 1.0) * C[0][0], (f[0] - 1.0) * C[0][1], inv_s * (c[1] * xs + c[0] * ys) - C[0][2]},
      {inv_s * (c[2] * ys + c[1] * zs) - C[1][0], (f[2] - 1.0) * C[1][1], (f[1] - 1.0) * C[1][2]},
      {(f[2] - 1.0) * C[2][0], inv_s * (c[2] * xs + c[0] * zs) - C[2][1], (f[0] - 1.0) * C[2][2]}};
  const Vec zero = simd::splat(0.0);
  for (int m = 0; m < 3; ++m)
    for (int i = 0; i < 3; ++i) {
      const Vec d = simd::select(any, D[m][i], zero);
      Q[m] = Q[m] + (d * c[i]) * ax[1 + i];
    }
}

/// The enhanced stabilisation: the stored resultants are turned with the element's spin
/// (`spin` = W01, W02, W12 of the mid-increment velocity gradient, 1/s), so that they follow
/// a rigid rotation, then advanced by the rate dt·K q̂/8 of hex8r_enhanced.hpp on the current
/// geometry (`g`, `vol`; `mu` = κμ and `lambda_bar` = κλ̄ per lane, Pa), and multiplied by
/// `relax` (the batch's radial-return factor in plastic batches, see Hex8rBlock) and bounded
/// by bound_enhanced() with `limit` (Pa per lane) unless these are null.
inline void enhanced_step(const V3<simd::Vec> ax[8], const V3<simd::Vec> av[8],
                          const V3<simd::Vec> g[8], const simd::Vec Ln[3][3], simd::Vec vol,
                          simd::Vec inv_vol, simd::Vec mu, simd::Vec lambda_bar,
                          const simd::Vec spin[3], Real dt, const simd::Vec* relax,
                          const simd::Vec* limit, const V3<simd::Vec> old[4], HourglassStep& s) {
  using simd::Vec;
  V3<Vec> q[4];
  for (int m = 0; m < 4; ++m) q[m] = av[4 + m] - projected_mode(Ln, ax[4 + m], inv_vol);
  const EnhancedGeometry<Vec> e = enhanced_geometry(g, inv_vol);
  // (V/3)·c and (V/9)·c with c = dt/8 (increment, Flanagan–Belytschko scaling).
  const Vec v3 = vol * (dt / 24.0), v9 = vol * (dt / 72.0);
  V3<Vec> dq[4];
  enhanced_forces(e, q, mu * v3, lambda_bar * v3, mu * v9, dq);
  const Vec w01 = spin[0], w02 = spin[1], w12 = spin[2];
  V3<Vec> turned[4], next[4];
  for (int m = 0; m < 4; ++m) {
    const V3<Vec>& o = old[m];
    // Q̇ = W Q for a vector that turns with the element.
    turned[m] = {o.x + dt * (w01 * o.y + w02 * o.z), o.y + dt * (w12 * o.z - w01 * o.x),
                 o.z - dt * (w02 * o.x + w12 * o.y)};
    next[m] = turned[m] + dq[m];
    if (relax != nullptr) next[m] = *relax * next[m];
  }
  if (limit != nullptr) bound_enhanced(ax, e, vol, *limit, next);
  s.power = simd::splat(0.0);
  for (int m = 0; m < 4; ++m) {
    s.stored[m] = next[m];
    s.force[m] = next[m];
    s.power += 8.0 * dot(0.5 * (turned[m] + next[m]), q[m]);
  }
}

}  // namespace xpl::elements
