#pragma once
/// \file The element graph handed to METIS (`METIS_PartGraphKway`, built with XPL_MPI=ON).

#include <vector>

#include "partition/element_graph.hpp"

namespace xpl::partition {

/// Part (0 .. parts − 1) of each vertex of `graph` from METIS k-way with a fixed seed;
/// vertex weights are the graph's weights in hundredths (at least 1). Throws
/// std::runtime_error when METIS fails or is not built in.
std::vector<int> metis_parts(const ElementGraph& graph, int parts);

}  // namespace xpl::partition
