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

  /// Rotation vectors (axis × angle, |angle| ≤ π) into `rotation` (n_nodes × 3).
  void rotation_vectors(NodalVectors& rotation) const;

 private:
  std::vector<Real> m_w, m_x, m_y, m_z;
};

}  // namespace xpl
