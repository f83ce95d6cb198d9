#pragma once
/// \file When field frames and history rows are due within a step, and what they contain.
/// Like Abaqus/Explicit without time marks, output is written at the first increment that
/// reaches the requested time; the last increment of a step always gets its output.

#include <string>
#include <utility>
#include <vector>

#include "common/types.hpp"
#include "solver/model/model.hpp"
#include "solver/model/state.hpp"
#include "solver/output/output_sink.hpp"
#include "solver/output/output_variables.hpp"

namespace xpl {

/// Whether `model` asks for no output at all (no step has an output request, SPEC I6): each of
/// its steps then gets default_output_requests() instead of writing nothing.
bool uses_default_output(const Model& model);

/// The output of every step of a deck without output requests, as Abaqus/CAE requests output
/// by default (field preselect, history energies), but with one frame per step: field U, V, S
/// (with PEEQ on plastic models; on shell models also UR, VR and the section-point stresses)
/// at the end of the step (frame 0 is the initial state), and history of every whole-model
/// energy 200 times a step (the Abaqus/Explicit default interval).
std::vector<OutputRequest> default_output_requests();

/// The warning a run of such a deck gives on the terminal and in the .msg file.
std::string default_output_warning();

/// The output requests of one step and their next due times.
class OutputSchedule {
 public:
  /// Prepares the requests of `step` (step time starts at 0).
  /// Field UR/VR/RM request U/V/RF (they are written together; FrameRequest); STH requests
  /// the thickness on shell models and nothing otherwise. History UR1..RM3 read the
  /// rotational state on shell models; on a model without shells their columns are declared
  /// as usual and hold zeros (nodes have no rotational DOFs, so their rotation is zero).
  /// The same variable asked for by two requests of the step is written once (as Abaqus
  /// merges them): a field variable only by the request with the finer interval, a history
  /// series once in the one history table (whose rows fall due at every request's times);
  /// notes() says which.
  void begin_step(const Model& model, int step);

  /// Notes the requests whose interval is shorter than the increment `dt` (s): output comes
  /// at most once per increment (TIME INTERVAL=1e-20, a huge NUMBER INTERVAL; fire() jumps
  /// over the skipped output times in one step). `dt` <= 0 notes nothing.
  void note_short_intervals(Real dt);

  /// Notes for the .msg file on merged and clamped requests, since the last take_notes().
  std::vector<std::string> take_notes() {
    std::vector<std::string> notes;
    notes.swap(m_notes);
    return notes;
  }
  /// Warnings for the .msg file (default output of a deck without requests), since the last
  /// take_warnings().
  std::vector<std::string> take_warnings() {
    std::vector<std::string> warnings;
    warnings.swap(m_warnings);
    return warnings;
  }

  /// Whether any field/history output exists in the step (P2: nothing to do otherwise).
  bool has_field() const { return !m_field.empty(); }
  bool has_history() const { return !m_history.empty(); }
  /// The nodes whose values of the state a history row reads, ascending (none: the row
  /// holds energies alone).
  const std::vector<Index>& history_nodes() const { return m_history_nodes; }

  /// Field variables due at `step_time` (any flag set means a frame is due); advances the
  /// due times of the requests that fire. `last` forces every request to fire.
  FrameRequest field_due(Real step_time, bool last);
  /// Union of all field requests (frame 0).
  FrameRequest field_all() const;
  /// Whether a history row is due at `step_time`; advances the due times.
  bool history_due(Real step_time, bool last);

  /// History columns of the step (for OutputSink::declare_history).
  const std::vector<HistorySeries>& series() const { return m_series; }
  /// One history row from the state, laid out as series() says.
  void history_row(const State& state, std::vector<Real>& row) const;

 private:
  struct Timed {
    Real interval = 0.0;   ///< step-time spacing of outputs
    Real next = 0.0;       ///< next due step time
    SourceLocation where;  ///< the *OUTPUT keyword (for notes)
  };
  struct FieldRequest {
    Timed when;
    FrameRequest what;
  };
  /// What a history column reads: an energy, or a component of a node variable.
  struct Column {
    int energy = -1;            ///< index into ENERGIES; -1: a node column
    NodeValue value = nullptr;  ///< node column; nullptr: zero (rotations without shells)
    int component = 0;          ///< 0..2
    Index node = NO_INDEX;
  };
  static bool fire(Timed& t, Real step_time, bool last, Real period);
  /// Leaves each frame flag in the field request of the finest interval only.
  void merge_field_requests(int step);
  /// Whether history series `path` of request `request` is new; notes a repeat.
  bool first_series(const std::string& path, std::size_t request);

  /// Per history series path, the request that declared it.
  std::vector<std::pair<std::string, std::size_t>> m_series_owner;
  /// Per (repeating request, first request), the names asked again.
  struct Repeat {
    std::size_t request = 0;
    std::size_t owner = 0;
    std::vector<std::string> names;
  };
  std::vector<Repeat> m_history_repeats;
  std::vector<std::string> m_notes;
  std::vector<std::string> m_warnings;

  Real m_period = 0.0;
  std::vector<FieldRequest> m_field;
  std::vector<Timed> m_history;
  std::vector<HistorySeries> m_series;
  std::vector<Column> m_columns;
  std::vector<Index> m_history_nodes;  ///< history_nodes()
};

}  // namespace xpl
