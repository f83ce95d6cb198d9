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

/// Elements grouped into batches of `lanes` elements of one colour.
struct BatchLayout {
  /// Block element of each lane ([batch][lane]); NO_INDEX marks padding lanes.
  std::vector<Index> lane_owner;
  /// Batches of colour c are [color_batches[c], color_batches[c + 1]).
  std::vector<Index> color_batches{0};
  Index batch_count() const { return color_batches.back(); }
};

/// Colours the elements (flat connectivity, n_elements × nodes_per_element) and packs each
/// colour, in element order, into batches of `lanes`.
BatchLayout make_batches(const std::vector<Index>& connectivity, int nodes_per_element,
                         Index node_count, int lanes);

}  // namespace xpl::elements
