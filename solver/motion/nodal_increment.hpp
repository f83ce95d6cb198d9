#pragma once
/// \file The increment of one nodal update (S2) as a value: its two half-step increments, the
/// weights of the velocities it pairs, and the times at which the boundary conditions are
/// evaluated. The integrator (central_difference.hpp), the prescribed motion
/// (prescribed_motion.hpp) and the rigid bodies (rigid_bodies.hpp) read the same one; and the
/// pointers to one kind of nodal DOF that the update writes.

#include "common/types.hpp"

namespace xpl {

/// The times and weights of one update from t_n: v(n−½) → v(n+½).
struct NodalIncrement {
  Real dt_prev = 0.0;  ///< Δt(n−½), s (0 at t = 0)
  Real dt_next = 0.0;  ///< Δt(n+½), s
  Real dt_avg = 0.0;   ///< (dt_prev + dt_next) / 2, s
  Real w_new = 0.0;    ///< weight of v(n+½) in the whole-step velocity v_n (0 at t = 0)
  /// v_before = v(n−½) + w_before (v(n+½) − v(n−½)) is the velocity that ALLKE pairs with
  /// v(n+½): the velocity at t_n − dt_next/2, (dt_prev − dt_next) / (dt_prev + dt_next);
  /// 0 at a constant increment (v(n−½)), −1 at t = 0 (2 v_0 − v(½)).
  Real w_before = 0.0;
  Real step_time = 0.0;       ///< t_n since the start of the step, s
  Real time = 0.0;            ///< t_n, total time, s
  Real step_next_half = 0.0;  ///< t_n + dt_next/2 in the step: velocity BCs are taken there
  Real time_next_half = 0.0;  ///< the same in total time, s
  Real step_next_end = 0.0;   ///< t_n + dt_next in the step: displacement BCs are taken there
  Real time_next_end = 0.0;   ///< the same in total time, s

  /// The increment from t_n (`step_time`, `time`) with dt_prev = Δt(n−½) (0 at t = 0) and
  /// dt_next = Δt(n+½); `time_next_half` and `time_next_end` are the total times at which
  /// velocity and displacement BCs are evaluated.
  static NodalIncrement make(Real dt_prev, Real dt_next, Real step_time, Real time,
                             Real time_next_half, Real time_next_end) {
    NodalIncrement inc;
    inc.dt_prev = dt_prev;
    inc.dt_next = dt_next;
    inc.dt_avg = 0.5 * (dt_prev + dt_next);
    // At t = 0 the whole-step velocity is the initial velocity itself.
    inc.w_new = dt_prev > 0.0 ? 0.5 : 0.0;
    // ALLKE pairs v(n+½) = v(t_n + dt_next/2) with the velocity at the mirror time
    // t_n − dt_next/2 under the acceleration at t_n: v(n−½) + (dt_prev − dt_next)/2 a_n, so
    // w_before = (dt_prev − dt_next) / (dt_prev + dt_next): 0 at a constant increment, −1 at
    // t = 0 (v_0 − dt_next/2 a_0 = 2 v_0 − v(½)). docs/theory/energy.md, "What ALLKE measures".
    inc.w_before = dt_prev + dt_next > 0.0 ? (dt_prev - dt_next) / (dt_prev + dt_next) : 0.0;
    inc.step_time = step_time;
    inc.time = time;
    inc.step_next_half = step_time + 0.5 * dt_next;
    inc.time_next_half = time_next_half;
    inc.step_next_end = step_time + dt_next;
    inc.time_next_end = time_next_end;
    return inc;
  }
};

/// Pointers to one kind of nodal DOF (translations or rotations) for one update, each
/// n_nodes × 3 column-major: component c of node i at c · n_nodes + i.
struct NodalField {
  Real* velocity_half = nullptr;  ///< v(n−½) in, v(n+½) out
  Real* velocity = nullptr;       ///< whole-step velocity v_n, out
  Real* acceleration = nullptr;   ///< a_n, out; nullptr: not kept
  const Real* force_internal = nullptr;
  const Real* force_external = nullptr;
  Real external_scale = 0.0;  ///< 0 when there is no external force array
  const Real* inverse_mass = nullptr;
  const Real* mass = nullptr;
};

}  // namespace xpl
