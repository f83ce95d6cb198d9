#pragma once
/// \file J2 (von Mises) plasticity with isotropic hardening: the hardening laws of `*PLASTIC`
/// and `*RATE DEPENDENT`, and the scalar return of one integration point.
///
/// The flow stress is σ_y(ε̄ᵖ, ε̇ᵖ) = σ_0(ε̄ᵖ) · R(ε̇ᵖ) · Θ, with ε̄ᵖ the equivalent plastic
/// strain (PEEQ) and ε̇ᵖ its rate:
/// - tabular hardening (`HARDENING=ISOTROPIC`): σ_0 piecewise linear in ε̄ᵖ through the
///   table, held at the last value beyond it (as Abaqus does);
/// - Johnson–Cook (`HARDENING=JOHNSON COOK`): σ_0 = A + B (ε̄ᵖ)ⁿ;
/// - rate factor R: 1 without `*RATE DEPENDENT`; Johnson–Cook R = 1 + C ln(ε̇ᵖ/ε̇_0) for
///   ε̇ᵖ > ε̇_0, else 1; power law (Cowper–Symonds) R = 1 + (ε̇ᵖ/D)^(1/n);
/// - thermal factor Θ = 1: xpl has no temperature field, so the Johnson–Cook thermal
///   softening (m, θ_melt, θ_transition) is read and reported but has no effect.
///
/// The element kernels keep elastic lanes branch-free; only integration points whose trial
/// stress lies outside the yield surface call the scalar functions below.

#include <cstdint>
#include <vector>

#include "common/types.hpp"

namespace xpl::elements {

/// Form of σ_0(ε̄ᵖ).
enum class Hardening : std::uint8_t {
  Tabular,      ///< `HARDENING=ISOTROPIC`: table of (yield stress, plastic strain)
  JohnsonCook,  ///< `HARDENING=JOHNSON COOK`: A + B (ε̄ᵖ)ⁿ
};

/// Form of the rate factor R(ε̇ᵖ).
enum class RateDependence : std::uint8_t {
  None,         ///< R = 1
  JohnsonCook,  ///< `*RATE DEPENDENT, TYPE=JOHNSON COOK`: 1 + C ln(ε̇ᵖ/ε̇_0), ε̇ᵖ > ε̇_0
  PowerLaw,     ///< `*RATE DEPENDENT, TYPE=POWER LAW`: 1 + (ε̇ᵖ/D)^(1/n)
};

/// The plastic part of one material (consistent units, e.g. SI: Pa, s).
struct Plasticity {
  Hardening hardening = Hardening::Tabular;
  /// Tabular: yield stress (Pa, > 0) at each plastic strain (-, first 0, strictly
  /// increasing); same length, at least one point (one point = perfectly plastic).
  std::vector<Real> yield_stress;
  std::vector<Real> plastic_strain;
  /// Johnson–Cook σ_0 = A + B (ε̄ᵖ)ⁿ (A > 0, B ≥ 0, n > 0); thermal data kept for reports.
  Real jc_a = 0.0;
  Real jc_b = 0.0;
  Real jc_n = 1.0;
  Real jc_m = 0.0;
  Real jc_melt = 0.0;
  Real jc_transition = 0.0;
  RateDependence rate = RateDependence::None;
  Real rate_c = 0.0;          ///< Johnson–Cook C (≥ 0)
  Real rate_reference = 1.0;  ///< Johnson–Cook ε̇_0, 1/s (> 0)
  Real power_d = 0.0;         ///< Cowper–Symonds D, 1/s (> 0)
  Real power_n = 1.0;         ///< Cowper–Symonds n (> 0)

  /// σ_y at ε̄ᵖ = 0, ε̇ᵖ = 0, Pa.
  Real initial_yield() const;
  /// The largest σ_y at plastic strains up to PLAUSIBLE_PLASTIC_STRAIN and strain rates up to
  /// PLAUSIBLE_STRAIN_RATE, Pa; +inf or NaN when the constants overflow there (a Cowper–Symonds
  /// D of 1e-300, an exponent n of 1e-3, a Johnson–Cook C of 1e308): the deck reader refuses
  /// such a law. Every law whose value is finite is solved by radial_return and
  /// plane_stress_return (beyond these bounds the flow stress may overflow; the returns'
  /// bisection takes +inf as above the trial stress).
  Real largest_flow_stress() const;
  /// Whether the static hardening curve falls anywhere (softening), for the .msg report.
  bool softens() const;
};

/// Plastic strain up to which the deck reader requires a finite flow stress, -.
inline constexpr Real PLAUSIBLE_PLASTIC_STRAIN = 10.0;
/// Strain rate up to which the deck reader requires a finite flow stress, 1/s (beyond the
/// 1e6–1e7 /s of ballistic impacts).
inline constexpr Real PLAUSIBLE_STRAIN_RATE = 1e8;

/// Flow stress and its partial derivatives at one state.
struct FlowStress {
  Real stress = 0.0;    ///< σ_y, Pa
  Real d_strain = 0.0;  ///< ∂σ_y/∂ε̄ᵖ, Pa (right derivative at table breaks)
  Real d_rate = 0.0;    ///< ∂σ_y/∂ε̇ᵖ, Pa·s
};

/// σ_y(ε̄ᵖ, ε̇ᵖ) with its derivatives. Where a derivative is unbounded (Johnson–Cook n < 1
/// at ε̄ᵖ = 0, the logarithm or a power law at ε̇ᵖ → 0) it is evaluated at a small positive
/// argument instead, which the safeguarded solver below tolerates.
FlowStress flow_stress(const Plasticity& law, Real peeq, Real peeq_rate);

/// Result of a return of one integration point.
struct PlasticIncrement {
  Real peeq_increment = 0.0;  ///< Δε̄ᵖ ≥ 0 (0: the trial state is admissible)
  Real yield_stress = 0.0;    ///< σ_y at the end of the increment, Pa
};

/// J2 radial return for a 3D (or any) state whose von Mises trial stress q_trial falls by
/// 3G per unit of Δε̄ᵖ: solves q_trial − 3G Δε̄ᵖ = σ_y(ε̄ᵖ_n + Δε̄ᵖ, Δε̄ᵖ/dt) for Δε̄ᵖ.
/// Exact (one step) for linear hardening without rate dependence; otherwise Newton on the
/// consistency condition, safeguarded by bisection on [0, q_trial/3G], to a relative residual
/// of 1e-12 of σ_y (or Δε̄ᵖ to 1e-15). Where Newton does not converge in 100 iterations (steep
/// rate laws and hardening exponents), bisection on the bracket it leaves finishes the solve
/// (plasticity_root.hpp): every law the reader accepts ends on the yield surface, at the
/// residual's root or between two adjacent doubles that bracket it (then σ_y = q_trial − 3GΔ).
/// `three_g` = 3G (Pa), `peeq` = ε̄ᵖ_n, `dt` > 0 (s; rate laws only). The deviatoric trial
/// stress is then scaled by σ_y/q_trial.
PlasticIncrement radial_return(const Plasticity& law, Real q_trial, Real three_g, Real peeq,
                               Real dt);

}  // namespace xpl::elements
