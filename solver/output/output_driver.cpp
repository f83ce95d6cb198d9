#include "solver/output/output_driver.hpp"

namespace xpl {

namespace {

/// The element fields of a frame made when the writer asks for them, from the elements at the
/// frame's state.
class ElementFieldPull final : public ElementFieldSource {
 public:
  ElementFieldPull(const ElementSet& elements, const State& state)
      : m_elements(elements), m_state(state) {}
  void fill(ElementField field, std::vector<Real>& rows) const override {
    m_elements.fill_output(m_state, field, rows);
  }

 private:
  const ElementSet& m_elements;
  const State& m_state;
};

}  // namespace

OutputDriver::OutputDriver(const Model& model, OutputSink& sink, PhaseTimers& timers)
    : m_model(model), m_sink(sink), m_timers(timers) {}

void OutputDriver::begin_step(int step) {
  m_schedule.begin_step(m_model, step);
}

void OutputDriver::declare_history(const ContactStage& contact) {
  if (!m_schedule.has_history()) return;
  std::vector<HistorySeries> series = m_schedule.series();
  contact.add_history_series(series);
  m_sink.declare_history(series);
}

void OutputDriver::note_short_intervals(Real dt) {
  m_schedule.note_short_intervals(dt);
  report_notes();
}

void OutputDriver::report_notes() {
  for (const std::string& warning : m_schedule.take_warnings())
    m_sink.message(Severity::Warning, warning);
  for (const std::string& note : m_schedule.take_notes()) m_sink.message(Severity::Note, note);
}

bool OutputDriver::history_due(Real step_time, bool last) {
  return m_schedule.has_history() && m_schedule.history_due(step_time, last);
}

void OutputDriver::write_frame(State& state, const FrameRequest& requested,
                               const ElementSet& elements, const ContactStage& contact,
                               CentralDifference& nodes) {
  ScopedTimer timer(m_timers, Phase::Output);
  FrameRequest what = requested;
  if (m_displacement_written) what.displacement = true;
  m_displacement_written = what.displacement;
  // One process: the writer pulls the element fields one at a time (nothing of them is kept
  // between frames, and a frame holds one field at a time: issue 38). Distributed: every
  // field gathered to rank 0 first, or, when every rank writes its rows, the rank's own.
  const ElementFieldPull pull(elements, state);
  if (elements.fills_fields_alone()) {
    elements.gather_plastic_strain(what, m_frame);
    m_frame.source = &pull;
  } else if (m_frame.rows.collective) {
    elements.gather_local_output(state, what, m_frame);
    m_frame.source = nullptr;
  } else {
    elements.gather_output(state, what, m_frame);
    m_frame.source = nullptr;
  }
  if (what.contact_stress || what.contact_status || what.contact_force)
    contact.fill_output(m_frame);
  nodes.sync_rotation(state);
  try {
    m_sink.write_frame(m_model, state, m_frame, what);
  } catch (...) {
    m_frame.source = nullptr;
    throw;
  }
  m_frame.source = nullptr;
}

void OutputDriver::write_history(State& state, const ContactStage& contact,
                                 CentralDifference& nodes) {
  ScopedTimer timer(m_timers, Phase::Output);
  nodes.sync_rotation(state);
  m_schedule.history_row(state, m_history_row);
  contact.add_history_values(m_history_row);
  m_sink.append_history(state.time, m_history_row);
}

void OutputDriver::write_status(const State& state, Real dt_next, const char* governing,
                                ExternalId critical_id, ExternalId contact_node) {
  ScopedTimer timer(m_timers, Phase::Output);
  StatusLine line;
  line.increment = state.increment;
  line.step_time = state.step_time;
  line.total_time = state.time;
  line.dt = dt_next;
  line.governing = governing;
  line.critical_element = critical_id;
  line.critical_contact_node = contact_node;
  line.energies = state.energies;
  m_sink.status(line);
}

RunSummary OutputDriver::summary(const State& state, Index element_count,
                                 double loop_seconds) const {
  RunSummary s;
  s.increments = state.increment;
  s.final_time = state.time;
  const double elements = element_count;
  const double cycles = elements * state.increment;
  s.element_cycles_per_second = loop_seconds > 0.0 ? cycles / loop_seconds : 0.0;
  s.timers = m_timers;
  s.energies = state.energies;
  return s;
}

}  // namespace xpl
