#pragma once
/// \file Kinematic ties (`*TIE`, SPEC S6): node-to-face constraints without penalty.
///
/// Each slave node within the position tolerance of its tie's master surface is bound to its
/// closest point there: face corners I = 0..3 with the bilinear weights N_I(ξ, η) at that
/// point (contact/closest_point.hpp), found on the reference coordinates. The constraint
/// v_s = Σ N_I v_I is kept exactly by the nodal update:
/// - mass: the slave's lumped mass goes to the corners, m_I += N_I m_s, the slave keeps none
///   (total mass and momentum unchanged; the element increments do not depend on the nodal
///   masses, so the stable increment does not change);
/// - force: before the master nodes are updated, the slave's whole nodal force (internal,
///   contact and external loads) goes to the corners, f_I += N_I f_s;
/// - after the update the slave takes v_{n+1/2}, v_n and a_n interpolated from the corners;
/// - contact reads for a slave its share of the corners' mass, m* = Σ N_I² m_I / W_I
///   (slave_points(), ContactStage::set_tie_slaves).
/// The forces then do in total the work they do on the corners (Σ f_s·v_s = Σ_I f_I·v_I), so
/// the tie does no work and ETOTAL stays balanced; ALLKE counts the slave's mass at its
/// corners (½ Σ m_I v_I²), which is the kinetic energy of the equations the update solves.
///
/// On shell masters (the master face belongs to an S4R element) a slave that is a shell node
/// also takes its rotations from the corners in the same way (rotary inertia and moments
/// distributed by N_I, ω_s = Σ N_I ω_I); a shell slave on a solid master keeps its own
/// rotations.
///
/// ADJUST=YES moves each bound slave node onto its closest point before anything else, strain
/// free as the overclosure adjustment (the position moves, U of frame 0 shows the move; an
/// imported run binds on the deck coordinates again and keeps the imported positions, so it
/// moves nothing again); ADJUST=NO keeps the gap, which then
/// stays a constant vector (the slave translates with the master point). Default position
/// tolerance: 5 % of the mean diagonal of the master faces (as Abaqus). Deck-level conflicts
/// (a node in two ties, a slave with a BC or in a rigid body) are refused by the deck reader
/// (io/deck/deck_tie.cpp); a slave node that is also a node of its own master surface stays
/// untied.

#include <array>
#include <string>
#include <vector>

#include "common/types.hpp"
#include "solver/model/model.hpp"
#include "solver/model/state.hpp"

namespace xpl {

/// Fraction of the mean master-face diagonal that is the default POSITION TOLERANCE.
inline constexpr Real TIE_DEFAULT_TOLERANCE = 0.05;

/// The ties of a model.
class Ties {
 public:
  Ties() = default;
  /// Binds the slave nodes on `state.reference`; ADJUST=YES moves them there (position). Nothing is
  /// allocated when the model has no ties.
  Ties(const Model& model, State& state);

  bool empty() const { return m_bindings.empty() && m_messages.empty(); }
  /// Whether any slave node is bound (then the nodal update runs the tie passes).
  bool active() const { return !m_bindings.empty(); }
  /// Per node: 1 for a bound slave node or a corner of a face one is bound to (n_nodes), empty
  /// without ties: the nodes the overclosure pass holds (reason "tie").
  const std::vector<char>& tied_nodes() const { return m_tied; }
  /// The bound slave nodes and the master nodes whose mass changes (for the inverse masses).
  std::vector<Index> changed_nodes() const;

  /// Moves the slave masses (and rotary inertias where rotations are tied) to the corners in
  /// `state`, and gives the slaves the interpolated initial velocity of their master point.
  void distribute_mass(State& state) const;
  /// Moves each slave's force to its corners: force_internal(I) += N_I (force_internal(s) −
  /// force_external(s)) (external may be null), and the internal moments of slaves with tied
  /// rotations (may be null). Master nodes in a fixed order: independent of the thread count.
  void gather(NodalVectors& force_internal, const NodalVectors* force_external,
              NodalVectors* moment_internal) const;
  /// Slave velocities (half and whole step), accelerations and tied angular velocities
  /// interpolated from their corners, after the corners' update.
  void follow(State& state) const;
  /// Distributed runs (docs/dev/mpi.md, "Ties where their nodes live"): restricts gather() to
  /// the master nodes with `gathers[i]` != 0 and follow() to the slaves with `follows[i]` != 0
  /// (n_nodes each): those whose forces this rank finishes and the slaves it moves. Each pass
  /// then does, for those nodes, exactly what it does on one rank.
  void set_local(const std::vector<unsigned char>& gathers,
                 const std::vector<unsigned char>& follows);
  /// One message per tie for the .msg file: tied slave nodes, largest adjustment, untied ones.
  const std::vector<std::string>& messages() const { return m_messages; }
  /// Warnings for the .msg file: a tie that binds no slave node (with the nearest distance
  /// against the tolerance), and ADJUST=YES moving slave nodes by more than the size of the
  /// master face they bind to (with the largest move).
  const std::vector<std::string>& warnings() const { return m_warnings; }
  /// A bound slave node, its master corners (NO_INDEX: none) and their weights N_I.
  struct SlavePoint {
    Index slave = NO_INDEX;
    std::array<Index, 4> corner{};
    std::array<Real, 4> weight{};
  };
  /// Every binding's slave point, in binding order (contact reads the mass a tied slave node
  /// moves with from them: ContactStage::set_tie_slaves).
  std::vector<SlavePoint> slave_points() const {
    std::vector<SlavePoint> points;
    points.reserve(m_bindings.size());
    for (const Binding& b : m_bindings) points.push_back({b.slave, b.corner, b.weight});
    return points;
  }
  /// Every (slave node, master corner node) a binding joins, in binding order: the partition
  /// keeps them on one part where it can (solver/model_partition.hpp).
  std::vector<std::pair<Index, Index>> slave_master_nodes() const {
    std::vector<std::pair<Index, Index>> pairs;
    for (const Binding& b : m_bindings)
      for (const Index corner : b.corner)
        if (corner != NO_INDEX) pairs.emplace_back(b.slave, corner);
    return pairs;
  }

 private:
  struct Binding {
    Index slave = NO_INDEX;
    std::array<Index, 4> corner{};
    std::array<Real, 4> weight{};
    bool rotations = false;  ///< shell slave on a shell master: rotations tied too
  };
  /// Binds the slave nodes of one tie (`shell_node`: 1 for the nodes of shells), with its
  /// message and warnings.
  void bind(const Model& model, const Tie& tie, const std::vector<char>& shell_node, State& state);
  /// Builds the per-master-node entries (m_master, m_entry_offsets, m_entries) of the
  /// bindings, over the model's n nodes.
  void index_masters(Index n);
  /// gather() at master node m_master[m]; follow() of binding `b`.
  void gather_master(std::size_t m, NodalVectors& force_internal,
                     const NodalVectors* force_external, NodalVectors* moment_internal) const;
  void follow_binding(const Binding& b, State& state, bool rotations) const;
  std::vector<Binding> m_bindings;  ///< in tie order, then slave node order
  /// Per master node (m_master, in node order): its (binding, corner) entries in binding
  /// order, CSR in m_entry_offsets.
  std::vector<Index> m_master;
  std::vector<Index> m_entry_offsets;
  std::vector<std::pair<Index, int>> m_entries;
  std::vector<char> m_tied;
  /// set_local(): the positions in m_master gather() visits and the bindings follow() visits;
  /// m_local false: every one.
  bool m_local = false;
  std::vector<std::size_t> m_local_masters, m_local_bindings;
  std::vector<std::string> m_messages;
  std::vector<std::string> m_warnings;
};

}  // namespace xpl
