#include "solver/energy_check.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/error.hpp"
#include "solver/message_text.hpp"

namespace xpl {

namespace {

/// Increments at the start of each step before the energy balance is checked.
constexpr long BALANCE_WARMUP = 10;

}  // namespace

EnergyCheck::EnergyCheck(const Model& model, Real dt_floor_ratio)
    : m_model(model), m_dt_floor_ratio(dt_floor_ratio) {}

void EnergyCheck::start(const State& state, Real dt_first) {
  m_dt_first = dt_first;
  m_initial_total = state.energies.total();
}

void EnergyCheck::check(const State& state, const ElementTotals& totals, Real dt_next,
                        ExternalId critical_id) {
  if (totals.failed_element != NO_INDEX) {
    const ExternalId id = m_model.element_ids[totals.failed_element];
    throw SolverError(
        "NaN/instability at increment " + std::to_string(state.increment) + ", element " +
            std::to_string(id) +
            ": non-positive or undefined volume or area (element inverted or collapsed)",
        id, state.increment, state.time);
  }
  const Energies& e = state.energies;
  if (!std::isfinite(e.kinetic) || !std::isfinite(e.total())) {
    throw SolverError("NaN/instability at increment " + std::to_string(state.increment) +
                          ", element " + std::to_string(critical_id) + ": energy is not finite",
                      critical_id, state.increment, state.time);
  }
  m_max_energy = std::max({m_max_energy, e.kinetic, e.internal(), std::abs(e.external_work)});
  const Real drift = std::abs(e.total() - m_initial_total);
  // The first increments of a step are skipped: a prescribed motion that starts from rest
  // leaves an O(Δt) mismatch between the work and the kinetic energy that is of the order of
  // these tiny energies themselves; a true instability keeps growing and is caught later.
  const bool settled = state.increment - m_step_first_increment >= BALANCE_WARMUP;
  if (settled && m_max_energy > 0.0 && drift > 0.5 * m_max_energy && drift > 1e-12) {
    throw SolverError("NaN/instability at increment " + std::to_string(state.increment) +
                          ", element " + std::to_string(critical_id) +
                          ": energy balance lost (ETOTAL drift " + format_real(drift) +
                          " J against energies up to " + format_real(m_max_energy) + " J)",
                      critical_id, state.increment, state.time);
  }
  if (dt_next < m_dt_floor_ratio * m_dt_first && !m_model.steps[state.step].fixed_increment) {
    throw SolverError("NaN/instability at increment " + std::to_string(state.increment) +
                          ", element " + std::to_string(critical_id) +
                          ": stable increment collapsed to " + format_real(dt_next) + " s",
                      critical_id, state.increment, state.time);
  }
}

}  // namespace xpl
