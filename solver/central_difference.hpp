#pragma once
/// \file The central-difference update of the nodes (S2): half-step velocities of the free
/// DOFs, prescribed DOFs and their reactions, rigid bodies, the external loads of the step
/// and the work they do, and the finite rotations of shell nodes.

#include <cstdint>
#include <vector>

#include "common/timer.hpp"
#include "solver/element_set.hpp"
#include "solver/kinetic_sums.hpp"
#include "solver/loads/boundary_state.hpp"
#include "solver/loads/external_loads.hpp"
#include "solver/model.hpp"
#include "solver/node_rotations.hpp"
#include "solver/output_sink.hpp"
#include "solver/rigid_bodies.hpp"
#include "solver/state.hpp"
#include "solver/ties.hpp"

namespace xpl {

/// The nodal half of the time loop: what moves the nodes once the forces are known.
class CentralDifference {
 public:
  /// `model` and `timers` must outlive the update; `shells`: the model has S4R elements, so
  /// nodes carry rotational DOFs (updated here, their finite rotations tracked for UR).
  CentralDifference(const Model& model, PhaseTimers& timers, bool shells);

  /// Sets the finite rotations of an imported state (rotation vectors, n_nodes × 3, rad) on
  /// shell models; state.rotation takes them too.
  void import_rotation(const NodalVectors& rotation, State& state);

  /// Takes in the BCs and loads of `step`: the prescribed DOFs that act on something (rigid
  /// bodies take those of their reference nodes), the loaded DOFs, zero reactions in `state`.
  void begin_step(int step, State& state, RigidBodies& rigid);
  /// Notes on the BCs of the step that begin_step() dropped, to the sink.
  void report_step(int step, OutputSink& sink) const;
  /// A warning to the sink when the last update_nodes() met a jump of the prescribed motion
  /// (see update_prescribed), with the energy the impulse put in; then forgets the jump.
  void report_jump(int step, OutputSink& sink);
  /// The prescribed DOFs of the step (those the nodal update drives).
  const std::vector<PrescribedDof>& prescribed() const { return m_prescribed; }

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
  /// The largest |v(n+½)| component of the free translational DOFs at the last
  /// update_nodes(), m/s (for the health check; NaN shows in ALLKE instead).
  Real largest_speed() const { return m_largest_speed; }

 private:
  /// Pointers to one kind of nodal DOF (translations or rotations), defined in the .cpp.
  struct Field;
  /// The times and weights of one update.
  struct Increment {
    Real dt_prev, dt_next;
    Real dt_avg;  ///< (dt_prev + dt_next) / 2
    Real w_new;   ///< weight of v_{n+1/2} in the whole-step velocity (0 at t = 0)
    /// v_before = v_{n-1/2} + w_before (v_{n+1/2} - v_{n-1/2}) is the velocity that ALLKE
    /// pairs with v_{n+1/2}: the velocity at t_n - dt_next/2, (dt_prev - dt_next) / (dt_prev
    /// + dt_next); 0 at a constant increment (v_{n-1/2}), -1 at t = 0 (2 v_0 - v_{1/2}).
    Real w_before;
    Real t_next_half, t_next_end;
  };
  /// Keeps only the prescribed DOFs of `active` that act on something (rotations need
  /// rotary inertia); sets their current values.
  void select_prescribed(const std::vector<PrescribedDof>& active, const State& state);
  /// The fused nodal pass on the nodes of one chunk: their loads (when apply_loads() set them
  /// due) and the load work on free DOFs, then the central-difference update of the free
  /// translations and rotations; the chunk's kinetic sums of v_before and v_{n+1/2} go to
  /// m_chunk_sums (translations at `chunk`, rotations after the translations' chunks).
  void update_chunk(State& state, const Field& translation, const Field& rotation,
                    const Increment& inc, Index chunk);
  /// Velocities from the BCs at the prescribed DOFs, their reactions and work (added to
  /// `work`); returns the correction of the kinetic sums to what the free update counted.
  KineticSums update_prescribed(State& state, const Field& translation, const Field& rotation,
                                const Increment& inc, Real& work);
  /// Whether the velocity v_old → v_new of prescribed DOF `d` at the first update of a step
  /// is a jump of the BC (its velocity at t_n itself is already the new one) rather than the
  /// central-difference sampling of a smooth motion (its velocity at t_n lies half-way).
  bool is_jump(const PrescribedDof& d, const State& state, const Increment& inc, Real v_old,
               Real v_new) const;
  /// At the first update of a step: the prescribed DOFs whose velocity jumps (is_jump), with
  /// their force of the previous increment, into m_jumps.
  void find_jumps(const State& state, const Increment& inc);
  /// After update_prescribed: the work of the jumps in m_jumps counted as impulses (their
  /// trapezoidal term replaced), into `work` and the pending work of the next increment;
  /// returns the correction of the kinetic sums (a DOF that jumps pairs its states before
  /// and after the jump; at t = 0 it counts its state before the jump) and adds the jumping
  /// DOFs' spread to `jump_spread`.
  KineticSums count_jump_work(const Field& translation, const Field& rotation, const Increment& inc,
                              Real& work, Real& jump_spread);

  const Model& m_model;
  PhaseTimers& m_timers;
  bool m_shells;
  BoundaryState m_boundary;
  ExternalLoads m_loads;  ///< CLOAD, pressure and gravity, their forces and work
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
  NodalVectors m_previous_moment;           ///< moment at prescribed rotations, previous inc.
  std::vector<PrescribedDof> m_prescribed;  ///< the step's prescribed DOFs that exist
  std::vector<Real> m_prescribed_value;     ///< current value of each prescribed DOF
  std::vector<Real> m_v_old_prescribed;     ///< v_{n-1/2} at each prescribed DOF
  /// The jumps of the prescribed motion met by the last update (BCs jump where they take
  /// effect: at the first update of a step).
  struct Jump {
    Index dofs = 0;      ///< prescribed DOFs whose velocity jumped
    Real energy = 0.0;   ///< Σ ½m(v_b² - v_a²): the work of the impulses, J
    Real largest = 0.0;  ///< largest |v_b - v_a|, m/s or rad/s
    Real time = 0.0;     ///< total time of the update, s
  };
  Jump m_jump;
  /// A prescribed DOF that jumps at this update, with f_before of the trapezoidal rule.
  struct PendingJump {
    std::size_t dof;  ///< index into m_prescribed
    Real f_before;    ///< its force at the previous increment, N or N m
  };
  std::vector<PendingJump> m_jumps;
  bool m_first_update = false;  ///< the next update is the first one of the step
  /// Work of the impulses of a jump that falls in the increment after it, J: added with the
  /// work of that increment (the second half of the velocity change, v_n → v_{n+1/2}).
  Real m_jump_work_pending = 0.0;
  bool m_dropped_rotations = false;  ///< begin_step dropped BCs on DOFs 4-6
  Index m_dropped_members = 0;       ///< BCs on rigid member nodes dropped
};

}  // namespace xpl
