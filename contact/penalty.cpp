#include "contact/penalty.hpp"

#include <algorithm>
#include <cmath>

namespace xpl::contact {

Real normal_contact_update(ContactConstraint& constraint, Real gap, Real stiffness) {
  if (!constraint.offset_permanent) constraint.offset = updated_offset(-gap, constraint.offset);
  const Real f = penalty_force(gap, constraint.offset, stiffness);
  constraint.status = f > 0.0 ? ContactStatus::Closed : ContactStatus::Open;
  return f;
}

Real onset_offset(const ContactConstraint& before, Index face, Real gap, const Vec3& normal,
                  const Vec3& relative_velocity, Real dt) {
  if (face == before.master_face) return 0.0;
  const bool same_side = before.master_face != NO_INDEX && before.normal.dot(normal) > 0.0;
  // What the spring held (its penetration beyond the offset), not the whole penetration: the
  // offset stays with the node (ContactConstraint), so carrying the offset part as well would
  // start the new spring compressed by the old offset on top (energy from nowhere at every
  // switch between two faces of a bent shell the node lies deep in).
  const Real carried = same_side ? std::max(0.0, -before.gap - before.offset) : 0.0;
  const Real approach = std::max(0.0, -relative_velocity.dot(normal)) * dt;
  const Real excess = -gap - carried - approach;
  return excess > (ONSET_REACH_FACTOR - 1.0) * approach ? excess : 0.0;
}

Real mass_at_point(const std::array<Real, 4>& weights, const std::array<Real, 4>& corner_mass) {
  Real m = 0.0;
  for (int a = 0; a < 4; ++a) m += weights[a] * corner_mass[a];
  return m;
}

Real default_penalty_stiffness(Real slave_mass, Real master_mass, Real dt, Real scale) {
  if (!(dt > 0.0)) return 0.0;
  // m_eff = 1/(1/m_s + 1/m_m); a rigid corner makes the master mass infinite, a rigid slave
  // node the slave mass.
  const bool master_moves = master_mass != RIGID_MASS && master_mass > 0.0;
  if (slave_mass == RIGID_MASS)
    return master_moves ? DEFAULT_PENALTY_FACTOR * scale * master_mass / (dt * dt) : 0.0;
  const Real m_eff =
      master_moves ? slave_mass * master_mass / (slave_mass + master_mass) : slave_mass;
  return DEFAULT_PENALTY_FACTOR * scale * m_eff / (dt * dt);
}

Real penalty_stiffness(const InteractionLaw& law, Real area, Real slave_mass, Real master_mass,
                       Real dt, Real scale) {
  if (law.pressure_slope > 0.0) return linear_penalty_stiffness(law.pressure_slope, area);
  return default_penalty_stiffness(slave_mass, master_mass, dt, scale);
}

FrictionUpdate friction_update(const Vec3& previous_force, const Vec3& relative_velocity,
                               const Vec3& normal, Real normal_force, Real mu, Real k_t, Real dt) {
  FrictionUpdate out;
  // Previous force turned into the current tangent plane with its magnitude kept.
  Vec3 f = previous_force - previous_force.dot(normal) * normal;
  const Real f_prev_len = std::sqrt(previous_force.dot(previous_force));
  const Real f_len = std::sqrt(f.dot(f));
  if (f_len > 0.0) f *= f_prev_len / f_len;

  const Vec3 v_t = relative_velocity - relative_velocity.dot(normal) * normal;
  const Vec3 trial = f - (k_t * dt) * v_t;
  const Real trial_len = std::sqrt(trial.dot(trial));
  const Real cap = mu * std::max(normal_force, 0.0);
  if (trial_len <= cap) {
    out.force = trial;
    return out;
  }
  out.slipping = true;
  out.force = (cap / trial_len) * trial;
  // Work of the returned force over the slip increment (backward Euler return map).
  out.dissipation = k_t > 0.0 ? cap * (trial_len - cap) / k_t : 0.0;
  return out;
}

}  // namespace xpl::contact
