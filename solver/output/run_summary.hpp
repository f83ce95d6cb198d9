#pragma once
/// \file What a finished run reports (ExplicitSolver::run, OutputDriver::summary): its own
/// header so that the parts of the loop need not include the solver that drives them.

#include "common/timer.hpp"
#include "common/types.hpp"
#include "solver/model/state.hpp"

namespace xpl {

/// What a finished run reports.
struct RunSummary {
  long increments = 0;
  Real final_time = 0.0;
  double element_cycles_per_second = 0.0;  ///< elements × increments / time-loop wall time
  PhaseTimers timers;
  Energies energies;    ///< at the end
  int stop_signal = 0;  ///< the signal that interrupted the run (status interrupted), or 0
  /// The largest |ETOTAL drift| of the run as a fraction of the largest energy, and when.
  Real energy_drift = 0.0;
  Real energy_drift_time = 0.0;  ///< s
};

}  // namespace xpl
