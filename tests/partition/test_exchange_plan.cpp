#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>
#include <random>
#include <set>
#include <string>

#include "partition/exchange_plan.hpp"

using namespace xpl;
using partition::ExchangePlan;
using partition::MeshPartition;
using partition::PartitionInput;

namespace {

constexpr int WIDTH = 3;  // force components per slot and per node

/// A random mesh: elements of 2, 3, 4 or 8 nodes (a corner may repeat a node, as a collapsed
/// hex does), nodes picked near the element's place along a line so that parts have
/// interiors and interfaces, some nodes unused; random coordinates for the bisection.
struct RandomMesh {
  Index node_count = 0;
  std::vector<Index> offsets{0}, nodes;
  NodalVectors coordinates;

  explicit RandomMesh(std::mt19937& rng) {
    node_count = std::uniform_int_distribution<Index>(20, 300)(rng);
    const Index n_elements = std::uniform_int_distribution<Index>(5, 250)(rng);
    const int sizes[] = {2, 3, 4, 8, 8, 8};
    std::uniform_int_distribution<int> size_pick(0, 5);
    std::uniform_int_distribution<Index> spread(-6, 6);
    for (Index e = 0; e < n_elements; ++e) {
      const Index centre = static_cast<Index>(static_cast<long long>(e) * node_count / n_elements);
      for (int a = 0, n = sizes[size_pick(rng)]; a < n; ++a)
        nodes.push_back(std::clamp<Index>(centre + spread(rng), 0, node_count - 1));
      offsets.push_back(static_cast<Index>(nodes.size()));
    }
    coordinates.resize(node_count, 3);
    std::uniform_real_distribution<Real> jitter(-0.5, 0.5);
    for (Index n = 0; n < node_count; ++n)
      coordinates.row(n) << static_cast<Real>(n) + 3.0 * jitter(rng), jitter(rng), jitter(rng);
  }
  Index element_count() const { return static_cast<Index>(offsets.size()) - 1; }
  PartitionInput input() const {
    PartitionInput in;
    in.node_count = node_count;
    in.element_offsets = offsets;
    in.element_nodes = nodes;
    in.coordinates = &coordinates;
    return in;
  }
};

/// A partition with a random part per element (the worst case: interfaces everywhere), each
/// node owned by the lowest part using it (part 0 when no element uses it).
MeshPartition random_partition(const RandomMesh& mesh, int parts, std::mt19937& rng) {
  MeshPartition p;
  p.parts = parts;
  std::uniform_int_distribution<int> pick(0, parts - 1);
  for (Index e = 0; e < mesh.element_count(); ++e) p.element_part.push_back(pick(rng));
  p.node_owner.assign(static_cast<std::size_t>(mesh.node_count), parts);
  for (Index e = 0; e < mesh.element_count(); ++e)
    for (Index k = mesh.offsets[e]; k < mesh.offsets[e + 1]; ++k)
      p.node_owner[mesh.nodes[k]] = std::min(p.node_owner[mesh.nodes[k]], p.element_part[e]);
  for (int& owner : p.node_owner)
    if (owner == parts) owner = 0;
  std::vector<std::set<int>> users(static_cast<std::size_t>(mesh.node_count));
  for (Index e = 0; e < mesh.element_count(); ++e)
    for (Index k = mesh.offsets[e]; k < mesh.offsets[e + 1]; ++k)
      users[mesh.nodes[k]].insert(p.element_part[e]);
  for (Index n = 0; n < mesh.node_count; ++n)
    if (users[n].size() > 1) p.interface_nodes.push_back(n);
  return p;
}

/// Random slot values of widely different magnitudes, so that the order of a sum shows in
/// its bits.
std::vector<Real> random_values(std::size_t n_slots, std::mt19937& rng) {
  std::uniform_real_distribution<Real> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-30, 30);
  std::vector<Real> v(n_slots * WIDTH);
  for (Real& x : v) x = std::ldexp(mantissa(rng), exponent(rng));
  return v;
}

/// A random order rank per element (a permutation).
std::vector<Index> random_ranks(Index n_elements, std::mt19937& rng) {
  std::vector<Index> rank(static_cast<std::size_t>(n_elements));
  std::iota(rank.begin(), rank.end(), 0);
  std::shuffle(rank.begin(), rank.end(), rng);
  return rank;
}

bool same_bits(Real a, Real b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

/// Simulates the distributed assembly of `plan` in one process: each part sees only its own
/// elements' slot values (the others NaN), packs its send buffers, receives its neighbours',
/// and sums its nodes. Checks every part's rows bitwise against `reference`; returns the
/// number of (part, node) rows compared.
long check_parts(const ExchangePlan& plan, const PartitionInput& input,
                 const MeshPartition& partition, const std::vector<Real>& values,
                 const std::vector<Real>& reference) {
  const Index n_elements = static_cast<Index>(input.element_offsets.size()) - 1;
  std::vector<std::vector<Real>> own(static_cast<std::size_t>(plan.parts));
  for (int p = 0; p < plan.parts; ++p) {
    own[p].assign(values.size(), std::numeric_limits<Real>::quiet_NaN());
    for (Index e = 0; e < n_elements; ++e)
      if (partition.element_part[e] == p)
        for (Index k = input.element_offsets[e]; k < input.element_offsets[e + 1]; ++k)
          for (int c = 0; c < WIDTH; ++c) own[p][k * WIDTH + c] = values[k * WIDTH + c];
  }
  long rows = 0;
  for (int p = 0; p < plan.parts; ++p) {
    const partition::PartPlan& pp = plan.part[p];
    std::vector<std::vector<Real>> received;
    for (const partition::NeighbourExchange& x : pp.neighbours) {
      const auto& back = plan.part[x.part].neighbours;
      const auto it =
          std::find_if(back.begin(), back.end(), [p](const auto& y) { return y.part == p; });
      REQUIRE(it != back.end());
      received.push_back(
          partition::pack(plan, x.part, static_cast<int>(it - back.begin()), own[x.part], WIDTH));
      REQUIRE(received.back().size() == static_cast<std::size_t>(x.receive_count) * WIDTH);
    }
    std::vector<Real> nodal(reference.size(), std::numeric_limits<Real>::quiet_NaN());
    partition::assemble_part(plan, p, own[p], received, WIDTH, nodal);
    for (const Index n : pp.nodes) {
      for (int c = 0; c < WIDTH; ++c)
        if (!same_bits(nodal[n * WIDTH + c], reference[n * WIDTH + c])) {
          FAIL_CHECK("part " << p << " of " << plan.parts << ", node " << n << ": "
                             << nodal[n * WIDTH + c] << " != " << reference[n * WIDTH + c]);
          return rows;
        }
      ++rows;
    }
  }
  return rows;
}

}  // namespace

TEST_CASE("assembling on 1 to 4 parts gives the bits of one part", "[partition][exchange]") {
  std::mt19937 rng(37);
  long rows = 0, interface_rows = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const RandomMesh mesh(rng);
    const PartitionInput input = mesh.input();
    const std::vector<Real> values = random_values(mesh.nodes.size(), rng);
    // By element number, and by a random order rank (as the colour order of a pass would be).
    const std::vector<Index> ranks = random_ranks(mesh.element_count(), rng);
    for (const bool ranked : {false, true}) {
      const std::span<const Index> rank =
          ranked ? std::span<const Index>(ranks) : std::span<const Index>();
      std::vector<Real> reference(static_cast<std::size_t>(mesh.node_count) * WIDTH);
      partition::assemble(partition::make_slot_order(input, rank), values, WIDTH, reference);
      for (int parts = 1; parts <= 4; ++parts)
        for (const bool random : {false, true}) {
          const MeshPartition partition =
              random ? random_partition(mesh, parts, rng)
                     : partition::partition_mesh(input, parts, partition::Method::Bisection);
          const ExchangePlan plan = partition::make_exchange_plan(input, partition, rank);
          rows += check_parts(plan, input, partition, values, reference);
          for (const auto& pp : plan.part)
            interface_rows += static_cast<long>(pp.interface_nodes.size());
        }
    }
  }
  // Many nodes were summed across parts, not only inside one.
  CHECK(interface_rows > 10000);
  CHECK(rows > 50000);
}

TEST_CASE("the random sums are order-sensitive: per-part partial sums differ",
          "[partition][exchange]") {
  // What the test above guards against: adding each part's partial sum gives other bits.
  std::mt19937 rng(5);
  long differing = 0, interface_nodes = 0;
  for (int trial = 0; trial < 10; ++trial) {
    const RandomMesh mesh(rng);
    const PartitionInput input = mesh.input();
    const std::vector<Real> values = random_values(mesh.nodes.size(), rng);
    const MeshPartition partition = random_partition(mesh, 3, rng);
    const ExchangePlan plan = partition::make_exchange_plan(input, partition);
    std::vector<Real> reference(static_cast<std::size_t>(mesh.node_count) * WIDTH);
    partition::assemble(plan.order, values, WIDTH, reference);
    for (Index n = 0; n < mesh.node_count; ++n) {
      Real partial[3] = {0.0, 0.0, 0.0};
      std::set<int> users;
      for (Index k = plan.order.node_start[n]; k < plan.order.node_start[n + 1]; ++k) {
        const Index s = plan.order.slots[k];
        const auto e =
            static_cast<Index>(std::upper_bound(mesh.offsets.begin(), mesh.offsets.end(), s) -
                               mesh.offsets.begin() - 1);
        users.insert(partition.element_part[e]);
        partial[partition.element_part[e]] += values[s * WIDTH];
      }
      if (users.size() < 2) continue;
      ++interface_nodes;
      if (!same_bits(partial[0] + partial[1] + partial[2], reference[n * WIDTH])) ++differing;
    }
  }
  CHECK(interface_nodes > 500);
  CHECK(differing > interface_nodes / 10);
}

TEST_CASE("a ranked slot order is the order of a scatter in rank order", "[partition][exchange]") {
  // The one-thread element pass scatters colour after colour (elements/element_coloring.hpp);
  // with the elements' colour-major position as the rank, the slot sums are today's sums.
  std::mt19937 rng(11);
  const RandomMesh mesh(rng);
  const PartitionInput input = mesh.input();
  const std::vector<Real> values = random_values(mesh.nodes.size(), rng);
  const std::vector<Index> rank = random_ranks(mesh.element_count(), rng);
  std::vector<Index> by_rank(rank.size());
  for (Index e = 0; e < mesh.element_count(); ++e) by_rank[rank[e]] = e;
  std::vector<Real> scattered(static_cast<std::size_t>(mesh.node_count) * WIDTH, 0.0);
  for (const Index e : by_rank)
    for (Index k = mesh.offsets[e]; k < mesh.offsets[e + 1]; ++k)
      for (int c = 0; c < WIDTH; ++c) scattered[mesh.nodes[k] * WIDTH + c] += values[k * WIDTH + c];
  std::vector<Real> summed(scattered.size());
  partition::assemble(partition::make_slot_order(input, rank), values, WIDTH, summed);
  for (std::size_t i = 0; i < summed.size(); ++i) REQUIRE(same_bits(summed[i], scattered[i]));
}

TEST_CASE("the exchange plan is symmetric and covers every contribution", "[partition][exchange]") {
  std::mt19937 rng(3);
  const RandomMesh mesh(rng);
  const PartitionInput input = mesh.input();
  for (int parts = 2; parts <= 4; ++parts) {
    const MeshPartition partition = random_partition(mesh, parts, rng);
    const ExchangePlan plan = partition::make_exchange_plan(input, partition);
    std::set<Index> interface;
    Index owned = 0;
    for (int p = 0; p < parts; ++p) {
      const partition::PartPlan& pp = plan.part[p];
      owned += static_cast<Index>(pp.owned.size());
      interface.insert(pp.interface_nodes.begin(), pp.interface_nodes.end());
      for (const Index n : pp.owned) CHECK(partition.node_owner[n] == p);
      for (std::size_t k = 0; k < pp.interface_nodes.size(); ++k) {
        const Index n = pp.interface_nodes[k];
        // Every contribution to the node, once.
        CHECK(pp.combine_start[k + 1] - pp.combine_start[k] ==
              plan.order.node_start[n + 1] - plan.order.node_start[n]);
      }
      for (const partition::NeighbourExchange& x : pp.neighbours) {
        CHECK(x.part != p);
        const auto& back = plan.part[x.part].neighbours;
        const auto it =
            std::find_if(back.begin(), back.end(), [p](const auto& y) { return y.part == p; });
        REQUIRE(it != back.end());
        CHECK(it->nodes == x.nodes);
        CHECK(it->receive_count == static_cast<Index>(x.send.size()));
        CHECK(x.receive_count == static_cast<Index>(it->send.size()));
      }
    }
    CHECK(owned == mesh.node_count);
    CHECK(std::vector<Index>(interface.begin(), interface.end()) == partition.interface_nodes);
  }
}

TEST_CASE("the partition reports the exchange of a plane cut", "[partition][exchange]") {
  // 4 × 2 × 2 unit hexes cut by the bisection at x = 2: 3 × 3 = 9 shared nodes; part 0 has at
  // them 4 corner nodes of 1 element, 4 edge nodes of 2 and the centre of 4: 16 slots.
  const Index nx = 4, ny = 2, nz = 2;
  const auto node = [&](Index i, Index j, Index k) { return i + (nx + 1) * (j + (ny + 1) * k); };
  NodalVectors coordinates((nx + 1) * (ny + 1) * (nz + 1), 3);
  for (Index k = 0; k <= nz; ++k)
    for (Index j = 0; j <= ny; ++j)
      for (Index i = 0; i <= nx; ++i) coordinates.row(node(i, j, k)) << i, j, k;
  std::vector<Index> offsets{0}, nodes;
  for (Index k = 0; k < nz; ++k)
    for (Index j = 0; j < ny; ++j)
      for (Index i = 0; i < nx; ++i) {
        for (const Index n : {node(i, j, k), node(i + 1, j, k), node(i + 1, j + 1, k),
                              node(i, j + 1, k), node(i, j, k + 1), node(i + 1, j, k + 1),
                              node(i + 1, j + 1, k + 1), node(i, j + 1, k + 1)})
          nodes.push_back(n);
        offsets.push_back(static_cast<Index>(nodes.size()));
      }
  PartitionInput input;
  input.node_count = static_cast<Index>(coordinates.rows());
  input.element_offsets = offsets;
  input.element_nodes = nodes;
  input.coordinates = &coordinates;
  const MeshPartition p = partition::partition_mesh(input, 2, partition::Method::Bisection);
  for (int k = 0; k < 2; ++k) {
    CHECK(p.stats[k].neighbours == 1);
    CHECK(p.stats[k].shared_nodes == 9);
    CHECK(p.stats[k].send_slots == 16);
  }
  const std::vector<std::string> report = partition::partition_report(p, 0.0);
  REQUIRE(report.size() == 3);
  CHECK(report[1].find("1 neighbours, 9 shared nodes, 16 force slots sent (0.4 kB)") !=
        std::string::npos);
  // One part: nothing to exchange.
  const MeshPartition one = partition::partition_mesh(input, 1, partition::Method::Bisection);
  CHECK(one.stats[0].send_slots == 0);
}

TEST_CASE("an element of no part (a rigid body's) has no slots in the exchange",
          "[partition][exchange]") {
  // Two-node elements: e0 = (0, 1) in part 0, e1 = (1, 2) in no part, e2 = (2, 3) in part 1,
  // e3 = (1, 4) in part 1. Node 2 is used by part 1 only (e1 is in no part): not an interface
  // node; node 1 is shared by parts 0 and 1 through e0 and e3, and e1's corner there is
  // neither combined nor sent.
  const std::vector<Index> offsets{0, 2, 4, 6, 8}, nodes{0, 1, 1, 2, 2, 3, 1, 4};
  PartitionInput input;
  input.node_count = 5;
  input.element_offsets = offsets;
  input.element_nodes = nodes;
  MeshPartition p;
  p.parts = 2;
  p.element_part = {0, -1, 1, 1};
  p.node_owner = {0, 0, 1, 1, 1};
  const ExchangePlan plan = partition::make_exchange_plan(input, p);
  CHECK(plan.part[0].elements == std::vector<Index>{0});
  CHECK(plan.part[1].elements == std::vector<Index>{2, 3});
  CHECK(plan.part[0].nodes == std::vector<Index>{0, 1});
  CHECK(plan.part[1].nodes == std::vector<Index>{1, 2, 3, 4});
  for (int k = 0; k < 2; ++k) {
    CHECK(plan.part[k].interface_nodes == std::vector<Index>{1});
    REQUIRE(plan.part[k].neighbours.size() == 1);
    CHECK(plan.part[k].neighbours[0].send.size() == 1);  // its one corner at node 1
    REQUIRE(plan.part[k].combine_start == std::vector<Index>{0, 2});
    for (const partition::SlotSource& s : plan.part[k].combine)
      CHECK((s.neighbour >= 0 || s.index == (k == 0 ? 1 : 6)));  // e0's or e3's corner
  }
}
