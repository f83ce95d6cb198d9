#pragma once
/// \file Greedy colouring of elements so that no two elements of one colour share a node.
/// Elements of one colour can scatter their nodal forces in parallel without races, and
/// every node receives its contributions in colour order whatever the thread count.

#include <vector>

#include "common/types.hpp"

namespace xpl::elements {

/// Colour of each element (0-based) for elements given by flat connectivity with a fixed
/// number of nodes per element (n_elements × nodes_per_element node indices).
std::vector<int> color_elements(const std::vector<Index>& connectivity, int nodes_per_element,
                                Index node_count);

}  // namespace xpl::elements
