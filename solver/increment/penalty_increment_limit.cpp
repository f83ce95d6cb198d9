#include "solver/increment/penalty_increment_limit.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "contact/contact_options.hpp"
#include "solver/message_text.hpp"

namespace xpl {

std::string PenaltyIncrementLimit::interaction_text(Index interaction) const {
  if (interaction == NO_INDEX ||
      interaction >= static_cast<Index>(m_model.surface_interactions.size()))
    return "the contact penalty";
  const SurfaceInteraction& i = m_model.surface_interactions[interaction];
  return "interaction " + i.name + " (PRESSURE-OVERCLOSURE=LINEAR, slope " +
         format_real(i.linear_slope) + " Pa/m)";
}

ContactIncrement PenaltyIncrementLimit::apply(const contact::PenaltyLimit& limit,
                                              const ElementIncrement& elements, int step, Real time,
                                              long increment) {
  const Step& s = m_model.steps[step];
  contact::PenaltyLimit use = limit;
  if (m_hold > 0 && m_held.omega_sq > use.omega_sq) use = m_held;
  const ContactIncrement springs = m_control.contact(step, elements, use.omega_sq, use.node);
  const Real dt = springs.dt;
  const Real dt_elements = elements.dt;
  const bool governs = dt < dt_elements;
  if (!governs) {
    if (m_governing) end_span();
    return {};
  }
  if (use.omega_sq == limit.omega_sq) {
    m_held = limit;  // springs act now: the hold starts again from here
    m_hold = HOLD_INCREMENTS;
  } else {
    --m_hold;
  }
  const ExternalId node = m_model.node_ids[use.node];
  const Real ratio = dt / dt_elements;
  if (!m_governing) {
    m_governing = true;
    m_step = step;
    m_increments = 0;
    m_smallest_ratio = 2.0;
    m_sink.message(Severity::Note,
                   "step " + s.name + ": " + interaction_text(use.interaction) +
                       " governs the stable increment from t = " + format_real(time) +
                       " s (increment " + std::to_string(increment) + "), contact node " +
                       std::to_string(node) + ": " + format_real(dt) +
                       " s instead of the elements' " + format_real(dt_elements) + " s (x" +
                       format_real(ratio) + ")");
    m_sink.status_note("contact node " + std::to_string(node) +
                       " governs the stable increment from increment " + std::to_string(increment) +
                       " (x" + format_real(ratio) + ")");
  }
  ++m_increments;
  m_end_time = time;
  m_critical_node = node;
  if (ratio < m_smallest_ratio) {
    m_smallest_ratio = ratio;
    m_smallest_dt = dt;
    m_smallest_node = node;
    m_smallest_interaction = use.interaction;
  }
  return springs;
}

void PenaltyIncrementLimit::end_span() {
  if (!m_governing) return;
  m_governing = false;
  m_hold = 0;
  m_held = {};
  m_sink.message(Severity::Note,
                 "step " + m_model.steps[m_step].name + ": " +
                     interaction_text(m_smallest_interaction) +
                     " governed the stable increment for " + std::to_string(m_increments) +
                     " increment(s) until t = " + format_real(m_end_time) + " s; shortest " +
                     format_real(m_smallest_dt) + " s (x" + format_real(m_smallest_ratio) +
                     " of the elements', contact node " + std::to_string(m_smallest_node) + ")");
  m_sink.status_note(
      "contact no longer governs the stable increment after t = " + format_real(m_end_time) + " s");
}

}  // namespace xpl
