// The per-thread partition of the element pass (elements/parallel/thread_partition.hpp): forces do
// not depend on the number of parts, bit for bit, and the exchange slots keep every node's
// contributions in batch order.
#include <catch2/catch.hpp>

#include <numeric>
#include <random>

#include <omp.h>
#include <Eigen/Dense>

#include "elements/hex/hex8.hpp"
#include "elements/hex/hex8r.hpp"
#include "elements/parallel/thread_partition.hpp"
#include "elements/shell/shell4r.hpp"
#include "hex_fixtures.hpp"

using namespace xpl;
using namespace xpl::elements;

namespace {

NodalVectors random_field(Index rows, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<Real> d(-1.0, 1.0);
  NodalVectors v(rows, 3);
  for (Index i = 0; i < rows; ++i)
    for (int c = 0; c < 3; ++c) v(i, c) = d(rng);
  return v;
}

template <class Block>
Block hex_block(const test::HexBlockMesh& mesh) {
  const auto n = static_cast<Index>(mesh.connectivity.size() / 8);
  std::vector<Index> ids(n);
  std::iota(ids.begin(), ids.end(), 0);
  std::vector<HexMaterial> mats(n, HexMaterial{7850.0, 200e9, 0.3, HourglassForm::Stiffness, 1.0});
  return Block(ids, mesh.connectivity, mats, static_cast<Index>(mesh.coordinates.rows()));
}

/// An n × n grid of slightly warped quads (side 10 mm), nodes row by row.
struct Plate {
  NodalVectors x;
  std::vector<Index> conn;
};

Plate plate(int n) {
  Plate p;
  const int m = n + 1;
  p.x = 1e-3 * random_field(m * m, 3);
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < m; ++i) {
      p.x(i + m * j, 0) += 0.01 * i;
      p.x(i + m * j, 1) += 0.01 * j;
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const Index a = i + m * j;
      for (Index k : {a, a + 1, a + 1 + m, a + m}) p.conn.push_back(k);
    }
  return p;
}

Shell4rBlock shell_block(const Plate& p) {
  const auto n = static_cast<Index>(p.conn.size() / 4);
  std::vector<Index> ids(n);
  std::iota(ids.begin(), ids.end(), 0);
  const ShellProperties props{7850.0, 200e9, 0.3, 0.002, 5, 0.0, 1.0};
  return Shell4rBlock(ids, p.conn, std::vector<ShellProperties>(n, props),
                      static_cast<Index>(p.x.rows()));
}

/// Runs `pass` with `threads` OpenMP threads (the parts of the pass) and restores the default.
template <class Pass>
void with_threads(int threads, Pass&& pass) {
  const int saved = omp_get_max_threads();
  omp_set_num_threads(threads);
  pass();
  omp_set_num_threads(saved);
}

}  // namespace

TEMPLATE_TEST_CASE("hex forces are bitwise the same with 1, 2 and 3 parts",
                   "[elements][hex][threads]", Hex8rBlock, Hex8Block) {
  // 12³ elements: 8 colours of 27 batches, so every part has batches in every colour.
  const auto mesh = test::make_block(12, 0.01, 0.2);
  const NodalVectors v = random_field(mesh.coordinates.rows(), 1);
  const NodalVectors x = mesh.coordinates + 1e-7 * v;
  std::vector<NodalVectors> forces;
  std::vector<HexStepTotals> totals;
  for (int parts : {1, 2, 3}) {
    auto block = hex_block<TestType>(mesh);
    NodalVectors f = NodalVectors::Zero(x.rows(), 3);
    HexStepTotals t;
    // Two increments: the second starts from the state the first left.
    with_threads(parts, [&] {
      block.internal_forces(x, v, 1e-7, 0.06, 1.2, f, t);
      f.setZero();
      t = HexStepTotals{};
      block.internal_forces(x + 1e-7 * v, v, 1e-7, 0.06, 1.2, f, t);
    });
    CHECK(block.parts() == parts);
    forces.push_back(f);
    totals.push_back(t);
  }
  REQUIRE(forces[0].cwiseAbs().maxCoeff() > 0.0);
  for (std::size_t k = 1; k < forces.size(); ++k) {
    CHECK((forces[k] - forces[0]).cwiseAbs().maxCoeff() == 0.0);
    CHECK(totals[k].strain_energy_increment == totals[0].strain_energy_increment);
    CHECK(totals[k].hourglass_energy_increment == totals[0].hourglass_energy_increment);
    CHECK(totals[k].viscous_energy_increment == totals[0].viscous_energy_increment);
    CHECK(totals[k].stable_dt == totals[0].stable_dt);
    CHECK(totals[k].critical_element == totals[0].critical_element);
  }
}

TEST_CASE("shell forces and moments are bitwise the same with 1, 2 and 3 parts",
          "[elements][shell][threads]") {
  const Plate p = plate(40);  // 1600 quads: 4 colours of 50 batches
  const NodalVectors v = random_field(p.x.rows(), 2), w = 10.0 * random_field(p.x.rows(), 3);
  std::vector<NodalVectors> forces, moments;
  std::vector<ShellStepTotals> totals;
  for (int parts : {1, 2, 3}) {
    auto block = shell_block(p);
    NodalVectors f = NodalVectors::Zero(p.x.rows(), 3), m = f;
    ShellStepTotals t;
    with_threads(parts, [&] {
      block.internal_forces(p.x, v, w, 1e-7, f, m, t);
      f.setZero();
      m.setZero();
      t = ShellStepTotals{};
      block.internal_forces(p.x + 1e-7 * v, v, w, 1e-7, f, m, t);
    });
    forces.push_back(f);
    moments.push_back(m);
    totals.push_back(t);
  }
  REQUIRE(forces[0].cwiseAbs().maxCoeff() > 0.0);
  REQUIRE(moments[0].cwiseAbs().maxCoeff() > 0.0);
  for (std::size_t k = 1; k < forces.size(); ++k) {
    CHECK((forces[k] - forces[0]).cwiseAbs().maxCoeff() == 0.0);
    CHECK((moments[k] - moments[0]).cwiseAbs().maxCoeff() == 0.0);
    CHECK(totals[k].strain_energy_increment == totals[0].strain_energy_increment);
    CHECK(totals[k].hourglass_energy_increment == totals[0].hourglass_energy_increment);
    CHECK(totals[k].stable_dt == totals[0].stable_dt);
  }
}

TEST_CASE("two parts of a block numbered in space share only a thin layer of nodes",
          "[elements][threads]") {
  // The parts take the same share of every colour, which on a mesh numbered layer by layer
  // is the same region: the nodes both touch (summed after the pass) are a few layers.
  const auto mesh = test::make_block(20, 0.01, 0.0);
  const auto block = hex_block<Hex8rBlock>(mesh);
  std::vector<Index> node_part(mesh.coordinates.rows(), UNTOUCHED);
  block.mark_nodes(2, node_part);
  const BoundaryNodes boundary = boundary_nodes(node_part);
  const Index layer = 21 * 21;  // nodes of one z-layer
  CHECK(boundary.size() > 0);
  CHECK(boundary.size() <= 3 * layer);
  for (Index mark : node_part) CHECK(mark != UNTOUCHED);
}

TEST_CASE("exchange slots of a node are contiguous and in batch order", "[elements][threads]") {
  // Three batches of two lanes, two corners each; nodes 1 and 3 are boundary nodes.
  const std::vector<Index> conn = {0, 1, 1, 2,   // batch 0: corner 0 lanes, corner 1 lanes
                                   1, 3, 4, 1,   // batch 1
                                   5, 6, 3, 7};  // batch 2
  const std::vector<Index> owner = {0, 1, 2, 3, 4, NO_INDEX};  // batch 2 lane 1 is padding
  std::vector<Index> marks(8, 0);
  marks[1] = marks[3] = SHARED;
  const BoundaryNodes boundary = boundary_nodes(marks);
  REQUIRE(boundary.nodes == std::vector<Index>{1, 3});
  const CornerExchange exchange(conn, owner, 2, 2, boundary);
  // Numbered as the kernels scatter (batch by batch, lane by lane, corner by corner). Node 1:
  // batch 0 lane 0 corner 1, batch 0 lane 1 corner 0, batch 1 lane 0 corner 0, batch 1 lane 1
  // corner 1: slots 0..3. Node 3: batch 1 lane 1 corner 0, batch 2 lane 0 corner 1 (lane 1 of
  // batch 2 is padding): slots 4, 5.
  CHECK(exchange.first(0) == 0);
  CHECK(exchange.first(1) == 4);
  CHECK(exchange.first(2) == 6);
  REQUIRE(exchange.batch_slots(0) != nullptr);
  CHECK(exchange.batch_slots(0)[0] == NO_INDEX);  // node 0
  CHECK(exchange.batch_slots(0)[1] == 1);
  CHECK(exchange.batch_slots(0)[2] == 0);
  CHECK(exchange.batch_slots(0)[3] == NO_INDEX);  // node 2
  CHECK(exchange.batch_slots(1)[0] == 2);
  CHECK(exchange.batch_slots(1)[1] == 4);
  CHECK(exchange.batch_slots(1)[3] == 3);
  CHECK(exchange.batch_slots(2)[2] == 5);
  CHECK(exchange.batch_slots(2)[3] == NO_INDEX);  // padding lane
  CHECK(exchange.size() == 6);
}

TEST_CASE("part ranges cover every batch of a colour once", "[elements][threads]") {
  const std::vector<Index> color_batches = {0, 7, 7, 20};  // the middle colour is empty
  for (int parts : {1, 2, 3, 8}) {
    for (int c = 0; c < 3; ++c) {
      Index next = color_batches[c];
      for (int p = 0; p < parts; ++p) {
        const auto [first, last] = part_batches(color_batches, c, p, parts);
        CHECK(first == next);
        CHECK(last >= first);
        next = last;
      }
      CHECK(next == color_batches[c + 1]);
    }
  }
}
