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

/// Plastic batches: the section's tangent ratios, membrane return ratio and flow stress
/// (ShellSectionResultants) into `out`, from the sums over its points with weights w: Σ w r
/// and Σ w ζ² r of the points' tangent ratios r, Σ w ζ², the trial and returned membrane
/// resultants Σ t w σ (the same end thickness t), and Σ w σ_y (end of increment; max(σ_y,
/// σ_vM) to the return's tolerance). The weights of a batch's points sum to 1 (Simpson,
/// shell4r_setup.cpp). `yielded`: whether a point of the batch yielded; where none did, the
/// membrane return ratio is 1 without its root and divisions (the trial is the return).
XPL_KERNEL_INLINE void section_tangents(Vec tan_m, Vec tan_b, Vec weight_b, const Vec trial_n[3],
                                        const Vec returned_n[3], Vec flow, bool yielded,
                                        ShellSectionResultants& out) {
  const Vec one = simd::splat(1.0), tiny = simd::splat(1e-300);
  out.tangent_membrane = simd::min(tan_m, one);
  out.tangent_bending =
      simd::select(simd::greater(weight_b, 0.0), tan_b / simd::max(weight_b, tiny), one);
  out.flow = flow;
  if (!yielded) return;
  const Vec n_trial =
      von_mises_product(trial_n[0], trial_n[1], trial_n[2], trial_n[0], trial_n[1], trial_n[2]);
  const Vec n_returned = von_mises_product(returned_n[0], returned_n[1], returned_n[2],
                                           returned_n[0], returned_n[1], returned_n[2]);
  out.membrane_return =
      simd::select(simd::greater(n_trial, 0.0),
                   simd::sqrt(simd::min(n_returned / simd::max(n_trial, tiny), one)), one);
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
