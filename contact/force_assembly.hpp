#pragma once
/// \file Assembly of contact forces onto the nodes (stage 5, after the penalty law): the force
/// of every slave node's constraint goes to the node itself (+f) and to the corners of its
/// master face (−N_I f), per-pair force sums and the work of the contact forces are summed.
///
/// Determinism: everything here runs over slave slots in order, one thread, so the nodal
/// forces and the sums do not depend on the number of threads that computed the constraint
/// forces. It visits only the slots that can carry force (the engine's list of slots with a
/// touch, ascending, and the slots whose assembled force is not zero), in that same order, so
/// every sum is the one over all slots to the bit.

#include <span>
#include <vector>

#include "contact/closest_point.hpp"
#include "contact/penalty.hpp"

namespace xpl::contact {

/// What one increment of contact did.
struct ContactTotals {
  /// Work done on the nodes by the contact forces over the increment (trapezoidal rule), J;
  /// negative while springs are loaded or friction dissipates.
  Real work = 0.0;
  Real friction_dissipation = 0.0;  ///< J, ≥ 0
  /// Energy held by the springs at the end of the increment, J: Σ ½ k (d − d0)² over the
  /// closed normal springs plus Σ ½ |f_t|²/k_t over the stick springs of friction (k_t = k).
  /// ALLPW should equal it (issue 20, item 4); what the springs hold beyond ALLPW was created
  /// by contact (ContactEnergyCheck).
  Real stored_energy = 0.0;
  /// Energy the interference ramp put into the springs this increment (SPEC C15), J: ½ (F_n +
  /// F_{n+1}) times the shrinking of the offsets d0, in the trapezoidal measure of `work`.
  /// An energy input, as the work of a load (the solver books it in ALLWK and ALLPW).
  Real interference_work = 0.0;
  Index closed = 0;  ///< slave nodes with a normal force
  /// Slave nodes released deeper than the element behind the solid face they were pressed on
  /// (ContactEngine, contact at speed), and the deepest of them: its node index, depth (m),
  /// the face's element index and the depth of that element (m).
  Index lost = 0;
  Index lost_node = NO_INDEX;
  Real lost_depth = 0.0;
  Index lost_element = NO_INDEX;
  Real lost_element_depth = 0.0;
  /// Slave nodes pressed on a side of a shell last increment and now behind its mid-surface
  /// with no face holding them on that side (ContactEngine::passed_depth): passed through it.
  /// The deepest: its node index, depth behind the mid-surface (m) and the shell element index.
  Index passed = 0;
  Index passed_node = NO_INDEX;
  Real passed_depth = 0.0;
  Index passed_element = NO_INDEX;
  /// Slave nodes still held on the side of a shell they were pressed on but behind its
  /// mid-surface, or overlapping a solid face by more than half the element behind it
  /// (ContactEngine::behind_depth), and the deepest: node, depth (m), element, and for a solid
  /// face the depth of that element (m; 0 for a shell).
  Index behind = 0;
  Index behind_node = NO_INDEX;
  Real behind_depth = 0.0;
  Index behind_element = NO_INDEX;
  Real behind_element_depth = 0.0;
  bool rebuilt = false;  ///< the broad phase was rebuilt
};

/// The assembled contact forces of the current and the previous increment (for the
/// trapezoidal work), per slave slot, and the per-pair force sums.
class ForceAssembly {
 public:
  ForceAssembly() = default;
  /// Room for `n_slave` slave slots and `n_pairs` included pairs, every force zero.
  ForceAssembly(Index n_slave, Index n_pairs);

  /// The springs of one side of every slave slot (ContactEngine: the nearest face, and the
  /// face on the other side of a pinched node), n_slave each.
  struct SpringSet {
    std::span<const SlaveTouch> touch;               ///< the touch, written by the search
    std::span<const Real> slave_force;               ///< (n_slave × 3) force on the slave node, N
    std::span<const Real> normal_force;              ///< normal force, N
    std::span<const ContactConstraint> constraints;  ///< for the friction force
    std::span<const Real> dissipation;               ///< frictional dissipation of the increment, J
  };

  /// One increment: per slave slot s of `slots` (ascending; every slot with a touch in
  /// `first` or `second` must be among them) with a touch in `first`, then per slot with one in
  /// `second`, the force on the slave node (normal plus friction, view weight included) is
  /// subtracted from `force_internal` (n_nodes × 3, N) at the node and added at the face
  /// corners with the weights N_I; the normal force and the friction force magnitude go to the
  /// pair sums, the frictional dissipation and the count of loaded springs to `totals`. Then
  /// the work of the nodal forces over the increment with velocities `velocity_half`
  /// (n_nodes × 3, m/s) and length dt (s; none when dt ≤ 0) is added to `totals.work`; or,
  /// when `slot_velocity` is not empty, with the velocity of each slot's node from there
  /// (n_slave × 3, m/s; read for the slots with a force now or before only).
  void assemble(const SlaveNodes& slaves, const std::vector<ContactFace>& faces,
                std::span<const Index> slots, const SpringSet& first, const SpringSet& second,
                const NodalVectors& velocity_half, std::span<const Real> slot_velocity, Real dt,
                NodalVectors& force_internal, ContactTotals& totals);
  /// Whether slot s's node had a contact force at the last assembly (before the next one:
  /// the previous increment's, which the next work term reads).
  bool has_force(Index s) const {
    return m_force[3 * s] != 0.0 || m_force[3 * s + 1] != 0.0 || m_force[3 * s + 2] != 0.0;
  }

  /// Total contact force on the node of slave slot s (as slave and as face corner), N.
  Vec3 nodal_force(Index s) const {
    return Vec3(m_force[3 * s], m_force[3 * s + 1], m_force[3 * s + 2]);
  }
  /// The slots whose assembled force (nodal_force) may be non-zero after the last assembly,
  /// ascending: every other slot's is zero.
  const std::vector<Index>& forced_slots() const { return m_forced; }
  /// Per included pair: sums of the normal force magnitudes (N) and of the friction force
  /// magnitudes (N) over the slave nodes touching through that pair, at the last assembly.
  const std::vector<Real>& pair_normal_force() const { return m_pair_normal; }
  const std::vector<Real>& pair_friction_force() const { return m_pair_friction; }

 private:
  /// The force of slot s's spring in `set` onto the nodes and the sums (assemble).
  void add_spring(const SlaveNodes& slaves, const std::vector<ContactFace>& faces,
                  const SpringSet& set, Index s, NodalVectors& force_internal,
                  ContactTotals& totals);
  /// Trapezoidal work ½ (f_n + f_{n−1})·v_{n+1/2} Δt of the assembled forces, added to `work`.
  /// Over the slots of m_forced and m_previous_forced, in slot order; with `slot_velocity`
  /// (when not empty) for the velocities, as assemble() says.
  void add_work(const SlaveNodes& slaves, const NodalVectors& velocity_half,
                std::span<const Real> slot_velocity, Real dt, Real& work);
  /// Slot s gets a share of the force: into m_forced (once).
  void mark(Index s) {
    if (m_marked[s]) return;
    m_marked[s] = 1;
    m_forced.push_back(s);
  }

  std::vector<Real> m_force;           // (n_slave × 3): assembled force, this increment
  std::vector<Real> m_previous_force;  // (n_slave × 3): assembled force, last increment
  std::vector<Real> m_pair_normal, m_pair_friction;
  // The slots m_force and m_previous_force may be non-zero at (ascending after assemble), the
  // marks of m_forced while it is gathered (all zero between assemblies), and the union of
  // both lists (add_work's scratch).
  std::vector<Index> m_forced, m_previous_forced, m_worked;
  std::vector<char> m_marked;
};

}  // namespace xpl::contact
