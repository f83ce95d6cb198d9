#pragma once
/// \file Geometric sanity check of hexahedra read from a deck (inverted or wrongly numbered).

#include <array>

#include <Eigen/Core>

#include "common/types.hpp"

namespace xpl::io {

/// The smallest corner Jacobian of a hexahedron and the corner (0..7) where it occurs.
struct CornerJacobian {
  Real determinant = 0.0;  ///< m^3: the volume of the parallelepiped spanned by the corner's edges
  int corner = 0;
};

/// Determinant of the trilinear map's Jacobian at each of the 8 corners of a hexahedron in
/// Abaqus C3D8R node order (x: corner coordinates, m), i.e. the triple product of the three
/// edges leaving the corner, oriented so that a well-numbered element gives positive values
/// everywhere. Returns the smallest.
CornerJacobian smallest_corner_jacobian(const std::array<Eigen::Vector3d, 8>& x);

}  // namespace xpl::io
