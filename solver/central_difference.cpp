#include "solver/central_difference.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "solver/message_text.hpp"

namespace xpl {

namespace {

/// Nodes per chunk of the nodal loops; partial sums per chunk are added in chunk order so
/// that energies do not depend on the thread count.
constexpr Index NODE_CHUNK = 2048;
/// A prescribed DOF's velocity jumps at the first update of a step when the BC's velocity at
/// t_n differs from v_{n-1/2} by more than this share of v_{n+1/2} - v_{n-1/2} (about ½ for a
/// smooth motion, about 1 after a jump).
constexpr Real JUMP_SHARE = 0.75;
/// Step of the forward difference that gives a displacement BC's velocity at t_n, as a
/// fraction of the next increment.
constexpr Real JUMP_PROBE = 1e-3;

}  // namespace

struct CentralDifference::Field {
  Real* velocity_half;
  Real* velocity;
  Real* acceleration;  ///< nullptr: not kept
  const Real* force_internal;
  const Real* force_external;
  Real external_scale;  ///< 0 when there is no external force array
  const Real* inverse_mass;
  const Real* mass;
};

CentralDifference::CentralDifference(const Model& model, PhaseTimers& timers, bool shells)
    : m_model(model), m_timers(timers), m_shells(shells) {
  const Index n = model.node_count();
  if (shells) m_rotations = NodeRotations(n);
  m_chunk_sums.assign(static_cast<std::size_t>((n + NODE_CHUNK - 1) / NODE_CHUNK) * 2, {});
  m_chunk_speed.assign(static_cast<std::size_t>((n + NODE_CHUNK - 1) / NODE_CHUNK), 0.0);
}

void CentralDifference::import_rotation(const NodalVectors& rotation, State& state) {
  m_rotations.set(rotation);
  state.rotation = rotation;
  m_rotation_synced = true;
}

void CentralDifference::begin_step(int step, State& state, RigidBodies& rigid) {
  const NodalVectors displacement = state.position - state.reference;
  sync_rotation(state);
  m_boundary.begin_step(m_model, step, displacement, state.velocity, state.rotation,
                        state.angular_velocity);
  state.reaction.setZero();
  if (m_shells) state.reaction_moment.setZero();
  // Reference nodes of rigid bodies drive their body; members cannot be prescribed.
  std::vector<PrescribedDof> active = m_boundary.prescribed();
  m_dropped_members = rigid.empty() ? 0 : rigid.begin_step(active);
  select_prescribed(active, state);
  m_loads.begin_step(m_model, step, m_boundary, state.reference, state.mass, m_prescribed);
  m_first_update = true;
  if (m_previous_force.rows() == 0 && (!m_prescribed.empty() || m_loads.has_free_loads()))
    m_previous_force = NodalVectors::Zero(m_model.node_count(), 3);
  if (m_shells && m_previous_moment.rows() == 0 && !m_prescribed.empty())
    m_previous_moment = NodalVectors::Zero(m_model.node_count(), 3);
}

void CentralDifference::select_prescribed(const std::vector<PrescribedDof>& active,
                                          const State& state) {
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
}

void CentralDifference::report_step(int step, OutputSink& sink) const {
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

void CentralDifference::apply_loads(const State&, Real step_time, Real total_time) {
  m_loads.apply(m_model, m_boundary, step_time, total_time);
}

void CentralDifference::advance_positions(State& state, ElementSet& elements, Real dt) {
  ScopedTimer timer(m_timers, Phase::Integration);
  const Index n = m_model.node_count();
  const Index n_chunks = (n + NODE_CHUNK - 1) / NODE_CHUNK;
  // One pass: positions, the rotations of shell nodes, and the element forces cleared for the
  // next element pass.
  NodalVectors& x = state.position;
  const NodalVectors& v = state.velocity_half;
  NodalVectors& f = elements.force_internal();
  NodalVectors& m = elements.moment_internal();
#pragma omp parallel for schedule(static) if (n_chunks > 1)
  for (Index chunk = 0; chunk < n_chunks; ++chunk) {
    const Index first = chunk * NODE_CHUNK, count = std::min(n, first + NODE_CHUNK) - first;
    for (int c = 0; c < 3; ++c) {
      x.col(c).segment(first, count) += dt * v.col(c).segment(first, count);
      f.col(c).segment(first, count).setZero();
    }
    if (m_shells) {
      m_rotations.advance_range(state.angular_velocity_half, dt, first, first + count);
      for (int c = 0; c < 3; ++c) m.col(c).segment(first, count).setZero();
    }
  }
  if (m_shells) m_rotation_synced = false;
}

void CentralDifference::sync_rotation(State& state) {
  if (!m_shells || m_rotation_synced) return;
  m_rotations.rotation_vectors(state.rotation);
  m_rotation_synced = true;
}

namespace {

/// What update_range sums over its nodes.
struct RangeSums {
  KineticSums kinetic;  ///< of v_before and v_{n+1/2} (kinetic_sums.hpp)
  Real speed = 0.0;     ///< largest |v_{n+1/2}| of the range (NaN shows in `kinetic` instead)
};

/// The free central-difference update of nodes [first, last) of one field component block;
/// returns its kinetic sums and largest speed. Accelerations are stored only where the field
/// keeps them.
template <bool STORE_ACCELERATION, class Field>
RangeSums update_range(const Field& d, Index off, Index first, Index last, Real dt_avg, Real w_new,
                       Real w_before) {
  Real* v = d.velocity_half + off;
  Real* vw = d.velocity + off;
  Real* a = STORE_ACCELERATION ? d.acceleration + off : nullptr;
  const Real* fi = d.force_internal + off;
  const Real* fe = d.force_external + off;
  const Real scale = d.external_scale;
  Real centred = 0.0, spread = 0.0, speed = 0.0;
#pragma omp simd reduction(+ : centred, spread) reduction(max : speed)
  for (Index i = first; i < last; ++i) {
    const Real acc = (scale * fe[i] - fi[i]) * d.inverse_mass[i];
    const Real v_new = v[i] + dt_avg * acc;
    const Real v_whole = v[i] + w_new * (v_new - v[i]);
    const Real v_before = v[i] + w_before * (v_new - v[i]);
    const Real sum = v_before + v_new, difference = v_new - v_before;
    centred += d.mass[i] * sum * sum;
    spread += d.mass[i] * difference * difference;
    speed = std::max(speed, std::abs(v_new));
    if constexpr (STORE_ACCELERATION) a[i] = acc;
    v[i] = v_new;
    vw[i] = v_whole;
  }
  return {{centred, spread}, speed};
}

}  // namespace

void CentralDifference::update_chunk(State& state, const Field& translation, const Field& rotation,
                                     const Increment& inc, Index chunk) {
  const Index n = m_model.node_count();
  const Index first = chunk * NODE_CHUNK, last = std::min(n, first + NODE_CHUNK);
  if (m_loads.pending())
    m_loads.evaluate(first, last, state.position, translation.velocity_half, inc.dt_prev,
                     m_previous_force);
  KineticSums ke;
  Real speed = 0.0;
  for (int c = 0; c < 3; ++c) {
    const RangeSums sums = translation.acceleration
                               ? update_range<true>(translation, c * n, first, last, inc.dt_avg,
                                                    inc.w_new, inc.w_before)
                               : update_range<false>(translation, c * n, first, last, inc.dt_avg,
                                                     inc.w_new, inc.w_before);
    ke += sums.kinetic;
    speed = std::max(speed, sums.speed);
  }
  m_chunk_sums[chunk] = ke;
  m_chunk_speed[chunk] = speed;
  if (!m_shells) return;
  ke = KineticSums{};
  for (int c = 0; c < 3; ++c)
    ke += update_range<false>(rotation, c * n, first, last, inc.dt_avg, inc.w_new, inc.w_before)
              .kinetic;
  m_chunk_sums[(n + NODE_CHUNK - 1) / NODE_CHUNK + chunk] = ke;
}

void CentralDifference::update_nodes(State& state, ElementSet& elements, RigidBodies& rigid,
                                     Real dt_prev, Real dt_next, Real t_next_half,
                                     Real t_next_end) {
  ScopedTimer timer(m_timers, Phase::Integration);
  const Index n = m_model.node_count();
  Increment inc;
  inc.dt_prev = dt_prev;
  inc.dt_next = dt_next;
  inc.dt_avg = 0.5 * (dt_prev + dt_next);
  // At t = 0 the whole-step velocity is the initial velocity itself.
  inc.w_new = dt_prev > 0.0 ? 0.5 : 0.0;
  // ALLKE pairs v_{n+1/2} = v(t_n + dt_next/2) with the velocity at the mirror time
  // t_n - dt_next/2 under the acceleration at t_n: v_{n-1/2} + (dt_prev - dt_next)/2 a_n, so
  // w_before = (dt_prev - dt_next) / (dt_prev + dt_next): 0 at a constant increment, -1 at
  // t = 0 (v_0 - dt_next/2 a_0 = 2 v_0 - v_{1/2}). README, "What ALLKE measures".
  inc.w_before = dt_prev + dt_next > 0.0 ? (dt_prev - dt_next) / (dt_prev + dt_next) : 0.0;
  inc.t_next_half = t_next_half;
  inc.t_next_end = t_next_end;
  const Index n_chunks = (n + NODE_CHUNK - 1) / NODE_CHUNK;
  // No loads in the model: the external force array does not exist and is not read.
  NodalVectors* force_external = m_loads.force();
  const bool loaded = force_external != nullptr;
  const Field translation{state.velocity_half.data(),
                          state.velocity.data(),
                          state.acceleration.data(),
                          elements.force_internal().data(),
                          loaded ? force_external->data() : elements.force_internal().data(),
                          loaded ? 1.0 : 0.0,
                          elements.inverse_mass().data(),
                          state.mass.data()};
  // Rotations carry no external moments.
  Field rotation{};
  if (m_shells)
    rotation = {state.angular_velocity_half.data(), state.angular_velocity.data(),     nullptr,
                elements.moment_internal().data(),  elements.moment_internal().data(), 0.0,
                elements.inverse_inertia().data(),  state.rotary_inertia.data()};

  // Prescribed and loaded DOFs keep their velocity at n-1/2 for the work and reaction terms.
  for (std::size_t k = 0; k < m_prescribed.size(); ++k) {
    const PrescribedDof& d = m_prescribed[k];
    const Field& field = d.component < 3 ? translation : rotation;
    m_v_old_prescribed[k] = field.velocity_half[(d.component % 3) * n + d.node];
  }

  // The fused pass over the nodes: loads, their work, the free updates of translations and
  // rotations. The kinetic energy is summed per chunk, then over the chunks in chunk order
  // (translations first): independent of the thread count.
  // Ties: the slaves' loads first (in their own pass), then every slave force to the master
  // corners, so that the fused pass updates the masters with them (solver/ties.hpp).
  const bool tied = m_ties != nullptr && m_ties->active();
  if (tied) {
    if (m_loads.pending()) {
#pragma omp parallel for schedule(static) if (n_chunks > 1)
      for (Index chunk = 0; chunk < n_chunks; ++chunk)
        m_loads.evaluate(chunk * NODE_CHUNK, std::min(n, (chunk + 1) * NODE_CHUNK), state.position,
                         translation.velocity_half, inc.dt_prev, m_previous_force);
      m_loads.set_evaluated();
    }
    m_ties->gather(elements.force_internal(), force_external,
                   m_shells ? &elements.moment_internal() : nullptr);
  }
#pragma omp parallel for schedule(static) if (n_chunks > 1)
  for (Index chunk = 0; chunk < n_chunks; ++chunk)
    update_chunk(state, translation, rotation, inc, chunk);
  KineticSums ke;
  m_largest_speed = 0.0;
  for (Index chunk = 0; chunk < n_chunks; ++chunk) {
    ke += m_chunk_sums[chunk];
    m_largest_speed = std::max(m_largest_speed, m_chunk_speed[chunk]);
  }
  if (m_shells) {
    KineticSums ke_rotation;
    for (Index chunk = 0; chunk < n_chunks; ++chunk) ke_rotation += m_chunk_sums[n_chunks + chunk];
    ke += ke_rotation;
  }
  Real work = 0.0;
  RigidJumps jumps;
  if (!rigid.empty()) {
    JumpTest jump_test;
    if (m_first_update)
      jump_test = [&](const PrescribedDof& d, Real v_old, Real v_new) {
        return is_jump(d, state, inc, v_old, v_new);
      };
    ke += rigid.update(
        m_model, m_boundary, state, elements.force_internal(), force_external, dt_prev, dt_next,
        inc.w_new, inc.w_before,
        {state.step_time + 0.5 * dt_next, t_next_half, state.step_time + dt_next, t_next_end},
        jump_test, work, jumps);
  }
  // Jumps of the prescribed motion: found before the update, their work corrected after it
  // (the update itself stays as it is for every other DOF).
  if (m_jump_work_pending != 0.0) {
    work += m_jump_work_pending;  // the second half of the impulses one update ago
    m_jump_work_pending = 0.0;
  }
  if (jumps.dofs > 0) {  // rigid bodies' jumps: booked like those of free DOFs
    m_jump_work_pending += jumps.pending;
    m_jump.dofs += jumps.dofs;
    m_jump.energy += jumps.energy;
    m_jump.largest = std::max(m_jump.largest, jumps.largest);
  }
  if (m_first_update) find_jumps(state, inc);
  ke += update_prescribed(state, translation, rotation, inc, work);
  // The DOFs that jumped pair the states before and after the jump, not the mirror-time
  // velocity: their spread is no Δt(n+½)² a² and takes no part in the shift below.
  Real jump_spread = jumps.spread;
  if (!m_jumps.empty()) ke += count_jump_work(translation, rotation, inc, work, jump_spread);
  if (tied) m_ties->follow(state);  // slaves after their masters (prescribed and rigid too)
  m_loads.add_work(work);
  // ALLKE ≥ 0 (R5): the sums are of squares; the corrections for prescribed DOFs and rigid
  // bodies take back what the free update counted, which round-off may leave a hair below 0.
  state.energies.kinetic = std::max(0.0, 0.125 * ke.centred);
  // A change of the increment changes the energy central differences conserve: for DOFs with
  // v⁺ − v⁻ = Δt(n+½) a(n) the next increment finds ½ v⁻·M·v⁺ off by
  // ⅛(Δt(n−½)² − Δt(n+½)²) a·M·a (README). ALLKD books that shift, so that the step's short
  // last increment, or a new step's first one, does not show as a drift of ETOTAL.
  if (dt_prev > 0.0 && dt_next > 0.0) {
    const Real ratio = dt_prev / dt_next;
    m_increment_shift += 0.125 * (ratio * ratio - 1.0) * (ke.spread - jump_spread);
  }
  state.energies.kinetic_defect = -0.125 * ke.spread - m_increment_shift;
  state.energies.external_work += work;
  m_first_update = false;
}

KineticSums CentralDifference::update_prescribed(State& state, const Field& translation,
                                                 const Field& rotation, const Increment& inc,
                                                 Real& work) {
  // Prescribed DOFs: velocity from the BC, reaction = m a - (f_ext - f_int).
  // External work by the trapezoidal rule over [t_{n-1}, t_n]: exact for constant forces.
  const Index n = m_model.node_count();
  KineticSums counted, kinetic;
  const Real step_next_half = state.step_time + 0.5 * inc.dt_next;
  const Real step_next_end = state.step_time + inc.dt_next;
  for (std::size_t k = 0; k < m_prescribed.size(); ++k) {
    const PrescribedDof& d = m_prescribed[k];
    const bool turn = d.component >= 3;
    const int c = d.component % 3;
    const Field& field = turn ? rotation : translation;
    const Index i = d.node, at = c * n + i;
    const Real v_old = m_v_old_prescribed[k];
    Real v_new = 0.0;
    if (d.type == BoundaryType::Velocity) {
      v_new = m_boundary.target(m_model, d, step_next_half, inc.t_next_half);
    } else {
      // Translations correct against the actual position; rotations against the prescribed
      // value carried along (components of the rotation vector, exact about a fixed axis).
      Real& current = m_prescribed_value[k];
      current = turn ? current + inc.dt_prev * v_old : state.displacement(i, c);
      if (inc.dt_next > 0.0)
        v_new =
            (m_boundary.target(m_model, d, step_next_end, inc.t_next_end) - current) / inc.dt_next;
    }
    const Real m = field.mass[i];
    // ALLKE: what the free update counted for the DOF, replaced by the prescribed motion's.
    const Real v_free = field.velocity_half[at];
    counted.add(m, v_old + inc.w_before * (v_free - v_old), v_free);
    kinetic.add(m, v_old + inc.w_before * (v_new - v_old), v_new);
    const Real v_whole = v_old + inc.w_new * (v_new - v_old);
    const Real acc = inc.dt_avg > 0.0 ? (v_new - v_old) / inc.dt_avg : 0.0;
    const Real f_ext = field.external_scale * field.force_external[at];
    const Real r = m * acc - (f_ext - field.force_internal[at]);
    (turn ? state.reaction_moment : state.reaction)(i, c) = r;
    if (field.acceleration) field.acceleration[at] = acc;
    field.velocity_half[at] = v_new;
    field.velocity[at] = v_whole;
    const Real f_now = f_ext + r;
    Real& f_before = (turn ? m_previous_moment : m_previous_force)(i, c);
    work += 0.5 * (f_before + f_now) * inc.dt_prev * v_old;
    f_before = f_now;
  }
  kinetic -= counted;
  return kinetic;
}

bool CentralDifference::is_jump(const PrescribedDof& d, const State& state, const Increment& inc,
                                Real v_old, Real v_new) const {
  // The BC's own velocity at t_n: for a smooth motion sampled at t_{n-1/2} and t_{n+1/2} it
  // lies about half-way between v_old and v_new; after a jump at the start of the step it is
  // already v_new (up to the change over half an increment).
  Real v_at = 0.0, v_later = v_new;
  if (d.type == BoundaryType::Velocity) {
    v_at = m_boundary.target(m_model, d, state.step_time, state.time);
  } else {
    // The rate of the prescribed displacement just after t_n (a forward difference over a
    // small fraction of the next increment), and its mean rate over the next increment. The
    // latter, not v_new: a BC that takes over at a step boundary finds the node half an
    // increment behind and v_new catches up, which would hide the jump in the share.
    const Real h = JUMP_PROBE * inc.dt_next;
    if (!(h > 0.0)) return false;
    const Real u_now = m_boundary.target(m_model, d, state.step_time, state.time);
    v_at = (m_boundary.target(m_model, d, state.step_time + h, state.time + h) - u_now) / h;
    v_later =
        (m_boundary.target(m_model, d, state.step_time + inc.dt_next, state.time + inc.dt_next) -
         u_now) /
        inc.dt_next;
  }
  return std::abs(v_at - v_old) > JUMP_SHARE * std::abs(v_later - v_old);
}

void CentralDifference::find_jumps(const State& state, const Increment& inc) {
  m_jumps.clear();
  m_jump.time = state.time;
  const Real step_next_half = state.step_time + 0.5 * inc.dt_next;
  const Real step_next_end = state.step_time + inc.dt_next;
  for (std::size_t k = 0; k < m_prescribed.size(); ++k) {
    const PrescribedDof& d = m_prescribed[k];
    const bool turn = d.component >= 3;
    const int c = d.component % 3;
    const Real v_old = m_v_old_prescribed[k];
    // v_{n+1/2} as update_prescribed will set it (for the classification only).
    Real v_new = 0.0;
    if (d.type == BoundaryType::Velocity) {
      v_new = m_boundary.target(m_model, d, step_next_half, inc.t_next_half);
    } else if (inc.dt_next > 0.0) {
      const Real current =
          turn ? m_prescribed_value[k] + inc.dt_prev * v_old : state.displacement(d.node, c);
      v_new =
          (m_boundary.target(m_model, d, step_next_end, inc.t_next_end) - current) / inc.dt_next;
    }
    if (v_new == v_old || !is_jump(d, state, inc, v_old, v_new)) continue;
    m_jumps.push_back({k, (turn ? m_previous_moment : m_previous_force)(d.node, c)});
  }
}

KineticSums CentralDifference::count_jump_work(const Field& translation, const Field& rotation,
                                               const Increment& inc, Real& work,
                                               Real& jump_spread) {
  // The BC's force at a jump is the impulse J = m (v_new - v_old) plus the internal force the
  // node passes on to the elements. The impulse does J (v_old + v_new) / 2 = ½m(v_new² -
  // v_old²), counted exactly and split at the DOF's kinetic energy at t_n, so that ETOTAL
  // balances at t_n too: ALLKE pairs v_old with v_new there (½m v_old v_new; at t = 0 the
  // state before the jump, ½m v_old², instead of the product with 2 v_old - v_new that
  // update_prescribed counted), so ½m v_old (v_new - v_old) is counted now and ½m v_new
  // (v_new - v_old) with the next increment. The trapezoidal rule of update_prescribed weighed
  // J by (dt_prev v_old + dt_next v_new) / 2 over dt_avg: off by ¼ m (v_new - v_old)²
  // (dt_next - dt_prev) / dt_avg, ½mΔv² at t = 0. Its term is replaced; the internal force
  // keeps the trapezoidal rule, the impulse leaves f_before. Returns the kinetic-energy
  // correction at t = 0.
  const Index n = m_model.node_count();
  KineticSums counted, paired;
  for (const PendingJump& j : m_jumps) {
    const PrescribedDof& d = m_prescribed[j.dof];
    const bool turn = d.component >= 3;
    const int c = d.component % 3;
    const Field& field = turn ? rotation : translation;
    const Index at = c * n + d.node;
    const Real m = field.mass[d.node];
    const Real v_old = m_v_old_prescribed[j.dof];
    const Real v_new = field.velocity_half[at];
    counted.add(m, v_old + inc.w_before * (v_new - v_old), v_new);
    const Real after = inc.dt_prev > 0.0 ? v_new : v_old;
    paired.add(m, v_old, after);
    jump_spread += m * (after - v_old) * (after - v_old);
    const Real kinetic = 0.5 * m * v_old * after;
    Real& f_before = (turn ? m_previous_moment : m_previous_force)(d.node, c);
    const Real f_now = f_before;  // what update_prescribed stored: f_ext + reaction
    const Real f_smooth = field.force_internal[at];
    const Real trapezoid = 0.5 * (j.f_before + f_now) * inc.dt_prev * v_old;
    const Real smooth = 0.5 * (j.f_before + f_smooth) * inc.dt_prev * v_old;
    const Real now = kinetic - 0.5 * m * v_old * v_old;
    const Real later = 0.5 * m * v_new * v_new - kinetic;
    work += (smooth + now) - trapezoid;
    m_jump_work_pending += later;
    f_before = f_smooth;
    ++m_jump.dofs;
    m_jump.energy += now + later;
    m_jump.largest = std::max(m_jump.largest, std::abs(v_new - v_old));
  }
  m_jumps.clear();
  paired -= counted;
  return paired;
}

void CentralDifference::report_jump(int step, OutputSink& sink) {
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
