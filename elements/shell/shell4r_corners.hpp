#pragma once
/// \file The corner coordinates of a shell element, for the S4R sources outside the kernel
/// (shell4r_setup.cpp, shell4r_output.cpp).

#include "common/types.hpp"
#include "elements/vec3.hpp"

namespace xpl::elements {

/// Coordinates of the 4 `nodes` in `position` (n_nodes × 3, m).
template <class T>
inline void gather_corners(const NodalVectors& position, const Index* nodes, V3<T> p[4]) {
  for (int a = 0; a < 4; ++a)
    p[a] = {position(nodes[a], 0), position(nodes[a], 1), position(nodes[a], 2)};
}

}  // namespace xpl::elements
