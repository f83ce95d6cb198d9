#pragma once
/// \file The health check of the time loop: collapsed elements, non-finite energies, a drifting
/// energy balance and a collapsing stable increment. A drift of ETOTAL above 1 % of the
/// largest energy is warned of once; above the run's limit (SolverOptions::energy_limit,
/// `xpl run --energy-limit`) and on every other failure the run stops with a SolverError.

#include <vector>

#include "common/types.hpp"
#include "solver/element_set.hpp"
#include "solver/model.hpp"
#include "solver/output_sink.hpp"
#include "solver/state.hpp"

namespace xpl {

/// ETOTAL drift (as a fraction of the largest energy) above which .msg and .sta warn, once.
inline constexpr Real ENERGY_WARNING_FRACTION = 0.01;
/// Increments below this fraction of the model's wave transit time stop the run, whatever
/// the first increment was (an initial velocity of 1e12 m/s makes even that one zero).
inline constexpr Real DT_TRANSIT_FLOOR = 1e-9;

/// The largest ETOTAL drift of a run: where it was and the energy that moved most then.
struct EnergyDrift {
  Real fraction = 0.0;      ///< |ETOTAL − ETOTAL_0| / largest energy
  Real drift = 0.0;         ///< ETOTAL − ETOTAL_0, J
  Real largest = 0.0;       ///< the largest energy (ALLKE, ALLIE or |ALLWK|) so far, J
  Real time = 0.0;          ///< total time, s
  long increment = 0;       ///< increment number
  const char* mover = "";   ///< the term of the balance that changed most ("ALLKE")
  Real mover_change = 0.0;  ///< its change since the reference, J
};

/// Watches the energy balance ETOTAL and the stable increment of a run.
class EnergyCheck {
 public:
  /// `model` must outlive the check; a stable increment below `dt_floor_ratio` times the
  /// first one (SolverOptions::dt_floor_ratio) or below DT_TRANSIT_FLOOR times the wave
  /// transit time stops the run; so does an ETOTAL drift above `energy_limit` (a fraction
  /// of the largest energy; SolverOptions::energy_limit).
  EnergyCheck(const Model& model, Real dt_floor_ratio, Real energy_limit);

  /// The reference of the balance: ETOTAL of the state after the first update (J) and the
  /// first increment (s).
  void start(const State& state, Real dt_first);
  /// A step starts at increment `increment`: the balance is checked only after a warm-up.
  void begin_step(long increment) { m_step_first_increment = increment; }
  /// Throws SolverError if the increment just taken went wrong: an element failed in
  /// `totals`, an energy is not finite, ETOTAL drifted beyond the limit, or the next
  /// increment `dt_next` (s) collapsed. Warns `sink` (.msg and .sta) once when the drift
  /// first passes ENERGY_WARNING_FRACTION. `critical_id` is the deck id of the element that
  /// limits the increment (for the message).
  void check(const State& state, const ElementTotals& totals, Real dt_next, ExternalId critical_id,
             OutputSink& sink);

  /// The largest drift seen so far (fraction 0 before the first check).
  const EnergyDrift& largest_drift() const { return m_largest; }
  /// The model's wave transit time: its largest extent over the fastest dilatational wave
  /// speed of its materials, s (0 when it has no elastic material).
  Real transit_time() const { return m_transit_time; }

 private:
  /// The drift of `state` against the reference, with the term that moved most.
  EnergyDrift drift_of(const State& state) const;

  const Model& m_model;
  Real m_dt_floor_ratio;
  Real m_energy_limit;
  Real m_transit_time = 0.0;        ///< s
  Real m_dt_first = 0.0;            ///< first stable increment, s
  Real m_max_energy = 0.0;          ///< running maximum of the energy scales, J
  Real m_initial_total = 0.0;       ///< ETOTAL after the first update, J
  std::vector<Real> m_initial;      ///< each term of the balance then (ENERGIES order), J
  long m_step_first_increment = 0;  ///< state.increment at the start of the current step
  bool m_warned = false;            ///< the 1 % warning has been given
  EnergyDrift m_largest;
};

/// "2.3 % of the largest energy 1.5 J at t = 3e-05 s (increment 120); ALLKE moved most
/// (-0.8 J)": the text of a drift for messages.
std::string describe(const EnergyDrift& drift);

}  // namespace xpl
