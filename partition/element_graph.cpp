#include "partition/element_graph.hpp"

#include <algorithm>

namespace xpl::partition {

ElementGraph build_element_graph(const PartitionInput& input) {
  const Index n_elements = static_cast<Index>(input.element_offsets.size()) - 1;
  ElementGraph g;
  // Vertices: elements without a group in element order, then one per group, numbered in
  // the order of the groups' first elements (deterministic).
  g.vertex_of_element.assign(static_cast<std::size_t>(std::max<Index>(n_elements, 0)), NO_INDEX);
  std::vector<Index> group_vertex;
  Index n_vertices = 0;
  for (Index e = 0; e < n_elements; ++e) {
    const Index group = input.element_group.empty() ? NO_INDEX : input.element_group[e];
    if (group == NO_INDEX) {
      g.vertex_of_element[e] = n_vertices++;
      continue;
    }
    if (group >= static_cast<Index>(group_vertex.size()))
      group_vertex.resize(static_cast<std::size_t>(group) + 1, NO_INDEX);
    if (group_vertex[group] == NO_INDEX) group_vertex[group] = n_vertices++;
    g.vertex_of_element[e] = group_vertex[group];
  }
  g.weight.assign(static_cast<std::size_t>(n_vertices), 0.0);
  g.centroid = NodalVectors::Zero(n_vertices, 3);
  std::vector<Index> members(static_cast<std::size_t>(n_vertices), 0);
  for (Index e = 0; e < n_elements; ++e) {
    const Index v = g.vertex_of_element[e];
    g.weight[v] += input.element_weight.empty() ? 1.0 : input.element_weight[e];
    const Index begin = input.element_offsets[e], end = input.element_offsets[e + 1];
    if (input.coordinates != nullptr && end > begin) {
      Eigen::Matrix<Real, 1, 3> c = Eigen::Matrix<Real, 1, 3>::Zero();
      for (Index k = begin; k < end; ++k) c += input.coordinates->row(input.element_nodes[k]);
      g.centroid.row(v) += c / static_cast<Real>(end - begin);
    }
    ++members[v];
  }
  for (Index v = 0; v < n_vertices; ++v)
    if (members[v] > 1) g.centroid.row(v) /= static_cast<Real>(members[v]);

  // Node -> vertices (CSR), then each vertex's neighbours: the vertices of its nodes.
  std::vector<Index> node_offsets(static_cast<std::size_t>(input.node_count) + 1, 0);
  for (Index e = 0; e < n_elements; ++e)
    for (Index k = input.element_offsets[e]; k < input.element_offsets[e + 1]; ++k)
      ++node_offsets[input.element_nodes[k] + 1];
  for (Index i = 0; i < input.node_count; ++i) node_offsets[i + 1] += node_offsets[i];
  std::vector<Index> node_vertices(static_cast<std::size_t>(node_offsets.back()));
  {
    std::vector<Index> fill(node_offsets.begin(), node_offsets.end() - 1);
    for (Index e = 0; e < n_elements; ++e)
      for (Index k = input.element_offsets[e]; k < input.element_offsets[e + 1]; ++k)
        node_vertices[fill[input.element_nodes[k]]++] = g.vertex_of_element[e];
  }
  // Extra edges per vertex (both directions).
  std::vector<std::vector<Index>> extra(static_cast<std::size_t>(n_vertices));
  for (const auto& [a, b] : input.extra_edges) {
    if (a < 0 || b < 0 || a >= n_elements || b >= n_elements) continue;
    const Index va = g.vertex_of_element[a], vb = g.vertex_of_element[b];
    if (va == vb) continue;
    extra[va].push_back(vb);
    extra[vb].push_back(va);
  }
  // Elements of each vertex (a group has several).
  std::vector<Index> vertex_elements_offsets(static_cast<std::size_t>(n_vertices) + 1, 0);
  for (Index e = 0; e < n_elements; ++e) ++vertex_elements_offsets[g.vertex_of_element[e] + 1];
  for (Index v = 0; v < n_vertices; ++v)
    vertex_elements_offsets[v + 1] += vertex_elements_offsets[v];
  std::vector<Index> vertex_elements(static_cast<std::size_t>(n_elements));
  {
    std::vector<Index> fill(vertex_elements_offsets.begin(), vertex_elements_offsets.end() - 1);
    for (Index e = 0; e < n_elements; ++e) vertex_elements[fill[g.vertex_of_element[e]]++] = e;
  }
  g.offsets.assign(1, 0);
  std::vector<Index> adjacent;
  for (Index v = 0; v < n_vertices; ++v) {
    adjacent.clear();
    for (Index m = vertex_elements_offsets[v]; m < vertex_elements_offsets[v + 1]; ++m) {
      const Index e = vertex_elements[m];
      for (Index k = input.element_offsets[e]; k < input.element_offsets[e + 1]; ++k) {
        const Index node = input.element_nodes[k];
        adjacent.insert(adjacent.end(), node_vertices.begin() + node_offsets[node],
                        node_vertices.begin() + node_offsets[node + 1]);
      }
    }
    adjacent.insert(adjacent.end(), extra[v].begin(), extra[v].end());
    std::sort(adjacent.begin(), adjacent.end());
    adjacent.erase(std::unique(adjacent.begin(), adjacent.end()), adjacent.end());
    for (const Index w : adjacent)
      if (w != v) g.neighbours.push_back(w);
    g.offsets.push_back(static_cast<Index>(g.neighbours.size()));
  }
  return g;
}

}  // namespace xpl::partition
