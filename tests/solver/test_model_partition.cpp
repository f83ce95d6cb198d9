#include <catch2/catch.hpp>

#include <algorithm>
#include <regex>

#include "elements/material/plasticity.hpp"
#include "solver/explicit_solver.hpp"
#include "solver/model_partition.hpp"
#include "solver_fixtures.hpp"

using namespace xpl;

TEST_CASE("element costs: C3D8R 1, C3D8 2.2, plastic hexes 1.12 times, rigid 0",
          "[solver][partition]") {
  test::BoxSpec spec;
  spec.nx = 2;
  spec.ny = spec.nz = 1;
  Model model = test::make_box(spec);
  CHECK(element_cost(model, 0, false) == 1.0);
  CHECK(element_cost(model, 0, true) == 0.0);
  model.element_types[1] = ElementType::C3D8;
  CHECK(element_cost(model, 1, false) == 2.2);
  model.materials[0].plastic = elements::Plasticity{};
  CHECK(element_cost(model, 0, false) == Approx(1.12).epsilon(1e-15));
  CHECK(element_cost(model, 1, false) == Approx(2.2 * 1.12).epsilon(1e-15));
}

TEST_CASE("partition_model keeps a rigid body whole and balances the deformable elements",
          "[solver][partition]") {
  test::BoxSpec spec;
  spec.nx = 12;
  spec.ny = spec.nz = 2;
  Model model = test::make_box(spec);
  // The 4 elements of the slice i = 0 (first of each row of 12) are one rigid body.
  NamedSet slice{"SLICE", {}, {}};
  for (Index e = 0; e < model.element_count(); e += 12) slice.members.push_back(e);
  model.element_sets.push_back(slice);
  model.rigid_bodies.push_back({0, 1, NO_INDEX, NO_INDEX, {}});
  const RigidBodies rigid(model);
  const Ties ties;
  for (const partition::Method method :
       {partition::Method::Bisection, partition::Method::Automatic}) {
    const partition::MeshPartition p = partition_model(model, rigid, ties, nullptr, 2, method);
    for (const Index e : slice.members) CHECK(p.element_part[e] == p.element_part[0]);
    // 44 deformable elements of weight 1 and 4 rigid ones of weight 0 on two parts.
    CHECK(p.stats[0].weight + p.stats[1].weight == 44.0);
    CHECK(p.imbalance <= 1.05);
  }
}

TEST_CASE("a run with partition_parts reports the partition once in the .msg, results unchanged",
          "[solver][partition]") {
  test::BoxSpec spec;
  spec.nx = 12;
  spec.ny = spec.nz = 2;
  spec.period = 2e-6;
  const Model model = test::make_box(spec);
  test::CaptureSink plain, parted;
  SolverOptions options;
  options.threads = 1;
  ExplicitSolver(model, plain, options).run();
  options.partition_parts = 3;
  options.partition_note = "note before the report";
  ExplicitSolver(model, parted, options).run();
  const std::regex summary(R"(partition: 3 parts by \w+ in .* s: imbalance 1\.\d+ .*)");
  int summaries = 0, parts = 0;
  for (const std::string& m : parted.messages) {
    summaries += std::regex_match(m, summary);
    parts += m.rfind("partition: part ", 0) == 0;
  }
  CHECK(summaries == 1);
  CHECK(parts == 3);
  CHECK(std::count(parted.messages.begin(), parted.messages.end(), "note before the report") == 1);
  CHECK(parted.messages.size() == plain.messages.size() + 5);
  REQUIRE(parted.rows.size() == plain.rows.size());
  CHECK(parted.rows == plain.rows);  // bitwise: the partition changes nothing of the run
}
