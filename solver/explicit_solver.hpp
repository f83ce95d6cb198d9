#pragma once
/// \file The central-difference time loop (S1–S5): lumped mass, half-step velocities,
/// element-by-element stable increment every increment, bulk viscosity, energy balance.

#include <csignal>
#include <memory>
#include <string>
#include <vector>

#include "common/timer.hpp"
#include "partition/mesh_partition.hpp"
#include "solver/model/model.hpp"
#include "solver/model/state.hpp"
#include "solver/output/output_sink.hpp"
#include "solver/output/run_summary.hpp"

namespace xpl {

/// Run options that do not come from the deck.
/// A state to start from (`xpl run --import`, SPEC S7): the last frame of an earlier run of
/// the same mesh. Rows follow the model's node and element indices.
struct InitialState {
  std::string source;                           ///< where it came from, for messages
  NodalVectors displacement;                    ///< U (n_nodes × 3), m
  NodalVectors velocity;                        ///< V (n_nodes × 3), m/s
  NodalVectors rotation;                        ///< UR (n_nodes × 3) or 0 rows
  NodalVectors angular_velocity;                ///< VR (n_nodes × 3) or 0 rows
  std::vector<Real> stress;                     ///< S (n_elements × 6) or empty
  std::vector<Real> stress_bottom, stress_top;  ///< shell S_SNEG / S_SPOS or empty
  std::vector<Real> peeq;                       ///< PEEQ (n_elements, -) or empty
  /// Shell PEEQ_SMID / PEEQ_SNEG / PEEQ_SPOS (n_elements each, -) or empty.
  std::vector<Real> peeq_middle, peeq_bottom, peeq_top;
  /// Hourglass state (n_elements × elements::HOURGLASS_STATE_WIDTH, State::hourglass_state)
  /// or empty (then it starts at zero).
  std::vector<Real> hourglass_state;
  /// Current shell thickness STH (n_elements, m; NaN rows of solids not read) or empty (then
  /// the shells start at their section thickness).
  std::vector<Real> shell_thickness;
};

struct SolverOptions {
  /// OpenMP threads; 0: one on small models, the OpenMP default on others (team_size(),
  /// solver/thread_team.hpp). The solver sets the team for its lifetime and restores the
  /// caller's afterwards.
  int threads = 0;
  /// Start from this state instead of the deck's initial conditions (not owned; must outlive
  /// the solver). Penetrations found then become offsets (C6).
  const InitialState* initial_state = nullptr;
  /// Safety factor applied on top of the deck's scale factor. The one-point hex estimate
  /// L_e/c_d is not conservative on every mesh (at ν = 0.45 the true limit is ~10 % below
  /// it), so xpl keeps a margin; tests/solver/test_stability.cpp measures it.
  Real dt_safety = 0.9;
  /// A run whose stable increment falls below this fraction of the first increment stops.
  Real dt_floor_ratio = 1e-4;
  /// A run whose ETOTAL drifts by more than this fraction of the largest energy stops as
  /// failed (`xpl run --energy-limit PERCENT`); above 1 % it is warned of once.
  Real energy_limit = 0.1;
  /// Set to a signal number by a signal handler (not owned; may be null): the time loop
  /// checks it once per increment and ends the run there as interrupted, last frame written.
  const volatile std::sig_atomic_t* stop_signal = nullptr;
  /// Parts of the domain decomposition (issue 37): when > 1, the model is partitioned once
  /// after the t = 0 contact search (in a data check: after the initial-overclosure pass,
  /// whose search is the t = 0 one when the domain has overclosures to look for) and the
  /// partition reported in the .msg (solver/model_partition.hpp); the run itself is not
  /// distributed yet.
  int partition_parts = 0;
  partition::Method partition_method = partition::Method::Automatic;
  /// A line for the .msg before the partition report (how MPI ranks share the run), or empty.
  std::string partition_note;
  /// Run distributed over the MPI ranks (issue 37 item 3, solver/distributed_run.hpp): each
  /// rank computes the forces of its part of the model; every rank must run the solver, rank
  /// 0's sink writes. The model must have no feature DistributedRun::refusals() names.
  bool distributed = false;
  /// Distributed: every rank writes its rows of each frame (its nodes and elements) into
  /// JOB.h5 together with the others (parallel HDF5, FrameRows; the sink of every rank must
  /// write frames); else rank 0 gathers every row and writes alone.
  bool shared_frames = false;
  /// Distributed: each rank searches and computes the contact springs of the slave nodes it
  /// integrates, the ranks exchanging the results (ContactStage::set_distribution); else
  /// every rank runs the whole contact pass (fewer collectives per increment).
  bool shared_contact = true;
};

/// Owns the state and runs the steps of a Model, reporting to an OutputSink.
class ExplicitSolver {
 public:
  /// Builds element blocks, lumped mass and initial state. The model must outlive the solver.
  ExplicitSolver(const Model& model, OutputSink& sink, SolverOptions options = {});
  ~ExplicitSolver();
  ExplicitSolver(const ExplicitSolver&) = delete;
  ExplicitSolver& operator=(const ExplicitSolver&) = delete;

  /// Runs every step to its end. On a physics failure writes what it has, tells the sink,
  /// and throws SolverError.
  RunSummary run();
  /// Data check: writes frame 0 and the model summary, stops before the first increment.
  RunSummary check();

  const State& state() const;
  /// The number of OpenMP threads the run uses.
  int threads() const { return m_threads; }

 private:
  struct Impl;
  int m_saved_threads = 0;  ///< the caller's omp_get_max_threads(), restored at the end
  int m_threads = 0;
  std::unique_ptr<Impl> m_impl;
};

}  // namespace xpl
