#pragma once
/// \file Per-phase wall-clock timers. With XPL_ENABLE_TIMERS=0 the scoped timer compiles away.

#include <array>
#include <chrono>
#include <string_view>

#ifndef XPL_ENABLE_TIMERS
#define XPL_ENABLE_TIMERS 1
#endif

namespace xpl {

/// The phases a run reports separately at the end ("time spent in each phase").
enum class Phase : int {
  Setup = 0,      ///< deck reading, model building, mass, colouring
  InternalForce,  ///< element loops: stress update, hourglass, internal forces, stable dt
  ContactSearch,  ///< broad and narrow phase
  ContactForce,   ///< penalty forces
  Integration,    ///< nodal update: accelerations, velocities, positions, BCs
  Output,         ///< field frames, history, status lines
  COUNT
};

/// Human-readable phase name ("internal force", ...).
std::string_view phase_name(Phase phase);

/// Accumulated seconds per phase.
class PhaseTimers {
 public:
  void add(Phase phase, double seconds) { m_seconds[static_cast<int>(phase)] += seconds; }
  double seconds(Phase phase) const { return m_seconds[static_cast<int>(phase)]; }
  double total() const;

 private:
  std::array<double, static_cast<int>(Phase::COUNT)> m_seconds{};
};

/// Adds the wall time of its own lifetime to one phase.
class ScopedTimer {
 public:
#if XPL_ENABLE_TIMERS
  ScopedTimer(PhaseTimers& timers, Phase phase)
      : m_timers(timers), m_phase(phase), m_start(std::chrono::steady_clock::now()) {}
  ~ScopedTimer() {
    const auto stop = std::chrono::steady_clock::now();
    m_timers.add(m_phase, std::chrono::duration<double>(stop - m_start).count());
  }
  ScopedTimer(const ScopedTimer&) = delete;
  ScopedTimer& operator=(const ScopedTimer&) = delete;

 private:
  PhaseTimers& m_timers;
  Phase m_phase;
  std::chrono::steady_clock::time_point m_start;
#else
  ScopedTimer(PhaseTimers&, Phase) {}
#endif
};

}  // namespace xpl
