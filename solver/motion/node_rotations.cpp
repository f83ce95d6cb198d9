#include "solver/motion/node_rotations.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace xpl {

NodeRotations::NodeRotations(Index node_count)
    : m_w(node_count, 1.0), m_x(node_count, 0.0), m_y(node_count, 0.0), m_z(node_count, 0.0) {}

void NodeRotations::advance(const NodalVectors& angular_velocity, Real dt) {
  const auto n = static_cast<Index>(m_w.size());
  advance_range(angular_velocity, dt, 0, n);
}

void NodeRotations::advance_range(const NodalVectors& angular_velocity, Real dt, Index first,
                                  Index last) {
  const auto n = static_cast<Index>(m_w.size());
  const Real* ox = angular_velocity.data();
  const Real* oy = ox + n;
  const Real* oz = oy + n;
  const Real h = 0.5 * dt;
#pragma omp simd
  for (Index i = first; i < last; ++i) {
    // Increment (1, a) / |(1, a)| with a = ω Δt / 2, then the product with q.
    const Real ax = h * ox[i], ay = h * oy[i], az = h * oz[i];
    const Real s = 1.0 / std::sqrt(1.0 + ax * ax + ay * ay + az * az);
    const Real w = m_w[i], x = m_x[i], y = m_y[i], z = m_z[i];
    m_w[i] = s * (w - ax * x - ay * y - az * z);
    m_x[i] = s * (x + ax * w + ay * z - az * y);
    m_y[i] = s * (y + ay * w + az * x - ax * z);
    m_z[i] = s * (z + az * w + ax * y - ay * x);
  }
}

void NodeRotations::rotation_vectors(NodalVectors& rotation) const {
  const auto n = static_cast<Index>(m_w.size());
  for (Index i = 0; i < n; ++i) {
    Real w = m_w[i], x = m_x[i], y = m_y[i], z = m_z[i];
    if (w < 0.0) {  // the same rotation with angle ≤ π
      w = -w;
      x = -x;
      y = -y;
      z = -z;
    }
    const Real s = std::sqrt(x * x + y * y + z * z);
    const Real factor = s > 1e-300 ? 2.0 * std::atan2(s, w) / s : 2.0;
    rotation(i, 0) = factor * x;
    rotation(i, 1) = factor * y;
    rotation(i, 2) = factor * z;
  }
}

void NodeRotations::set(const NodalVectors& rotation_vectors) {
  const auto n = static_cast<Index>(m_w.size());
  if (rotation_vectors.rows() != n) {
    throw std::invalid_argument("NodeRotations::set: " + std::to_string(rotation_vectors.rows()) +
                                " rotation vectors for " + std::to_string(n) + " nodes");
  }
  for (Index i = 0; i < n; ++i) {
    const Real x = rotation_vectors(i, 0), y = rotation_vectors(i, 1), z = rotation_vectors(i, 2);
    const Real angle = std::sqrt(x * x + y * y + z * z);
    // q = (cos θ/2, sin(θ/2) θ̂); sin(θ/2)/θ → 1/2 as θ → 0.
    const Real s = angle > 0.0 ? std::sin(0.5 * angle) / angle : 0.5;
    m_w[i] = std::cos(0.5 * angle);
    m_x[i] = s * x;
    m_y[i] = s * y;
    m_z[i] = s * z;
  }
}

}  // namespace xpl
