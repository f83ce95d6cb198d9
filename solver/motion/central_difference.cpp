#include "solver/motion/central_difference.hpp"

#include <algorithm>
#include <cmath>

namespace xpl {

CentralDifference::CentralDifference(const Model& model, PhaseTimers& timers, bool shells)
    : m_model(model), m_timers(timers), m_shells(shells), m_motion(model, m_boundary, shells) {
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
  m_motion.begin_step(rigid, state);
  m_loads.begin_step(m_model, step, m_boundary, state.reference, state.mass, m_motion.prescribed());
  if (m_previous_force.rows() == 0 && (!m_motion.prescribed().empty() || m_loads.has_free_loads()))
    m_previous_force = NodalVectors::Zero(m_model.node_count(), 3);
}

void CentralDifference::apply_loads(const State&, Real step_time, Real total_time) {
  m_loads.apply(m_model, m_boundary, step_time, total_time);
}

void CentralDifference::set_spans(const std::vector<unsigned char>& integrated) {
  const Index n = m_model.node_count();
  const Index n_chunks = (n + NODE_CHUNK - 1) / NODE_CHUNK;
  m_span_start.assign(1, 0);
  m_spans.clear();
  for (Index chunk = 0; chunk < n_chunks; ++chunk) {
    const Index last = std::min(n, (chunk + 1) * NODE_CHUNK);
    for (Index i = chunk * NODE_CHUNK; i < last;) {
      if (integrated[i] == 0) {
        ++i;
        continue;
      }
      const Index first = i;
      while (i < last && integrated[i] != 0) ++i;
      m_spans.insert(m_spans.end(), {first, i});
    }
    m_span_start.push_back(static_cast<Index>(m_spans.size() / 2));
  }
}

Index CentralDifference::integrated_count() const {
  if (m_span_start.empty()) return m_model.node_count();
  Index count = 0;
  for (std::size_t k = 0; k + 1 < m_spans.size(); k += 2) count += m_spans[k + 1] - m_spans[k];
  return count;
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
    // Every force cleared (a rank's contact pass adds to nodes it does not move); only the
    // nodes this rank moves advance (the others stay at rest here, for_each_span()).
    const Index first = chunk * NODE_CHUNK, count = std::min(n, first + NODE_CHUNK) - first;
    for (int c = 0; c < 3; ++c) f.col(c).segment(first, count).setZero();
    if (m_shells)
      for (int c = 0; c < 3; ++c) m.col(c).segment(first, count).setZero();
    for_each_span(chunk, [&](Index a, Index b) {
      for (int c = 0; c < 3; ++c) x.col(c).segment(a, b - a) += dt * v.col(c).segment(a, b - a);
      if (m_shells) m_rotations.advance_range(state.angular_velocity_half, dt, a, b);
    });
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
template <bool STORE_ACCELERATION>
RangeSums update_range(const NodalField& d, Index off, Index first, Index last, Real dt_avg,
                       Real w_new, Real w_before) {
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

void CentralDifference::update_chunk(State& state, const NodalField& translation,
                                     const NodalField& rotation, const NodalIncrement& inc,
                                     Index chunk) {
  // A chunk this rank counts is one span, so that its sums are the one-rank sums; the sums
  // of the others are replaced by their counting rank's (set_distribution()).
  const Index n = m_model.node_count();
  KineticSums ke, ke_rotation;
  Real speed = 0.0;
  for_each_span(chunk, [&](Index first, Index last) {
    if (m_loads.pending())
      m_loads.evaluate(first, last, state.position, translation.velocity_half, inc.dt_prev,
                       m_previous_force);
    for (int c = 0; c < 3; ++c) {
      const RangeSums sums = translation.acceleration
                                 ? update_range<true>(translation, c * n, first, last, inc.dt_avg,
                                                      inc.w_new, inc.w_before)
                                 : update_range<false>(translation, c * n, first, last, inc.dt_avg,
                                                       inc.w_new, inc.w_before);
      ke += sums.kinetic;
      speed = std::max(speed, sums.speed);
    }
    if (!m_shells) return;
    for (int c = 0; c < 3; ++c)
      ke_rotation +=
          update_range<false>(rotation, c * n, first, last, inc.dt_avg, inc.w_new, inc.w_before)
              .kinetic;
  });
  m_chunk_sums[chunk] = ke;
  m_chunk_speed[chunk] = speed;
  if (m_shells) m_chunk_sums[(n + NODE_CHUNK - 1) / NODE_CHUNK + chunk] = ke_rotation;
}

KineticSums CentralDifference::sum_chunks(Index n_chunks) {
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
  return ke;
}

void CentralDifference::update_nodes(State& state, ElementSet& elements, RigidBodies& rigid,
                                     Real dt_prev, Real dt_next, Real t_next_half,
                                     Real t_next_end) {
  ScopedTimer timer(m_timers, Phase::Integration);
  const Index n = m_model.node_count();
  const NodalIncrement inc =
      NodalIncrement::make(dt_prev, dt_next, state.step_time, state.time, t_next_half, t_next_end);
  const Index n_chunks = (n + NODE_CHUNK - 1) / NODE_CHUNK;
  // No loads in the model: the external force array does not exist and is not read.
  NodalVectors* force_external = m_loads.force();
  const NodalField translation{
      state.velocity_half.data(),
      state.velocity.data(),
      state.acceleration.data(),
      elements.force_internal().data(),
      force_external ? force_external->data() : elements.force_internal().data(),
      force_external ? 1.0 : 0.0,
      elements.inverse_mass().data(),
      state.mass.data()};
  // Rotations carry no external moments.
  NodalField rotation{};
  if (m_shells)
    rotation = {state.angular_velocity_half.data(), state.angular_velocity.data(),     nullptr,
                elements.moment_internal().data(),  elements.moment_internal().data(), 0.0,
                elements.inverse_inertia().data(),  state.rotary_inertia.data()};

  if (m_share_loads) m_loads.share_positions(m_share_loads, state.position);
  // Prescribed and loaded DOFs keep their velocity at n-1/2 for the work and reaction terms.
  m_motion.keep_old_velocities(translation, rotation, n);

  // The fused pass over the nodes: loads, their work, the free updates of translations and
  // rotations. The kinetic energy is summed per chunk, then over the chunks in chunk order
  // (translations first): independent of the thread count.
  // Ties: the slaves' loads first (in their own pass), then every slave force to the master
  // corners, so that the fused pass updates the masters with them (solver/motion/ties.hpp).
  const bool tied = m_ties != nullptr && m_ties->active();
  if (tied) {
    if (m_loads.pending()) {
#pragma omp parallel for schedule(static) if (n_chunks > 1)
      for (Index chunk = 0; chunk < n_chunks; ++chunk)
        for_each_span(chunk, [&](Index first, Index last) {
          m_loads.evaluate(first, last, state.position, translation.velocity_half, inc.dt_prev,
                           m_previous_force);
        });
      m_loads.set_evaluated();
    }
    if (m_share_tie_forces) {
      std::vector<NodalVectors*> rows{&elements.force_internal()};
      if (force_external != nullptr) rows.push_back(force_external);
      if (m_shells) rows.push_back(&elements.moment_internal());
      m_share_tie_forces(rows);
    }
    m_ties->gather(elements.force_internal(), force_external,
                   m_shells ? &elements.moment_internal() : nullptr);
  }
#pragma omp parallel for schedule(static) if (n_chunks > 1)
  for (Index chunk = 0; chunk < n_chunks; ++chunk)
    update_chunk(state, translation, rotation, inc, chunk);
  NodalSums sums;
  RigidUpdate bodies;
  if (!m_share_chunks) {
    sums.kinetic = sum_chunks(n_chunks);
    if (!rigid.empty()) {
      bodies = rigid.update(m_motion, state, elements.force_internal(), force_external, inc);
      sums.kinetic += bodies.kinetic;
      sums.work = bodies.work;
    }
    m_motion.update(state, translation, rotation, inc, bodies.jumps, m_previous_force, sums);
  } else {
    // Distributed runs: the bodies and the prescribed DOFs move first (neither reads the
    // kinetic sums), so that the chunks' sums, the prescribed DOFs' rows and the stop signal
    // travel in one collective; then the sums in the one-rank order.
    // Each body moves on the rank owning it, from its nodes' forces (point to point from
    // the ranks integrating them); its rows ride with the prescribed DOFs' to every rank.
    // The rows in buffers kept between increments (584 kB on the 46³ block's fixed face).
    m_body_rows.clear();
    if (!rigid.empty()) {
      if (m_share_rigid) {
        std::vector<NodalVectors*> rows{&elements.force_internal()};
        if (force_external != nullptr) rows.push_back(force_external);
        m_share_rigid(rows);
      }
      rigid.update_owned(m_motion, state, elements.force_internal(), force_external, inc,
                         m_body_rows);
    }
    const bool same_counts = !m_motion.first_update();
    std::vector<Real>& rows = m_rows;
    m_motion.prescribe(state, translation, rotation, inc, m_previous_force, rows);
    rows.insert(rows.end(), m_body_rows.begin(), m_body_rows.end());
    m_share_chunks(m_chunk_sums, m_chunk_speed, rows, same_counts);
    if (!rigid.empty()) bodies = rigid.take_shared(rows, state, inc);
    sums.kinetic = sum_chunks(n_chunks);
    if (!rigid.empty()) {
      sums.kinetic += bodies.kinetic;
      sums.work = bodies.work;
    }
    m_motion.finish(inc, bodies.jumps, m_previous_force, rows, sums);
  }
  if (tied) {  // slaves after their masters (prescribed and rigid too)
    if (m_share_tie_motion) {
      std::vector<NodalVectors*> rows{&state.velocity_half, &state.velocity, &state.acceleration};
      if (state.angular_velocity_half.rows() > 0)
        rows.insert(rows.end(), {&state.angular_velocity_half, &state.angular_velocity});
      m_share_tie_motion(rows);
    }
    m_ties->follow(state);
  }
  if (m_share_loads) m_loads.share_work(m_share_loads);
  m_loads.add_work(sums.work);
  book_energies(state, inc, sums);
}

void CentralDifference::book_energies(State& state, const NodalIncrement& inc,
                                      const NodalSums& sums) {
  // ALLKE ≥ 0 (R5): the sums are of squares; the corrections for prescribed DOFs and rigid
  // bodies take back what the free update counted, which round-off may leave a hair below 0.
  state.energies.kinetic = std::max(0.0, 0.125 * sums.kinetic.centred);
  // A change of the increment changes the energy central differences conserve: for DOFs with
  // v⁺ − v⁻ = Δt(n+½) a(n) the next increment finds ½ v⁻·M·v⁺ off by
  // ⅛(Δt(n−½)² − Δt(n+½)²) a·M·a (docs/theory/energy.md). ALLKD books that shift, so that the
  // step's short last increment, or a new step's first one, does not show as a drift of ETOTAL.
  if (inc.dt_prev > 0.0 && inc.dt_next > 0.0) {
    const Real ratio = inc.dt_prev / inc.dt_next;
    m_increment_shift += 0.125 * (ratio * ratio - 1.0) * (sums.kinetic.spread - sums.jump_spread);
  }
  state.energies.kinetic_defect = -0.125 * sums.kinetic.spread - m_increment_shift;
  state.energies.external_work += sums.work;
}

}  // namespace xpl
