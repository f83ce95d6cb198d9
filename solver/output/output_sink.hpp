#pragma once
/// \file What the solver tells the outside world: frames, history, status lines, messages.
/// `io` implements it (HDF5 + XDMF + .sta + .msg); tests implement it to capture data.

#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "common/timer.hpp"
#include "common/types.hpp"
#include "solver/model/model.hpp"
#include "solver/model/state.hpp"
#include "solver/output/frame_fields.hpp"

namespace xpl {

/// What a field frame contains.
/// On models with shells, U/V/RF also write UR/VR/RM (as Abaqus does) and S also writes the
/// shell section stresses S_SNEG and S_SPOS.
struct FrameRequest {
  bool displacement = false;    ///< U (+ UR)
  bool velocity = false;        ///< V (+ VR)
  bool acceleration = false;    ///< A
  bool reaction = false;        ///< RF (+ RM)
  bool stress = false;          ///< S (also writes the von Mises MISES)
  bool volume = false;          ///< EVOL
  bool thickness = false;       ///< STH (shells)
  bool plastic_strain = false;  ///< PEEQ (models with plastic materials)
  bool contact_stress = false;  ///< CSTRESS: CPRESS (scalar) and CSHEAR (vector) per node
  bool contact_status = false;  ///< CSTATUS per node: 0 open, 1 slipping, 2 sticking
  bool contact_force = false;   ///< CFORCE: CNORMF and CSHEARF (vectors) per node
  /// Whether anything at all is requested.
  bool any() const {
    return displacement || velocity || acceleration || reaction || stress || volume || thickness ||
           plastic_strain || contact_stress || contact_status || contact_force;
  }
};

/// One column group of history output: `path` names an HDF5 dataset below /history
/// ("energy/ALLKE", "node/FIXED/RF1"); width 1 is a scalar series, width > 1 has one
/// column per node (node_ids gives the deck ids of the columns). Node series are (nt, n) also
/// for one node. `component` ("U3", "ALLKE", "CFN") and `unit` ("m") become the dataset's
/// attributes components and units.
struct HistorySeries {
  std::string path;
  Index width = 1;
  std::vector<ExternalId> node_ids;
  std::string component;
  std::string unit;
};

/// One line of the .sta file.
struct StatusLine {
  long increment = 0;
  Real step_time = 0.0;
  Real total_time = 0.0;
  Real dt = 0.0;
  /// What governs the increment: "element", "global", "maximum", "fixed", "contact" or
  /// "step-end" (solver/increment/increment_control.hpp).
  std::string governing;
  ExternalId critical_element = 0;  ///< deck id of the element that limits the increment
  /// Deck id of the contact node whose penalty limits the increment instead, 0 when none.
  ExternalId critical_contact_node = 0;
  Energies energies;
};

/// One column of a ResultTable: integers (deck ids, codes) or reals, `width` values per row.
struct TableColumn {
  std::string name;
  Index width = 1;
  bool integer = false;           ///< `ids` holds the data, else `values`
  std::vector<std::int64_t> ids;  ///< integer column (rows × width)
  std::vector<Real> values;       ///< real column (rows × width)
  std::string description;        ///< units or the meaning of codes (an attribute)
};

/// A table of per-node results of the setup (initial overclosures): written to the results
/// file as a group of column datasets at `path` (below the file root).
struct ResultTable {
  std::string path;  ///< e.g. "overclosure/step_1/adjusted"
  Index rows = 0;
  std::vector<TableColumn> columns;
  std::string description;
  std::vector<std::pair<std::string, std::string>> attributes;  ///< more string attributes
};

/// The largest energy-balance drift of a run as the solver's check measured it (every
/// increment from the first one): what the run summary reports, so that it says what the
/// terminal, .msg and .sta say.
struct BalanceDrift {
  Real fraction = 0.0;  ///< |ETOTAL − ETOTAL₀| / energy scale at the time of the drift
  Real drift = 0.0;     ///< ETOTAL − ETOTAL₀, J
  Real scale = 0.0;     ///< the energy scale then (largest energy of the run so far), J
  Real time = 0.0;      ///< total time, s
};

/// A run distributed over MPI ranks (issue 37, docs/dev/mpi.md): its partition and each
/// rank's share and time, for the run summary.
struct DistributionSummary {
  /// One rank's part and its time loop, s: compute = time_loop − exchange − wait − output
  /// (the element and nodal passes, contact), exchange = the exchanges' and collectives' own
  /// work (packing, posting, unpacking), wait = waiting in them for the other ranks, output =
  /// frames, history and status lines (this rank's rows of a frame, or rank 0 everything).
  struct Rank {
    Index elements = 0;         ///< elements of its SIMD batches
    Index owned_nodes = 0;      ///< nodes it owns (and writes)
    Index interface_nodes = 0;  ///< its nodes that other ranks use too
    Index neighbours = 0;       ///< ranks it exchanges interface forces with
    double time_loop = 0.0, compute = 0.0, exchange = 0.0, wait = 0.0, output = 0.0;
    /// Its contact phases (whole run, Phase::ContactSearch and ContactForce), and the part of
    /// the force phase spent exchanging the slots' results (waits included), s.
    double contact_search = 0.0, contact_force = 0.0, contact_exchange = 0.0;
    /// Contact nodes' values (positions, v(n+½)) it received per increment with contact, and
    /// what gathering every contact node each increment would have been (shared slots only).
    double contact_values = 0.0, contact_values_whole = 0.0;
    /// The contact rows' values it sent per increment (as contact_values, without the
    /// velocities); per build of the broad phase, those it received and sent for the build
    /// (ghost faces and the new lists' rows); per making of the read lists, those the lists'
    /// exchanges carried to and from it.
    double contact_values_sent = 0.0, contact_build_received = 0.0, contact_build_sent = 0.0,
           contact_lists_received = 0.0, contact_lists_sent = 0.0;
    /// Tie rows' values it received and sent per increment (slave forces, master corners'
    /// motion, point to point), and what the first design's two gathers of every tie node
    /// delivered to it (docs/dev/mpi.md, "Ties where their nodes live").
    double tie_values = 0.0, tie_values_sent = 0.0, tie_values_whole = 0.0;
    /// The slots' results (ContactEngine's two exchanges, padding included) it received and
    /// sent per increment with shared contact slots.
    double contact_slot_received = 0.0, contact_slot_sent = 0.0;
  };
  std::string method;          ///< the partitioner ("METIS", "bisection")
  Real imbalance = 1.0;        ///< largest part weight over the mean
  Index interface_nodes = 0;   ///< nodes used by two or more ranks
  long cut_edges = 0;          ///< graph edges across ranks (of the SIMD batch graph)
  bool shared_frames = false;  ///< every rank writes its rows of a frame (else rank 0 all)
  /// The ranks' times were gathered at the end of the run (not for a failed run, which ends
  /// without the collective): each Rank's times are then zero and not reported.
  bool times_gathered = false;
  std::vector<Rank> ranks;
};

/// Severity of a .msg entry.
enum class Severity { Info, Note, Warning, Error };

/// How a run ended. Interrupted: stopped on a signal (SIGINT/SIGTERM) after a whole
/// increment, with its last frame written.
enum class RunStatus { Completed, Checked, Failed, Interrupted };

/// Receives everything a run produces, in this order: begin_run, (begin_step, frames,
/// history rows, status lines, messages)*, end_run. Implementations write files; the solver
/// never touches a file itself.
class OutputSink {
 public:
  virtual ~OutputSink() = default;
  /// Mesh and model summary; called once before frame 0.
  virtual void begin_run(const Model& model) = 0;
  /// A new step starts (zero-based index).
  virtual void begin_step(const Model& model, int step) = 0;
  /// Declares the history columns of the current step (called after begin_step, before any
  /// append_history of that step).
  virtual void declare_history(const std::vector<HistorySeries>& series) = 0;
  /// One field frame at state.time (frame 0 is the initial state): the nodal fields of
  /// `state`, the output-only fields of `fields` (filled for `what`).
  virtual void write_frame(const Model& model, const State& state, const FrameFields& fields,
                           const FrameRequest& what) = 0;
  /// One history row; `values` holds the declared series' columns back to back.
  virtual void append_history(Real time, std::span<const Real> values) = 0;
  /// One .sta line.
  virtual void status(const StatusLine& line) = 0;
  /// One .msg entry.
  virtual void message(Severity severity, const std::string& text) = 0;
  /// A summary line in the .sta file between status lines (initial overclosures).
  virtual void status_note(const std::string& text) { (void)text; }
  /// The largest energy-balance drift of the run (called before end_run, also after an
  /// error; sinks that keep no summary ignore it).
  virtual void energy_drift(const BalanceDrift& drift) { (void)drift; }
  /// The partition and the ranks' times of a distributed run (called at its end, before
  /// end_run, on every rank; sinks that keep no summary ignore it).
  virtual void distribution(const DistributionSummary& summary) { (void)summary; }
  /// A table of setup results (written once; sinks that keep no files ignore it).
  virtual void write_table(const ResultTable& table) { (void)table; }
  /// Called when the run ends, also after an error (`error` then says what happened),
  /// with the per-phase timers and the element-cycles per second of the time loop.
  virtual void end_run(RunStatus status, const std::string& error, const PhaseTimers& timers,
                       double element_cycles_per_second) = 0;
};

}  // namespace xpl
