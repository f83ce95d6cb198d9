#pragma once
/// \file The weighted element graph that partition_mesh() splits: one vertex per element
/// outside a group and one per group (a rigid body, contracted so that it cannot be cut),
/// an edge between vertices whose elements share a node or are contact partners.

#include <vector>

#include "partition/mesh_partition.hpp"

namespace xpl::partition {

/// Symmetric graph in CSR form (no self edges, neighbours ascending), with vertex weights
/// and the centroid of each vertex for the bisection.
struct ElementGraph {
  std::vector<Index> vertex_of_element;  ///< (n_elements)
  std::vector<Index> offsets;            ///< (n_vertices + 1) into neighbours
  std::vector<Index> neighbours;         ///< adjacent vertices, ascending per vertex
  std::vector<Real> weight;              ///< (n_vertices), sum of its elements' weights
  NodalVectors centroid;                 ///< (n_vertices × 3): weighted by element count, m
  Index vertex_count() const { return static_cast<Index>(weight.size()); }
};

/// Builds the graph of `input` (contracting its groups, adding its extra edges).
ElementGraph build_element_graph(const PartitionInput& input);

}  // namespace xpl::partition
