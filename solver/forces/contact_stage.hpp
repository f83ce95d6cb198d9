#pragma once
/// \file The contact stage of the time loop: builds the contact engine of each step from the
/// deck's `*CONTACT` / `*CONTACT PAIR` definitions, treats the initial overclosures and
/// clearances, adds the penalty forces every increment and gathers the contact output.

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "common/timer.hpp"
#include "contact/contact_clearance.hpp"
#include "contact/contact_engine.hpp"
#include "solver/forces/contact_rows.hpp"
#include "solver/forces/element_set.hpp"
#include "solver/forces/overclosure_report.hpp"
#include "solver/increment/penalty_increment_limit.hpp"
#include "solver/loads/boundary_state.hpp"
#include "solver/model/model.hpp"
#include "solver/model/state.hpp"
#include "solver/motion/rigid_bodies.hpp"
#include "solver/motion/ties.hpp"
#include "solver/output/output_sink.hpp"

namespace xpl {

class DistributedRun;

/// General contact and contact pairs of the current step; nothing to do when it has none (P2).
class ContactStage {
 public:
  /// `model`, `sink`, `timers` and `control` (the run's increment control) must outlive the
  /// stage; `imported_start`: the run starts from an imported state (penetrations of step 1
  /// then become offsets, C6).
  ContactStage(const Model& model, OutputSink& sink, PhaseTimers& timers,
               const IncrementControl& control, bool imported_start);

  /// Builds the engine of `step` when the step changes the contact definition (the latest
  /// `*CONTACT` up to it and every `*CONTACT PAIR`), else keeps the engine in force. A new
  /// engine resolves the initial overclosures and clearances on `state` (it may move nodes
  /// at step 1; `prescribed` DOFs and rigid-body nodes stay), or carries the offsets of the
  /// engine it replaces; it reports to the sink.
  void begin_step(int step, State& state, ElementSet& elements, const RigidBodies& rigid,
                  const std::vector<PrescribedDof>& prescribed);
  /// Nodes of ties (Ties::tied_nodes, n_nodes): held by the overclosure pass, their
  /// penetration an offset with reason "tie".
  void set_tied_nodes(std::vector<char> tied) { m_tied = std::move(tied); }
  /// The ties' slave points (Ties::slave_points). A tied slave node keeps no mass (its corners
  /// carry it) and its contact force goes to the corners, so contact reads for it its share of
  /// the corners' mass: m* = Σ_I N_I² m_I / W_I, W_I the sum of the weights bound to corner I
  /// (each corner's mass shared among its slaves as their weights; a slave alone on a corner
  /// with weight 1 reads the corner's mass), rigid where a corner it weighs on is. The slaves'
  /// springs on one corner then sum to what one spring on the corner would be. Read as
  /// massless, a tied node had no spring of its own and was a rigid master for the others'
  /// springs, too stiff for the corners that move (contact created energy).
  void set_tie_slaves(std::vector<Ties::SlavePoint> points);
  /// Distributed runs (docs/dev/mpi.md, "Contact under N ranks"): every rank reads the
  /// positions and velocities of the contact nodes gathered from the ranks that integrate
  /// them; it searches and computes the springs of the slave slots whose node it integrates
  /// (DistributedRun::row_source()) and takes the other slots' results from their ranks, then
  /// adds to the nodes it integrates the one-rank contact forces in the one-rank order. The
  /// start-of-step passes run whole on every rank. `shared` false: every rank runs the whole
  /// contact pass instead (the first, redundant design). `root_writes`: rank 0 writes every
  /// frame alone (--gather-frames), so it reads every node's contact area and normal. `run`
  /// must outlive the stage.
  void set_distribution(const DistributedRun* run, bool shared, bool root_writes) {
    m_run = run;
    m_shared = shared;
    m_root_writes = root_writes;
  }
  /// Distributed runs, for the partition's graph (issue 37 item 2): the (slave node, element
  /// of a master face) pairs the broad phase of step 1's contact lists on `position`, from an
  /// engine of its own (nothing of the run changes); empty without contact in step 1.
  std::vector<std::pair<Index, Index>> start_candidates(const NodalVectors& position,
                                                        const ElementSet& elements,
                                                        const RigidBodies& rigid);
  /// Distributed runs: wall time in the exchanges of the slots' results (waits for the other
  /// ranks included; a part of the contact force phase), s.
  double sharing_seconds() const;
  /// Distributed runs with shared slots: the values of the slots' results (both exchanges,
  /// the velocities of the work terms and any padding included) this rank received and sent
  /// per shared increment.
  std::pair<double, double> slot_values() const;
  /// Distributed runs with shared slots: the contact nodes' values this rank received per
  /// increment (ContactRows' rows, and the velocities of the work terms that come with the
  /// slots' forces), and what gathering every contact node's rows would have been.
  std::pair<double, double> rows_received() const {
    const double velocities =
        m_engine && m_rows.gathers() > 0
            ? m_engine->received_velocities() / static_cast<double>(m_rows.gathers())
            : 0.0;
    return {m_rows.values_per_gather() + velocities, m_rows.whole_values_per_gather()};
  }
  /// Distributed runs with shared slots: the contact rows' values this rank sent per
  /// increment, and what a build of the broad phase and a making of the read lists carry
  /// (ContactRows::values_per_build()).
  double rows_sent() const { return m_rows.values_sent_per_gather(); }
  ContactRows::BuildValues rows_per_build() const { return m_rows.values_per_build(); }
  /// Whether contact is active in the current step.
  bool active() const { return m_engine != nullptr; }
  /// The engine of the current step (null without contact): its t = 0 candidate pairs feed
  /// the partition (solver/model_partition.hpp).
  const contact::ContactEngine* engine() const { return m_engine.get(); }

  /// Contact forces at the state's positions subtracted from elements.force_internal();
  /// friction and penalty energies into state.energies. `dt_taken` is the increment just
  /// taken (0 at t = 0), `dt_penalty` the increment the penalty stiffness is tied to, s.
  void apply(State& state, ElementSet& elements, Real dt_taken, Real dt_penalty);
  /// Energy held by the contact springs after the last apply() (ContactTotals::stored_energy),
  /// J, 0 without contact: what ALLPW should be (ContactEnergyCheck).
  Real stored_energy() const { return m_stored_energy; }

  /// The increment a deck's own penalty stiffness allows after the last apply() (+inf when it
  /// does not govern: no contact, default penalty, or springs no stiffer than the default)
  /// against the elements' increment `elements` of `step`; reports the spans where it governs
  /// (PenaltyIncrementLimit).
  ContactIncrement penalty_increment(const ElementIncrement& elements, int step,
                                     const State& state);
  /// Deck id of the contact node that governs the last penalty_increment(), 0 when none.
  ExternalId critical_contact_node() const { return m_penalty.critical_node(); }
  /// Ends the step: the summary of a span in which contact governed the increment.
  /// Ends the step: the summary of a span in which contact governed the increment, and of
  /// the nodes released inside another body (contact at speed) beyond the first one warned of.
  void end_step();
  /// `xpl check`: a warning when a LINEAR penalty will govern the increment once in contact,
  /// estimated on the slave nodes' tributary areas (ContactEngine::estimate_penalty_limit)
  /// with `inverse_mass` (n_nodes, 1/kg) against the elements' increment `elements` of `step`.
  void check_penalty(const ElementIncrement& elements, int step,
                     const std::vector<Real>& inverse_mass) const;

  /// Per-node contact pressure, status and forces into `frame` (zero without contact).
  void fill_output(FrameFields& frame) const;
  /// Appends the history columns of the contact pairs (CFN, CFS per pair) to `series`.
  void add_history_series(std::vector<HistorySeries>& series) const;
  /// Appends the current values of those columns to `row`, N.
  void add_history_values(std::vector<Real>& row) const;

 private:
  /// Whether the definition in force at `step` has contact (general contact with surfaces,
  /// or a contact pair).
  bool defines_contact(int step) const;
  /// The engine of the definition in force at `step` on `position` (null: no contact); fills
  /// m_pair_names.
  std::unique_ptr<contact::ContactEngine> build_engine(int step, const NodalVectors& position,
                                                       const ElementSet& elements,
                                                       const RigidBodies& rigid);
  /// Domain of the general contact `general` (may be null) and the pairs `pairs`; fills
  /// m_pair_names in the engine's pair order.
  contact::DomainSpec domain_spec(const GeneralContact* general,
                                  const std::vector<ContactPair>& pairs);
  /// The rigid bodies' nodes and masses of the current step to the engine (its bound on the
  /// springs that push a body).
  void set_rigid_bodies(const RigidBodies& rigid);
  /// Distributed runs on more than one rank: the engine's slots shared out among the ranks
  /// by the rank integrating each slave node (ContactEngine::share_slots()).
  void share_slots();
  /// m_contact_inverse and m_contact_mass: `inverse_mass` (n_nodes, 1/kg) and `mass` (kg) with
  /// the tie slaves' replaced (set_tie_slaves()).
  void contact_masses(const std::vector<Real>& inverse_mass, const std::vector<Real>& mass);
  /// Initial overclosures of a newly built engine (SPEC C2–C6): adjusts (step 1) or stores
  /// offsets (later step, import); with an engine of an earlier step, carries its offsets
  /// over instead.
  void resolve_overclosures(int step, const contact::ContactEngine* previous, State& state,
                            ElementSet& elements, const RigidBodies& rigid,
                            const std::vector<PrescribedDof>& prescribed);
  /// The clearance views of the assignments given with the step's *CONTACT (and their names
  /// for the reports); empty when there are none.
  std::vector<contact::ClearanceView> clearance_views(int step,
                                                      std::vector<ClearanceViewNames>& names) const;

  const Model& m_model;
  OutputSink& m_sink;
  PhaseTimers& m_timers;
  const IncrementControl& m_control;
  bool m_imported_start;
  std::unique_ptr<contact::ContactEngine> m_engine;  ///< null when the step has no contact
  std::vector<std::string> m_pair_names;  ///< in the engine's pair order (history output)
  PenaltyIncrementLimit m_penalty;        ///< the increment a LINEAR penalty allows
  Real m_stored_energy = 0.0;             ///< ContactTotals::stored_energy of the last apply, J
  std::vector<char> m_tied;               ///< Ties::tied_nodes(), empty without ties
  std::vector<Ties::SlavePoint> m_tie_slaves;  ///< set_tie_slaves(), empty without ties
  std::vector<Real> m_tie_corner_weight;       ///< W_I per node (set_tie_slaves())
  /// The masses and inverse masses contact reads (n_nodes) where there are tie slaves:
  /// the state's with each tie slave's replaced (contact_masses(), at each begin_step()).
  std::vector<Real> m_contact_mass, m_contact_inverse;
  const DistributedRun* m_run = nullptr;            ///< distributed runs only
  bool m_shared = true;                             ///< set_distribution()
  bool m_root_writes = false;                       ///< set_distribution()
  std::unique_ptr<contact::SlotSharing> m_sharing;  ///< share_slots(), its collectives
  /// Distributed runs: the nodes the engine reads (its slave nodes: every face node and the
  /// point nodes), ascending, and the run's positions and half-step velocities of them.
  std::vector<Index> m_shared_nodes;
  NodalVectors m_position, m_velocity;
  /// Shared slots on more than one rank: which of those rows travel each increment.
  ContactRows m_rows;
  bool m_rows_shared = false;
  long m_lost = 0;               ///< releases in the step (ContactTotals::lost)
  long m_lost_increments = 0;    ///< increments with a release in the step
  long m_behind_increments = 0;  ///< increments with a node behind a held shell's mid-surface
  Real m_behind_deepest = 0.0;   ///< the deepest such node in the step, m
};

}  // namespace xpl
