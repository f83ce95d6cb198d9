#include "io/deck_geometry.hpp"

#include <Eigen/Geometry>

namespace xpl::io {

CornerJacobian smallest_corner_jacobian(const std::array<Eigen::Vector3d, 8>& x) {
  CornerJacobian smallest;
  for (int c = 0; c < 8; ++c) {
    const int ring = c < 4 ? 0 : 4;  // bottom face 0-3, top face 4-7, both numbered alike
    const int local = c - ring;
    const int next = ring + (local + 1) % 4;
    const int previous = ring + (local + 3) % 4;
    const int across = c < 4 ? c + 4 : c - 4;
    const Eigen::Vector3d to_next = x[next] - x[c];
    const Eigen::Vector3d to_previous = x[previous] - x[c];
    const Eigen::Vector3d to_across = x[across] - x[c];
    // Bottom corners see (ξ, η, ζ) as (next, previous, up) up to a rotation; on the top face
    // the third edge points down, which flips the orientation, so next and previous swap.
    const Real det = c < 4 ? to_next.dot(to_previous.cross(to_across))
                           : to_previous.dot(to_next.cross(to_across));
    if (c == 0 || det < smallest.determinant) smallest = {det, c};
  }
  return smallest;
}

}  // namespace xpl::io
