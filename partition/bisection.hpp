#pragma once
/// \file Recursive coordinate bisection: the fallback partitioner when the build has no
/// METIS. Cuts the vertex centroids across the longest side of their box at the weight that
/// gives each half its share of the parts, recursively; ties in the coordinate are broken by
/// vertex number, so the result depends on the input only. Ignores the graph's edges (contact
/// partners may land on different parts; METIS keeps them together).

#include <vector>

#include "partition/element_graph.hpp"

namespace xpl::partition {

/// Part (0 .. parts − 1) of each vertex of `graph`.
std::vector<int> bisect(const ElementGraph& graph, int parts);

}  // namespace xpl::partition
