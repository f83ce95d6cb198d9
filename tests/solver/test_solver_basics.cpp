#include <catch2/catch.hpp>

#include <cmath>

#include "solver/explicit_solver.hpp"
#include "solver_fixtures.hpp"

using namespace xpl;

TEST_CASE("a free body in uniform motion stays unstrained and keeps its energy",
          "[solver][basics]") {
  test::BoxSpec spec;
  spec.nx = 4;
  spec.ny = spec.nz = 2;
  spec.lx = spec.ly = spec.lz = 0.01;
  spec.fix_x0 = false;
  spec.period = 20e-6;
  const Model model = test::make_box(spec);
  test::CaptureSink sink;
  ExplicitSolver solver(model, sink);
  const RunSummary s = solver.run();
  CHECK(s.energies.strain < 1e-12 * s.energies.kinetic);
  const Real mass = spec.density * spec.lx * spec.ly * spec.lz;
  CHECK(s.energies.kinetic == Approx(0.5 * mass * 100.0).epsilon(1e-12));
  // Moved by v t.
  const State& st = solver.state();
  CHECK(st.displacement(0, 0) == Approx(spec.velocity_x * spec.period).epsilon(1e-9));
  CHECK(s.final_time == Approx(spec.period).epsilon(1e-12));
}

TEST_CASE("a constant force accelerates a free body: work equals kinetic energy",
          "[solver][basics]") {
  test::BoxSpec spec;
  spec.nx = spec.ny = spec.nz = 2;
  spec.lx = spec.ly = spec.lz = 0.01;
  spec.fix_x0 = false;
  spec.velocity_x = 0.0;
  spec.period = 50e-6;
  Model model = test::make_box(spec);
  // 1 N in x on every node.
  for (Index n = 0; n < model.node_count(); ++n)
    model.steps[0].loads.push_back({n, 1, 1.0, NO_INDEX, {}});
  test::CaptureSink sink;
  ExplicitSolver solver(model, sink);
  const RunSummary s = solver.run();
  // Equal forces on unequal nodal masses also deform the body: check momentum (exact for
  // central differences with constant forces) and the full energy balance.
  const Real force = model.node_count() * 1.0;
  const State& st = solver.state();
  Real momentum = 0.0;
  for (Index n = 0; n < model.node_count(); ++n) momentum += st.mass[n] * st.velocity(n, 0);
  CHECK(momentum == Approx(force * spec.period).epsilon(1e-10));
  const Real balance = s.energies.kinetic + s.energies.internal() + s.energies.viscous;
  // O(dt^2) error of the kinetic-energy estimate from averaged half-step velocities.
  CHECK(s.energies.external_work == Approx(balance).epsilon(1e-4));
}

TEST_CASE("an element that inverts stops the run with its id and increment", "[solver][errors]") {
  test::BoxSpec spec;
  spec.nx = 2;
  spec.ny = spec.nz = 1;
  spec.lx = 0.02;
  spec.ly = spec.lz = 0.01;
  spec.velocity_x = -20000.0;  // faster than the wave speed: crushes the first element
  spec.period = 20e-6;
  const Model model = test::make_box(spec);
  test::CaptureSink sink;
  ExplicitSolver solver(model, sink);
  CHECK_THROWS_AS(solver.run(), SolverError);
  CHECK(sink.run_status == RunStatus::Failed);
  CHECK(sink.error.find("NaN/instability at increment") != std::string::npos);
  CHECK(sink.error.find("element") != std::string::npos);
}

TEST_CASE("data check stops before the first increment", "[solver][check]") {
  const Model model = test::make_box(test::BoxSpec{});
  test::CaptureSink sink;
  ExplicitSolver solver(model, sink);
  const RunSummary s = solver.check();
  CHECK(s.increments == 0);
  CHECK(sink.run_status == RunStatus::Checked);
  CHECK(sink.frame_times.size() == 1);
}
