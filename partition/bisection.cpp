#include "partition/bisection.hpp"

#include <algorithm>
#include <numeric>

namespace xpl::partition {

namespace {

/// Assigns the vertices [first, last) of `order` to parts first_part .. first_part + parts − 1.
void split(const ElementGraph& g, std::vector<Index>::iterator first,
           std::vector<Index>::iterator last, int first_part, int parts, std::vector<int>& out) {
  if (parts == 1 || last - first <= 1) {
    for (auto it = first; it != last; ++it) out[*it] = first_part;
    return;
  }
  Eigen::Matrix<Real, 1, 3> low = g.centroid.row(*first), high = low;
  for (auto it = first; it != last; ++it) {
    low = low.cwiseMin(g.centroid.row(*it));
    high = high.cwiseMax(g.centroid.row(*it));
  }
  int axis = 0;
  for (int c = 1; c < 3; ++c)
    if (high(c) - low(c) > high(axis) - low(axis)) axis = c;
  std::sort(first, last, [&](Index a, Index b) {
    const Real ca = g.centroid(a, axis), cb = g.centroid(b, axis);
    return ca < cb || (ca == cb && a < b);
  });
  const int low_parts = parts / 2;
  Real total = 0.0;
  for (auto it = first; it != last; ++it) total += g.weight[*it];
  const Real target = total * low_parts / parts;
  // The cut nearest the target weight, at least one vertex on each side.
  Real before = 0.0;
  auto cut = first;
  while (cut != last && before + g.weight[*cut] <= target) before += g.weight[*cut++];
  if (cut != last && (before + g.weight[*cut]) - target < target - before) ++cut;
  cut = std::clamp(cut, first + 1, last - 1);
  split(g, first, cut, first_part, low_parts, out);
  split(g, cut, last, first_part + low_parts, parts - low_parts, out);
}

}  // namespace

std::vector<int> bisect(const ElementGraph& graph, int parts) {
  std::vector<int> part(static_cast<std::size_t>(graph.vertex_count()), 0);
  std::vector<Index> order(static_cast<std::size_t>(graph.vertex_count()));
  std::iota(order.begin(), order.end(), Index{0});
  split(graph, order.begin(), order.end(), 0, parts, part);
  return part;
}

}  // namespace xpl::partition
