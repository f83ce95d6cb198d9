#pragma once
/// \file The health check of the time loop: collapsed elements, non-finite energies, a lost
/// energy balance and a collapsing stable increment stop the run with a SolverError.

#include "common/types.hpp"
#include "solver/element_set.hpp"
#include "solver/model.hpp"
#include "solver/state.hpp"

namespace xpl {

/// Watches the energy balance ETOTAL and the stable increment of a run.
class EnergyCheck {
 public:
  /// `model` must outlive the check; a stable increment below `dt_floor_ratio` times the
  /// first one stops the run (SolverOptions::dt_floor_ratio).
  EnergyCheck(const Model& model, Real dt_floor_ratio);

  /// The reference of the balance: ETOTAL of the state after the first update (J) and the
  /// first increment (s).
  void start(const State& state, Real dt_first);
  /// A step starts at increment `increment`: the balance is checked only after a warm-up.
  void begin_step(long increment) { m_step_first_increment = increment; }
  /// Throws SolverError if the increment just taken went wrong: an element failed in
  /// `totals`, an energy is not finite, ETOTAL drifted by more than half the largest energy
  /// seen, or the next increment `dt_next` (s) collapsed. `critical_id` is the deck id of
  /// the element that limits the increment (for the message).
  void check(const State& state, const ElementTotals& totals, Real dt_next, ExternalId critical_id);

 private:
  const Model& m_model;
  Real m_dt_floor_ratio;
  Real m_dt_first = 0.0;            ///< first stable increment, s
  Real m_max_energy = 0.0;          ///< running maximum of the energy scales, J
  Real m_initial_total = 0.0;       ///< ETOTAL after the first update, J
  long m_step_first_increment = 0;  ///< state.increment at the start of the current step
};

}  // namespace xpl
