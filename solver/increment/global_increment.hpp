#pragma once
/// \file The global stable-increment limit: the model's highest frequency ω_max, estimated by
/// Lanczos iterations on the linearised operator M⁻¹K of the hex elements, bounds the
/// element-by-element estimate where that is not conservative (elements with few
/// neighbours: single elements, single element layers, bars one element thick).

#include <functional>
#include <vector>

#include "common/types.hpp"
#include "elements/hex/hex8r.hpp"
#include "elements/increment_limit.hpp"

namespace xpl {

/// One estimate of the highest frequency and what it does to the increment.
struct FrequencyEstimate {
  Real omega_max = 0.0;   ///< estimated highest circular frequency of M⁻¹K, rad/s
  Real global_dt = 0.0;   ///< (2/ω_max)·(√(1+ξ²)−ξ), ξ = linear bulk viscosity, s
  Real element_dt = 0.0;  ///< element-by-element estimate at the same time, s
  Real ratio = 1.0;       ///< factor on the element estimate until the next estimate (≤ 1)
  int products = 0;       ///< stiffness products (element passes) the estimate took
  double seconds = 0.0;   ///< wall time of the estimate
  bool governs() const { return ratio < 1.0; }
};

/// Calibrates and applies the global limit: Δt = min(Δt_e, Δt_global / GLOBAL_MARGIN).
/// The estimate is made at the start of each step and again when the element estimate has
/// moved by more than RECALIBRATE_CHANGE since (at most every MIN_INCREMENTS_BETWEEN
/// increments); in between the element estimate is scaled by
/// the calibrated ratio (a property of the mesh topology and material), which is never above 1.
class GlobalIncrementLimit {
 public:
  /// Δt ≤ Δt_global / GLOBAL_MARGIN before the safety factor: with the default safety 0.9 the
  /// linear limit lies at scale factor 0.97/0.9 = 1.078 where the global limit governs (the
  /// stress test fails at 1.06–1.15); meshes whose element estimate is within 1/0.97 = 1.031
  /// of the global limit (regular meshes: 1.00–1.025) keep the element estimate bit for bit.
  static constexpr Real GLOBAL_MARGIN = 0.97;
  /// Relative change of the element estimate that calls for a new estimate.
  static constexpr Real RECALIBRATE_CHANGE = 0.1;
  /// Fewest increments between two estimates within a step (an element estimate that swings
  /// with the bulk viscosity must not call for one every increment).
  static constexpr int MIN_INCREMENTS_BETWEEN = 100;
  /// Most Lanczos iterations (stiffness products) per estimate.
  static constexpr int MAX_ITERATIONS = 60;
  /// Convergence: relative change of the largest Ritz value per iteration (the remaining
  /// error is then about as large: ~0.05 % on Δt).
  static constexpr Real TOLERANCE = 1e-3;

  /// Starts a step: the next apply() estimates anew.
  void begin_step() { m_due = true; }

  /// y += K u of the elements at the current positions (u, y: n_nodes × 3; m, N).
  using StiffnessProduct = std::function<void(const NodalVectors& u, NodalVectors& y)>;

  /// The factor r ≤ 1 the limit puts on `limit.stable_dt` (element estimate, s; the increment
  /// control applies it, increment_control.hpp), estimating ω_max with `hex` at `position`
  /// (n_nodes × 3) and `inverse_mass` (n_nodes, 1/kg) when due; `bulk_linear` is the step's
  /// b1. Exactly 1 where the element estimate is safe, or not finite, or an element failed.
  Real apply(const elements::Hex8rBlock& hex, const NodalVectors& position,
             const std::vector<Real>& inverse_mass, Real bulk_linear,
             const elements::IncrementLimit& limit);
  /// The same with the stiffness product of any set of elements (C3D8R and C3D8 blocks) over
  /// `n_nodes` nodes.
  Real apply(const StiffnessProduct& product, Index n_nodes, const std::vector<Real>& inverse_mass,
             Real bulk_linear, const elements::IncrementLimit& limit);

  /// Distributed runs (solver/distributed_run.hpp): the estimate is made on one rank only and
  /// shared. When an estimate is due, every rank calls `prepare` (collective: e.g. the positions
  /// gathered to the rank that estimates), the rank with `estimates` runs the Lanczos
  /// iteration, and `share(lambda, products)` puts its largest eigenvalue and product count on
  /// every rank (collective); the same λ gives every rank the same ratio, bit for bit.
  using Prepare = std::function<void()>;
  using Share = std::function<void(Real& lambda, int& products)>;
  void set_distribution(bool estimates, Share share) {
    m_estimates = estimates;
    m_share = std::move(share);
  }
  /// apply() with a `prepare` step (set_distribution()).
  Real apply(const StiffnessProduct& product, Index n_nodes, const std::vector<Real>& inverse_mass,
             Real bulk_linear, const elements::IncrementLimit& limit, const Prepare& prepare);

  /// The estimate made since the last call, if any (for the .msg); false if none.
  bool take_new_estimate(FrequencyEstimate& out);
  /// The last estimate (ratio 1 and omega 0 before the first).
  const FrequencyEstimate& last() const { return m_last; }

 private:
  /// Largest eigenvalue of M⁻¹K (1/s²) by Lanczos on D K D, D = M^{-1/2} (0 at nodes
  /// without mass of their own: rigid-body and massless nodes).
  Real largest_eigenvalue(const StiffnessProduct& product, Index n_nodes,
                          const std::vector<Real>& inverse_mass, int& products) const;

  bool m_due = true;
  int m_since = 0;          ///< apply() calls since the last estimate
  bool m_estimates = true;  ///< set_distribution(): this rank runs the estimate
  Share m_share;            ///< set_distribution(); empty: one rank
  bool m_reported = true;
  FrequencyEstimate m_last;
};

}  // namespace xpl
