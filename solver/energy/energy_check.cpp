#include "solver/energy/energy_check.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "common/error.hpp"
#include "solver/message_text.hpp"
#include "solver/output/output_variables.hpp"

namespace xpl {

namespace {

/// Whether ENERGIES[i] is a term of the balance (not the sums ALLIE and ETOTAL).
bool is_term(std::size_t i) {
  return ENERGIES[i].name != "ALLIE" && ENERGIES[i].name != "ETOTAL";
}

/// The diagonal of the bounding box of `model`'s nodes, m.
Real model_extent(const Model& model) {
  if (model.coordinates.rows() == 0) return 0.0;
  Real extent2 = 0.0;
  for (int c = 0; c < 3; ++c) {
    Real lo = model.coordinates(0, c), hi = lo;
    for (Index i = 1; i < model.coordinates.rows(); ++i) {
      lo = std::min(lo, model.coordinates(i, c));
      hi = std::max(hi, model.coordinates(i, c));
    }
    extent2 += (hi - lo) * (hi - lo);
  }
  return std::sqrt(extent2);
}

/// The fastest dilatational wave speed c_d = sqrt(E (1 − ν) / (ρ (1 + ν)(1 − 2ν))) of the
/// model's materials, m/s (0 when it has no elastic material).
Real fastest_wave_speed(const Model& model) {
  Real speed = 0.0;
  for (const Material& m : model.materials)
    if (m.density > 0.0 && m.young > 0.0 && m.poisson < 0.5 && m.poisson > -1.0)
      speed = std::max(speed, std::sqrt(m.young * (1.0 - m.poisson) /
                                        (m.density * (1.0 + m.poisson) * (1.0 - 2.0 * m.poisson))));
  return speed;
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

EnergyCheck::EnergyCheck(const Model& model, Real energy_limit)
    : m_model(model),
      m_energy_limit(energy_limit),
      m_extent(model_extent(model)),
      m_wave_speed(fastest_wave_speed(model)) {
  m_transit_time = m_wave_speed > 0.0 ? m_extent / m_wave_speed : 0.0;
}

void EnergyCheck::start(const State& state) {
  m_initial_total = state.energies.total();
  m_initial.resize(ENERGIES.size());
  for (std::size_t i = 0; i < ENERGIES.size(); ++i)
    m_initial[i] = ENERGIES[i].value(state.energies);
  Real mass = 0.0;
  for (const Real m : state.mass) mass += m;
  m_max_energy = ROUND_OFF_MOTION * ROUND_OFF_MOTION * 0.5 * mass * m_wave_speed * m_wave_speed;
  m_input_initial = m_max_energy;
  for (std::size_t i = 0; i < ENERGIES.size(); ++i)
    if (is_term(i) && ENERGIES[i].name != "ALLKD") m_input_initial += std::abs(m_initial[i]);
  m_input = m_input_initial;
  m_initial_work = state.energies.external_work;
  m_initial_contact = state.energies.contact;
  m_largest_work = 0.0;
  m_largest_release = 0.0;
  m_largest_kinetic = 0.0;
  m_defect_created = false;
  widen_scale(state.energies);
}

void EnergyCheck::widen_input(const Energies& e) {
  m_largest_work = std::max(m_largest_work, std::abs(e.external_work - m_initial_work));
  m_largest_release = std::max(m_largest_release, m_initial_contact - e.contact);
  m_largest_kinetic = std::max(m_largest_kinetic, e.kinetic);
  m_input = std::max(
      m_input, std::max(m_input_initial + m_largest_work + m_largest_release, m_largest_kinetic));
}

void EnergyCheck::widen_scale(const Energies& e) {
  // Every energy of the model, the work put in and the energy released by contact included,
  // so that the scale is what the run has held or exchanged, never below what it started
  // with; not ALLKD, the scheme's own term, which grows without bound in an instability.
  for (const EnergyVariable& v : ENERGIES)
    if (v.name != "ETOTAL" && v.name != "ALLKD")
      m_max_energy = std::max(m_max_energy, std::abs(v.value(e)));
}

void EnergyCheck::check_speed(const State& state, Real dt, Real largest_speed,
                              ExternalId critical_id) const {
  // No stable increment lets a node of a deformable model cross the whole model in one
  // increment (it is at most an element's length over the wave speed); a node that does is
  // the mark of an instability whose energies may still look balanced (a linear mode that
  // grows conserves the ETOTAL of central differences).
  if (!(dt > 0.0) || !(m_extent > 0.0) || m_transit_time <= 0.0) return;
  if (!(largest_speed * dt > m_extent)) return;
  Index fastest = 0;
  Real speed2 = -1.0;
  for (Index i = 0; i < state.velocity_half.rows(); ++i) {
    const Real v2 = state.velocity_half.row(i).squaredNorm();
    if (v2 > speed2) {
      speed2 = v2;
      fastest = i;
    }
  }
  throw SolverError("NaN/instability at increment " + std::to_string(state.increment) +
                        ", element " + std::to_string(critical_id) + ": node " +
                        std::to_string(m_model.node_ids[fastest]) + " moves at " +
                        format_real(std::sqrt(speed2)) + " m/s, farther in one increment of " +
                        format_real(dt) + " s than the model's extent " + format_real(m_extent) +
                        " m (an instability: the state is no longer a solution)",
                    critical_id, state.increment, state.time);
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
                        Real largest_speed, ExternalId critical_id, OutputSink& sink) {
  if (totals.failed_element != NO_INDEX) {
    const ExternalId id = m_model.element_ids[totals.failed_element];
    throw SolverError("NaN/instability at increment " + std::to_string(state.increment) +
                          ", element " + std::to_string(id) +
                          ": non-positive or undefined volume, area or corner Jacobian (element "
                          "inverted, folded over at a corner, or collapsed)",
                      id, state.increment, state.time);
  }
  const Energies& e = state.energies;
  if (!std::isfinite(e.kinetic) || !std::isfinite(e.total())) {
    throw SolverError("NaN/instability at increment " + std::to_string(state.increment) +
                          ", element " + std::to_string(critical_id) + ": energy is not finite",
                      critical_id, state.increment, state.time);
  }
  check_speed(state, dt_next, largest_speed, critical_id);
  widen_scale(e);
  // A mode beyond the stability limit grows while the energy central differences conserve
  // stays balanced: ALLKE and ALLIE grow together and ALLKD, −⅛Δt²a·M·a, takes the growth.
  // For every stable mode |ALLKD| is (ωΔt/2)² < 1 of its strain energy, so ALLKD beyond every
  // energy of the model is the mark of an instability (a one-element S4R at scale factor 2
  // gained a factor 5e4 in 4 increments, ETOTAL balanced to 1 %). Beyond it in two increments
  // in a row and growing, not once: prescribed DOFs are not bound by that argument, and a
  // velocity ramp from rest starts with |ALLKD| = ⅛Δt²a·M·a = ALLKE (blocks_bc's second step
  // stopped at its first increment), after which ALLKE grows past it; a growing mode stays
  // beyond and grows.
  const Real defect = std::abs(e.kinetic_defect);
  const bool beyond = defect > m_max_energy;
  const bool growing = beyond && m_defect_beyond && defect > m_last_defect;
  m_defect_beyond = beyond;
  if (growing)
    throw SolverError("NaN/instability at increment " + std::to_string(state.increment) +
                          ", element " + std::to_string(critical_id) +
                          ": the half-step velocities hold more energy than the model, and more "
                          "each increment (ALLKD " +
                          format_real(e.kinetic_defect) + " J, the largest energy " +
                          format_real(m_max_energy) +
                          " J): a mode above the stability limit of the increment " +
                          format_real(state.dt) + " s grows",
                      critical_id, state.increment, state.time);
  // The same mode can grow without ALLKD passing every energy: ALLKD, negative, balances the
  // strain energy the mode builds, so ALLSE grows with it and carries the scale along (stress
  // scene 43, an S4R box of 4.5:1 elements, held a period-2Δt mode with ALLSE 0.12 J and ALLKD
  // −0.12 J for 1600 increments against 0.002 J of initial kinetic energy, ETOTAL drift 1.9 %,
  // and "completed"). The work done on the model does not grow with the mode: |ALLKD| beyond
  // DEFECT_INPUT_FACTOR times the energy put in, in two checks in a row and growing, is the
  // same mark.
  widen_input(e);
  const bool created = defect > DEFECT_INPUT_FACTOR * m_input;
  const bool created_growing = created && m_defect_created && defect > m_last_defect;
  m_defect_created = created;
  m_last_defect = defect;
  if (created_growing)
    throw SolverError(
        "NaN/instability at increment " + std::to_string(state.increment) + ", element " +
            std::to_string(critical_id) +
            ": the half-step velocities hold more energy than was put into the "
            "model, and more each increment (ALLKD " +
            format_real(e.kinetic_defect) + " J, ALLIE " + format_real(e.internal()) +
            " J, the energy put in " + format_real(m_input) +
            " J: initial energies, work, contact release or the largest ALLKE): a mode above the "
            "stability limit of the increment " +
            format_real(state.dt) + " s grows",
        critical_id, state.increment, state.time);
  const Real drift = std::abs(e.total() - m_initial_total);
  // Checked from the first increment: an element that explodes may end the step within a
  // few increments. The balance of central differences holds from the start (every term is
  // booked by the trapezoidal rule, ALLKE as the scheme conserves it: docs/theory/energy.md), and
  // the scale holds the initial energies and the work put in, so a start from rest is not measured
  // against nothing.
  if (m_max_energy > 0.0 && drift > 0.0) {
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
}

}  // namespace xpl
