#pragma once
/// \file The run behind ExplicitSolver (explicit_solver.hpp): its state and the parts of the
/// time loop. Private to solver/: the loop is in explicit_solver.cpp, the set-up (the parts,
/// the initial or imported state, the set-up report) in solver_setup.cpp.

#include <memory>
#include <string>
#include <vector>

#include "common/timer.hpp"
#include "solver/distributed_run.hpp"
#include "solver/energy/contact_energy_check.hpp"
#include "solver/energy/energy_check.hpp"
#include "solver/explicit_solver.hpp"
#include "solver/forces/contact_stage.hpp"
#include "solver/forces/element_set.hpp"
#include "solver/increment/increment_control.hpp"
#include "solver/motion/central_difference.hpp"
#include "solver/motion/rigid_bodies.hpp"
#include "solver/motion/ties.hpp"
#include "solver/output/output_driver.hpp"
#include "solver/tie_routes.hpp"

namespace xpl {

/// The run: its state and the parts of the time loop, each owning its own data. The parts
/// are built (masses, element blocks, colours) in the constructor, timed as setup by
/// ExplicitSolver's constructor.
struct ExplicitSolver::Impl {
 public:
  Impl(const Model& model, OutputSink& sink, SolverOptions options);

  const State& state() const { return m_state; }
  /// Adds the wall time of the setup (timed by ExplicitSolver's constructor), s.
  void add_setup_time(double seconds) { m_timers.add(Phase::Setup, seconds); }
  RunSummary run();
  RunSummary check();

 private:
  /// The state before the first increment: reference = current positions, the deck's
  /// initial velocities, zero mass (the element set lumps it).
  static State initial_state(const Model& model);
  /// Rotational fields of a model whose rigid bodies carry rotations without shells, and the
  /// bodies' mass properties; returns their messages.
  std::vector<std::string> set_up_rigid_bodies();
  /// Distributed runs: the partition, this rank's elements, the masks of the nodal sums and
  /// the partition report.
  void set_up_distribution();
  /// Distributed runs: contact, rigid bodies, ties and loads run whole on every rank on the
  /// nodal rows gathered from the ranks that integrate them (docs/dev/mpi.md).
  void share_features(DistributedRun& run);
  /// Distributed runs with rigid bodies: each rank's bodies and the forces it receives and
  /// sends per increment, in the .msg (rank 0's sink writes it).
  void report_rigid_owners(const DistributedRun& run);
  /// Distributed runs with ties: each rank's tie nodes and the rows it receives and sends per
  /// increment for them, in the .msg (rank 0's sink writes it).
  void report_tie_routes();
  /// Distributed runs with rigid bodies: each body's owner (m_body_owner) and this rank's role
  /// for it (RigidBodies::set_roles()); marks in `integrated` the nodes of the bodies it owns
  /// or replays, which it returns.
  std::vector<unsigned char> set_rigid_roles(const DistributedRun& run,
                                             std::vector<unsigned char>& integrated);
  /// Distributed runs: every node's state from its owner to rank 0 before output.
  void gather_state();
  /// Puts an imported state (positions, velocities, rotations, stresses) into place.
  void apply_initial_state(const InitialState& imported);
  /// The setup messages after begin_run, in their fixed order.
  void report_setup(const std::vector<std::string>& rigid_messages);

  /// BCs, loads, output requests and contact of `step`, in the order the sink expects.
  void begin_step(int step);
  /// t = 0: forces on the initial geometry, the first increment, v_{1/2}, frame 0.
  void start_run(int step, Real period);
  /// Advances the clock by the increment `dt` just taken; returns whether it ends the step.
  bool advance_clock(Real dt, Real step_start, Real period);
  /// The force evaluations of the run: at t = 0, after each increment, in the data check.
  enum class Pass { Start, Increment, Check };
  /// Forces at the state's positions after the increment `dt_taken` (0 at t = 0): elements
  /// (their energies into the state, the rest of `totals` to the caller), loads and contact;
  /// returns the increment the increment control chooses for `remaining` (s) of the step.
  /// Pass::Check books no energies, applies no loads or contact and leaves no forces; it
  /// warns of a LINEAR penalty that will govern once in contact.
  IncrementDecision evaluate_forces(Pass pass, Real dt_taken, Real remaining,
                                    ElementTotals& totals);
  /// Keeps the element that limits the increment of `totals`, when there is one.
  void note_critical(const ElementTotals& totals);
  /// The time loop of one step: increments until the step time reaches its period, or until
  /// a stop signal arrives.
  void run_step(int step);
  /// The signal that asks the run to stop (SolverOptions::stop_signal), or 0. Distributed
  /// runs: the largest of the ranks' signals as the increment's nodal update shared them.
  int stop_requested() const;
  /// This rank's stop signal now, or 0.
  int local_signal() const;
  /// Ends the increment a stop signal interrupted: the frame, history row and status line
  /// that did not fall due there, so that the results end at the time reached.
  void write_interrupted(bool frame_written, bool history_written);
  /// end_run with status failed and `cause`; a second failure there (a full disk) is dropped
  /// so that the first one reaches the caller.
  void end_failed(const std::string& cause) noexcept;
  /// The largest ETOTAL drift of the run in the .msg and .sta files (before end_run).
  void report_drift();
  /// Distributed runs: each rank's exchange time in the .msg, and the partition and each
  /// rank's times for the summary (OutputSink::distribution) (collective).
  void report_exchange();
  /// The partition of a distributed run, each rank's share without times (no collective).
  DistributionSummary partition_summary() const;
  /// The end message of an interrupted run: the signal and the time reached.
  std::string interrupted_text() const;
  /// Output through the driver, with the parts that fill the state for it.
  void write_frame(const FrameRequest& what);
  void write_history();
  void write_status();
  RunSummary summary() const;

  const Model& m_model;
  OutputSink& m_sink;
  SolverOptions m_options;
  PhaseTimers m_timers;
  State m_state;
  RigidBodies m_rigid;
  Ties m_ties;  ///< before m_elements: ADJUST moves slave nodes before the masses are lumped
  ElementSet m_elements;
  CentralDifference m_nodes;
  EnergyCheck m_energy;
  IncrementControl m_increment;  ///< the one owner of the stable increment
  ContactStage m_contact;
  ContactEnergyCheck m_contact_energy;  ///< energy created by the contact springs
  OutputDriver m_output;
  std::unique_ptr<DistributedRun> m_run;  ///< distributed runs only
  /// Distributed runs: the partition for the summary (rank 0's; the summary's rank
  /// entries come from the exchange plan and the ranks' timers).
  DistributionSummary m_distribution;
  /// Distributed runs with rigid bodies: the rank owning each body (set_rigid_roles()).
  std::vector<int> m_body_owner;
  /// Distributed runs with ties: each rank's tie passes and rows (tie_routes.hpp), and the
  /// values this rank's routes carried (and the first design's gathers would have) so far.
  std::vector<TieRoutes::Rank> m_tie_ranks;
  struct TieTraffic {
    double received = 0.0, sent = 0.0, whole = 0.0;
    Index increments = 0;
  };
  TieTraffic m_tie_traffic;
  IncrementDecision m_next;      ///< dt_{n+1/2}: the increment about to be taken, and why
  ExternalId m_critical_id = 0;  ///< deck id of the element that limits it
  double m_loop_seconds = 0.0;   ///< wall time of the time loops
  /// Seconds so far in output, and in a distributed run's exchanges and their waits
  /// (DistributedRun::exchange_seconds()), of the whole run or (m_loop_shares) of the time
  /// loops only, for the summary's per-rank times.
  struct LoopShares {
    double output = 0.0, exchange = 0.0, wait = 0.0;
  };
  LoopShares loop_shares() const;
  LoopShares m_loop_shares;
  /// Seconds of exchanges made within the output timer (the frame gathers of a distributed
  /// run with --gather-frames), which loop_shares() counts as exchanges only.
  double m_output_exchange = 0.0;
  bool m_started = false;  ///< t = 0 has been taken
  int m_stopped_by = 0;    ///< the signal that stopped the run, 0 while it runs
  /// Distributed runs: the largest stop signal of the ranks, read and shared with the kinetic
  /// sums of the last nodal update (one collective less per increment).
  int m_shared_signal = 0;
};

}  // namespace xpl
