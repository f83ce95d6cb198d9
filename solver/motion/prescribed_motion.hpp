#pragma once
/// \file The prescribed motion of the nodal update (S2): the DOFs the boundary conditions
/// drive, their velocity v(n+½) taken from the BC, their reactions, the work those do, and the
/// jumps of the prescribed velocity at the start of a step, counted as impulses.

#include <cstddef>
#include <functional>
#include <vector>

#include "common/types.hpp"
#include "solver/loads/boundary_state.hpp"
#include "solver/model/model.hpp"
#include "solver/model/state.hpp"
#include "solver/motion/kinetic_sums.hpp"
#include "solver/motion/nodal_increment.hpp"
#include "solver/output/output_sink.hpp"

namespace xpl {

class RigidBodies;
struct RigidJumps;

/// What one nodal update sums over its DOFs, in the order the parts add to it.
struct NodalSums {
  KineticSums kinetic;  ///< of v_before and v(n+½) (kinetic_sums.hpp)
  Real work = 0.0;      ///< external work of the increment, J
  /// The kinetic spread of the DOFs whose prescribed velocity jumped: no Δt(n+½)² a² (it
  /// takes no part in the shift of ALLKD when the increment changes).
  Real jump_spread = 0.0;
};

/// The prescribed DOFs of a step and what they do to the nodal update.
class PrescribedMotion {
 public:
  /// `model` and `boundary` (the step's BCs) must outlive the motion; `shells`: the model has
  /// rotational DOFs.
  PrescribedMotion(const Model& model, const BoundaryState& boundary, bool shells);

  /// Takes in the prescribed DOFs of the BCs in force (boundary.begin_step() ran): those of
  /// rigid bodies' reference nodes drive their body (`rigid` takes them), those on rigid
  /// member nodes and rotations of nodes without rotary inertia are dropped; the others are
  /// the step's, their current values from `state`. The next update is the step's first.
  void begin_step(RigidBodies& rigid, const State& state);
  /// Notes on the BCs that begin_step() dropped, to the sink.
  void report_step(int step, OutputSink& sink) const;
  /// Distributed runs (distributed_run.hpp): what one prescribed DOF adds to the sums, as
  /// FOLD_WIDTH values (its index, mass, the velocities before and after of the counted and
  /// of the prescribed motion, f_before, f_now, v_old, 1 if it jumps at this update else 0,
  /// and its internal force): prescribe() gives the rank's rows, finish() folds every rank's,
  /// the jumps' work too, so that every rank books every jump.
  static constexpr int FOLD_WIDTH = 11;
  /// `counted`: 1 for the nodes whose DOFs this rank counts (exactly one rank counts each);
  /// `moved`: 1 for the nodes this rank moves (prescribe() leaves the others' DOFs alone).
  void set_distribution(std::vector<unsigned char> counted, std::vector<unsigned char> moved) {
    m_counted = std::move(counted);
    m_moved = std::move(moved);
  }
  /// The prescribed DOFs of the step (those the nodal update drives).
  const std::vector<PrescribedDof>& prescribed() const { return m_prescribed; }

  /// v(n+½) of prescribed DOF `d` over `inc`: a velocity BC's value at t_n + dt_next/2, or
  /// the rate that takes a displacement BC from `current` (its value at t_n) to its value at
  /// t_n + dt_next (0 when dt_next is 0). The one evaluation the update and the jump test
  /// share; rigid bodies take their reference nodes' from it too.
  Real velocity_half(const PrescribedDof& d, Real current, const NodalIncrement& inc) const;
  /// Whether the next update may meet a jump of the prescribed motion (the first of a step).
  bool first_update() const { return m_first_update; }
  /// Whether the velocity v_old → v_new of prescribed DOF `d` at the first update of a step
  /// is a jump of the BC (its velocity at t_n itself is already the new one) rather than the
  /// central-difference sampling of a smooth motion (its velocity at t_n lies half-way).
  bool is_jump(const PrescribedDof& d, const NodalIncrement& inc, Real v_old, Real v_new) const;

  /// Keeps v(n−½) of the prescribed DOFs (before the free update overwrites it).
  void keep_old_velocities(const NodalField& translation, const NodalField& rotation, Index n);
  /// After the free update and the rigid bodies (`rigid_jumps`: theirs): books the pending
  /// work of the impulses one update ago and the bodies' jumps into `sums`, then sets the
  /// prescribed DOFs' velocities from the BCs, their reactions (into `state`) and work, and
  /// counts the work of their jumps as impulses. `sums.kinetic` takes the correction of what
  /// the free update counted; `previous_force` (n_nodes × 3, N) holds f_ext + reaction of
  /// the previous increment for the trapezoidal rule.
  void update(State& state, const NodalField& translation, const NodalField& rotation,
              const NodalIncrement& inc, const RigidJumps& rigid_jumps,
              NodalVectors& previous_force, NodalSums& sums);
  /// Distributed runs: update() in two halves around one collective (the rows travel with the
  /// nodal chunks' sums): prescribe() sets the prescribed DOFs' motion and reactions and
  /// puts this rank's rows into `rows` (FOLD_WIDTH values per DOF it counts; a buffer the
  /// caller keeps, cleared first); finish() books what update() books, with every rank's
  /// rows `all` (in any order) folded in DOF order.
  void prescribe(State& state, const NodalField& translation, const NodalField& rotation,
                 const NodalIncrement& inc, NodalVectors& previous_force, std::vector<Real>& rows);
  void finish(const NodalIncrement& inc, const RigidJumps& rigid_jumps,
              NodalVectors& previous_force, const std::vector<Real>& all, NodalSums& sums);
  /// A warning to the sink when the last update() met a jump of the prescribed motion, with
  /// the energy the impulse put in; then forgets the jump.
  void report_jump(int step, OutputSink& sink);

 private:
  /// A prescribed DOF that jumps at this update, with what its work as an impulse reads.
  struct PendingJump {
    std::size_t dof;  ///< index into m_prescribed
    Real mass;        ///< of its node, kg (or its rotary inertia)
    Real v_old;       ///< v(n−½) before the jump
    Real v_new;       ///< v(n+½) the BC sets
    Real f_before;    ///< its force at the previous increment, N or N m
    Real f_now;       ///< f_ext + reaction of this increment
    Real f_internal;  ///< its internal force, which keeps the trapezoidal rule
  };
  /// Velocities from the BCs at the prescribed DOFs (and, at the first update, the DOFs that
  /// jump with their previous force, into m_jumps), their reactions and work; adds to `sums`
  /// the correction of the kinetic sums to what the free update counted. The velocity at t_n
  /// (state.velocity, output V) of a DOF with a prescribed velocity is the BC's own value at
  /// t_n (after t = 0), not the mean of the half-step velocities.
  /// Distributed runs (`rows` not null): the sums are left alone and the rank's rows appended
  /// to `rows` instead, for fold_rows().
  void update_prescribed(State& state, const NodalField& translation, const NodalField& rotation,
                         const NodalIncrement& inc, NodalVectors& previous_force, NodalSums& sums,
                         std::vector<Real>* rows);
  /// Distributed runs: every rank's rows (`all`) into `sums` in DOF order, as
  /// update_prescribed() adds them on one rank, and the DOFs that jump into m_jumps.
  void fold_rows(const std::vector<Real>& all, const NodalIncrement& inc, NodalSums& sums);
  /// Before the prescribed DOFs: the pending work of the impulses and the bodies' jumps.
  void book_jumps(const RigidJumps& rigid_jumps, NodalSums& sums);
  /// After them: the jumps' spread and work; the update is no longer the step's first.
  void end_update(const NodalIncrement& inc, const RigidJumps& rigid_jumps,
                  NodalVectors& previous_force, NodalSums& sums);
  /// After update_prescribed: the work of the jumps in m_jumps counted as impulses (their
  /// trapezoidal term replaced), into `sums.work` and the pending work of the next increment;
  /// adds the correction of the kinetic sums (a DOF that jumps pairs its states before and
  /// after the jump; at t = 0 it counts its state before the jump) and the jumping DOFs'
  /// spread to `sums`.
  void count_jump_work(const NodalIncrement& inc, NodalVectors& previous_force, NodalSums& sums);

  const Model& m_model;
  const BoundaryState& m_boundary;
  bool m_shells;
  std::vector<PrescribedDof> m_prescribed;  ///< the step's prescribed DOFs that exist
  /// Distributed runs: 1 for the nodes whose work and jumps this rank counts (set_counted()),
  /// empty: every node.
  std::vector<unsigned char> m_counted;
  std::vector<unsigned char> m_moved;    ///< set_distribution(); empty: every node
  std::vector<Real> m_prescribed_value;  ///< current value of each prescribed DOF
  std::vector<Real> m_v_old_prescribed;  ///< v(n−½) at each prescribed DOF
  NodalVectors m_previous_moment;        ///< moment at prescribed rotations, previous inc.
  /// The jumps of the prescribed motion met by the last update (BCs jump where they take
  /// effect: at the first update of a step).
  struct Jump {
    Index dofs = 0;      ///< prescribed DOFs whose velocity jumped
    Real energy = 0.0;   ///< Σ ½m(v_b² - v_a²): the work of the impulses, J
    Real largest = 0.0;  ///< largest |v_b - v_a|, m/s or rad/s
    Real time = 0.0;     ///< total time of the update, s
  };
  Jump m_jump;
  std::vector<PendingJump> m_jumps;
  std::vector<const Real*> m_by_dof;  ///< fold_rows(): each DOF's row, kept between increments
  bool m_first_update = false;        ///< the next update is the first one of the step
  /// Work of the impulses of a jump that falls in the increment after it, J: added with the
  /// work of that increment (the second half of the velocity change, v_n → v(n+½)).
  Real m_jump_work_pending = 0.0;
  bool m_dropped_rotations = false;  ///< begin_step dropped BCs on DOFs 4-6
  Index m_dropped_members = 0;       ///< BCs on rigid member nodes dropped
};

}  // namespace xpl
