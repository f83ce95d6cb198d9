#pragma once
/// \file The hourglass resultants of one C3D8R batch over one increment, in the two families
/// the block runs (hex8r.cpp): Flanagan–Belytschko's stiffness and viscous forms, and the
/// enhanced assumed-strain stabilisation (hex8r_enhanced.hpp) with its plastic bound. Both
/// return the resultants Q_α (α = 4..7, global, conjugate to q_α = γ_α·v = 8 (av_α − L a_α))
/// that the force assembly applies, the state kept for the next increment (12 values per
/// element: the stiffness form's resultants, or the enhanced form's frame stresses), and the
/// hourglass power (W) whose integral is the artificial energy ALLAE.

#include <limits>

#include "elements/hex/hex8r_enhanced.hpp"
#include "elements/parallel/simd.hpp"

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

/// Amplitude of the linear hourglass stress that carries a section's fully plastic moment:
/// σ_y t²/4 = (κ σ_y) t²/6 with κ = 3/2.
inline constexpr Real HOURGLASS_PLASTIC_AMPLITUDE = 1.5;

/// What the radial return of a lane's stress gives the enhanced stabilisation (hex8r.hpp).
struct PlasticHourglass {
  simd::Vec relax;    ///< |dev σ| / |dev σ_trial|: 1 where nothing yielded
  simd::Vec limit;    ///< bound of the plane hourglass stresses, Pa (+inf: none)
  simd::Vec flow[6];  ///< unit flow direction dev σ/|dev σ| (Voigt), 0 where nothing flowed
};

/// An elastic lane's: no relaxation, no bound, no flow.
inline PlasticHourglass elastic_hourglass() {
  PlasticHourglass h;
  h.relax = simd::splat(1.0);
  h.limit = simd::splat(std::numeric_limits<Real>::infinity());
  for (simd::Vec& n : h.flow) n = simd::splat(0.0);
  return h;
}

/// A plastic lane's, from the returned stress `sn` (Voigt, Pa), the squared deviator norms
/// before (`trial`) and after (`returned`) the return and the static yield stress `yield` (Pa):
/// the return factor, 3/2 of the flow stress (the static yield stress, or the rate-raised von
/// Mises stress of a flowing lane; HOURGLASS_PLASTIC_AMPLITUDE) and the flow direction.
inline PlasticHourglass plastic_hourglass(const simd::Vec sn[6], simd::Vec trial,
                                          simd::Vec returned, simd::Vec yield) {
  using simd::Vec;
  PlasticHourglass h;
  h.relax = return_factor(trial, returned);
  h.limit = HOURGLASS_PLASTIC_AMPLITUDE * simd::max(yield, simd::sqrt(1.5 * returned));
  const Vec p = (sn[0] + sn[1] + sn[2]) * (1.0 / 3.0);
  const Vec inv = simd::select(
      h.relax < 1.0, 1.0 / simd::sqrt(simd::max(returned, simd::splat(1e-300))), simd::splat(0.0));
  for (int c = 0; c < 3; ++c) h.flow[c] = (sn[c] - p) * inv;
  for (int c = 3; c < 6; ++c) h.flow[c] = sn[c] * inv;
  return h;
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

/// The plastic bound of the enhanced state `S` (ENHANCED_STATE values per lane, see
/// hex8r_enhanced.hpp): each plane's von Mises stress, √(S_a² + S_b² − S_a S_b + 3 S_ab²), is
/// scaled down to `limit` (Pa per lane; +inf: no bound) where it exceeds it; the ξηζ
/// resultant to the energy of a shear at the limit, Σ_i Q̂7_i²/(2 k7_i) ≤ (V/9) limit²/(6μ)
/// with k7_i = (V/9) μ d_i (`d` = Σc² + c_i², 1/m²; `v9` = V/9, m³). A lane within the bound
/// is untouched.
inline void bound_enhanced(simd::Vec limit, const V3<simd::Vec>& d, simd::Vec v9,
                           simd::Vec S[ENHANCED_STATE]) {
  using simd::Vec;
  const Vec limit2 = limit * limit;
  for (int p = 0; p < 3; ++p) {
    const Vec a = S[3 * p], b = S[3 * p + 1], t = S[3 * p + 2];
    const Vec m2 = a * a + b * b - a * b + 3.0 * t * t;
    const simd::Mask over = m2 > limit2;
    if (!simd::any(over)) continue;
    const Vec f = simd::select(over, limit / simd::sqrt(simd::max(m2, limit2)), simd::splat(1.0));
    for (int k = 0; k < 3; ++k) S[3 * p + k] = f * S[3 * p + k];
  }
  const Vec q = S[9] * S[9] / d.x + S[10] * S[10] / d.y + S[11] * S[11] / d.z;
  const Vec cap = v9 * v9 * limit2 * (1.0 / 3.0);
  const simd::Mask over = q > cap;
  if (!simd::any(over)) return;
  const Vec f = simd::select(over, simd::sqrt(cap / simd::max(q, cap)), simd::splat(1.0));
  for (int k = 9; k < 12; ++k) S[k] = f * S[k];
}

/// The hourglass strain rates `eps` (enhanced_strains()) of a lane whose centre flows, less
/// their part along the centre's flow direction: `flow` the unit deviatoric direction
/// dev σ/|dev σ| (Voigt 11 22 33 12 13 23, global; all zero in a lane that does not flow),
/// `ratio` = λ̄/2μ (the plane-stress transverse strain −ratio (ε_a + ε_b) of each plane).
/// Each plane's strain, completed by its transverse strain, loses (N:ε) N on the plane's
/// components: the elastic–plastic tangent of J2 flow with a hardening modulus small next to
/// μ, which a fully integrated element's points apply to the linear variation of the strain.
inline void flow_projected(const EnhancedFrame<simd::Vec>& f, const simd::Vec* flow,
                           simd::Vec ratio, const simd::Vec eps[9], simd::Vec out[9]) {
  using simd::Vec;
  // N in the element frame, n[i][j] = e_i·N·e_j.
  Vec n[3][3];
  for (int i = 0; i < 3; ++i) {
    const V3<Vec>& e = f.e[i];
    const V3<Vec> ne{flow[0] * e.x + flow[3] * e.y + flow[4] * e.z,
                     flow[3] * e.x + flow[1] * e.y + flow[5] * e.z,
                     flow[4] * e.x + flow[5] * e.y + flow[2] * e.z};
    for (int j = 0; j < 3; ++j) n[i][j] = dot(f.e[j], ne);
  }
  // Planes ξ, η, ζ: in-plane axes (a, b) and normal c.
  constexpr int axes[3][3] = {{1, 2, 0}, {0, 2, 1}, {0, 1, 2}};
  for (int p = 0; p < 3; ++p) {
    const int a = axes[p][0], b = axes[p][1], c = axes[p][2];
    const Vec ea = eps[3 * p], eb = eps[3 * p + 1], g = eps[3 * p + 2];
    const Vec ec = -ratio * (ea + eb);
    const Vec along = n[a][a] * ea + n[b][b] * eb + n[a][b] * g + n[c][c] * ec;
    out[3 * p] = ea - along * n[a][a];
    out[3 * p + 1] = eb - along * n[b][b];
    out[3 * p + 2] = g - 2.0 * along * n[a][b];
  }
}

/// The enhanced stabilisation over one increment (hex8r_enhanced.hpp). Hourglass velocities
/// q̂_α = av_α − L a_α on the mid-increment geometry (`L` the mid velocity gradient, 1/s; the
/// mid modes a − ½dt av), so that a linear field gives exactly zero; the frame on the end
/// geometry (`ax`, `g3` = ∂V/∂a3 there, `vol`, `inv_vol`). The state `old` (ENHANCED_STATE
/// rows) advances to `next` with the moduli `mu` = κμ, `lambda_bar` = κλ̄ (Pa per lane), then
/// is multiplied by `relax` and bounded by `limit` (bound_enhanced) unless these are null.
/// PROJECT (a plastic batch): the strain increments lose their part along the centre's flow
/// direction `flow` first (flow_projected(); 6 rows, 0 in a lane that does not flow).
/// `force` receives the Flanagan–Belytschko resultants Q_α = R Q̂_α / 8 (N) the assembly
/// applies, `power` the hourglass power with the mean stresses of the increment (W).
template <bool PROJECT>
inline void enhanced_step(const V3<simd::Vec> ax[8], const V3<simd::Vec> av[8],
                          const V3<simd::Vec>& g3, const simd::Vec L[3][3], simd::Vec vol,
                          simd::Vec inv_vol, simd::Vec mu, simd::Vec lambda_bar, Real dt,
                          const simd::Vec* relax, const simd::Vec* limit, const simd::Vec* flow,
                          const simd::Vec old[ENHANCED_STATE], simd::Vec next[ENHANCED_STATE],
                          V3<simd::Vec> force[4], simd::Vec& power) {
  using simd::Vec;
  const Real half_dt = 0.5 * dt;
  V3<Vec> q[4];
  for (int m = 0; m < 4; ++m) {
    const V3<Vec> a = ax[4 + m] - half_dt * av[4 + m];
    q[m] = av[4 + m] - V3<Vec>{L[0][0] * a.x + L[0][1] * a.y + L[0][2] * a.z,
                               L[1][0] * a.x + L[1][1] * a.y + L[1][2] * a.z,
                               L[2][0] * a.x + L[2][1] * a.y + L[2][2] * a.z};
  }
  const EnhancedFrame<Vec> f = enhanced_frame(ax, g3, inv_vol);
  V3<Vec> u[4];
  to_frame(f, q, u);
  Vec eps[9], ds[9];
  enhanced_strains(f, u, eps);
  const Vec lb = lambda_bar * dt;
  if constexpr (PROJECT) {
    // The hourglass strain along the centre's flow direction is plastic (0 where none flows).
    Vec moved[9];
    flow_projected(f, flow, lambda_bar / simd::max(2.0 * mu, simd::splat(1e-300)), eps, moved);
    enhanced_stress_increment(moved, mu * (2.0 * dt) + lb, lb, mu * dt, ds);
  } else {
    enhanced_stress_increment(eps, mu * (2.0 * dt) + lb, lb, mu * dt, ds);
  }
  for (int k = 0; k < 9; ++k) next[k] = old[k] + ds[k];
  const Vec v9 = vol * (1.0 / 9.0);
  const V3<Vec> k7 = enhanced_mode7_stiffness(f, v9 * mu);
  next[9] = old[9] + dt * k7.x * u[3].x;
  next[10] = old[10] + dt * k7.y * u[3].y;
  next[11] = old[11] + dt * k7.z * u[3].z;
  if (relax != nullptr)
    for (int k = 0; k < ENHANCED_STATE; ++k) next[k] = *relax * next[k];
  if (limit != nullptr) {
    const Vec c1 = f.c[0] * f.c[0], c2 = f.c[1] * f.c[1], c3 = f.c[2] * f.c[2];
    const Vec sum = c1 + c2 + c3;
    bound_enhanced(*limit, V3<Vec>{sum + c1, sum + c2, sum + c3}, v9, next);
  }
  const Vec v3 = vol * (1.0 / 3.0);
  Vec work = simd::splat(0.0);
  for (int k = 0; k < 9; ++k) work += (old[k] + next[k]) * eps[k];
  power = 0.5 * (v3 * work + (old[9] + next[9]) * u[3].x + (old[10] + next[10]) * u[3].y +
                 (old[11] + next[11]) * u[3].z);
  V3<Vec> Q[3];
  enhanced_forces(f, next, v3, Q);
  for (int m = 0; m < 3; ++m) force[m] = from_frame(f, 0.125 * Q[m]);
  force[3] = from_frame(f, 0.125 * V3<Vec>{next[9], next[10], next[11]});
}

}  // namespace xpl::elements
