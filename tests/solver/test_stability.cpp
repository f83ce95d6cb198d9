// Stability stress test (S2): the time-increment scale factor is raised until the run
// fails. Factors up to 1 must be stable; the first failing factor is reported.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

#include "solver/explicit_solver.hpp"
#include "solver_fixtures.hpp"

using namespace xpl;

namespace {

/// Runs `increments`-ish increments at `factor`; returns false if the solver stops with an
/// instability, and the largest ETOTAL drift relative to ALLKE(0) otherwise.
bool stable_at(test::BoxSpec spec, Real factor, Real& drift_ratio) {
  spec.scale_factor = factor;
  Model model = test::make_box(spec);
  // Seed every mode with a small random velocity so that an instability shows quickly.
  std::mt19937 rng(42);
  std::uniform_real_distribution<Real> noise(-0.05, 0.05);
  for (Index n = 0; n < model.node_count(); ++n)
    for (int c = 0; c < 3; ++c)
      if (!spec.fix_x0 || model.coordinates(n, 0) > 0.0) model.initial_velocity(n, c) += noise(rng);
  test::CaptureSink sink;
  ExplicitSolver solver(model, sink);
  try {
    solver.run();
  } catch (const SolverError&) {
    return false;
  }
  const Index et = sink.column("energy/ETOTAL"), ke = sink.column("energy/ALLKE");
  Real drift = 0.0;
  for (const auto& row : sink.rows) drift = std::max(drift, std::abs(row[et] - sink.rows[0][et]));
  drift_ratio = drift / sink.rows[0][ke];
  return true;
}

Real first_failing_factor(const test::BoxSpec& spec) {
  for (Real f = 1.05; f < 3.0; f += 0.05) {
    Real drift = 0.0;
    if (!stable_at(spec, f, drift) || drift > 0.5) return f;
  }
  return 3.0;
}

}  // namespace

TEST_CASE("stability: bar at factors 0.5, 0.9, 1.0 is stable; the limit lies above 1",
          "[solver][stability]") {
  test::BoxSpec spec;    // the steel bar of the wave test, ν = 0
  spec.period = 1.5e-3;  // about 3500 increments at factor 1
  spec.history_dt = 1e-6;
  for (Real f : {0.5, 0.9, 1.0}) {
    Real drift = 0.0;
    INFO("factor " << f);
    REQUIRE(stable_at(spec, f, drift));
    CHECK(drift < 0.01);  // energy bounded: ETOTAL within 1 % of ALLKE(0)
  }
  const Real fail = first_failing_factor(spec);
  std::printf("stability (bar, nu = 0): first failing scale factor %.2f\n", fail);
  CHECK(fail > 1.0);
  CHECK(fail < 3.0);  // the stress test must actually find the limit
}

TEST_CASE("stability: nearly incompressible block (nu = 0.45) is stable at factor 1",
          "[solver][stability]") {
  test::BoxSpec spec;
  spec.nx = spec.ny = spec.nz = 8;
  spec.lx = spec.ly = spec.lz = 0.02;
  spec.poisson = 0.45;
  spec.fix_x0 = false;
  spec.velocity_x = 1.0;
  spec.period = 4e-4;
  spec.history_dt = 1e-6;
  for (Real f : {0.5, 0.9, 1.0}) {
    Real drift = 0.0;
    INFO("factor " << f);
    REQUIRE(stable_at(spec, f, drift));
    CHECK(drift < 0.01);
  }
  const Real fail = first_failing_factor(spec);
  std::printf("stability (block, nu = 0.45): first failing scale factor %.2f\n", fail);
  CHECK(fail > 1.0);
  CHECK(fail < 3.0);
}
