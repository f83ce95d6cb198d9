#pragma once
/// \file The penalty law of node-to-face contact, its offset rule and friction (stage 4).
///
/// Everything here is a small pure function of one constraint so that the force loop, the
/// initial-overclosure module and the tests share one definition. Sign conventions: the gap
/// g is positive when the slave node is outside the master face (ClosestPoint::gap), the
/// penetration is d = −g, and forces are magnitudes along the contact normal (pushing the
/// slave node out along +normal, the master face nodes by −N_I·f·normal).

#include <array>
#include <cstdint>
#include <limits>
#include <span>

#include "contact/contact_faces.hpp"
#include "contact/contact_options.hpp"

namespace xpl::contact {

/// What a slave node's constraint is doing in this increment.
enum class ContactStatus : std::uint8_t {
  Inactive,  ///< no master face found (no candidate, or excluded)
  Open,      ///< paired with a face, no normal force
  Closed,    ///< paired with a face and pressed: normal force > 0
};

/// The contact state of one slave node, kept from increment to increment.
///
/// The offset belongs to the slave node, not to a node–face pair: a node that slides onto
/// the next face keeps its unresolved overclosure. The initial-overclosure module (SPEC C2,
/// C3, C6, C7) fills `offset` (and `offset_permanent`) for every slave slot at t = 0 before the
/// first increment; a default-constructed constraint has no offset.
struct ContactConstraint {
  Index master_face = NO_INDEX;  ///< index into the contact face list, NO_INDEX when none
  Real xi = 0.0, eta = 0.0;      ///< face coordinates of the closest point
  Real offset = 0.0;             ///< d0 ≥ 0: penetration that produces no force, m
  /// `*CONTACT CLEARANCE, ADJUST=NO` (C7): the offset is kept, never shrunk by the C3 rule.
  bool offset_permanent = false;
  ContactStatus status = ContactStatus::Inactive;
  Vec3 tangential_force = Vec3::Zero();  ///< friction force on the slave node, N
  /// Gap (m) and unit contact normal of the touch on `master_face` at the last update, for
  /// the onset rule of a touch on another face (ContactEngine).
  Real gap = 0.0;
  Vec3 normal = Vec3::Zero();
  /// Stiffness of the default-penalty spring at the last update while it was loaded (N/m,
  /// view weight and node budget included), 0 when it was not: a spring whose stiffness
  /// changes while loaded moves its offset so that it holds the energy the motion put in
  /// (ContactEngine).
  Real stiffness = 0.0;
};

/// Normal force magnitude f = k·max(0, d − d0) for gap g (d = −g, m), offset d0 (m) and
/// stiffness k (N/m); N.
inline Real penalty_force(Real gap, Real offset, Real stiffness) {
  const Real excess = -gap - offset;
  return excess > 0.0 ? stiffness * excess : 0.0;
}

/// Energy ½ k·max(0, d − d0)² stored in the penalty spring, J.
inline Real penalty_energy(Real gap, Real offset, Real stiffness) {
  const Real excess = -gap - offset;
  return excess > 0.0 ? 0.5 * stiffness * excess * excess : 0.0;
}

/// The offset rule of SPEC C3 for penetration d (m) and offset d0 (m): whenever d < d0 the
/// offset becomes max(d, 0). It shrinks as the surfaces separate, never grows, reaches zero
/// and stays there; so the force k·(d − d0) is zero at the moment the offset is reduced and
/// an offset never pushes.
inline Real updated_offset(Real penetration, Real offset) {
  if (penetration >= offset) return offset;
  return penetration > 0.0 ? penetration : 0.0;
}

/// One increment of the normal law for a paired constraint with gap g (m) and stiffness k
/// (N/m): applies the offset rule (unless the offset is permanent), then returns the normal
/// force (N) and sets the status to Closed or Open.
Real normal_contact_update(ContactConstraint& constraint, Real gap, Real stiffness);

/// The offset (m) a touch needs at its onset: the penetration beyond what the last increment
/// can have produced, or 0.
///
/// A touch on face `face` (gap `gap`, m, unit contact normal `normal`) that is not the face of
/// last increment's constraint `before` is as deep as the relative approach of the increment
/// along the normal, −v_rel·n Δt (relative velocity of the slave node to the face point
/// `relative_velocity`, m/s, over the increment dt, s), plus the compression `before`'s spring
/// held (its penetration beyond its offset) when its face is on the same side (normals less
/// than 90° apart: sliding on to the next face). Deeper than that (more than ONSET_REACH_FACTOR
/// times the approach), the node was already inside when the face turned admissible for it: a fold
/// turning a face towards it, a node coming within the lateral rule of a face's edge, a node past a
/// shell's mid-surface seeing the other side. The spring then holds only what the approach made
/// (its energy is the work the approach took), and the rest becomes offset, so that a touch never
/// starts with a force the motion did not build (energy from nowhere) and never pushes a node on
/// through a wall it has crossed. Zero for the face of `before` (a continuing touch).
Real onset_offset(const ContactConstraint& before, Index face, Real gap, const Vec3& normal,
                  const Vec3& relative_velocity, Real dt);

/// The mass of a rigid side of a spring — a master face with a rigid corner (a corner of zero
/// inverse mass), or a slave node of a rigid body: infinite, since the body's mass does not
/// move with one spring's force (a body driven by a boundary condition not at all, a free body
/// as a whole, bounded by the engine's body cap), so that m_eff is the other side's mass.
inline constexpr Real RIGID_MASS = std::numeric_limits<Real>::infinity();

/// The contact law of one surface interaction.
struct InteractionLaw {
  Real friction = 0.0;        ///< Coulomb coefficient μ ≥ 0
  Real pressure_slope = 0.0;  ///< Pa/m; > 0: k = slope × tributary area, else the default
};

/// Mass of the master face at the contact point, Σ N_I m_I (weights N_I, corner masses m_I in
/// kg); kg.
Real mass_at_point(const std::array<Real, 4>& weights, const std::array<Real, 4>& corner_mass);

/// Master mass at the contact point of a face with corners `corners` (node indices), shape
/// weights `weights`, nodal masses `mass` (kg) and inverse masses `inverse_mass` (1/kg, 0 for
/// a rigid body node): mass_at_point of the corner masses, or RIGID_MASS when a corner
/// is rigid (its mass does not move with the contact force); kg.
///
/// Inline, and summed straight from the nodal masses: the engine's force loop has always
/// summed it in place, and the compiler contracts that sum (fused multiply–adds) where it sees
/// it; an out-of-line copy through a corner array rounds differently.
inline Real master_mass_at_point(const std::array<Real, 4>& weights,
                                 const std::array<Index, 4>& corners, std::span<const Real> mass,
                                 std::span<const Real> inverse_mass) {
  Real master_mass = 0.0;
  bool rigid = false;
  for (int a = 0; a < 4; ++a) {
    master_mass += weights[a] * mass[corners[a]];
    rigid = rigid || inverse_mass[corners[a]] == 0.0;
  }
  return rigid ? RIGID_MASS : master_mass;
}

/// Default penalty stiffness k = α·s·m_eff/Δt², N/m, with α = DEFAULT_PENALTY_FACTOR, s the
/// user's penalty scale factor, Δt the stable time increment (s) and m_eff = m_s m_m /
/// (m_s + m_m) the harmonic mean of the slave node's mass and the master mass at the contact
/// point (kg), as LS-DYNA's soft-constraint formulation (SOFT=1) does.
///
/// Why this does not lower the stable increment (SPEC C1): a spring k between masses m_s and
/// m_m oscillates at ω² = k (1/m_s + 1/m_m) = k / m_eff, and central differences are stable
/// for ω Δt < 2, i.e. k < 4 m_eff/Δt². With α = 0.5 the spring alone reaches ω² Δt² = 0.5, an
/// eighth of the limit, which leaves room for the element stiffness already on the node
/// (frequencies add in squares) and for a node carrying several springs (a slave node that is
/// also a master corner, both views of balanced contact).
///
/// A rigid master (master_mass = RIGID_MASS, 1/m_m = 0) and a master without mass (m_m ≤ 0:
/// nothing to share the spring with) give m_eff = m_s. A rigid slave node (slave_mass =
/// RIGID_MASS, 1/m_s = 0) gives m_eff = m_m, the mass the spring actually moves: the lumped
/// mass of a rigid body's node is its share of the body's volume, not what resists the spring,
/// and a finely meshed rigid punch would otherwise press with springs softer by the ratio of
/// its node masses to the partner's (Abaqus/Explicit and LS-DYNA likewise take a rigid
/// body's penalty from its deformable partner). A slave node without mass gives 0, and so do
/// a rigid slave on a rigid or massless master and Δt ≤ 0 (a caller error).
Real default_penalty_stiffness(Real slave_mass, Real master_mass, Real dt, Real scale = 1.0);

/// Stiffness of a LINEAR pressure–overclosure law: k = slope (Pa/m) × tributary area (m²); N/m.
inline Real linear_penalty_stiffness(Real pressure_slope, Real area) {
  return pressure_slope * area;
}

/// The penalty stiffness of a constraint under `law` (N/m, before the view weight): the LINEAR
/// law for a positive pressure slope with the slave node's tributary area `area` (m²), else
/// default_penalty_stiffness of the slave mass, master mass (kg), Δt (s) and penalty scale.
Real penalty_stiffness(const InteractionLaw& law, Real area, Real slave_mass, Real master_mass,
                       Real dt, Real scale);

/// Result of one friction update.
struct FrictionUpdate {
  Vec3 force = Vec3::Zero();  ///< tangential force on the slave node after the update, N
  Real dissipation = 0.0;     ///< frictional dissipation of this increment (for ALLFD), J
  bool slipping = false;      ///< the force was capped at μ·f_n
};

/// Coulomb friction regularised by an elastic stick spring ("penalty stick"), one increment.
///
/// The previous force (N) is turned into the current tangent plane of unit normal `normal`
/// (keeping its magnitude), the trial force is f* = f_prev − k_t·v_t·Δt with v_t the tangential
/// part of the slave-minus-master velocity `relative_velocity` (m/s) over Δt (s), and f* is
/// scaled back onto the Coulomb cone |f| ≤ μ f_n (normal force f_n in N, μ ≥ 0; k_t in N/m,
/// the normal penalty stiffness by default). The dissipation is the work of the new force
/// over the slip part of the tangential motion, |f| (|f*| − |f|)/k_t ≥ 0: zero while sticking,
/// μ f_n times the slip distance in steady sliding. When the normal force drops, the part of
/// the stored tangential force above the new cap is counted as slip.
FrictionUpdate friction_update(const Vec3& previous_force, const Vec3& relative_velocity,
                               const Vec3& normal, Real normal_force, Real mu, Real k_t, Real dt);

}  // namespace xpl::contact
