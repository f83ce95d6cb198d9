#include "contact/contact_engine.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numeric>

#include "contact/closest_point.hpp"

namespace xpl::contact {

namespace {

/// Default margin: MARGIN_FRACTION × the mean square root of the face areas.
Real mean_face_size(const std::vector<ContactFace>& faces, const NodalVectors& position) {
  if (faces.empty()) return 1.0;
  Real sum = 0.0;
  for (const ContactFace& f : faces) {
    Vec3 corner[4];
    face_corners(f, position, {}, corner);
    sum += std::sqrt(quad_area(corner));
  }
  return sum / static_cast<Real>(faces.size());
}

Real max_thickness(std::span<const Real> thickness) {
  Real t = 0.0;
  for (Real v : thickness)
    if (std::isfinite(v)) t = std::max(t, v);
  return t;
}

/// The broad phase with its search margin (m) and rebuild motion (m): the motion leaves room
/// for half a shell thickness around every slave node.
BroadPhase make_broad_phase(const ContactOptions& options, const std::vector<ContactFace>& faces,
                            const NodalVectors& position, std::span<const Real> node_thickness) {
  Real base =
      options.margin > 0.0 ? options.margin : MARGIN_FRACTION * mean_face_size(faces, position);
  if (!(base > 0.0)) base = FALLBACK_MARGIN;
  const Real half_t = 0.5 * max_thickness(node_thickness);
  return BroadPhase(base + half_t, 0.5 * base);
}

}  // namespace

ContactEngine::ContactEngine(ContactDomain domain, std::vector<InteractionLaw> laws,
                             ContactOptions options, const NodalVectors& position,
                             std::span<const Real> node_thickness)
    : m_domain(std::move(domain)),
      m_laws(std::move(laws)),
      m_options(options),
      m_broad(make_broad_phase(options, m_domain.faces(), position, node_thickness)),
      m_sleep(m_domain.slaves().size()) {
  const auto n = static_cast<std::size_t>(m_domain.slaves().size());
  m_constraints.assign(n, ContactConstraint{});
  m_touch.assign(n, SlaveTouch{});
  m_lost_depth.assign(n, 0.0);
  m_passed_depth.assign(n, 0.0);
  m_behind_depth.assign(n, 0.0);
  m_second.assign(n, ContactConstraint{});
  m_second_touch.assign(n, SlaveTouch{});
  m_warm.assign(n, WarmStarts{});
  m_second_force.assign(3 * n, 0.0);
  m_second_normal_force.assign(n, 0.0);
  m_second_dissipation.assign(n, 0.0);
  m_spring.assign(2 * n, Spring{});
  m_normal_force.assign(n, 0.0);
  m_slave_force.assign(3 * n, 0.0);
  m_dissipation.assign(n, 0.0);
  m_stored.assign(n, 0.0);
  m_output_status.assign(n, OutputStatus::Open);
  m_event_face.assign(n, NO_INDEX);
  m_all_slots.resize(n);
  std::iota(m_all_slots.begin(), m_all_slots.end(), Index{0});
  m_assembly = ForceAssembly(m_domain.slaves().size(), m_domain.pair_count());
  for (const InteractionLaw& law : m_laws)
    m_user_stiffness = m_user_stiffness || law.pressure_slope > 0.0;
  if (m_user_stiffness) {
    m_user_k.assign(2 * n, 0.0);
    m_user_law.assign(2 * n, NO_INDEX);
  }
}

ContactTotals ContactEngine::update(const NodalVectors& position, const NodalVectors& velocity_half,
                                    Real dt, Real dt_penalty, std::span<const Real> node_thickness,
                                    std::span<const Real> mass, std::span<const Real> inverse_mass,
                                    NodalVectors& force_internal, PhaseTimers& timers) {
  ContactTotals totals;
  SlaveNodes& slaves = m_domain.slaves();
  const std::vector<ContactFace>& faces = m_domain.faces();
  const Index n_slave = slaves.size();
  {
    ScopedTimer timer(timers, Phase::ContactSearch);
    m_shared_pass = m_sharing != nullptr;
    // The sleeping slots' path (slot_sleep.hpp): this update's step motion, measured with the
    // rebuild motion (< 0: not measured there) or decided by the processes together
    // (decide_rebuild()).
    Real step_sq = -1.0;
    totals.rebuilt = refresh_broad_phase(position, node_thickness, &step_sq) || m_built_ahead;
    m_built_ahead = false;
    const bool decided = m_sleep.step_decision >= 0.0 && m_shared_pass;
    m_sleep.advance(totals.rebuilt, totals.rebuilt   ? 0.0
                                    : decided        ? m_sleep.step_decision
                                    : step_sq >= 0.0 ? step_sq
                                                     : m_broad.step_motion_sq(position));
    m_sleep.step_decision = -1.0;
    build_visits();
    // Only the search of a slot with candidates reads its area and normal, and so does a
    // user-stiffness law's spring (same slots); a LINEAR law's increment estimate reads all.
    if (m_user_stiffness)
      slaves.update_areas(faces, position);
    else
      slaves.update_areas(faces, position, m_active_slot, m_active_face);
    search(position, node_thickness);
    if (m_sleep.mode == SleepMode::Check)
      for (const Index s : m_live)
        if (m_sleep.asleep[s] != 0) put_to_sleep(s, true);
    // The face a released or passed node was pressed on, before the springs move on.
    for (const Index s : m_live)
      m_event_face[s] = m_lost_depth[s] > 0.0 || m_passed_depth[s] > 0.0
                            ? m_constraints[s].master_face
                            : NO_INDEX;
  }

  ScopedTimer timer(timers, Phase::ContactForce);
  prepare_springs(position, velocity_half, dt, dt_penalty, mass, inverse_mass);
  if (m_shared_pass) share_springs();
  count_events(totals);
  cap_default_springs(dt_penalty, mass, inverse_mass);
  spring_forces(dt, dt_penalty);
  if (m_shared_pass) share_forces(velocity_half);

  // Assembly, sums and work, in slot order (independent of the thread count).
  const std::span<const Index> visited = visits();
  m_assembly.assemble(
      slaves, faces, visited,
      {m_touch, m_slave_force, m_normal_force, m_constraints, m_dissipation},
      {m_second_touch, m_second_force, m_second_normal_force, m_second, m_second_dissipation},
      velocity_half, m_work_velocity, dt, force_internal, totals);
  for (const Index s : visited) totals.stored_energy += m_stored[s];
  if (m_ramping > 0) {
    // In slot order; a ramp that has reached zero ends (its offset stays permanent only
    // where a base is left).
    for (Index s = 0; s < n_slave; ++s) {
      Interference& ramp = m_interference[s];
      if (!(ramp.amount > 0.0)) continue;
      totals.interference_work += m_ramp_work[s];
      m_ramp_work[s] = 0.0;
      if (m_step_time < ramp.duration) continue;
      ramp.amount = 0.0;
      m_constraints[s].offset = ramp.base;
      m_constraints[s].offset_permanent = ramp.base != 0.0;
      --m_ramping;
    }
  }
  // A face corner without candidates of its own that carries force: its area and normal
  // (read by the contact output) as the full pass would have made them.
  // (Every other slot's assembled force is zero.)
  if (!m_user_stiffness) {
    const std::vector<Index>& forced = m_assembly.forced_slots();
    bool extra = false;
    for (std::size_t k = 0; k < forced.size() && !extra; ++k) {
      const Vec3 f = m_assembly.nodal_force(forced[k]);
      extra = !m_active_slot[forced[k]] && f.dot(f) != 0.0;
    }
    if (extra) {
      m_extra_slot.assign(static_cast<std::size_t>(n_slave), 0);
      m_extra_face.assign(faces.size(), 0);
      for (const Index s : forced) {
        const Vec3 f = m_assembly.nodal_force(s);
        if (m_active_slot[s] || f.dot(f) == 0.0) continue;
        m_extra_slot[s] = 1;
        for (Index g : slaves.faces_of(s)) m_extra_face[g] = 1;
      }
      slaves.update_areas(faces, position, m_extra_slot, m_extra_face);
    }
  }
  m_updated = true;
  if (m_user_stiffness) {
    m_penalty_sum.reset(static_cast<Index>(mass.size()));
    for (const Index s : visited)
      for (int side = 0; side < 2; ++side) {
        const SlaveTouch& t = side == 0 ? m_touch[s] : m_second_touch[s];
        const Index j = 2 * s + side;
        if (m_user_k[j] > 0.0)
          m_penalty_sum.add_spring(slaves.nodes()[s], faces[t.face].nodes, t.shape, m_user_k[j],
                                   m_user_law[j], inverse_mass);
      }
    m_penalty_limit = m_penalty_sum.largest(inverse_mass);
  }
  keep_held();
  m_shared_pass = false;
  return totals;
}

void ContactEngine::build_visits() {
  m_live.clear();
  if (m_visit_all) {
    m_sleep.forget();
    for (const Index s : m_all_slots)
      if (owned(s)) m_live.push_back(s);
  } else {
    // Sleeping slots (slot_sleep.hpp) are left out once quiet; the check mode searches them.
    m_sleep.awake_listed.clear();
    for (const Index s : m_listed_slots) {
      m_sleep.asleep[s] = m_sleep.sleeps(s) ? 1 : 0;
      if (m_sleep.asleep[s] == 0) m_sleep.awake_listed.push_back(s);
    }
    const auto n_asleep =
        static_cast<long long>(m_listed_slots.size() - m_sleep.awake_listed.size());
    m_sleep.counts.searched += static_cast<long long>(m_sleep.awake_listed.size());
    m_sleep.counts.asleep += n_asleep;
    const bool check = m_sleep.mode == SleepMode::Check;
    if (check) m_sleep.counts.checked += n_asleep;
    const std::vector<Index>& listed = check ? m_listed_slots : m_sleep.awake_listed;
    std::set_union(listed.begin(), listed.end(), m_held.begin(), m_held.end(),
                   std::back_inserter(m_live));
    // A whole build (probe()) listed every process's slots.
    if (m_shared_pass)
      m_live.erase(std::remove_if(m_live.begin(), m_live.end(), [&](Index s) { return !owned(s); }),
                   m_live.end());
  }
  // The slots search() looks at: a sleeping one still held is put to sleep at once.
  m_sleep.searched.clear();
  for (const Index s : m_live) {
    if (m_sleep.asleep[s] != 0 && m_sleep.mode != SleepMode::Check)
      put_to_sleep(s, false);
    else
      m_sleep.searched.push_back(s);
  }
}

void ContactEngine::keep_held() {
  m_held.clear();
  const bool ramps = !m_interference.empty();
  for (const Index s : m_live)
    if (m_touch[s].face != NO_INDEX || m_second_touch[s].face != NO_INDEX ||
        m_lost_depth[s] != 0.0 || m_passed_depth[s] != 0.0 || m_behind_depth[s] != 0.0 ||
        m_warm[s].count > 0 || (ramps && m_interference[s].amount > 0.0))
      m_held.push_back(s);
  m_visit_all = false;
}

void ContactEngine::count_events(ContactTotals& totals) const {
  const SlaveNodes& slaves = m_domain.slaves();
  const std::vector<ContactFace>& faces = m_domain.faces();
  const auto deeper = [](Real depth, Index& count, Real& deepest) {
    if (!(depth > 0.0)) return false;
    ++count;
    if (depth <= deepest) return false;
    deepest = depth;
    return true;
  };
  for (const Index s : visits()) {
    if (deeper(m_lost_depth[s], totals.lost, totals.lost_depth)) {
      totals.lost_node = slaves.nodes()[s];
      totals.lost_element = faces[m_event_face[s]].element;
      totals.lost_element_depth = 2.0 * m_domain.face_depth(m_event_face[s]);
    }
    if (deeper(m_passed_depth[s], totals.passed, totals.passed_depth)) {
      totals.passed_node = slaves.nodes()[s];
      totals.passed_element = faces[m_event_face[s]].element;
    }
    if (deeper(m_behind_depth[s], totals.behind, totals.behind_depth)) {
      totals.behind_node = slaves.nodes()[s];
      const Index f = m_touch[s].face;
      totals.behind_element = faces[f].element;
      totals.behind_element_depth = faces[f].shell ? 0.0 : 2.0 * m_domain.face_depth(f);
    }
  }
}

void ContactEngine::set_interference(Index s, Real amount, Real base, Real duration) {
  const auto n = static_cast<std::size_t>(m_domain.slaves().size());
  if (m_interference.empty()) {
    m_interference.assign(n, Interference{});
    m_ramp_before.assign(n, 0.0);
    m_ramp_work.assign(n, 0.0);
  }
  m_visit_all = true;
  Interference& ramp = m_interference[s];
  if (!(ramp.amount > 0.0) && amount > 0.0) ++m_ramping;
  if (ramp.amount > 0.0 && !(amount > 0.0)) --m_ramping;
  ramp = {amount, base, duration};
  m_constraints[s].offset = base + amount;
  m_constraints[s].offset_permanent = amount > 0.0 || base != 0.0;
}

void ContactEngine::set_rigid_bodies(std::vector<Index> node_body,
                                     std::vector<std::array<Real, 3>> body_translation_mass) {
  m_node_body = std::move(node_body);
  m_body_mass = std::move(body_translation_mass);
  m_body_row.assign(m_body_mass.size(), {0.0, 0.0, 0.0});
  m_body_factor.assign(m_body_mass.size(), 1.0);
}

}  // namespace xpl::contact
