#include <catch2/catch.hpp>

#include <algorithm>
#include <set>

#include "partition/mesh_partition.hpp"

using namespace xpl;
using partition::MeshPartition;
using partition::Method;
using partition::PartitionInput;

namespace {

/// A structured block of nx × ny × nz hexes (node and element numbering x fastest), with a
/// weight per element, an optional rigid group and optional extra edges.
struct Block {
  Index nx, ny, nz;
  NodalVectors coordinates;
  std::vector<Index> offsets{0}, nodes;
  std::vector<Real> weight;
  std::vector<Index> group;
  std::vector<Index> node_group;
  std::vector<std::pair<Index, Index>> edges;

  Block(Index x, Index y, Index z) : nx(x), ny(y), nz(z) {
    const Index n_nodes = (nx + 1) * (ny + 1) * (nz + 1);
    coordinates.resize(n_nodes, 3);
    auto node = [&](Index i, Index j, Index k) { return i + (nx + 1) * (j + (ny + 1) * k); };
    for (Index k = 0; k <= nz; ++k)
      for (Index j = 0; j <= ny; ++j)
        for (Index i = 0; i <= nx; ++i) coordinates.row(node(i, j, k)) << i, j, k;
    for (Index k = 0; k < nz; ++k)
      for (Index j = 0; j < ny; ++j)
        for (Index i = 0; i < nx; ++i) {
          for (const Index n : {node(i, j, k), node(i + 1, j, k), node(i + 1, j + 1, k),
                                node(i, j + 1, k), node(i, j, k + 1), node(i + 1, j, k + 1),
                                node(i + 1, j + 1, k + 1), node(i, j + 1, k + 1)})
            nodes.push_back(n);
          offsets.push_back(static_cast<Index>(nodes.size()));
          // C3D8R and, every third element, a C3D8 (cost 2.2).
          weight.push_back(weight.size() % 3 == 0 ? 2.2 : 1.0);
        }
  }
  Index element_count() const { return static_cast<Index>(offsets.size()) - 1; }
  PartitionInput input() const {
    PartitionInput in;
    in.node_count = static_cast<Index>(coordinates.rows());
    in.element_offsets = offsets;
    in.element_nodes = nodes;
    in.element_weight = weight;
    in.coordinates = &coordinates;
    in.element_group = group;
    in.node_group = node_group;
    in.extra_edges = edges;
    return in;
  }
};

std::vector<Method> methods() {
  std::vector<Method> m{Method::Bisection};
  if (partition::metis_available()) m.push_back(Method::Metis);
  return m;
}

/// Interface nodes and per-part counts recomputed from the elements alone.
void check_consistent(const Block& b, const MeshPartition& p) {
  const Index n_nodes = static_cast<Index>(b.coordinates.rows());
  REQUIRE(p.element_part.size() == static_cast<std::size_t>(b.element_count()));
  std::vector<std::set<int>> parts_of(static_cast<std::size_t>(n_nodes));
  std::vector<Index> elements(static_cast<std::size_t>(p.parts), 0);
  for (Index e = 0; e < b.element_count(); ++e) {
    // Every element exactly once, on a valid part.
    REQUIRE(p.element_part[e] >= 0);
    REQUIRE(p.element_part[e] < p.parts);
    ++elements[p.element_part[e]];
    for (Index k = b.offsets[e]; k < b.offsets[e + 1]; ++k)
      parts_of[b.nodes[k]].insert(p.element_part[e]);
  }
  std::vector<Index> interface;
  std::vector<Index> interface_per_part(static_cast<std::size_t>(p.parts), 0);
  for (Index i = 0; i < n_nodes; ++i) {
    if (parts_of[i].size() >= 2) {
      interface.push_back(i);
      for (const int part : parts_of[i]) ++interface_per_part[part];
    }
    if (!parts_of[i].empty()) CHECK(p.node_owner[i] == *parts_of[i].begin());
  }
  CHECK(p.interface_nodes == interface);
  Index owned = 0, total = 0;
  for (int k = 0; k < p.parts; ++k) {
    CHECK(p.stats[k].elements == elements[k]);
    CHECK(p.stats[k].interface_nodes == interface_per_part[k]);
    owned += p.stats[k].owned_nodes;
    total += p.stats[k].elements;
  }
  CHECK(owned == n_nodes);  // every node owned exactly once
  CHECK(total == b.element_count());
}

}  // namespace

TEST_CASE("partition covers every element once; interface nodes are those of several parts",
          "[partition]") {
  const Block b(12, 8, 5);
  for (const Method method : methods())
    for (const int parts : {1, 2, 3, 4, 7}) {
      CAPTURE(partition::method_name(method), parts);
      const MeshPartition p = partition::partition_mesh(b.input(), parts, method);
      CHECK(p.method == method);
      check_consistent(b, p);
      if (parts == 1) CHECK(p.interface_nodes.empty());
      // Balanced within 10 % on a regular block (METIS' default tolerance is 3 %).
      CHECK(p.imbalance >= 1.0);
      CHECK(p.imbalance < 1.10);
      for (int k = 0; k < parts; ++k) CHECK(p.stats[k].elements > 0);
    }
}

TEST_CASE("bisection of a bar into two cuts across its length at the middle", "[partition]") {
  Block b(10, 1, 1);
  std::fill(b.weight.begin(), b.weight.end(), 1.0);
  const MeshPartition p = partition::partition_mesh(b.input(), 2, Method::Bisection);
  for (Index e = 0; e < 10; ++e) CHECK(p.element_part[e] == (e < 5 ? 0 : 1));
  // The four nodes of the plane x = 5.
  CHECK(p.interface_nodes == std::vector<Index>{5, 16, 27, 38});
  CHECK(p.imbalance == 1.0);
  CHECK(p.cut_edges == 1);
  CHECK(p.extra_pairs == 0);
}

TEST_CASE("a rigid body stays on one part and owns its reference node", "[partition]") {
  Block b(12, 6, 4);
  // The elements of the layer k = 0 are one rigid body (cost 0), spanning the whole block.
  b.group.assign(static_cast<std::size_t>(b.element_count()), NO_INDEX);
  for (Index e = 0; e < 12 * 6; ++e) {
    b.group[e] = 0;
    b.weight[e] = 0.0;
  }
  // A reference node no element holds.
  b.coordinates.conservativeResize(b.coordinates.rows() + 1, 3);
  b.coordinates.row(b.coordinates.rows() - 1) << 6.0, 3.0, -1.0;
  b.node_group.assign(static_cast<std::size_t>(b.coordinates.rows()), NO_INDEX);
  b.node_group.back() = 0;
  for (const Method method : methods())
    for (const int parts : {2, 3, 4}) {
      CAPTURE(partition::method_name(method), parts);
      const MeshPartition p = partition::partition_mesh(b.input(), parts, method);
      check_consistent(b, p);
      for (Index e = 1; e < 12 * 6; ++e) REQUIRE(p.element_part[e] == p.element_part[0]);
      CHECK(p.node_owner.back() == p.element_part[0]);
    }
}

TEST_CASE("the same input gives the same partition", "[partition]") {
  Block b(9, 7, 6);
  b.edges = {{0, 300}, {5, 377}, {100, 12}, {12, 100}, {3, 3}};
  for (const Method method : methods())
    for (const int parts : {2, 3, 5}) {
      CAPTURE(partition::method_name(method), parts);
      const MeshPartition first = partition::partition_mesh(b.input(), parts, method);
      for (int repeat = 0; repeat < 3; ++repeat) {
        const MeshPartition again = partition::partition_mesh(b.input(), parts, method);
        CHECK(again.element_part == first.element_part);
        CHECK(again.node_owner == first.node_owner);
      }
      check_consistent(b, first);
      // Duplicates (either order) and self pairs count once / not at all.
      CHECK(first.extra_pairs == 3);
      long cut = 0;
      for (const auto& [x, y] : {std::pair<Index, Index>{0, 300}, {5, 377}, {12, 100}})
        cut += first.element_part[x] != first.element_part[y];
      CHECK(first.cut_extra_pairs == cut);
    }
}

TEST_CASE("contact edges pull partners together under METIS", "[partition]") {
  if (!partition::metis_available()) return;
  // Two blocks side by side with no shared node, joined only by contact edges across their
  // facing layers: with 2 parts METIS cuts between them (no edge cut) when the edges are
  // missing; with them it may still cut there, but the cut counts the contact edges.
  Block b(8, 4, 4);
  const MeshPartition without = partition::partition_mesh(b.input(), 2, Method::Metis);
  for (Index e = 0; e < b.element_count(); e += 8) b.edges.emplace_back(e, e + 7);
  const MeshPartition with = partition::partition_mesh(b.input(), 2, Method::Metis);
  CHECK(with.graph_edges > without.graph_edges);
  CHECK(with.extra_pairs == 16);  // one per row of 8 elements
  CHECK(without.extra_pairs == 0);
  check_consistent(b, with);
}

TEST_CASE("partition refuses no parts and METIS without METIS", "[partition]") {
  const Block b(2, 2, 2);
  CHECK_THROWS_AS(partition::partition_mesh(b.input(), 0), std::invalid_argument);
  if (!partition::metis_available())
    CHECK_THROWS_AS(partition::partition_mesh(b.input(), 2, Method::Metis), std::invalid_argument);
  // More parts than elements: one element each, the rest empty.
  const MeshPartition p = partition::partition_mesh(b.input(), 10, Method::Bisection);
  check_consistent(b, p);
  CHECK(std::count(p.element_part.begin(), p.element_part.end(), 0) == 1);
}
