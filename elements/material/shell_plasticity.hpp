#pragma once
/// \file Plane-stress J2 plasticity of the S4R section points: the closest-point return in
/// the plane-stress subspace (Simo & Taylor 1986; Simo & Hughes, Computational Inelasticity,
/// §3.4) and the plastic state of a shell block's section points.
///
/// Stress vector σ = (σxx, σyy, σxy), engineering shear strain. The yield condition is
/// σᵀPσ = ⅔ σ_y² with P = ⅓[[2,−1,0],[−1,2,0],[0,0,6]], i.e. the von Mises ellipse
/// σxx² − σxxσyy + σyy² + 3σxy² = σ_y², and σ33 = 0 holds by construction (the return never
/// leaves the plane-stress subspace; no 3D return with σ33 zeroed afterwards). The backward-
/// Euler return σ = (I + Δγ C P)⁻¹ σ_trial is diagonal in the common eigenbasis of the
/// plane-stress elasticity C and P:
///   (σxx+σyy)/√2 scaled by 1/(1 + Δγ E/(3(1−ν))),
///   (σyy−σxx)/√2 and σxy scaled by 1/(1 + 2GΔγ),
/// so the consistency condition is one scalar equation in Δγ, solved by safeguarded Newton,
/// finished by bisection where Newton does not converge (steep laws: plasticity_root.hpp).
/// The transverse shear stresses stay elastic (as in Belytschko–Tsay codes): they are not
/// part of the yield condition.

#include <span>
#include <vector>

#include "common/types.hpp"
#include "elements/material/plasticity.hpp"
#include "elements/parallel/simd.hpp"

namespace xpl::elements {

/// Result of the plane-stress return of one section point.
struct PlaneStressReturn {
  Real sxx = 0.0, syy = 0.0, sxy = 0.0;  ///< returned stress, Pa
  Real peeq_increment = 0.0;             ///< Δε̄ᵖ ≥ 0, -
  Real yield_stress = 0.0;               ///< σ_y at the end (with the rate factor), Pa
  Real static_yield = 0.0;               ///< σ_y(ε̄ᵖ_{n+1}, 0), Pa: the next trial's test
  /// Plastic thickness strain Δε33ᵖ = −(Δε11ᵖ + Δε22ᵖ) (plastic incompressibility), -.
  Real thickness_strain = 0.0;
  Real dissipation = 0.0;  ///< σ_y Δε̄ᵖ = σ : Δεᵖ, J/m^3
};

/// Plane-stress J2 return of one section point from the elastic trial stress
/// (σxx, σyy, σxy) (Pa), with plane-stress moduli `q11` = E/(1−ν²), `q12` = νE/(1−ν²),
/// `shear` = G (Pa), plastic strain `peeq` = ε̄ᵖ_n and increment `dt` (s; used by rate laws
/// only, ε̇ᵖ = Δε̄ᵖ/dt). Solves ‖σ(Δγ)‖_vM = σ_y(ε̄ᵖ_n + ⅔Δγ‖σ(Δγ)‖_vM, Δε̄ᵖ/dt) to a
/// relative residual of 1e-13; a trial inside σ_y(ε̄ᵖ_n, 0) is returned unchanged.
PlaneStressReturn plane_stress_return(const Plasticity& law, Real q11, Real q12, Real shear,
                                      Real sxx, Real syy, Real sxy, Real peeq, Real dt);

/// Plastic state of the section points of a batched shell block: equivalent plastic strain,
/// its rate and the static yield stress per point, and the laws of the plastic lanes.
/// Empty (no arrays, no work) when no element of the block is plastic.
class ShellPlasticState {
 public:
  static constexpr int W = simd::W;

  ShellPlasticState() = default;
  /// `lane_law`: per batch lane ([b][W]) the plastic law of its element, nullptr where
  /// elastic; `points` = section points per element of the block (max).
  ShellPlasticState(std::span<const Plasticity* const> lane_law, int points);

  bool empty() const { return m_laws.empty(); }
  /// Whether any lane of batch b is plastic.
  bool batch_plastic(std::size_t b) const { return !empty() && m_batch_plastic[b] != 0; }

  /// Plane-stress return of section point k of batch b, in place on the trial stresses
  /// (Pa) of the increment from the stresses `start` (σxx, σyy, σxy at t_n, Pa): one SIMD
  /// yield test, then the scalar return only in the lanes that yield. Returns the plastic
  /// work ½(σ_n + σ_{n+1}) : Δεᵖ (J/m^3) and adds Δε33ᵖ to `thickness_strain` weighted by
  /// `weight`, both zero in the lanes that stay elastic.
  simd::Vec point_return(std::size_t b, int k, simd::Vec q11, simd::Vec q12, simd::Vec shear,
                         Real dt, simd::Vec weight, const simd::Vec start[3], simd::Vec& sxx,
                         simd::Vec& syy, simd::Vec& sxy, simd::Vec& thickness_strain);

  /// σ_y(ε̄ᵖ, 0) (Pa) of section point k of batch b per lane after its last return (the next
  /// trial's yield test); +inf in elastic lanes.
  simd::Vec static_yield(std::size_t b, int k) const { return simd::load(&m_yield[row(b, k)]); }
  /// ε̄ᵖ (-) of section point k of batch b, lane l; 0 where elastic.
  Real peeq(std::size_t b, int k, std::size_t l) const;
  /// Δε̄ᵖ/dt (1/s) of the last increment of section point k of batch b, lane l.
  Real peeq_rate(std::size_t b, int k, std::size_t l) const;
  /// Sets ε̄ᵖ (≥ 0) of section point k of batch b, lane l (an imported state); the static
  /// yield stress follows. Elastic lanes are left alone.
  void set_peeq(std::size_t b, int k, std::size_t l, Real value);

 private:
  std::size_t row(std::size_t b, int k) const {
    return (b * static_cast<std::size_t>(m_points) + static_cast<std::size_t>(k)) * W;
  }

  int m_points = 0;
  std::vector<Plasticity> m_laws;              ///< distinct laws of the block
  std::vector<int> m_lane_law;                 ///< [b][W] index into m_laws, −1 elastic
  std::vector<unsigned char> m_batch_plastic;  ///< [b] any lane plastic
  std::vector<Real> m_peeq;                    ///< [b][points][W] ε̄ᵖ, -
  std::vector<Real> m_rate;                    ///< [b][points][W] Δε̄ᵖ/dt, 1/s
  std::vector<Real> m_yield;  ///< [b][points][W] σ_y(ε̄ᵖ, 0), Pa; +inf elastic
  /// [b][points][W] tabular laws: the table segment holding ε̄ᵖ (the last point ε_i ≤ ε̄ᵖ),
  /// kept up as ε̄ᵖ grows so that a return does not search the table.
  std::vector<int> m_segment;
  std::vector<std::vector<Real>> m_slopes;  ///< per law (tabular): slope of each segment, Pa
};

}  // namespace xpl::elements
