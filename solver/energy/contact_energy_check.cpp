#include "solver/energy/contact_energy_check.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"
#include "solver/message_text.hpp"

namespace xpl {

namespace {

/// Below this C (J) nothing is reported: the rounding of sums of tiny spring energies.
constexpr Real CREATION_FLOOR = 1e-12;

std::string describe(Real created, Real stored, Real allpw, Real scale) {
  return "contact created energy: the penalty springs hold " + format_real(stored) +
         " J but ALLPW, the work they have taken, is " + format_real(allpw) + " J, so " +
         format_real(created) + " J came from contact (" + format_real(100.0 * created / scale) +
         " % of the largest energy " + format_real(scale) +
         " J); the contact stiffness is too high for the increment";
}

}  // namespace

std::string ContactEnergyCheck::check(const State& state, Real stored, ExternalId critical_id) {
  const Energies& e = state.energies;
  m_scale = std::max({m_scale, e.kinetic, e.internal(), std::abs(e.external_work), stored});
  if (m_baseline_pending) {
    m_baseline = stored - e.contact;
    m_baseline_pending = false;
  }
  m_created = stored - e.contact - m_baseline;
  if (state.increment - m_step_first_increment < CONTACT_CHECK_WARMUP) return {};
  if (!(m_scale > 0.0) || !(m_created > CREATION_FLOOR)) return {};
  if (m_created > CONTACT_CREATION_LIMIT * m_scale)
    throw SolverError("NaN/instability at increment " + std::to_string(state.increment) +
                          ", element " + std::to_string(critical_id) + ": " +
                          describe(m_created, stored, e.contact, m_scale),
                      critical_id, state.increment, state.time);
  if (m_warned || !(m_created > CONTACT_CREATION_WARNING * m_scale)) return {};
  m_warned = true;
  return "increment " + std::to_string(state.increment) + ", t = " + format_real(state.time) +
         " s: " + describe(m_created, stored, e.contact, m_scale);
}

}  // namespace xpl
