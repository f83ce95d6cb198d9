#include "solver/motion/prescribed_motion.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "solver/message_text.hpp"
#include "solver/motion/rigid_bodies.hpp"

namespace xpl {

namespace {

/// A prescribed DOF's velocity jumps at the first update of a step when the BC's velocity at
/// t_n differs from v(n−½) by more than this share of v(n+½) − v(n−½) (about ½ for a smooth
/// motion, about 1 after a jump).
constexpr Real JUMP_SHARE = 0.75;
/// Step of the forward difference that gives a displacement BC's velocity at t_n, as a
/// fraction of the next increment.
constexpr Real JUMP_PROBE = 1e-3;

}  // namespace

PrescribedMotion::PrescribedMotion(const Model& model, const BoundaryState& boundary, bool shells)
    : m_model(model), m_boundary(boundary), m_shells(shells) {}

void PrescribedMotion::begin_step(RigidBodies& rigid, const State& state) {
  // Reference nodes of rigid bodies drive their body; members cannot be prescribed.
  std::vector<PrescribedDof> active = m_boundary.prescribed();
  m_dropped_members = rigid.empty() ? 0 : rigid.begin_step(active);
  // Rotations prescribed on nodes that belong to no shell have nothing to act on.
  m_prescribed.clear();
  m_dropped_rotations = m_boundary.has_rotational_dofs();
  for (const PrescribedDof& d : active) {
    if (d.component >= 3 && (state.rotary_inertia.empty() || state.rotary_inertia[d.node] <= 0.0)) {
      m_dropped_rotations = true;
      continue;
    }
    m_prescribed.push_back(d);
  }
  m_v_old_prescribed.assign(m_prescribed.size(), 0.0);
  m_prescribed_value.resize(m_prescribed.size());
  for (std::size_t k = 0; k < m_prescribed.size(); ++k)
    m_prescribed_value[k] =
        m_prescribed[k].component >= 3
            ? state.rotation(m_prescribed[k].node, m_prescribed[k].component - 3)
            : 0.0;
  m_first_update = true;
  if (m_shells && m_previous_moment.rows() == 0 && !m_prescribed.empty())
    m_previous_moment = NodalVectors::Zero(m_model.node_count(), 3);
}

void PrescribedMotion::report_step(int step, OutputSink& sink) const {
  if (m_dropped_rotations)
    sink.message(Severity::Note, "step " + m_model.steps[step].name +
                                     ": boundary conditions on DOFs 4-6 of nodes that belong "
                                     "to no shell are ignored (solid element nodes have no "
                                     "rotations)");
  if (m_dropped_members > 0)
    sink.message(Severity::Warning,
                 "step " + m_model.steps[step].name + ": " + std::to_string(m_dropped_members) +
                     " boundary condition(s) on member nodes of rigid bodies are ignored; "
                     "prescribe the motion on the REF NODE");
}

Real PrescribedMotion::velocity_half(const PrescribedDof& d, Real current,
                                     const NodalIncrement& inc) const {
  if (d.type == BoundaryType::Velocity)
    return m_boundary.target(m_model, d, inc.step_next_half, inc.time_next_half);
  if (!(inc.dt_next > 0.0)) return 0.0;
  return (m_boundary.target(m_model, d, inc.step_next_end, inc.time_next_end) - current) /
         inc.dt_next;
}

bool PrescribedMotion::is_jump(const PrescribedDof& d, const NodalIncrement& inc, Real v_old,
                               Real v_new) const {
  // The BC's own velocity at t_n: for a smooth motion sampled at t(n−½) and t(n+½) it lies
  // about half-way between v_old and v_new; after a jump at the start of the step it is
  // already v_new (up to the change over half an increment).
  Real v_at = 0.0, v_later = v_new;
  if (d.type == BoundaryType::Velocity) {
    v_at = m_boundary.target(m_model, d, inc.step_time, inc.time);
  } else {
    // The rate of the prescribed displacement just after t_n (a forward difference over a
    // small fraction of the next increment), and its mean rate over the next increment. The
    // latter, not v_new: a BC that takes over at a step boundary finds the node half an
    // increment behind and v_new catches up, which would hide the jump in the share.
    const Real h = JUMP_PROBE * inc.dt_next;
    if (!(h > 0.0)) return false;
    const Real u_now = m_boundary.target(m_model, d, inc.step_time, inc.time);
    v_at = (m_boundary.target(m_model, d, inc.step_time + h, inc.time + h) - u_now) / h;
    v_later = (m_boundary.target(m_model, d, inc.step_time + inc.dt_next, inc.time + inc.dt_next) -
               u_now) /
              inc.dt_next;
  }
  return std::abs(v_at - v_old) > JUMP_SHARE * std::abs(v_later - v_old);
}

void PrescribedMotion::keep_old_velocities(const NodalField& translation,
                                           const NodalField& rotation, Index n) {
  for (std::size_t k = 0; k < m_prescribed.size(); ++k) {
    const PrescribedDof& d = m_prescribed[k];
    const NodalField& field = d.component < 3 ? translation : rotation;
    m_v_old_prescribed[k] = field.velocity_half[(d.component % 3) * n + d.node];
  }
}

void PrescribedMotion::update(State& state, const NodalField& translation,
                              const NodalField& rotation, const NodalIncrement& inc,
                              const RigidJumps& rigid_jumps, NodalVectors& previous_force,
                              NodalSums& sums) {
  book_jumps(rigid_jumps, sums);
  update_prescribed(state, translation, rotation, inc, previous_force, sums, nullptr);
  end_update(inc, rigid_jumps, previous_force, sums);
}

void PrescribedMotion::prescribe(State& state, const NodalField& translation,
                                 const NodalField& rotation, const NodalIncrement& inc,
                                 NodalVectors& previous_force, std::vector<Real>& rows) {
  rows.clear();
  NodalSums untouched;
  update_prescribed(state, translation, rotation, inc, previous_force, untouched, &rows);
}

void PrescribedMotion::finish(const NodalIncrement& inc, const RigidJumps& rigid_jumps,
                              NodalVectors& previous_force, const std::vector<Real>& all,
                              NodalSums& sums) {
  book_jumps(rigid_jumps, sums);
  fold_rows(all, inc, sums);
  end_update(inc, rigid_jumps, previous_force, sums);
}

void PrescribedMotion::book_jumps(const RigidJumps& rigid_jumps, NodalSums& sums) {
  // Jumps of the prescribed motion: found with the update, their work corrected after it
  // (the update itself stays as it is for every other DOF).
  if (m_jump_work_pending != 0.0) {
    sums.work += m_jump_work_pending;  // the second half of the impulses one update ago
    m_jump_work_pending = 0.0;
  }
  if (rigid_jumps.dofs > 0) {  // rigid bodies' jumps: booked like those of free DOFs
    m_jump_work_pending += rigid_jumps.pending;
    m_jump.dofs += rigid_jumps.dofs;
    m_jump.energy += rigid_jumps.energy;
    m_jump.largest = std::max(m_jump.largest, rigid_jumps.largest);
  }
}

void PrescribedMotion::end_update(const NodalIncrement& inc, const RigidJumps& rigid_jumps,
                                  NodalVectors& previous_force, NodalSums& sums) {
  // The DOFs that jumped pair the states before and after the jump, not the mirror-time
  // velocity: their spread is no Δt(n+½)² a² and takes no part in the increment shift.
  sums.jump_spread = rigid_jumps.spread;
  if (!m_jumps.empty()) count_jump_work(inc, previous_force, sums);
  m_first_update = false;
}

void PrescribedMotion::update_prescribed(State& state, const NodalField& translation,
                                         const NodalField& rotation, const NodalIncrement& inc,
                                         NodalVectors& previous_force, NodalSums& sums,
                                         std::vector<Real>* rows) {
  // Prescribed DOFs: velocity from the BC, reaction = m a - (f_ext - f_int).
  // External work by the trapezoidal rule over [t_{n-1}, t_n]: exact for constant forces.
  const Index n = m_model.node_count();
  if (m_first_update) {
    m_jumps.clear();
    m_jump.time = inc.time;
  }
  KineticSums counted, kinetic;
  for (std::size_t k = 0; k < m_prescribed.size(); ++k) {
    const PrescribedDof& d = m_prescribed[k];
    // Distributed runs: a node this rank does not move is no one's business here (its
    // counting rank has it: the counted nodes are moved).
    if (rows != nullptr && !m_moved.empty() && m_moved[d.node] == 0) continue;
    const bool turn = d.component >= 3;
    const int c = d.component % 3;
    const NodalField& field = turn ? rotation : translation;
    const Index i = d.node, at = c * n + i;
    const Real v_old = m_v_old_prescribed[k];
    Real current = 0.0;
    if (d.type != BoundaryType::Velocity) {
      // Translations correct against the actual position; rotations against the prescribed
      // value carried along (components of the rotation vector, exact about a fixed axis).
      m_prescribed_value[k] = current =
          turn ? m_prescribed_value[k] + inc.dt_prev * v_old : state.displacement(i, c);
    }
    const Real v_new = velocity_half(d, current, inc);
    Real& f_before = (turn ? m_previous_moment : previous_force)(i, c);
    const bool count = m_counted.empty() || m_counted[i] != 0;
    const bool jump = m_first_update && count && v_new != v_old && is_jump(d, inc, v_old, v_new);
    const Real m = field.mass[i];
    // ALLKE: what the free update counted for the DOF, replaced by the prescribed motion's.
    const Real v_free = field.velocity_half[at];
    const Real free_before = v_old + inc.w_before * (v_free - v_old);
    const Real new_before = v_old + inc.w_before * (v_new - v_old);
    if (rows == nullptr) {
      counted.add(m, free_before, v_free);
      kinetic.add(m, new_before, v_new);
    }
    // V at t_n: a prescribed velocity is known there, and the mean of the half-step velocities
    // is not it where the BC's amplitude has a corner. A body stopped by a velocity ramp that
    // ends with the step kept v(n-1/2) ≈ slope·Δt/2 in that mean, so the last frame showed it
    // still moving and a run continued from it (--import) started with that motion (issue 35:
    // 3 mm/s, ALLKE 2e-10 J and 0.25 N of contact force in a model that should rest).
    const Real v_whole = d.type == BoundaryType::Velocity && inc.dt_prev > 0.0
                             ? m_boundary.target(m_model, d, inc.step_time, inc.time)
                             : v_old + inc.w_new * (v_new - v_old);
    const Real acc = inc.dt_avg > 0.0 ? (v_new - v_old) / inc.dt_avg : 0.0;
    const Real f_ext = field.external_scale * field.force_external[at];
    const Real r = m * acc - (f_ext - field.force_internal[at]);
    (turn ? state.reaction_moment : state.reaction)(i, c) = r;
    if (field.acceleration) field.acceleration[at] = acc;
    field.velocity_half[at] = v_new;
    field.velocity[at] = v_whole;
    const Real f_now = f_ext + r;
    const Real f_internal = field.force_internal[at];
    if (rows != nullptr) {
      if (count)
        rows->insert(rows->end(), {static_cast<Real>(k), m, free_before, v_free, new_before, v_new,
                                   f_before, f_now, v_old, jump ? 1.0 : 0.0, f_internal});
    } else {
      sums.work += 0.5 * (f_before + f_now) * inc.dt_prev * v_old;
      if (jump) m_jumps.push_back({k, m, v_old, v_new, f_before, f_now, f_internal});
    }
    f_before = f_now;
  }
  if (rows != nullptr) return;  // fold_rows() books them
  kinetic -= counted;
  sums.kinetic += kinetic;
}

void PrescribedMotion::fold_rows(const std::vector<Real>& all, const NodalIncrement& inc,
                                 NodalSums& sums) {
  // Every rank's DOFs, folded in DOF order as update_prescribed() does on one rank.
  KineticSums counted, kinetic;
  std::vector<const Real*>& by_dof = m_by_dof;
  by_dof.assign(m_prescribed.size(), nullptr);
  for (std::size_t r = 0; r + FOLD_WIDTH <= all.size(); r += FOLD_WIDTH)
    by_dof[static_cast<std::size_t>(all[r])] = &all[r + 1];
  for (std::size_t k = 0; k < by_dof.size(); ++k) {
    const Real* d = by_dof[k];
    if (d == nullptr) continue;
    const Real m = d[0], free_before = d[1], v_free = d[2], new_before = d[3], v_new = d[4];
    const Real f_before = d[5], f_now = d[6], v_old = d[7];
    counted.add(m, free_before, v_free);
    kinetic.add(m, new_before, v_new);
    sums.work += 0.5 * (f_before + f_now) * inc.dt_prev * v_old;
    // Every rank books every jump (the counting rank alone finds it): the same work, the
    // same pending half and the same warning on all.
    if (d[8] != 0.0) m_jumps.push_back({k, m, v_old, v_new, f_before, f_now, d[9]});
  }
  kinetic -= counted;
  sums.kinetic += kinetic;
}

void PrescribedMotion::count_jump_work(const NodalIncrement& inc, NodalVectors& previous_force,
                                       NodalSums& sums) {
  // The BC's force at a jump is the impulse J = m (v_new - v_old) plus the internal force the
  // node passes on to the elements. The impulse does J (v_old + v_new) / 2 = ½m(v_new² -
  // v_old²), counted exactly and split at the DOF's kinetic energy at t_n, so that ETOTAL
  // balances at t_n too: ALLKE pairs v_old with v_new there (½m v_old v_new; at t = 0 the
  // state before the jump, ½m v_old², instead of the product with 2 v_old - v_new that
  // update_prescribed counted), so ½m v_old (v_new - v_old) is counted now and ½m v_new
  // (v_new - v_old) with the next increment. The trapezoidal rule of update_prescribed weighed
  // J by (dt_prev v_old + dt_next v_new) / 2 over dt_avg: off by ¼ m (v_new - v_old)²
  // (dt_next - dt_prev) / dt_avg, ½mΔv² at t = 0. Its term is replaced; the internal force
  // keeps the trapezoidal rule, the impulse leaves f_before.
  KineticSums counted, paired;
  for (const PendingJump& j : m_jumps) {
    const PrescribedDof& d = m_prescribed[j.dof];
    const bool turn = d.component >= 3;
    const int c = d.component % 3;
    const Real m = j.mass, v_old = j.v_old, v_new = j.v_new;
    counted.add(m, v_old + inc.w_before * (v_new - v_old), v_new);
    const Real after = inc.dt_prev > 0.0 ? v_new : v_old;
    paired.add(m, v_old, after);
    sums.jump_spread += m * (after - v_old) * (after - v_old);
    const Real kinetic = 0.5 * m * v_old * after;
    const Real f_now = j.f_now;  // what update_prescribed stored: f_ext + reaction
    const Real f_smooth = j.f_internal;
    const Real trapezoid = 0.5 * (j.f_before + f_now) * inc.dt_prev * v_old;
    const Real smooth = 0.5 * (j.f_before + f_smooth) * inc.dt_prev * v_old;
    const Real now = kinetic - 0.5 * m * v_old * v_old;
    const Real later = 0.5 * m * v_new * v_new - kinetic;
    sums.work += (smooth + now) - trapezoid;
    m_jump_work_pending += later;
    (turn ? m_previous_moment : previous_force)(d.node, c) = f_smooth;
    ++m_jump.dofs;
    m_jump.energy += now + later;
    m_jump.largest = std::max(m_jump.largest, std::abs(v_new - v_old));
  }
  m_jumps.clear();
  paired -= counted;
  sums.kinetic += paired;
}

void PrescribedMotion::report_jump(int step, OutputSink& sink) {
  if (m_jump.dofs == 0) return;
  sink.message(Severity::Warning,
               "step " + m_model.steps[step].name +
                   ": a prescribed velocity jump at t = " + format_real(m_jump.time) + " s on " +
                   std::to_string(m_jump.dofs) + " DOF(s) (|dv| up to " +
                   format_real(m_jump.largest) + ") put " + format_real(m_jump.energy) +
                   " J into the model (impulsive input, counted in ALLWK)");
  m_jump = Jump{};
}

}  // namespace xpl
