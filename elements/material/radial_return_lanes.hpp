#pragma once
/// \file The J2 radial return of the hex integration points, one SIMD batch at a time.
///
/// A piecewise-linear hardening curve without rate dependence (tabular `*PLASTIC`, the
/// common metal deck) makes the consistency condition linear inside one table segment:
///   q_trial − 3G Δε̄ᵖ = σ_i + H_i (ε̄ᵖ_n + Δε̄ᵖ − ε_i)   ⇒   Δε̄ᵖ = (q_trial − σ_y,n) / (3G + H_i),
/// with (ε_i, σ_i, H_i) the segment that holds ε̄ᵖ_n. The lanes of a batch whose solution stays
/// inside their segment are returned together with masks, branch-free (one square root and
/// two divisions per batch instead of a scalar Newton per lane). The other yielding lanes (a
/// segment crossed within the increment, Johnson–Cook, rate laws, softening) take the scalar
/// `radial_return`, which is exact for them.

#include <cstddef>
#include <vector>

#include "common/types.hpp"
#include "elements/material/plasticity.hpp"
#include "elements/parallel/simd.hpp"

namespace xpl::elements {

/// Plastic work of one increment, ½(σ_n + σ_{n+1}) : Δεᵖ (J/m^3, Voigt 11 22 33 12 13 23),
/// from the stress at its start, the elastic trial and the returned stress: the return changes
/// the deviator only, σ_trial − σ_{n+1} = 2G Δεᵖ. The trapezoidal rule of the stress work
/// (ALLIE) makes ΔALLIE − ΔALLPD = ½(σ_n + σ_{n+1}) : C⁻¹ : (σ_{n+1} − σ_n), the change of the
/// elastic energy ½ σ : C⁻¹ : σ (up to the spin of the Jaumann rate, second order in dt): ALLSE
/// is the energy of the stress state. σ_y Δε̄ᵖ = σ_{n+1} : Δεᵖ (the backward-Euler work) books
/// ½(σ_{n+1} − σ_n) : Δεᵖ more each increment, and ALLSE drifts below it, negative in impacts.
inline simd::Vec return_work(const simd::Vec start[6], const simd::Vec trial[6],
                             const simd::Vec end[6], simd::Vec two_mu) {
  simd::Vec normal = simd::splat(0.0), shear = simd::splat(0.0);
  for (int c = 0; c < 3; ++c) normal += (start[c] + end[c]) * (trial[c] - end[c]);
  for (int c = 3; c < 6; ++c) shear += (start[c] + end[c]) * (trial[c] - end[c]);
  return (normal + 2.0 * shear) / (2.0 * two_mu);
}

/// Plastic state of the integration points of a hex block, one row of W lanes per batch
/// (and point): ε̄ᵖ, the static yield stress the next trial is tested against, and the
/// table segment that holds ε̄ᵖ. Slots are `row + lane`.
class RadialReturnLanes {
 public:
  static constexpr int W = simd::W;

  RadialReturnLanes() = default;
  /// `slots` points in all (a multiple of W); every lane elastic (σ_y = +inf) until `reset`.
  explicit RadialReturnLanes(std::size_t slots);

  /// Sets slot `slot` to plastic strain `peeq` (≥ 0) on `law`: its yield stress and segment.
  void reset(std::size_t slot, const Plasticity& law, Real peeq);

  /// Return of the W lanes of row `row` (a slot multiple of W), in place on the trial stress
  /// `sn` (Voigt 11 22 33 12 13 23, Pa) of the increment from the stress `start`; `two_mu` =
  /// 2G per lane (Pa), `laws[lane_law[l]]` the law of lane l (−1: elastic, never yields),
  /// dt > 0 (s). Writes Δε̄ᵖ/dt (1/s, 0 where elastic) to `rate` unless it is null; returns
  /// the plastic work per lane, return_work() (J/m^3; 0 where elastic).
  simd::Vec return_row(std::size_t row, const int* lane_law, const std::vector<Plasticity>& laws,
                       const simd::Vec start[6], simd::Vec sn[6], simd::Vec two_mu, Real dt,
                       Real* rate);

  Real peeq(std::size_t slot) const { return m_peeq[slot]; }
  /// The static yield stress σ_y(ε̄ᵖ, 0) of the W lanes of row `row` (Pa; +inf in elastic
  /// lanes): the bound of the C3D8R enhanced hourglass stresses (hex8r_hourglass.hpp).
  const Real* yield_row(std::size_t row) const { return &m_yield[row]; }

 private:
  std::vector<Real> m_peeq;   ///< ε̄ᵖ, -
  std::vector<Real> m_yield;  ///< σ_y(ε̄ᵖ, 0), Pa; +inf in elastic lanes
  /// The segment holding ε̄ᵖ: start (ε_i, σ_i), slope H_i ≥ 0 and end strain. The end is
  /// +inf on the last segment (constant after the table) and −inf where the batch return
  /// does not apply (not tabular, rate dependent, softening): those lanes always go scalar.
  std::vector<Real> m_seg_strain;
  std::vector<Real> m_seg_stress;
  std::vector<Real> m_seg_slope;
  std::vector<Real> m_seg_end;
};

}  // namespace xpl::elements
