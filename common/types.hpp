#pragma once
/// \file Scalar and index types and the nodal-array type shared by every module.

#include <cstdint>

#include <Eigen/Core>

namespace xpl {

/// Floating-point type of every physical quantity.
using Real = double;
/// Internal (contiguous, zero-based) index of a node, element, set, ...
using Index = std::int32_t;
/// Identifier as written in a deck (arbitrary, sparse, positive).
using ExternalId = std::int64_t;

/// A nodal vector field, one row per node (n_nodes × 3), column-major so that each
/// component is a contiguous array (x, then y, then z): positions, velocities, forces.
using NodalVectors = Eigen::Matrix<Real, Eigen::Dynamic, 3>;

/// Marker for "no index" (no amplitude, no set, ...).
inline constexpr Index NO_INDEX = -1;

}  // namespace xpl
