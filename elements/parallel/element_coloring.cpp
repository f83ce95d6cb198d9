#include "elements/parallel/element_coloring.hpp"

#include <algorithm>

namespace xpl::elements {

std::vector<int> color_elements(const std::vector<Index>& connectivity, int nodes_per_element,
                                Index node_count) {
  const auto n_elements = static_cast<Index>(connectivity.size() / nodes_per_element);
  // Node -> elements (CSR).
  std::vector<Index> start(static_cast<std::size_t>(node_count) + 1, 0);
  for (Index n : connectivity) ++start[static_cast<std::size_t>(n) + 1];
  for (Index i = 0; i < node_count; ++i) start[i + 1] += start[i];
  std::vector<Index> fill(start.begin(), start.end() - 1);
  std::vector<Index> node_elements(connectivity.size());
  for (Index e = 0; e < n_elements; ++e)
    for (int a = 0; a < nodes_per_element; ++a)
      node_elements[fill[connectivity[e * nodes_per_element + a]]++] = e;

  std::vector<int> color(n_elements, -1);
  std::vector<Index> seen_by;  // seen_by[c] == e: colour c is taken by a neighbour of e
  for (Index e = 0; e < n_elements; ++e) {
    for (int a = 0; a < nodes_per_element; ++a) {
      const Index n = connectivity[e * nodes_per_element + a];
      for (Index k = start[n]; k < start[n + 1]; ++k) {
        const int c = color[node_elements[k]];
        if (c < 0) continue;
        if (static_cast<std::size_t>(c) >= seen_by.size()) seen_by.resize(c + 1, -1);
        seen_by[c] = e;
      }
    }
    int c = 0;
    while (static_cast<std::size_t>(c) < seen_by.size() && seen_by[c] == e) ++c;
    color[e] = c;
  }
  return color;
}

BatchLayout make_batches(const std::vector<Index>& connectivity, int nodes_per_element,
                         Index node_count, int lanes) {
  const std::vector<int> color = color_elements(connectivity, nodes_per_element, node_count);
  const int n_colors = color.empty() ? 0 : *std::max_element(color.begin(), color.end()) + 1;
  // Elements of each colour in their original order (keeps some locality), then batches.
  std::vector<std::vector<Index>> by_color(n_colors);
  for (std::size_t e = 0; e < color.size(); ++e)
    by_color[color[e]].push_back(static_cast<Index>(e));
  BatchLayout layout;
  for (const auto& members : by_color) {
    const auto batches = static_cast<Index>((members.size() + lanes - 1) / lanes);
    for (Index b = 0; b < batches; ++b)
      for (int l = 0; l < lanes; ++l) {
        const std::size_t k = static_cast<std::size_t>(b) * lanes + l;
        layout.lane_owner.push_back(k < members.size() ? members[k] : NO_INDEX);
      }
    layout.color_batches.push_back(layout.color_batches.back() + batches);
  }
  return layout;
}

}  // namespace xpl::elements
