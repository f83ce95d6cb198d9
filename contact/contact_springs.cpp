// The force half of ContactEngine (contact_engine.hpp): each spring's onset offset and
// stiffness, the cap on the default springs, the normal law and friction of a spring, and the
// penalty-increment estimate.
#include <algorithm>
#include <cmath>

#include "common/parallel_error.hpp"
#include "contact/contact_engine.hpp"
#include "contact/parallel_size.hpp"

namespace xpl::contact {

void ContactEngine::prepare_springs(const NodalVectors& position, const NodalVectors& velocity_half,
                                    Real dt, Real dt_penalty, std::span<const Real> mass,
                                    std::span<const Real> inverse_mass) {
  const auto n_live = static_cast<Index>(m_live.size());
  ParallelErrors errors;
#pragma omp parallel for schedule(static) if (n_live >= PARALLEL_MIN_SLOTS)
  for (Index k = 0; k < n_live; ++k) {
    const Index s = m_live[k];  // this process's (build_visits())
    errors.guard(ParallelSite::ContactForces, s, [&] {
      ContactConstraint& c = m_constraints[s];
      ContactConstraint& c2 = m_second[s];
      const SlaveTouch& t = m_touch[s];
      const SlaveTouch& t2 = m_second_touch[s];
      // The memory of a side follows its side (file comment): each constraint continues
      // with the touch that looks the way it looked last increment.
      if ((c.master_face != NO_INDEX || c2.master_face != NO_INDEX) && !c.offset_permanent &&
          !c2.offset_permanent) {
        const auto alike = [](const SlaveTouch& now, const ContactConstraint& before) {
          return now.face != NO_INDEX && before.master_face != NO_INDEX
                     ? now.normal.dot(before.normal)
                     : -2.0;
        };
        if (alike(t, c2) + alike(t2, c) > alike(t, c) + alike(t2, c2)) std::swap(c, c2);
      }
      // Interference ramp (set_interference): the offset of this update's step time.
      if (!m_interference.empty() && m_interference[s].amount > 0.0) {
        const Interference& ramp = m_interference[s];
        const Real r = ramp.duration > 0.0 ? std::max(0.0, 1.0 - m_step_time / ramp.duration) : 0.0;
        m_ramp_before[s] = c.offset;
        c.offset = ramp.base + ramp.amount * r;
      }
      prepare_spring(s, c, t, m_spring[2 * s], position, velocity_half, dt, dt_penalty, mass,
                     inverse_mass);
      if (t2.face == NO_INDEX) {
        // No face on the other side is penetrated: that side's offset is spent (C3).
        c2.master_face = NO_INDEX;
        c2.status = ContactStatus::Inactive;
        c2.tangential_force = Vec3::Zero();
        if (!c2.offset_permanent) c2.offset = 0.0;
        c2.stiffness = 0.0;
        m_spring[2 * s + 1].k = 0.0;
        return;
      }
      // A node held with an offset at the start is held on both sides (C3, C6).
      if (!m_updated && c2.master_face == NO_INDEX && c.offset > 0.0)
        c2.offset = std::max(c2.offset, -t2.gap);
      prepare_spring(s, c2, t2, m_spring[2 * s + 1], position, velocity_half, dt, dt_penalty, mass,
                     inverse_mass);
    });
  }
  errors.rethrow_if_any();
}

void ContactEngine::spring_forces(Real dt, Real dt_penalty) {
  const auto n_live = static_cast<Index>(m_live.size());
  ParallelErrors errors;
#pragma omp parallel for schedule(static) if (n_live >= PARALLEL_MIN_SLOTS)
  for (Index k = 0; k < n_live; ++k) {
    const Index s = m_live[k];  // this process's (build_visits())
    errors.guard(ParallelSite::ContactForces, s, [&] {
      m_dissipation[s] = 0.0;
      m_second_dissipation[s] = 0.0;
      m_stored[s] = 0.0;
      OutputStatus status = OutputStatus::Open;
      if (m_user_stiffness) m_user_k[2 * s] = m_user_k[2 * s + 1] = 0.0;
      const Real fn_before = m_normal_force[s];
      const Vec3 f = spring_force(s, 0, m_constraints[s], m_touch[s], dt, dt_penalty, status);
      if (!m_interference.empty() && m_interference[s].amount > 0.0) {
        // The work of the ramp step on the spring, in the trapezoidal measure of the work the
        // contact forces do on the nodes (ForceAssembly): with F = k (d − d0), ½ k e² grows
        // by ½ (F_n + F_{n+1}) (Δd − Δd0), the nodes' part of which ALLPW books.
        m_ramp_work[s] =
            0.5 * (fn_before + m_spring[2 * s].fn) * (m_ramp_before[s] - m_constraints[s].offset);
      }
      for (int d = 0; d < 3; ++d) m_slave_force[3 * s + d] = f[d];
      m_normal_force[s] = m_spring[2 * s].fn;
      const Vec3 f2 =
          m_second_touch[s].face == NO_INDEX
              ? Vec3::Zero()
              : spring_force(s, 1, m_second[s], m_second_touch[s], dt, dt_penalty, status);
      for (int d = 0; d < 3; ++d) m_second_force[3 * s + d] = f2[d];
      m_second_normal_force[s] = m_spring[2 * s + 1].fn;
      m_output_status[s] = status;
    });
  }
  errors.rethrow_if_any();
}

void ContactEngine::prepare_spring(Index s, ContactConstraint& c, const SlaveTouch& t,
                                   Spring& spring, const NodalVectors& position,
                                   const NodalVectors& velocity_half, Real dt, Real dt_penalty,
                                   std::span<const Real> mass,
                                   std::span<const Real> inverse_mass) const {
  (void)position;
  spring = Spring{};
  if (t.face == NO_INDEX) {
    c.master_face = NO_INDEX;
    c.status = ContactStatus::Inactive;
    c.tangential_force = Vec3::Zero();
    return;
  }
  const SlaveNodes& slaves = m_domain.slaves();
  const Index node = slaves.nodes()[s];
  spring.interaction = m_domain.interaction(s, t.face);
  spring.law =
      spring.interaction != NO_INDEX && spring.interaction < static_cast<Index>(m_laws.size())
          ? m_laws[spring.interaction]
          : InteractionLaw{};
  const ContactFace& face = m_domain.faces()[t.face];
  Vec3 v_rel = node_point(velocity_half, node);
  for (int a = 0; a < 4; ++a) v_rel -= t.shape[a] * node_point(velocity_half, face.nodes[a]);
  spring.v_rel = v_rel;
  // A touch the increment's motion cannot have made starts without force (file comment).
  if (m_updated && !c.offset_permanent)
    c.offset = std::max(c.offset, onset_offset(c, t.face, t.gap, t.normal, v_rel, dt));
  c.gap = t.gap;
  c.normal = t.normal;
  const Real master_mass = master_mass_at_point(t.shape, face.nodes, mass, inverse_mass);
  // A rigid body's node does not move with its spring (penalty.hpp, RIGID_MASS).
  const Real slave_mass = m_domain.slave_rigid(s) ? RIGID_MASS : mass[node];
  Real k = penalty_stiffness(spring.law, slaves.areas()[s], slave_mass, master_mass, dt_penalty,
                             m_options.penalty_scale);
  k *= t.weight;
  spring.k = k;
  spring.acts = -t.gap - c.offset > 0.0;
}

void ContactEngine::cap_default_springs(Real dt_penalty, std::span<const Real> mass,
                                        std::span<const Real> inverse_mass) {
  const SlaveNodes& slaves = m_domain.slaves();
  const std::vector<ContactFace>& faces = m_domain.faces();
  const std::span<const Index> visited = visits();
  auto touch_of = [&](Index j) -> const SlaveTouch& {
    return j % 2 == 0 ? m_touch[j / 2] : m_second_touch[j / 2];
  };
  auto counted = [&](const Spring& spring) {
    return spring.k > 0.0 && spring.acts && !(spring.law.pressure_slope > 0.0);
  };
  m_default_sum.reset(static_cast<Index>(mass.size()));
  bool any = false;
  // In slot order, side 0 before side 1 (a quiet slot's springs are zero: not counted).
  for (const Index s : visited)
    for (Index j = 2 * s; j < 2 * s + 2; ++j) {
      const Spring& spring = m_spring[j];
      if (!counted(spring)) continue;
      const SlaveTouch& t = touch_of(j);
      m_default_sum.add_spring(slaves.nodes()[s], faces[t.face].nodes, t.shape, spring.k, NO_INDEX,
                               inverse_mass);
      any = true;
    }
  // The user's penalty scale raises every default spring, and the node budget with them.
  const Real budget =
      DEFAULT_PENALTY_NODE_BUDGET * m_options.penalty_scale / (dt_penalty * dt_penalty);
  // The rigid body a spring pushes (its slave node's or its face's), NO_INDEX: none.
  auto body_of = [&](Index j) {
    if (m_node_body.empty()) return NO_INDEX;
    const Index slave_body = m_node_body[slaves.nodes()[j / 2]];
    if (slave_body != NO_INDEX) return slave_body;
    return m_node_body[faces[touch_of(j).face].nodes[0]];
  };
  if (!m_body_mass.empty()) {
    const Real body_budget =
        DEFAULT_PENALTY_BODY_BUDGET * m_options.penalty_scale / (dt_penalty * dt_penalty);
    for (auto& r : m_body_row) r = {0.0, 0.0, 0.0};
    for (const Index s : visited)
      for (Index j = 2 * s; j < 2 * s + 2; ++j) {
        const Spring& spring = m_spring[j];
        if (!counted(spring)) continue;
        const Index b = body_of(j);
        if (b == NO_INDEX) continue;
        const Vec3& n = touch_of(j).normal;
        const Real spread = std::abs(n[0]) + std::abs(n[1]) + std::abs(n[2]);
        for (int d = 0; d < 3; ++d) m_body_row[b][d] += spring.k * std::abs(n[d]) * spread;
      }
    for (std::size_t b = 0; b < m_body_mass.size(); ++b) {
      Real largest = 0.0;
      for (int d = 0; d < 3; ++d)
        if (std::isfinite(m_body_mass[b][d]) && m_body_mass[b][d] > 0.0)
          largest = std::max(largest, m_body_row[b][d] / m_body_mass[b][d]);
      m_body_factor[b] = largest > body_budget ? body_budget / largest : 1.0;
    }
  }
  // This process's live slots: the other slots' springs are their owners' (share_slots), and
  // a quiet slot's are zero.
  const auto cap = [&](Index j) {
    Spring& spring = m_spring[j];
    ContactConstraint& c = j % 2 == 0 ? m_constraints[j / 2] : m_second[j / 2];
    Real factor = 1.0;
    if (any && counted(spring)) {
      const SlaveTouch& t = touch_of(j);
      Real largest = m_default_sum.row(slaves.nodes()[j / 2]) * inverse_mass[slaves.nodes()[j / 2]];
      for (int a = 0; a < 4; ++a)
        if (t.shape[a] > 0.0 && inverse_mass[faces[t.face].nodes[a]] > 0.0)
          largest = std::max(largest, m_default_sum.row(faces[t.face].nodes[a]) *
                                          inverse_mass[faces[t.face].nodes[a]]);
      if (largest > budget) factor = budget / largest;
      if (!m_body_mass.empty()) {
        const Index b = body_of(j);
        if (b != NO_INDEX) factor = std::min(factor, m_body_factor[b]);
      }
    }
    if (factor < 1.0) spring.k *= factor;
    // A default spring whose stiffness changes while loaded (its share of the node's budget,
    // the increment it is tied to as the elements are squashed, the master mass at a sliding
    // point) would hold another energy at the same depth than the motion put in, and give it
    // back as it opens: the offset moves so that the stored energy stays. Both ways, so that
    // the offset depends on the stiffness now, not on the path: a stiffness that goes up and
    // down again leaves it where it was (a softening spring's offset stops at zero).
    const bool user = spring.law.pressure_slope > 0.0;
    if (!user && spring.acts && c.stiffness > 0.0 && spring.k != c.stiffness &&
        !c.offset_permanent) {
      const Real excess = -c.gap - c.offset;
      c.offset = std::max(0.0, -c.gap - std::sqrt(c.stiffness / spring.k) * excess);
    }
    c.stiffness = !user && spring.acts ? spring.k : 0.0;
  };
  for (const Index s : m_live) {
    cap(2 * s);
    cap(2 * s + 1);
  }
}

Vec3 ContactEngine::spring_force(Index s, int side, ContactConstraint& c, const SlaveTouch& t,
                                 Real dt, Real dt_penalty, OutputStatus& status) {
  Spring& spring = m_spring[2 * s + side];
  spring.fn = 0.0;
  if (t.face == NO_INDEX) return Vec3::Zero();
  const Real k = spring.k;
  const InteractionLaw& law = spring.law;
  c.master_face = t.face;
  c.xi = t.xi;
  c.eta = t.eta;
  const Real fn = normal_contact_update(c, t.gap, k);
  spring.fn = fn;
  m_stored[s] += penalty_energy(t.gap, c.offset, k);
  Vec3 f = fn * t.normal;
  if (law.pressure_slope > 0.0) {
    // Counted while closed, or when the approach closes it within the look-ahead.
    const Real ahead =
        t.gap + PENALTY_LOOKAHEAD_INCREMENTS * dt_penalty * spring.v_rel.dot(t.normal);
    const bool acts = fn > 0.0 || penalty_force(ahead, c.offset, k) > 0.0;
    m_user_k[2 * s + side] = acts ? k : 0.0;
    m_user_law[2 * s + side] = spring.interaction;
  }
  if (law.friction > 0.0 && dt > 0.0) {
    const FrictionUpdate fr =
        friction_update(c.tangential_force, spring.v_rel, t.normal, fn, law.friction, k, dt);
    c.tangential_force = fr.force;
    (side == 0 ? m_dissipation : m_second_dissipation)[s] = fr.dissipation;
    if (k > 0.0) m_stored[s] += 0.5 * fr.force.dot(fr.force) / k;
    f += fr.force;
    if (fn > 0.0 && status != OutputStatus::Stick)
      status = fr.slipping ? OutputStatus::Slip : OutputStatus::Stick;
  } else {
    c.tangential_force = Vec3::Zero();
    if (fn > 0.0 && status == OutputStatus::Open) status = OutputStatus::Slip;
  }
  return f;
}

PenaltyLimit ContactEngine::estimate_penalty_limit(std::span<const Real> inverse_mass) const {
  PenaltyLimit out;
  if (!m_user_stiffness) return out;
  const SlaveNodes& slaves = m_domain.slaves();
  for (Index s = 0; s < slaves.size(); ++s) {
    if (m_domain.slave_rigid(s)) continue;
    const Index node = slaves.nodes()[s];
    for (Index ia = 0; ia < static_cast<Index>(m_laws.size()); ++ia) {
      if (!(m_laws[ia].pressure_slope > 0.0) || !m_domain.may_use(s, ia)) continue;
      const Real k = linear_penalty_stiffness(m_laws[ia].pressure_slope, slaves.areas()[s]);
      const Real w = 2.0 * k * inverse_mass[node];
      if (w > out.omega_sq) out = {w, node, ia};
    }
  }
  return out;
}

}  // namespace xpl::contact
