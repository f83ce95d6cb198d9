#pragma once
/// \file The stable increment a deck's own penalty stiffness allows (a LINEAR
/// pressure–overclosure slope): the highest frequency of the contact springs a node actually
/// sees, bounded from the springs' stiffness matrices, and the increment that keeps it within
/// the budget the default penalty is built for.
///
/// Derivation. A spring of stiffness k (N/m, view weight included) between a slave node s and
/// the point of a master face with shape weights N_I (Σ N_I = 1) has the stiffness matrix
/// k·[1, −Nᵀ; −N, N Nᵀ] along the contact normal. The highest eigenvalue of M⁻¹K is bounded by
/// the largest row sum of |M⁻¹K| (Gershgorin), summed over every spring on the node — its own
/// slave spring and its shares N_I as a corner of faces other nodes press on, both views of a
/// balanced pair:
///   row of the slave node:   k (1 + Σ_movable N_J) / m_s,
///   row of a master corner:  k N_I (1 + Σ_movable N_J) / m_I,
/// where only corners that move (inverse mass > 0) count in the sums: a rigid master gives the
/// spring on a node, k/m. For two equal masses face to face (N = 1 at one corner) the bound is
/// 2k/m = k/m_eff, exact. Elements and springs add in squares (Weyl: λ_max(A + B) ≤ λ_max(A) +
/// λ_max(B)), so a contact frequency with ω_c²Δt² ≤ PENALTY_INCREMENT_BUDGET, the value the
/// default penalty k = ½ m_eff/Δt² reaches by construction, leaves the central-difference
/// limit ω Δt < 2 room for the elements at their own limit (0.9² · 4 + ½ = 3.74 < 4).
/// A user's spring stiffer than that shortens the increment to Δt = √(budget)/ω_c: the default
/// rule, and every spring no stiffer than the default, leaves it unchanged.

#include <array>
#include <limits>
#include <span>
#include <vector>

#include "common/types.hpp"

namespace xpl::contact {

/// The stiffest node of the user-stiffness springs at one increment.
struct PenaltyLimit {
  Real omega_sq = 0.0;           ///< largest row-sum bound of M⁻¹K_contact, 1/s²; 0: none
  Index node = NO_INDEX;         ///< the node where it is reached (0-based), NO_INDEX: none
  Index interaction = NO_INDEX;  ///< the interaction of the largest spring on that node
  /// √(PENALTY_INCREMENT_BUDGET)/ω_c, s; +inf when no spring acts.
  Real stable_dt() const;
};

/// Row sums of the contact stiffness matrix per node, accumulated spring by spring.
class PenaltyStiffnessSum {
 public:
  /// Starts an increment on a model of `n_nodes` nodes (keeps the storage).
  void reset(Index n_nodes);
  /// Adds one spring of stiffness `k` (N/m, view weight included) of interaction
  /// `interaction` between `slave_node` and the master face point with corner nodes `corners`
  /// and shape weights `weights`; `inverse_mass` (n_nodes, 1/kg; 0: the node does not move).
  void add_spring(Index slave_node, const std::array<Index, 4>& corners,
                  const std::array<Real, 4>& weights, Real k, Index interaction,
                  std::span<const Real> inverse_mass);
  /// Row sum of node i so far, N/m (0 for a node no spring reaches).
  Real row(Index i) const { return m_row[i]; }
  /// The node with the largest row sum times its inverse mass (ties: the lower node index).
  PenaltyLimit largest(std::span<const Real> inverse_mass) const;

 private:
  void add_row(Index node, Real value, Index interaction);

  std::vector<Real> m_row;           // (n_nodes) row sums, N/m
  std::vector<Real> m_largest;       // (n_nodes) largest single contribution, N/m
  std::vector<Index> m_interaction;  // (n_nodes) its interaction
  std::vector<Index> m_touched;      // nodes with a non-zero row, in order of first touch
};

}  // namespace xpl::contact
