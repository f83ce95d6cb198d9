// The team size of a run (solver/thread_team.hpp): small models run on one thread unless
// the caller insists, larger ones on the OpenMP default, and the choice changes no bit.
#include <catch2/catch.hpp>

#include <omp.h>

#include "solver/explicit_solver.hpp"
#include "solver/thread_team.hpp"
#include "solver_fixtures.hpp"

using namespace xpl;

TEST_CASE("small models run on one thread unless the caller insists", "[solver][threads]") {
  test::BoxSpec spec;  // 40 × 4 × 4 = 640 elements
  const Model small = test::make_box(spec);
  REQUIRE(small.element_count() < SMALL_MODEL_ELEMENTS);
  CHECK(team_size(small, 0, 2) == 1);
  CHECK(team_size(small, 2, 2) == 2);
  CHECK(team_size(small, 3, 2) == 3);
  spec.nx = 40;
  spec.ny = spec.nz = 16;  // 10,240 elements
  const Model large = test::make_box(spec);
  REQUIRE(large.element_count() >= SMALL_MODEL_ELEMENTS);
  CHECK(team_size(large, 0, 2) == 2);
  CHECK(team_size(large, 0, 0) == 1);
  CHECK(team_size(large, 1, 2) == 1);
}

TEST_CASE("the team chosen for a small model gives the bits of two threads", "[solver][threads]") {
  test::BoxSpec spec;
  spec.period = 20e-6;
  const Model model = test::make_box(spec);
  const int saved = omp_get_max_threads();
  omp_set_num_threads(2);  // the OpenMP default the automatic choice overrides
  std::vector<std::vector<Real>> runs;
  std::vector<int> teams;
  for (int requested : {0, 2}) {
    test::CaptureSink sink;
    SolverOptions options;
    options.threads = requested;
    {
      ExplicitSolver solver(model, sink, options);
      teams.push_back(solver.threads());
      CHECK(omp_get_max_threads() == solver.threads());
      solver.run();
      std::vector<Real> flat;
      for (const auto& row : sink.rows) flat.insert(flat.end(), row.begin(), row.end());
      const NodalVectors& u = solver.state().position;
      flat.insert(flat.end(), u.data(), u.data() + u.size());
      runs.push_back(flat);
    }
    CHECK(omp_get_max_threads() == 2);  // the caller's team is restored
  }
  omp_set_num_threads(saved);
  CHECK(teams == std::vector<int>{1, 2});
  REQUIRE(runs[0].size() == runs[1].size());
  REQUIRE(runs[0].size() > 100);
  for (std::size_t k = 0; k < runs[0].size(); ++k) CHECK(runs[0][k] == runs[1][k]);
}
