#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "solver/explicit_solver.hpp"
#include "solver_fixtures.hpp"

using namespace xpl;

namespace {

/// A free 2 × 2 × 2 steel box of 10 mm at rest, every node prescribed in x by `type` (value
/// `value`, amplitude RAMP when `ramp`) in one step, and by -value in a second when `reverse`.
Model driven_box(BoundaryType type, Real value, bool ramp, bool reverse) {
  test::BoxSpec spec;
  spec.nx = spec.ny = spec.nz = 2;
  spec.lx = spec.ly = spec.lz = 0.01;
  spec.fix_x0 = false;
  spec.velocity_x = 0.0;
  spec.period = 10e-6;
  Model model = test::make_box(spec);
  Step& push = model.steps[0];
  push.name = "PUSH";
  push.ramp_amplitude = ramp;
  for (Index n = 0; n < model.node_count(); ++n)
    push.boundaries.push_back({n, 1, 1, value, type, NO_INDEX, {}});
  if (reverse) {
    Step pull = push;
    pull.name = "PULL";
    for (BoundaryCondition& bc : pull.boundaries) bc.value = -value;
    model.steps.push_back(pull);
  }
  return model;
}

int jump_messages(const test::CaptureSink& sink) {
  int count = 0;
  for (const std::string& m : sink.messages)
    if (m.find("prescribed velocity jump") != std::string::npos) ++count;
  return count;
}

}  // namespace

TEST_CASE("a velocity BC that jumps from rest and reverses: its work is the impulse's",
          "[solver][prescribed]") {
  const Model model = driven_box(BoundaryType::Velocity, 1.0, false, true);
  test::CaptureSink sink;
  ExplicitSolver solver(model, sink);
  const RunSummary s = solver.run();  // the trapezoidal rule lost the balance: SolverError
  const Real kinetic = 0.5 * 7850.0 * 1e-6 * 1.0;  // ½ m v², m = ρ (10 mm)³
  CHECK(s.energies.kinetic == Approx(kinetic).epsilon(1e-12));
  // The start puts ½mv² in (the trapezoid counted mv²), the reversal nothing.
  CHECK(s.energies.external_work == Approx(kinetic).epsilon(1e-12));
  CHECK(std::abs(s.energies.total()) < 1e-12 * kinetic);
  CHECK(jump_messages(sink) == 2);
}

TEST_CASE("a velocity BC ramped from rest is smooth: no jump", "[solver][prescribed]") {
  const Model model = driven_box(BoundaryType::Velocity, 1.0, true, false);
  test::CaptureSink sink;
  ExplicitSolver solver(model, sink);
  const RunSummary s = solver.run();
  CHECK(jump_messages(sink) == 0);
  // The trapezoidal rule, O(Δt) off for the accelerating rigid body.
  CHECK(std::abs(s.energies.total()) < 1e-2 * s.energies.kinetic);
}

TEST_CASE("a displacement BC ramped from rest starts with a velocity jump",
          "[solver][prescribed]") {
  // u = 10 µm over 10 µs: the velocity jumps from 0 to 1 m/s at t = 0.
  const Model model = driven_box(BoundaryType::Displacement, 1e-5, true, false);
  test::CaptureSink sink;
  // The stop of the ramp in the step's last update (1 m/s to rest) keeps the trapezoidal
  // rule; with ALLKE = ½ v(n−½) m v(n+½) that balances too (before, with the whole-step
  // velocity, ETOTAL was off there by ⅛mΔv², 25 % of ALLKE, and the run needed
  // --energy-limit 50).
  ExplicitSolver solver(model, sink);
  solver.run();
  CHECK(jump_messages(sink) == 1);
  const Index et = sink.column("energy/ETOTAL"), ke = sink.column("energy/ALLKE");
  REQUIRE(sink.rows.size() > 10);
  const Real kinetic = 0.5 * 7850.0 * 1e-6 * 1.0;
  CHECK(sink.rows[sink.rows.size() / 2][ke] == Approx(kinetic).epsilon(1e-9));
  // Balanced to round-off at every row, the stop at the end of the step included.
  for (std::size_t r = 0; r < sink.rows.size(); ++r) {
    INFO("row " << r << " at t = " << sink.times[r]);
    CHECK(std::abs(sink.rows[r][et]) < 1e-9 * kinetic);
  }
}
