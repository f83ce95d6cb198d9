#pragma once
/// \file The through-thickness integration of the S4R kernel (Shell4rBlock::section_resultants,
/// shell4r_kernel.hpp): what it takes and leaves, and the sums of plastic batches it takes
/// after its loop over the section points.

#include <limits>

#include "common/types.hpp"
#include "elements/material/shell_plasticity.hpp"
#include "elements/parallel/kernel_inline.hpp"
#include "elements/parallel/simd.hpp"

namespace xpl::elements {

using simd::Vec;

/// Strain rates of a batch's reference surface on the mid-increment geometry (1/s): membrane
/// d, curvature κ (1/(m·s)), transverse shear γ.
struct ShellPlaneRates {
  Vec dxx, dyy, gxy, kxx, kyy, kxy, gxz, gyz;
};

/// What the through-thickness integration of a batch leaves: the end thickness (m), the
/// resultants per unit length (N/m, N), the strain and plastic work per unit area (J/m²).
struct ShellSectionResultants {
  Vec t, nxx, nyy, nxy, mxx, myy, mxy, qx, qy, work, plastic_work;
  /// Plastic batches, the state the physical hourglass follows: the section's tangent ratios
  /// over the increment, membrane (weights w) and bending (weights w ζ²), each in [0, 1]; the
  /// membrane return ratio |N| / |N_trial| (von Mises norms); the flow stress Σ w σ_y(end)
  /// (Pa). Elastic batches: 1, 1, 1 and +inf.
  Vec tangent_membrane = simd::splat(1.0), tangent_bending = simd::splat(1.0),
      membrane_return = simd::splat(1.0), flow = simd::splat(std::numeric_limits<Real>::infinity());
};

namespace shell4r_kernel {

/// Plastic batches with a yielding point: the section's tangent ratios, membrane return ratio
/// and flow stress (ShellSectionResultants) into `out`, from the sums over its points with
/// weights w: Σ w r and Σ w ζ² r of the points' tangent ratios r, Σ w ζ², the trial and
/// returned membrane resultants Σ t w σ (the same end thickness t), and Σ w σ_y (end of
/// increment; max(σ_y, σ_vM) to the return's tolerance). The weights of a batch's points sum
/// to 1 (Simpson, shell4r_setup.cpp).
XPL_KERNEL_INLINE void section_tangents(Vec tan_m, Vec tan_b, Vec weight_b, const Vec trial_n[3],
                                        const Vec returned_n[3], Vec flow,
                                        ShellSectionResultants& out) {
  const Vec one = simd::splat(1.0), tiny = simd::splat(1e-300);
  out.tangent_membrane = simd::min(tan_m, one);
  out.tangent_bending =
      simd::select(simd::greater(weight_b, 0.0), tan_b / simd::max(weight_b, tiny), one);
  out.flow = flow;
  const Vec n_trial =
      von_mises_product(trial_n[0], trial_n[1], trial_n[2], trial_n[0], trial_n[1], trial_n[2]);
  const Vec n_returned = von_mises_product(returned_n[0], returned_n[1], returned_n[2],
                                           returned_n[0], returned_n[1], returned_n[2]);
  out.membrane_return =
      simd::select(simd::greater(n_trial, 0.0),
                   simd::sqrt(simd::min(n_returned / simd::max(n_trial, tiny), one)), one);
}

/// Σ w over the `points` section points of a batch (rows of `weights`, [points][W]), in order:
/// the membrane tangent sum Σ w r of a batch where no point yielded (every r exactly 1).
XPL_KERNEL_INLINE Vec weight_sum(const Real* weights, int points) {
  Vec sum = simd::splat(0.0);
  for (int k = 0; k < points; ++k) sum += simd::load(weights + k * simd::W);
  return sum;
}

/// Section point k of a batch: its strain increment over the increment dt and its trial
/// stress (plane-stress moduli q11, q12, g) from the stresses at `s` (σxx, σyy, σxy rows);
/// ζ from the reference surface (`zetas` row k, `offset` its place), and the point's weights
/// `weight` times the mid-increment thickness (work) and the end thickness (resultants).
struct SectionTrial {
  Vec zeta, tw, zk_n, tw_n, exx, eyy, exy, sxx, syy, sxy, sxx_n, syy_n, sxy_n;
};
XPL_KERNEL_INLINE SectionTrial section_trial(const Real* zetas, int k, const Real* s, Vec weight,
                                             Vec offset, Vec t_mid, Vec t, Real dt,
                                             const ShellPlaneRates& r, Vec q11, Vec q12, Vec g) {
  SectionTrial p;
  p.zeta = 0.5 * simd::load(zetas + k * simd::W) - offset;
  const Vec zk = t_mid * p.zeta;  // mid-increment: strain and work
  p.tw = t_mid * weight;
  p.zk_n = t * p.zeta;  // end of increment: resultants
  p.tw_n = t * weight;
  p.exx = dt * (r.dxx + zk * r.kxx);
  p.eyy = dt * (r.dyy + zk * r.kyy);
  p.exy = dt * (r.gxy + zk * r.kxy);
  p.sxx = simd::load(s);
  p.syy = simd::load(s + simd::W);
  p.sxy = simd::load(s + 2 * simd::W);
  p.sxx_n = p.sxx + q11 * p.exx + q12 * p.eyy;
  p.syy_n = p.syy + q12 * p.exx + q11 * p.eyy;
  p.sxy_n = p.sxy + g * p.exy;
  return p;
}

/// Plastic batch b of `state`: whether the trial (section_trial) of one of its `points` section
/// points yields in a lane, by the test of the section loop (ShellPlasticState::yield_test).
/// `stress`: the batch's stress rows ([points][3][W]).
XPL_KERNEL_INLINE bool any_point_yields(const ShellPlasticState& state, std::size_t b, int points,
                                        const Real* stress, const Real* zetas, Vec offset,
                                        Vec t_mid, Vec t, Real dt, const ShellPlaneRates& r,
                                        Vec q11, Vec q12, Vec g) {
  for (int k = 0; k < points; ++k) {
    const SectionTrial p = section_trial(zetas, k, stress + k * 3 * simd::W, simd::splat(0.0),
                                         offset, t_mid, t, dt, r, q11, q12, g);
    if (simd::any(state.yield_test(b, k, p.sxx_n, p.syy_n, p.sxy_n).yielding)) return true;
  }
  return false;
}

/// Plastic incompressibility: Δε33 = −ν/(1−ν)(Δε11ᵉ + Δε22ᵉ) − (Δε11ᵖ + Δε22ᵖ). The section's
/// thickness update took the elastic term on the total strain Δεᵉ + Δεᵖ, so the plastic part
/// adds (1 − ν/(1−ν)) Δε33ᵖ, Δε33ᵖ averaged through the thickness with the weights
/// (`thinning`, Σ w Δε33ᵖ; `nu_ratio` ν/(1−ν)): the factor of the end thickness. N scales with
/// t and M with t², so the resultants follow it as in the elastic case (scale_resultants).
XPL_KERNEL_INLINE Vec plastic_thickness_factor(Vec nu_ratio, Vec thinning) {
  return 1.0 + (1.0 - nu_ratio) * thinning;
}

/// The transverse shear of a batch over the increment dt: the stresses in `shear` (τxz, τyz
/// rows) advanced elastically (modulus kg) by the rates gxz, gyz, their work per unit area
/// (mid-increment thickness t_mid) added to `work`, and the shear resultants of the end
/// thickness t into `out`.
XPL_KERNEL_INLINE void transverse_shear(Real* shear, Vec kg, Real dt, Vec gxz, Vec gyz, Vec t_mid,
                                        Vec t, Vec& work, ShellSectionResultants& out) {
  const Vec txz = simd::load(shear), tyz = simd::load(shear + simd::W);
  const Vec txz_n = txz + (kg * dt) * gxz, tyz_n = tyz + (kg * dt) * gyz;
  simd::store(shear, txz_n);
  simd::store(shear + simd::W, tyz_n);
  work += (0.5 * dt) * t_mid * ((txz + txz_n) * gxz + (tyz + tyz_n) * gyz);
  out.qx = t * txz_n;
  out.qy = t * tyz_n;
}

/// The membrane resultants times f and the bending ones times f² (a thickness scaled by f).
XPL_KERNEL_INLINE void scale_resultants(Vec f, Vec& nxx, Vec& nyy, Vec& nxy, Vec& mxx, Vec& myy,
                                        Vec& mxy) {
  const Vec f2 = f * f;
  nxx *= f;
  nyy *= f;
  nxy *= f;
  mxx *= f2;
  myy *= f2;
  mxy *= f2;
}

/// Plastic batches: the section's tangents and flow stress into `out` after the loop over its
/// `points` (rows of `weights`): where a point yielded (`yielded`), section_tangents of the
/// sums (the membrane resultants N = (nxx, nyy, nxy) returned, N + `returned_off` the
/// trial); where none did, every ratio is exactly 1, so the bending tangent Σ w ζ² r / Σ w ζ²
/// is 1 (out's default; Σ w ζ² ≥ 1e-300 or 0 with the section's weights) and the membrane one
/// Σ w as the loop forms it with r = 1, and the sums were never formed.
XPL_KERNEL_INLINE void plastic_tangents(bool yielded, Vec tan_m, Vec tan_b, Vec weight_b,
                                        const Vec returned_off[3], Vec nxx, Vec nyy, Vec nxy,
                                        Vec flow, const Real* weights, int points,
                                        ShellSectionResultants& out) {
  if (yielded) {
    const Vec returned_n[3] = {nxx, nyy, nxy};
    const Vec trial_n[3] = {nxx + returned_off[0], nyy + returned_off[1], nxy + returned_off[2]};
    section_tangents(tan_m, tan_b, weight_b, trial_n, returned_n, flow, out);
  } else {
    out.tangent_membrane = simd::min(weight_sum(weights, points), simd::splat(1.0));
    out.flow = flow;
  }
}

/// Perfectly plastic batches (ShellPlasticState::batch_constant `b` of `state`): the flow stress
/// Σ w σ_y over the `points` section rows of `weights` ([points][W]), every point's σ_y the
/// batch's one yield stress whether it yields or not (the return with slope 0 ends at σ_y = s +
/// 0·Δε̄ᵖ = s). The sum the section loop formed point by point, in the same order with the same
/// products, taken after it: carried through the returns, it was spilled at every point on AVX2.
XPL_KERNEL_INLINE Vec one_yield_flow(const Real* weights, int points,
                                     const ShellPlasticState& state, std::size_t b) {
  const Vec yield = state.static_yield(b, 0);
  Vec flow = simd::splat(0.0);
  for (int k = 0; k < points; ++k) {
    const Vec weight = simd::load(weights + k * simd::W);
    flow += simd::select(simd::greater(weight, 0.0), weight * yield, simd::splat(0.0));
  }
  return flow;
}

}  // namespace shell4r_kernel

}  // namespace xpl::elements
