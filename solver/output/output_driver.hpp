#pragma once
/// \file What the time loop hands to the output sink and when: field frames and history rows
/// as the step's output requests fall due, .sta status lines, and the run summary.

#include <vector>

#include "common/timer.hpp"
#include "solver/forces/contact_stage.hpp"
#include "solver/forces/element_set.hpp"
#include "solver/model/model.hpp"
#include "solver/model/state.hpp"
#include "solver/motion/central_difference.hpp"
#include "solver/output/frame_fields.hpp"
#include "solver/output/output_schedule.hpp"
#include "solver/output/output_sink.hpp"
#include "solver/output/run_summary.hpp"

namespace xpl {

/// The output requests of the current step and the writing of frames, rows and lines.
class OutputDriver {
 public:
  /// `model`, `sink` and `timers` must outlive the driver.
  OutputDriver(const Model& model, OutputSink& sink, PhaseTimers& timers);

  /// Prepares the output requests of `step`.
  void begin_step(int step);
  /// Declares the history columns of the step (requests, then the contact pairs' forces);
  /// nothing when the step has no history output.
  void declare_history(const ContactStage& contact);
  /// Notes the output requests whose interval is shorter than the increment `dt` (s)
  /// (OutputSchedule) and writes the notes to the .msg file.
  void note_short_intervals(Real dt);
  /// Writes the warnings (default output) and the notes on merged requests of the step to
  /// the .msg file.
  void report_notes();

  /// Whether the step has field / history output at all.
  bool has_field() const { return m_schedule.has_field(); }
  bool has_history() const { return m_schedule.has_history(); }
  /// The nodes a history row reads, ascending (OutputSchedule::history_nodes()).
  const std::vector<Index>& history_nodes() const { return m_schedule.history_nodes(); }
  /// Frame 0: every field variable any request of the step asks for.
  FrameRequest field_all() const { return m_schedule.field_all(); }
  /// The field variables due at `step_time` (none set: no frame); `last` forces all.
  FrameRequest field_due(Real step_time, bool last) {
    return m_schedule.field_due(step_time, last);
  }
  /// Whether a history row is due at `step_time` (and the step has history output).
  bool history_due(Real step_time, bool last);

  /// One field frame of `what`: PEEQ and contact output gathered into the driver's
  /// FrameFields, rotations into `state`, first; the writer pulls the other element fields
  /// one at a time from `elements` (FrameFields::source; a distributed run gathers them all
  /// first) and makes the global-axis copies of the shell stresses (global_axis_rows). Once a
  /// frame has written U, every later frame writes it too (a frame of another request without U
  /// would be drawn undeformed in ParaView).
  void write_frame(State& state, const FrameRequest& what, const ElementSet& elements,
                   const ContactStage& contact, CentralDifference& nodes);
  /// A distributed run whose ranks write each frame together (issue 37 item 5): this rank's
  /// rows of the frame datasets (FrameRows). From then on write_frame gathers nothing: each
  /// rank's sink writes the rows of its nodes and elements.
  void set_frame_rows(FrameRows rows) { m_frame.rows = std::move(rows); }
  /// Whether every rank writes its rows of a frame (set_frame_rows).
  bool shared_frames() const { return m_frame.rows.collective; }
  /// One history row (requests, then contact pair forces) at state.time.
  void write_history(State& state, const ContactStage& contact, CentralDifference& nodes);
  /// One .sta line: the increment `dt_next` (s) about to be taken, what governs it
  /// (`governing`, cause_name of solver/increment/increment_control.hpp), the element `critical_id`
  /// (deck id) that limits the elements' increment and the contact node `contact_node` whose
  /// penalty limits it instead (0: none).
  void write_status(const State& state, Real dt_next, const char* governing, ExternalId critical_id,
                    ExternalId contact_node = 0);

  /// The run summary of `state`: `element_count` elements cycled over the increments in
  /// `loop_seconds` of time-loop wall time.
  RunSummary summary(const State& state, Index element_count, double loop_seconds) const;

 private:
  const Model& m_model;
  OutputSink& m_sink;
  PhaseTimers& m_timers;
  OutputSchedule m_schedule;
  FrameFields m_frame;  ///< the output-only fields of the last frame
  std::vector<Real> m_history_row;
  bool m_displacement_written = false;  ///< a frame has written U
};

}  // namespace xpl
