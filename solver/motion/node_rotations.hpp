#pragma once
/// \file Finite rotations of shell nodes, tracked for output (UR) only: the shell element is
/// rate-based and never reads them. Each node keeps a unit quaternion, advanced every
/// increment by the rotation ω_{n+1/2} Δt (Cayley form: error O(|ωΔt|³) per increment).

#include <vector>

#include "common/types.hpp"

namespace xpl {

/// Unit quaternions of n nodes (struct of arrays), starting at the identity.
class NodeRotations {
 public:
  explicit NodeRotations(Index node_count = 0);

  /// q ← q(ω Δt) q for every node: ω (n_nodes × 3) is the spatial angular velocity.
  void advance(const NodalVectors& angular_velocity, Real dt);
  /// The same for nodes [first, last) only (one thread's share of a nodal pass).
  void advance_range(const NodalVectors& angular_velocity, Real dt, Index first, Index last);

  /// Rotation vectors (axis × angle, |angle| ≤ π) into `rotation` (n_nodes × 3).
  void rotation_vectors(NodalVectors& rotation) const;

  /// Sets every node's rotation from rotation vectors (axis × angle, rad; n_nodes × 3), e.g.
  /// UR of an imported state: the inverse of rotation_vectors (a vector of angle > π gives
  /// the same rotation, which rotation_vectors returns with the angle 2π − |θ|). Throws
  /// std::invalid_argument if the number of rows is not the node count.
  void set(const NodalVectors& rotation_vectors);

 private:
  std::vector<Real> m_w, m_x, m_y, m_z;
};

}  // namespace xpl
