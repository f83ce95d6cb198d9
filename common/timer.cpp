#include "common/timer.hpp"

namespace xpl {

std::string_view phase_name(Phase phase) {
  switch (phase) {
    case Phase::Setup:
      return "setup";
    case Phase::InternalForce:
      return "internal force";
    case Phase::ContactSearch:
      return "contact search";
    case Phase::ContactForce:
      return "contact force";
    case Phase::Integration:
      return "integration";
    case Phase::Output:
      return "output";
    case Phase::COUNT:
      break;
  }
  return "?";
}

double PhaseTimers::total() const {
  double sum = 0.0;
  for (double s : m_seconds) sum += s;
  return sum;
}

}  // namespace xpl
