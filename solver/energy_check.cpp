#include "solver/energy_check.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/error.hpp"
#include "solver/message_text.hpp"
#include "solver/output_variables.hpp"

namespace xpl {

namespace {

/// Increments at the start of each step before the energy balance is checked.
constexpr long BALANCE_WARMUP = 10;

/// Whether ENERGIES[i] is a term of the balance (not the sums ALLIE and ETOTAL).
bool is_term(std::size_t i) {
  return ENERGIES[i].name != "ALLIE" && ENERGIES[i].name != "ETOTAL";
}

/// Largest extent of the model over its fastest dilatational wave speed
/// c_d = sqrt(E (1 − ν) / (ρ (1 + ν)(1 − 2ν))), s.
Real wave_transit_time(const Model& model) {
  Real speed = 0.0;
  for (const Material& m : model.materials)
    if (m.density > 0.0 && m.young > 0.0 && m.poisson < 0.5 && m.poisson > -1.0)
      speed = std::max(speed, std::sqrt(m.young * (1.0 - m.poisson) /
                                        (m.density * (1.0 + m.poisson) * (1.0 - 2.0 * m.poisson))));
  if (!(speed > 0.0) || model.coordinates.rows() == 0) return 0.0;
  Real extent2 = 0.0;
  for (int c = 0; c < 3; ++c) {
    Real lo = model.coordinates(0, c), hi = lo;
    for (Index i = 1; i < model.coordinates.rows(); ++i) {
      lo = std::min(lo, model.coordinates(i, c));
      hi = std::max(hi, model.coordinates(i, c));
    }
    extent2 += (hi - lo) * (hi - lo);
  }
  const Real extent = std::sqrt(extent2);
  return extent / speed;
}

std::string percent(Real fraction) {
  return format_real(100.0 * fraction) + " %";
}

}  // namespace

std::string describe(const EnergyDrift& d) {
  return "ETOTAL drift " + format_real(d.drift) + " J, " + percent(d.fraction) +
         " of the largest energy " + format_real(d.largest) + " J, at t = " + format_real(d.time) +
         " s (increment " + std::to_string(d.increment) + "); " + d.mover + " moved most (" +
         (d.mover_change >= 0.0 ? "+" : "") + format_real(d.mover_change) + " J)";
}

EnergyCheck::EnergyCheck(const Model& model, Real dt_floor_ratio, Real energy_limit)
    : m_model(model),
      m_dt_floor_ratio(dt_floor_ratio),
      m_energy_limit(energy_limit),
      m_transit_time(wave_transit_time(model)) {}

void EnergyCheck::start(const State& state, Real dt_first) {
  m_dt_first = dt_first;
  m_initial_total = state.energies.total();
  m_initial.resize(ENERGIES.size());
  for (std::size_t i = 0; i < ENERGIES.size(); ++i)
    m_initial[i] = ENERGIES[i].value(state.energies);
}

EnergyDrift EnergyCheck::drift_of(const State& state) const {
  EnergyDrift d;
  d.drift = state.energies.total() - m_initial_total;
  d.largest = m_max_energy;
  d.fraction = m_max_energy > 0.0 ? std::abs(d.drift) / m_max_energy : 0.0;
  d.time = state.time;
  d.increment = state.increment;
  for (std::size_t i = 0; i < ENERGIES.size() && i < m_initial.size(); ++i) {
    if (!is_term(i)) continue;
    const Real change = ENERGIES[i].value(state.energies) - m_initial[i];
    if (*d.mover == '\0' || std::abs(change) > std::abs(d.mover_change)) {
      d.mover = ENERGIES[i].name.data();  // the names are literals: NUL-terminated
      d.mover_change = change;
    }
  }
  return d;
}

void EnergyCheck::check(const State& state, const ElementTotals& totals, Real dt_next,
                        ExternalId critical_id, OutputSink& sink) {
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
  if (settled && m_max_energy > 0.0 && drift > 1e-12) {
    const Real fraction = drift / m_max_energy;
    if (fraction > m_largest.fraction) m_largest = drift_of(state);
    if (fraction > m_energy_limit) {
      throw SolverError("NaN/instability at increment " + std::to_string(state.increment) +
                            ", element " + std::to_string(critical_id) + ": energy balance lost (" +
                            describe(drift_of(state)) + "; the limit is " +
                            percent(m_energy_limit) + ", xpl run --energy-limit)",
                        critical_id, state.increment, state.time);
    }
    if (fraction > ENERGY_WARNING_FRACTION && !m_warned) {
      m_warned = true;
      const EnergyDrift now = drift_of(state);
      sink.message(Severity::Warning, "energy balance: " + describe(now) +
                                          "; warned once; the run fails above " +
                                          percent(m_energy_limit) + " (xpl run --energy-limit)");
      sink.status_note("WARNING: energy balance: ETOTAL drift " + percent(now.fraction) +
                       " of the largest energy at t = " + format_real(now.time) + " s; " +
                       now.mover + " moved most");
    }
  }
  if (m_model.steps[state.step].fixed_increment) return;
  const Real floor = std::max(m_dt_floor_ratio * m_dt_first, DT_TRANSIT_FLOOR * m_transit_time);
  if (dt_next < floor || !(dt_next > 0.0)) {
    throw SolverError(
        "NaN/instability at increment " + std::to_string(state.increment) + ", element " +
            std::to_string(critical_id) + ": stable increment collapsed to " +
            format_real(dt_next) + " s (the floor is " + format_real(floor) +
            " s: " + format_real(m_dt_floor_ratio) + " x the first increment " +
            format_real(m_dt_first) + " s, at least " + format_real(DT_TRANSIT_FLOOR) +
            " x the wave transit time " + format_real(m_transit_time) +
            " s of the model); an extreme initial velocity or load, or an "
            "element crushed to nothing",
        critical_id, state.increment, state.time);
  }
}

}  // namespace xpl
