#pragma once
// The stability stress test (S2) shared by tests/solver/test_stability.cpp (C3D8R) and
// test_c3d8.cpp (C3D8): runs at raised time-increment scale factors until one fails.

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>

#include "solver/explicit_solver.hpp"
#include "solver_fixtures.hpp"

namespace xpl::test {

/// Runs `increments`-ish increments at `factor`; returns false if the solver stops with an
/// instability, and the largest ETOTAL drift relative to ALLKE(0) otherwise.
inline bool stable_at(test::BoxSpec spec, Real factor, Real& drift_ratio) {
  spec.scale_factor = factor;
  Model model = test::make_box(spec);
  // Seed every mode with a small random velocity so that an instability shows quickly.
  std::mt19937 rng(42);
  std::uniform_real_distribution<Real> noise(-0.05, 0.05);
  for (Index n = 0; n < model.node_count(); ++n)
    for (int c = 0; c < 3; ++c)
      if (!spec.fix_x0 || model.coordinates(n, 0) > 0.0) model.initial_velocity(n, c) += noise(rng);
  test::CaptureSink sink;
  // The run's own energy check (default limit 10 %) tells an instability.
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

inline Real first_failing_factor(const test::BoxSpec& spec) {
  for (Real f = 1.05; f < 3.0; f += 0.05) {
    Real drift = 0.0;
    if (!stable_at(spec, f, drift) || drift > 0.5) return f;
  }
  return 3.0;
}

/// A steel box of nx × ny × nz cubes of 1 mm (ν = 0.3) run for about 700 increments: fixed
/// at x = 0 and pushed onto it at 10 m/s, or free at 1 m/s (plus the noise of stable_at).
inline test::BoxSpec deficient_mesh(int nx, int ny, int nz, bool fixed) {
  test::BoxSpec spec;
  spec.nx = nx;
  spec.ny = ny;
  spec.nz = nz;
  spec.lx = 1e-3 * nx;
  spec.ly = 1e-3 * ny;
  spec.lz = 1e-3 * nz;
  spec.poisson = 0.3;
  spec.fix_x0 = fixed;
  spec.velocity_x = fixed ? -10.0 : 1.0;
  spec.period = 1e-4;
  spec.history_dt = 1e-6;
  return spec;
}

/// Stable at factors 0.5, 0.9 and 1 with the ETOTAL drift below `max_drift` (of ALLKE(0));
/// the first failing factor (printed, on the 0.05 grid of first_failing_factor) in (1.05, 1.3].
inline void check_limit(const char* name, const test::BoxSpec& spec, Real max_drift = 0.01,
                        Real max_fail = 1.3) {
  for (Real f : {0.5, 0.9, 1.0}) {
    Real drift = 0.0;
    INFO(name << ", factor " << f);
    REQUIRE(stable_at(spec, f, drift));
    std::printf("stability (%s): factor %.2f, ETOTAL drift %.2g of ALLKE(0)\n", name, f, drift);
    CHECK(drift < max_drift);
  }
  const Real fail = first_failing_factor(spec);
  std::printf("stability (%s): first failing scale factor %.2f\n", name, fail);
  INFO(name);
  CHECK(fail > 1.06);       // stable at 1.05 as well
  CHECK(fail <= max_fail);  // the global estimate must not waste increments either
}

}  // namespace xpl::test
