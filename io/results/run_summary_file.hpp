#pragma once
/// \file JOB.summary.json and /summary of JOB.h5: the machine-readable record of how a run
/// went (status, increments, wall time per phase, speed, memory, energies), written at the
/// end of every run and data check, failed and interrupted ones included. The keys are
/// described by apps/summary.schema.json.

#include <filesystem>
#include <optional>
#include <string>

#include "common/timer.hpp"
#include "common/types.hpp"
#include "common/units.hpp"
#include "io/result_tools/json_value.hpp"
#include "solver/model/state.hpp"
#include "solver/output/output_sink.hpp"

namespace xpl::io {

/// Version of the summary's layout; raised when a key changes meaning or disappears.
constexpr int SUMMARY_FORMAT = 1;

/// What the summary records, gathered by ResultFiles while the run goes.
struct SummaryRecord {
  std::string job;               ///< job name (deck stem)
  std::string status;            ///< completed, checked, failed, interrupted
  std::string exit_reason;       ///< the error or interruption text; "" when completed or checked
  int threads = 0;               ///< OpenMP threads of the run
  Index nodes = 0;               ///< nodes of the model
  Index elements = 0;            ///< elements of the model
  int steps = 0;                 ///< steps of the model
  ModelUnits units;              ///< the units of the model's numbers
  int steps_started = 0;         ///< steps begun by the run
  long increments = 0;           ///< increments at the last status line
  Real simulated_time = 0;       ///< total time at the last status line, s
  Real first_increment = 0;      ///< stable increment of the first status line, s
  Real last_increment = 0;       ///< increment of the last status line, s
  PhaseTimers timers;            ///< wall time per phase of the solver, s
  double elapsed_seconds = 0.0;  ///< wall time from opening the files to the end, s
  double element_cycles_per_second = 0.0;  ///< elements × increments / time-loop wall time
  bool has_energies = false;               ///< a status line was written
  Energies energies;                       ///< at the last status line, J
  /// The largest energy-balance drift of the run: the solver's (every increment, set by
  /// set_drift) once the run has one; before that (a data check, a run that failed before
  /// its first increment) the largest |ETOTAL − ETOTAL₀| over the status lines, J, with
  /// ETOTAL₀ that of the first status line, the total time where it occurred (s), and the
  /// energy scale it is measured against, J.
  Real energy_error = 0.0;
  Real energy_error_time = 0.0;
  Real energy_scale = 0.0;
  Real relative_error = 0.0;  ///< energy_error / energy_scale
  /// The partition and the ranks' times of a run distributed over MPI ranks ("mpi"), else
  /// none (no key).
  std::optional<DistributionSummary> distribution;

  /// Takes in one .sta line: increments, time, energies, the balance error.
  void add_status(const StatusLine& line);
  /// The solver's largest drift, which the summary then reports instead of its own.
  void set_drift(const BalanceDrift& drift);
  /// The summary as a JSON tree (keys as in apps/summary.schema.json); adds the xpl version,
  /// build flags and the peak memory of this process.
  JsonValue json() const;

 private:
  Real m_initial_total = 0.0;   ///< ETOTAL of the first status line, J
  bool m_solver_drift = false;  ///< set_drift() was called
};

/// Peak resident memory of this process (getrusage), MB.
double peak_memory_mb();

/// Writes `summary` as JSON text to `path` through a temporary file renamed into place, so
/// that a reader never sees half a file. Throws std::runtime_error if it cannot.
void write_summary_json(const std::filesystem::path& path, const JsonValue& summary);

/// Where the summary of the job whose JOB.h5 is `h5` goes: JOB.summary.json beside it.
std::filesystem::path summary_path(const std::filesystem::path& h5);

}  // namespace xpl::io
