#pragma once
/// \file The central-difference update of the nodes (S1): positions, the free update of the
/// half-step velocities and the kinetic energy, with the two parts that act on the same pass
/// over the nodes: the prescribed motion (prescribed_motion.hpp: BCs, reactions, jumps) and
/// the external loads (solver/loads/external_loads.hpp); the rigid bodies (rigid_bodies.hpp) and
/// the finite rotations of shell nodes (node_rotations.hpp).

#include <algorithm>
#include <functional>
#include <vector>

#include "common/timer.hpp"
#include "solver/forces/element_set.hpp"
#include "solver/loads/boundary_state.hpp"
#include "solver/loads/external_loads.hpp"
#include "solver/model/model.hpp"
#include "solver/model/state.hpp"
#include "solver/motion/kinetic_sums.hpp"
#include "solver/motion/nodal_increment.hpp"
#include "solver/motion/node_rotations.hpp"
#include "solver/motion/prescribed_motion.hpp"
#include "solver/motion/rigid_bodies.hpp"
#include "solver/motion/ties.hpp"
#include "solver/output/output_sink.hpp"

namespace xpl {

/// The nodal half of the time loop: what moves the nodes once the forces are known.
class CentralDifference {
 public:
  /// `model` and `timers` must outlive the update; `shells`: the model has S4R elements, so
  /// nodes carry rotational DOFs (updated here, their finite rotations tracked for UR).
  CentralDifference(const Model& model, PhaseTimers& timers, bool shells);
  CentralDifference(const CentralDifference&) = delete;  // m_motion keeps &m_boundary
  CentralDifference& operator=(const CentralDifference&) = delete;

  /// Sets the finite rotations of an imported state (rotation vectors, n_nodes × 3, rad) on
  /// shell models; state.rotation takes them too.
  void import_rotation(const NodalVectors& rotation, State& state);

  /// Takes in the BCs and loads of `step`: the prescribed DOFs that act on something (rigid
  /// bodies take those of their reference nodes), the loaded DOFs, zero reactions in `state`.
  void begin_step(int step, State& state, RigidBodies& rigid);
  /// Notes on the BCs of the step that begin_step() dropped, to the sink.
  void report_step(int step, OutputSink& sink) const { m_motion.report_step(step, sink); }
  /// A warning to the sink when the last update_nodes() met a jump of the prescribed motion
  /// (PrescribedMotion::report_jump); then forgets the jump.
  void report_jump(int step, OutputSink& sink) { m_motion.report_jump(step, sink); }
  /// The prescribed DOFs of the step (those the nodal update drives).
  const std::vector<PrescribedDof>& prescribed() const { return m_motion.prescribed(); }

  /// External forces (CLOAD, pressure, gravity) at step time `step_time` / total time
  /// `total_time`, on the state's positions: the next update_nodes() evaluates them node by
  /// node in its pass (the positions must not change in between); nothing when the step has
  /// no loads.
  void apply_loads(const State& state, Real step_time, Real total_time);
  /// x_{n+1} = x_n + Δt v_{n+1/2}; shell node rotations advance by ω_{n+1/2} Δt; the forces
  /// of `elements` are cleared for its next element pass. One parallel pass over the nodes.
  void advance_positions(State& state, ElementSet& elements, Real dt);
  /// One velocity update with the forces of `elements` and the loads:
  /// dt_prev = Δt_{n-1/2} (0 at t = 0), dt_next = Δt_{n+1/2}; t_next_half and t_next_end are
  /// the total times at which velocity and displacement BCs are evaluated. Writes the
  /// velocities, accelerations, reactions, kinetic energies (ALLKE, ALLKD) and external work
  /// into `state`.
  void update_nodes(State& state, ElementSet& elements, RigidBodies& rigid, Real dt_prev,
                    Real dt_next, Real t_next_half, Real t_next_end);
  /// The model's ties (must outlive the update); null or inactive: none, and the nodal update
  /// runs exactly as without (no extra pass).
  void set_ties(const Ties* ties) { m_ties = ties; }
  /// Brings state.rotation up to date with the tracked rotations (before output).
  void sync_rotation(State& state);
  /// Nodes per chunk of the nodal loops; partial sums per chunk are added in chunk order so
  /// that energies do not depend on the thread count (nor, in a distributed run, on the rank
  /// count: each chunk's sums are those of the rank that integrates all its nodes).
  static constexpr Index NODE_CHUNK = 2048;

  /// Distributed runs (distributed_run.hpp): `share` replaces the kinetic sums and largest
  /// speeds of the chunks this rank does not count ([translations, rotations] per chunk,
  /// speeds per chunk) by those of the ranks that do, and the rank's rows of the prescribed
  /// DOFs (PrescribedMotion::prescribe()) by every rank's, in one collective; `same_counts`:
  /// every rank has as many rows as at the last call.
  /// `integrated`: 1 for the nodes this rank moves (those its elements use, the nodes of the
  /// chunks it counts, the nodes of the rigid bodies it owns or replays); the nodal
  /// passes skip the others, which no one reads on this rank (set_spans()).
  using ChunkShare = std::function<void(std::vector<KineticSums>& sums, std::vector<Real>& speed,
                                        std::vector<Real>& rows, bool same_counts)>;
  void set_distribution(ChunkShare share, std::vector<unsigned char> counted,
                        const std::vector<unsigned char>& integrated) {
    m_share_chunks = std::move(share);
    m_motion.set_distribution(std::move(counted), integrated);
    set_spans(integrated);
  }
  /// Nodes the nodal passes visit on this rank (all without a distribution).
  Index integrated_count() const;
  /// Distributed runs with rigid bodies: each body is updated by the rank owning it
  /// (RigidBodies::set_roles()); `share` puts into the given rows (n_nodes × 3: the internal
  /// forces, the external ones when the step has loads) the run's values at the nodes of the
  /// bodies this rank owns, from the ranks that integrate them (point to point), before the
  /// bodies' update. The bodies' rows then travel with the prescribed DOFs' rows.
  using RowShare = std::function<void(const std::vector<NodalVectors*>& rows)>;
  void set_rigid_share(RowShare share) { m_share_rigid = std::move(share); }
  /// Distributed runs with ties: each rank moves the slave forces to the master corners it
  /// integrates and makes the slaves it integrates follow (Ties::set_local(),
  /// solver/tie_routes.hpp); `forces` puts into the given rows the run's values at the slave
  /// nodes it needs and does not integrate (internal forces, external ones when the step has
  /// loads, internal moments with shells) before the forces move, `motion` those at the master
  /// corners it needs (v(n+½), v, a, and the angular velocities with rotations) before the
  /// slaves follow (point to point).
  void set_tie_share(RowShare forces, RowShare motion) {
    m_share_tie_forces = std::move(forces);
    m_share_tie_motion = std::move(motion);
  }
  /// Distributed runs with loads: the positions the pressures read before the loads are
  /// evaluated, and the work terms of the loaded DOFs before their work is summed, through
  /// `share` (ExternalLoads::share_positions, share_work; collective).
  void set_load_share(ExternalLoads::NodeRowShare share) { m_share_loads = std::move(share); }
  /// The largest |v(n+½)| component of the free translational DOFs at the last
  /// update_nodes(), m/s (for the health check; NaN shows in ALLKE instead).
  Real largest_speed() const { return m_largest_speed; }

 private:
  /// The fused nodal pass on the nodes of one chunk: their loads (when apply_loads() set them
  /// due) and the load work on free DOFs, then the central-difference update of the free
  /// translations and rotations; the chunk's kinetic sums of v_before and v_{n+1/2} go to
  /// m_chunk_sums (translations at `chunk`, rotations after the translations' chunks).
  void update_chunk(State& state, const NodalField& translation, const NodalField& rotation,
                    const NodalIncrement& inc, Index chunk);
  /// The kinetic sums of the chunks, added in chunk order (translations first), and the
  /// largest speed.
  KineticSums sum_chunks(Index n_chunks);
  /// The runs of consecutive nodes with `integrated` 1, per chunk (m_spans).
  void set_spans(const std::vector<unsigned char>& integrated);
  /// `f(first, last)` for each run of nodes of `chunk` the passes visit: the whole chunk
  /// without a distribution (and for a chunk this rank counts, so that its sums are the
  /// one-rank sums).
  template <class F>
  void for_each_span(Index chunk, F&& f) const {
    if (m_span_start.empty()) {
      const Index first = chunk * NODE_CHUNK;
      f(first, std::min(m_model.node_count(), first + NODE_CHUNK));
      return;
    }
    for (Index k = m_span_start[chunk]; k < m_span_start[chunk + 1]; ++k)
      f(m_spans[2 * k], m_spans[2 * k + 1]);
  }
  /// ALLKE, ALLKD and ALLWK of the update into `state` from its sums.
  void book_energies(State& state, const NodalIncrement& inc, const NodalSums& sums);

  const Model& m_model;
  PhaseTimers& m_timers;
  bool m_shells;
  BoundaryState m_boundary;  ///< the step's BCs and loads, read by the two parts below
  PrescribedMotion m_motion;
  ExternalLoads m_loads;
  const Ties* m_ties = nullptr;
  NodeRotations m_rotations;
  bool m_rotation_synced = true;  ///< state.rotation matches m_rotations
  std::vector<KineticSums> m_chunk_sums;
  std::vector<Real> m_chunk_speed;  ///< largest |v(n+½)| of each chunk's translations
  Real m_largest_speed = 0.0;       ///< largest_speed()
  /// Σ over the updates of ⅛(Δt(n−½)²/Δt(n+½)² − 1) × the spread: the energy the changes of
  /// the increment moved into ½ v⁻·M·v⁺, taken out of ALLKD (J).
  Real m_increment_shift = 0.0;
  /// The external force on each DOF at the previous increment, f_ext + reaction (n_nodes × 3,
  /// N), for the trapezoidal work of the loads and the prescribed DOFs alike (a DOF may be
  /// prescribed in one step and loaded in the next); allocated when a step has either.
  NodalVectors m_previous_force;
  ChunkShare m_share_chunks;  ///< set_distribution(); empty: one rank
  /// Distributed runs: the prescribed DOFs' and the bodies' rows (buffers kept between
  /// increments).
  std::vector<Real> m_rows, m_body_rows;
  /// Distributed runs: the runs [first, last) of the nodes this rank moves, chunk by chunk
  /// (runs of chunk c: m_span_start[c] to m_span_start[c + 1]); empty: every node.
  std::vector<Index> m_span_start, m_spans;
  RowShare m_share_rigid;  ///< set_rigid_share(); empty: one rank or no bodies
  RowShare m_share_tie_forces, m_share_tie_motion;  ///< set_tie_share(); empty: one rank
  ExternalLoads::NodeRowShare m_share_loads;        ///< set_load_share(); empty: one rank
};

}  // namespace xpl
