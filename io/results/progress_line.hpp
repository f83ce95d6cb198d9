#pragma once
/// \file The progress line a run shows on the terminal: where the analysis is (step, time,
/// increment), how long it has run, how fast it goes and when it should end. The estimate
/// divides the simulated time still to run by the simulated time per wall-clock second
/// measured since the time loop started (a mean over the whole run, not a recent window:
/// steady, though slow to follow a run whose cost per increment changes, such as contact that
/// starts late).

#include <string>

#include "common/types.hpp"
#include "solver/output/output_sink.hpp"

namespace xpl::io {

/// Wall-clock seconds as "m:ss" (below an hour) or "h:mm:ss"; "--:--" for a negative or
/// non-finite value.
std::string clock_text(double seconds);

/// Turns status lines and wall-clock times into the text of the progress line.
class ProgressMeter {
 public:
  /// `analysis_time`: the sum of the step periods (the total time at the end of the last
  /// step), in the deck's time unit `time_unit` ("s"); `steps`: the number of steps.
  ProgressMeter(Real analysis_time, int steps, std::string time_unit);

  /// The progress line for status line `line` of step `step` (1-based, of period
  /// `step_period`), reached `wall` seconds after the run started. The first call is the
  /// reference of the rates: its line says "ETA" with no estimate yet.
  /// Example: "step 1/1  t = 1.2000e-04 of 2.0000e-04 s (60.0%)  increment 1234  dt
  /// 9.876e-08 s  elapsed 0:12  103 inc/s  ETA 0:08".
  std::string text(const StatusLine& line, int step, Real step_period, double wall);

 private:
  Real m_analysis_time;
  int m_steps;
  std::string m_time_unit;
  bool m_started = false;
  double m_wall0 = 0.0;      ///< wall time of the reference line, s
  long m_increment0 = 0;     ///< increment count of the reference line
  Real m_total_time0 = 0.0;  ///< total time of the reference line
};

}  // namespace xpl::io
