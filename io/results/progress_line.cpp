#include "io/results/progress_line.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

namespace xpl::io {

namespace {

/// Wall time a rate needs before it is shown, s: the first increments (caches, page faults)
/// are slower than the rest.
constexpr double RATE_DELAY = 0.5;

}  // namespace

std::string clock_text(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0.0 || seconds > 1e9) return "--:--";
  const auto whole = static_cast<long long>(std::llround(seconds));
  const long long hours = whole / 3600, minutes = (whole / 60) % 60, secs = whole % 60;
  char text[40];
  if (hours > 0)
    std::snprintf(text, sizeof text, "%lld:%02lld:%02lld", hours, minutes, secs);
  else
    std::snprintf(text, sizeof text, "%lld:%02lld", minutes, secs);
  return text;
}

ProgressMeter::ProgressMeter(Real analysis_time, int steps, std::string time_unit)
    : m_analysis_time(analysis_time), m_steps(steps), m_time_unit(std::move(time_unit)) {}

std::string ProgressMeter::text(const StatusLine& line, int step, Real step_period, double wall) {
  if (!m_started) {
    m_started = true;
    m_wall0 = wall;
    m_increment0 = line.increment;
    m_total_time0 = line.total_time;
  }
  const double measured = wall - m_wall0;
  const double percent = step_period > 0.0 ? 100.0 * line.step_time / step_period : 100.0;
  const char* unit = m_time_unit.c_str();
  char head[200];
  std::snprintf(head, sizeof head,
                "step %d/%d  t = %.4e of %.4e %s (%5.1f%%)  increment %ld  dt %.3e %s  elapsed %s",
                step, m_steps, line.step_time, step_period, unit, percent, line.increment, line.dt,
                unit, clock_text(wall).c_str());
  std::string text = head;
  const double simulated = line.total_time - m_total_time0;
  if (measured < RATE_DELAY || !(simulated > 0.0)) return text + "  ETA --:--";
  const double increments_per_second =
      static_cast<double>(line.increment - m_increment0) / measured;
  const double remaining = std::max(0.0, m_analysis_time - line.total_time);
  const double eta = remaining / (simulated / measured);
  char tail[80];
  std::snprintf(tail, sizeof tail,
                increments_per_second >= 100.0 ? "  %.0f inc/s  ETA %s" : "  %.3g inc/s  ETA %s",
                increments_per_second, clock_text(eta).c_str());
  return text + tail;
}

}  // namespace xpl::io
