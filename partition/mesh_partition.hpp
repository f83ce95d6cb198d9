#pragma once
/// \file Domain decomposition of the mesh for distributed runs (issue 37 item 2): the
/// elements split into parts of about equal cost, elements that share nodes or are contact
/// partners at t = 0 kept together, each rigid body whole. METIS (`METIS_PartGraphKway`)
/// when the build has it (XPL_MPI=ON), else recursive coordinate bisection; both
/// deterministic (same input, same partition).
///
/// The partition is of elements; a node belongs to every part that has one of its elements
/// (an interface node when that is two or more) and is owned by the lowest of them.

#include <span>
#include <string>
#include <utility>
#include <vector>

#include "common/types.hpp"

namespace xpl::partition {

/// How the parts are found.
enum class Method {
  Automatic,  ///< METIS when built in, else Bisection
  Metis,      ///< METIS_PartGraphKway on the weighted element graph (needs XPL_MPI=ON)
  Bisection,  ///< recursive coordinate bisection of the element centroids, weighted
};

/// Whether this build has METIS (XPL_MPI=ON).
bool metis_available();

/// What is partitioned: the elements of a mesh (not owned; must outlive the call).
struct PartitionInput {
  Index node_count = 0;
  std::span<const Index> element_offsets;  ///< (n_elements + 1) into element_nodes
  std::span<const Index> element_nodes;    ///< node indices of every element, CSR
  /// Relative cost of each element (n_elements, ≥ 0; solver/model_partition.hpp); empty:
  /// all 1.
  std::span<const Real> element_weight;
  /// Reference coordinates (n_nodes × 3), m: the bisection cuts along them.
  const NodalVectors* coordinates = nullptr;
  /// Group of each element that must stay on one part (n_elements; a rigid body), NO_INDEX
  /// for none; empty: no groups.
  std::span<const Index> element_group;
  /// Group of nodes no element holds (a rigid body's reference node), so that they are owned
  /// where their group's elements are (n_nodes, NO_INDEX for none; empty: none). Other nodes
  /// without an element are owned by part 0.
  std::span<const Index> node_group;
  /// Extra graph edges between elements (contact partners of the t = 0 search: the element
  /// of a slave node and that of a candidate master face); duplicates and self edges allowed.
  std::span<const std::pair<Index, Index>> extra_edges;
};

/// Per part: its elements, nodes and cost.
struct PartStats {
  Index elements = 0;
  Index owned_nodes = 0;      ///< nodes owned (the lowest part using them is this one)
  Index interface_nodes = 0;  ///< nodes used by this part and at least one other
  Real weight = 0.0;          ///< sum of element weights
  /// The exchange of an increment (exchange_plan.hpp), parts > 1 only: the parts it shares
  /// nodes with, those nodes counted once per neighbour, and the contribution slots it sends
  /// them (every element corner of this part at a node a neighbour uses, once per neighbour).
  Index neighbours = 0;
  Index shared_nodes = 0;
  Index send_slots = 0;
};

/// The result of partition_mesh().
struct MeshPartition {
  int parts = 1;
  Method method = Method::Bisection;  ///< the method used (never Automatic)
  std::vector<int> element_part;      ///< part of each element (n_elements)
  std::vector<int> node_owner;        ///< owning part of each node (n_nodes)
  /// Nodes used by elements of two or more parts, ascending.
  std::vector<Index> interface_nodes;
  std::vector<PartStats> stats;  ///< (parts)
  /// Largest part weight over the mean part weight (1 = perfect balance).
  Real imbalance = 1.0;
  /// Graph edges cut (element pairs in different parts, contact edges included), for quality.
  long cut_edges = 0;
  long graph_edges = 0;  ///< undirected edges of the (contracted) element graph
  /// Distinct element pairs of the input's extra edges (contact, tie partners; self pairs
  /// left out) and how many of them lie across parts: what the contact exchange will carry.
  long extra_pairs = 0;
  long cut_extra_pairs = 0;
};

/// Splits the elements of `input` into `parts` (≥ 1) parts with `method`. Throws
/// std::invalid_argument for parts < 1, or Method::Metis without METIS.
MeshPartition partition_mesh(const PartitionInput& input, int parts,
                             Method method = Method::Automatic);

/// Name of a method ("METIS", "bisection").
const char* method_name(Method method);

/// The partition as .msg lines: one summary line and one per part.
std::vector<std::string> partition_report(const MeshPartition& partition, double seconds);

}  // namespace xpl::partition
