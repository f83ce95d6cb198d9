#pragma once
/// \file Geometric sanity checks of elements read from a deck: inverted or wrongly numbered
/// hexahedra, degenerate (collapsed, zero-area, crossed) quadrilateral shells.

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

/// Size and shape measures of a 4-node quadrilateral (Abaqus S4R node order), which need
/// not be planar.
struct QuadShape {
  /// m^2: |(x3 − x1) × (x4 − x2)| / 2, the area projected on the element normal
  /// n = (x3 − x1) × (x4 − x2) (exact for a planar quadrilateral).
  Real area = 0.0;
  Real longest_edge = 0.0;      ///< m
  Real shortest_edge = 0.0;     ///< m
  int shortest_edge_start = 0;  ///< the shortest edge runs from this corner (0..3) to the next
  /// m^2: (x_next − x_k) × (x_previous − x_k) · n / |n| at each corner k: positive at every
  /// corner of a convex quadrilateral, negative at the corner where it is concave and at two
  /// corners of a crossed ("bow-tie") one. All 0 if the area is 0.
  std::array<Real, 4> corner{};
};

/// Shape measures of the quadrilateral with corner coordinates x (m).
QuadShape quad_shape(const std::array<Eigen::Vector3d, 4>& x);

}  // namespace xpl::io
