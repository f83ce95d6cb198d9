#include "solver/increment/increment_control.hpp"

#include <algorithm>
#include <cmath>

#include "common/error.hpp"
#include "contact/contact_options.hpp"
#include "solver/message_text.hpp"

namespace xpl {

const char* cause_name(IncrementCause cause) {
  switch (cause) {
    case IncrementCause::Element:
      return "element";
    case IncrementCause::Global:
      return "global";
    case IncrementCause::Maximum:
      return "maximum";
    case IncrementCause::Fixed:
      return "fixed";
    case IncrementCause::Contact:
      return "contact";
    case IncrementCause::StepEnd:
      return "step-end";
  }
  return "";
}

const char* cause_text(IncrementCause cause) {
  switch (cause) {
    case IncrementCause::Element:
      return "the element-by-element estimate";
    case IncrementCause::Global:
      return "the global estimate (highest frequency of the hexes)";
    case IncrementCause::Maximum:
      return "the step's maximum increment";
    case IncrementCause::Fixed:
      return "the step's fixed increment";
    case IncrementCause::Contact:
      return "the contact penalty springs";
    case IncrementCause::StepEnd:
      return "the end of the step";
  }
  return "";
}

Real ElementIncrement::penalty_dt(Real fallback) const {
  return std::isfinite(dt) ? dt : fallback;
}

ElementIncrement element_increment(const IncrementControls& controls, Real safety,
                                   const ElementEstimate& estimate) {
  ElementIncrement out;
  out.critical_element = estimate.critical_element;
  out.raw_dt = estimate.stable_dt;
  // Where the element estimate is safe the ratio is exactly 1 and the increment keeps its bits.
  if (estimate.global_ratio < 1.0) {
    out.raw_dt = estimate.stable_dt * estimate.global_ratio;
    out.cause = IncrementCause::Global;
  }
  if (controls.fixed) {
    out.dt = *controls.fixed;
    out.cause = IncrementCause::Fixed;
    return out;
  }
  out.dt = out.raw_dt * controls.scale_factor * safety;
  if (controls.max && *controls.max < out.dt) {
    out.dt = *controls.max;
    out.cause = IncrementCause::Maximum;
  }
  return out;
}

IncrementDecision choose_increment(const ElementIncrement& elements,
                                   const ContactIncrement& contact, Real remaining) {
  IncrementDecision out;
  out.critical_element = elements.critical_element;
  out.dt = elements.dt;
  out.cause = elements.cause;
  if (contact.dt < out.dt) {
    out.dt = contact.dt;
    out.cause = IncrementCause::Contact;
    out.critical_node = contact.node;
  }
  if (!std::isfinite(out.dt)) {  // no elements: one increment to the end
    out.dt = remaining;
    out.cause = IncrementCause::StepEnd;
  }
  // Land exactly on the end of the step; avoid a sliver increment just before it.
  if ((out.dt >= remaining || remaining - out.dt < 1e-3 * out.dt) && out.dt != remaining) {
    out.dt = remaining;
    out.cause = IncrementCause::StepEnd;
  }
  return out;
}

IncrementDecision carry_increment(const IncrementDecision& carried, Real period) {
  IncrementDecision out = carried;
  if (period < carried.dt) {
    out.dt = period;
    out.cause = IncrementCause::StepEnd;
  }
  return out;
}

Real contact_increment(Real raw_dt, Real dt_elements, Real scale, Real omega_sq) {
  if (!(omega_sq > 0.0) || !(raw_dt > 0.0) || !std::isfinite(raw_dt))
    return std::numeric_limits<Real>::infinity();
  // (ω_eΔt_e)² = (2 Δt_e/Δt_raw)² = (2sφ)²; the budget B is scaled with s like the elements'.
  const Real share = 2.0 * dt_elements / raw_dt;
  const Real omega_e = 2.0 / raw_dt;
  const Real budget = share * share + contact::PENALTY_INCREMENT_BUDGET * scale * scale;
  const Real combined = std::sqrt(budget / (omega_e * omega_e + omega_sq));
  const Real alone = scale * std::sqrt(contact::PENALTY_ALONE_BUDGET / omega_sq);
  return std::min(combined, alone);
}

Real increment_floor(Real floor_ratio, Real dt_first, Real transit_time) {
  return std::max(floor_ratio * dt_first, DT_TRANSIT_FLOOR * transit_time);
}

IncrementControl::IncrementControl(const Model& model, OutputSink& sink, Real safety,
                                   Real floor_ratio, Real transit_time)
    : m_model(model),
      m_sink(sink),
      m_safety(safety),
      m_floor_ratio(floor_ratio),
      m_transit_time(transit_time) {}

ContactIncrement IncrementControl::contact(int step, const ElementIncrement& elements,
                                           Real omega_sq, Index node) const {
  const IncrementControls& c = m_model.steps[step].increment;
  ContactIncrement out;
  if (c.fixed || !std::isfinite(elements.dt)) return out;
  out.dt = contact_increment(elements.raw_dt, elements.dt, c.scale_factor, omega_sq);
  out.node = node;
  return out;
}

void IncrementControl::check_floor(const State& state, Real dt_next, ExternalId critical_id) const {
  if (m_model.steps[state.step].increment.fixed) return;
  const Real floor = increment_floor(m_floor_ratio, m_dt_first, m_transit_time);
  if (dt_next < floor || !(dt_next > 0.0)) {
    throw SolverError(
        "NaN/instability at increment " + std::to_string(state.increment) + ", element " +
            std::to_string(critical_id) + ": stable increment collapsed to " +
            format_real(dt_next) + " s (the floor is " + format_real(floor) +
            " s: " + format_real(m_floor_ratio) + " x the first increment " +
            format_real(m_dt_first) + " s, at least " + format_real(DT_TRANSIT_FLOOR) +
            " x the wave transit time " + format_real(m_transit_time) +
            " s of the model); an extreme initial velocity or load, or an "
            "element crushed to nothing",
        critical_id, state.increment, state.time);
  }
}

std::string IncrementControl::critical_text(const IncrementDecision& decision) const {
  if (decision.cause == IncrementCause::Contact && decision.critical_node != NO_INDEX)
    return "contact node " + std::to_string(m_model.node_ids[decision.critical_node]);
  if (decision.critical_element != NO_INDEX)
    return "critical element " + std::to_string(m_model.element_ids[decision.critical_element]);
  return "";
}

void IncrementControl::report_start(int step, const IncrementDecision& first) {
  const std::string critical = critical_text(first);
  m_sink.message(Severity::Info, "step " + m_model.steps[step].name + ": the first increment " +
                                     format_real(first.dt) + " s" +
                                     (step > 0 ? " (carried over from the step before)" : "") +
                                     " is governed by " + cause_text(first.cause) +
                                     (critical.empty() ? "" : " (" + critical + ")"));
}

void IncrementControl::report_step(int step) {
  std::string text;
  long total = 0;
  for (int c = 0; c < CAUSES; ++c) {
    total += m_counts[c];
    if (m_counts[c] == 0) continue;
    text += (text.empty() ? "" : ", ") + std::string(cause_name(static_cast<IncrementCause>(c))) +
            " " + std::to_string(m_counts[c]);
  }
  std::fill(std::begin(m_counts), std::end(m_counts), 0L);
  if (total == 0) return;
  m_sink.message(Severity::Info, "step " + m_model.steps[step].name + ": " + std::to_string(total) +
                                     " increment(s) governed by: " + text);
}

}  // namespace xpl
