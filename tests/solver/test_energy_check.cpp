// The health check of the time loop runs from the first increment of every step (issue 33,
// item 1): an element that explodes may end its step within a few increments, and a run of
// fewer than ten increments per step was never checked while the check waited for a warm-up.
#include <catch2/catch.hpp>

#include <random>
#include <string>

#include "common/error.hpp"
#include "shell_fixtures.hpp"
#include "solver/energy/energy_check.hpp"
#include "solver/explicit_solver.hpp"
#include "solver_fixtures.hpp"

using namespace xpl;

namespace {

/// One 100 mm steel S4R, 5 mm thick, free, with random velocities of up to 1 m/s on its
/// translations (every mode excited), at `scale_factor` times the stable increment for 1 ms.
Model one_shell(Real scale_factor) {
  test::PlateSpec spec;
  spec.nx = spec.ny = 1;
  spec.lx = spec.ly = 0.1;
  spec.thickness = 0.005;
  spec.period = 1e-3;
  spec.history_dt = 1e-5;
  spec.scale_factor = scale_factor;
  Model model = test::make_plate(spec);
  model.steps[0].boundaries.clear();
  std::mt19937 rng(1);
  std::uniform_real_distribution<Real> noise(-1.0, 1.0);
  model.initial_velocity = NodalVectors::Zero(model.node_count(), 3);
  for (Index n = 0; n < model.node_count(); ++n)
    for (int c = 0; c < 3; ++c) model.initial_velocity(n, c) = noise(rng);
  return model;
}

}  // namespace

TEST_CASE("an S4R that explodes in its step's first increments fails the run", "[solver][energy]") {
  // Above the stable increment the element's energy grows by orders of magnitude per increment
  // and its own increment grows with it: the step of 1 ms ended after 5-8 increments with
  // ALLKE of 1e33-1e38 J, "completed", while the check waited for 10 increments.
  for (Real factor : {2.0, 3.0, 5.0}) {
    const Model model = one_shell(factor);
    test::CaptureSink sink;
    ExplicitSolver solver(model, sink);
    long increment = 0;
    std::string what;
    try {
      solver.run();
    } catch (const SolverError& e) {
      increment = e.increment();
      what = e.what();
    }
    INFO("scale factor " << factor << ": " << what);
    CHECK(sink.run_status == RunStatus::Failed);
    CHECK(increment >= 1);
    CHECK(increment < 10);  // inside the old warm-up
    CHECK(what.find("NaN/instability") != std::string::npos);
  }
}

TEST_CASE("the same S4R at the stable increment completes", "[solver][energy]") {
  // The check from the first increment does not misfire on a stable run (69 increments).
  const Model model = one_shell(1.0);
  test::CaptureSink sink;
  ExplicitSolver solver(model, sink);
  CHECK_NOTHROW(solver.run());
  CHECK(sink.run_status == RunStatus::Completed);
}

TEST_CASE("a linear instability that keeps ETOTAL balanced fails the run", "[solver][energy]") {
  // An undamped hex box at a fixed increment 3 times the stable one, with velocities of
  // 1e-12 m/s: its highest modes grow by ~30 per increment while ETOTAL of central
  // differences stays balanced as long as the motion is linear (docs/theory/energy.md, "What ALLKE
  // measures"); ALLKD takes the growth and passes every energy of the model at once.
  test::BoxSpec spec;
  spec.nx = 2;
  spec.ny = 2;
  spec.nz = 1;
  spec.lx = 2e-3;
  spec.ly = 2e-3;
  spec.lz = 1e-3;
  spec.fix_x0 = false;
  spec.velocity_x = 0.0;
  spec.period = 200e-6;
  spec.history_dt = 1e-6;
  Model model = test::make_box(spec);
  std::mt19937 rng(3);
  std::uniform_real_distribution<Real> noise(-1e-12, 1e-12);
  for (Index n = 0; n < model.node_count(); ++n)
    for (int c = 0; c < 3; ++c) model.initial_velocity(n, c) = noise(rng);
  for (Step& s : model.steps) {
    s.bulk_linear = 0.0;
    s.bulk_quadratic = 0.0;
    s.increment.fixed = 0.5e-6;  // 1 mm / 5900 m/s = 0.17 µs
  }
  test::CaptureSink sink;
  ExplicitSolver solver(model, sink);
  std::string what;
  long increment = 0;
  try {
    solver.run();
  } catch (const SolverError& e) {
    what = e.what();
    increment = e.increment();
  }
  INFO(what);
  CHECK(sink.run_status == RunStatus::Failed);
  CHECK(what.find(
            "the half-step velocities hold more energy than the model, and more each increment") !=
        std::string::npos);
  // It starts below the round-off floor of the scale (1e-12 m/s against 1e-10 of the wave
  // speed) and passes it after 5 increments.
  CHECK(increment <= 6);
}

namespace {

/// A one-element model (a 1 mm steel cube, extent √3 mm, c_d 5.8 km/s) and a state of it at
/// increment 5 with the given energies; `check` runs the health check on it.
struct CheckFixture {
  Model model;
  State state;
  test::CaptureSink sink;

  CheckFixture() {
    test::BoxSpec spec;
    spec.nx = spec.ny = spec.nz = 1;
    spec.lx = spec.ly = spec.lz = 1e-3;
    spec.poisson = 0.3;
    model = test::make_box(spec);
    const Index n = model.node_count();
    state.position = state.reference = model.coordinates;
    state.velocity = state.velocity_half = NodalVectors::Zero(n, 3);
    state.mass.assign(static_cast<std::size_t>(n), 7850e-9 / 8.0);
    state.increment = 5;
    state.time = 5e-7;
    state.dt = 1e-7;
  }
  /// Starts the check on the state with ALLKE(0) = `kinetic`, then checks the state with the
  /// energies `now`, the next increment 1e-7 s and the largest speed `speed`.
  void check(Real kinetic, const Energies& now, Real speed) {
    EnergyCheck health(model, 0.1);
    state.energies = Energies{};
    state.energies.kinetic = kinetic;
    health.start(state);
    state.energies = now;
    health.check(state, ElementTotals{}, 1e-7, speed, 1, sink);
  }
};

}  // namespace

TEST_CASE("the health check: a node that crosses the model in one increment", "[solver][energy]") {
  CheckFixture f;
  Energies e;
  e.kinetic = 1e-3;
  f.state.velocity_half(5, 2) = -2e4;  // 2 mm per increment of 0.1 µs: beyond √3 mm
  try {
    f.check(1e-3, e, 2e4);
    FAIL("no error");
  } catch (const SolverError& err) {
    const std::string what = err.what();
    INFO(what);
    CHECK(what.find("node " + std::to_string(f.model.node_ids[5]) + " moves at 2e+04 m/s") !=
          std::string::npos);
    CHECK(err.increment() == 5);
  }
  CHECK_NOTHROW(f.check(1e-3, e, 1.5e4));  // 1.5 mm per increment
}

TEST_CASE("the health check: energies at round-off are not measured against nothing",
          "[solver][energy]") {
  // A model at rest whose first increments move it by round-off (1e-44 J of drift in
  // examples/overclosure's pinched): the scale is at least ½ M (1e-10 c_d)², 1.3e-19 J here.
  CheckFixture f;
  Energies e;
  e.kinetic = 1e-44;
  CHECK_NOTHROW(f.check(0.0, e, 1e-20));
  // A real drift of a moving model fails: 20 % of 1 mJ.
  e.kinetic = 0.8e-3;
  CHECK_THROWS_WITH(f.check(1e-3, e, 1.0), Catch::Contains("energy balance lost"));
}

TEST_CASE("the health check: a mode that grows with ALLSE carrying the scale along",
          "[solver][energy]") {
  // Stress scene 43 (an S4R box with 4.5:1 elements on a rigid plate, issue 32) held a
  // period-2Δt mode from increment ~20 on: ALLSE rose to 0.12 J against 0.002 J of initial
  // kinetic energy while ALLKD fell by the same amount, so ETOTAL stayed within 2 %, |ALLKD|
  // never passed the largest energy (ALLSE) and the run "completed". The energy put in (the
  // initial ALLKE, no work) does not grow with the mode.
  CheckFixture f;
  const Real kinetic0 = 2e-3;
  EnergyCheck health(f.model, 0.1);
  f.state.energies = Energies{};
  f.state.energies.kinetic = kinetic0;
  health.start(f.state);
  auto state_with = [&](Real created, long increment) {
    f.state.increment = increment;
    f.state.energies = Energies{};
    f.state.energies.kinetic = kinetic0 - 1e-4;
    f.state.energies.strain = 1e-4 + created;
    f.state.energies.kinetic_defect = -created;  // balanced: ETOTAL unchanged
  };
  // Below DEFECT_INPUT_FACTOR (20) times the input: what a stable mode can hold.
  state_with(3.9e-2, 40);
  CHECK_NOTHROW(health.check(f.state, ElementTotals{}, 1e-7, 1.0, 1, f.sink));
  // Beyond once: not yet (a prescribed velocity ramp from rest starts with |ALLKD| = ALLKE).
  state_with(8e-2, 41);
  CHECK_NOTHROW(health.check(f.state, ElementTotals{}, 1e-7, 1.0, 1, f.sink));
  CHECK(health.input() == Approx(kinetic0).epsilon(1e-9));
  // Beyond again and growing: the mode grows; ETOTAL is still balanced.
  state_with(1.2e-1, 42);
  CHECK(f.state.energies.total() == Approx(kinetic0).epsilon(1e-12));
  CHECK_THROWS_WITH(health.check(f.state, ElementTotals{}, 1e-7, 1.0, 1, f.sink),
                    Catch::Contains("more energy than was put into the model"));
}

TEST_CASE("the health check: ALLKD of energy put in by work is no instability",
          "[solver][energy]") {
  // The same growth with the energy put in by loads (ALLWK): |ALLKD| stays below
  // DEFECT_INPUT_FACTOR times the work done, the run goes on (without the work it would fail
  // at the second increment).
  CheckFixture f;
  EnergyCheck health(f.model, 0.1);
  f.state.energies = Energies{};
  f.state.energies.kinetic = 2e-3;
  health.start(f.state);
  for (long i = 0; i < 3; ++i) {
    const Real created = 5e-2 * static_cast<Real>(i + 1);
    f.state.increment = 40 + i;
    f.state.energies = Energies{};
    f.state.energies.kinetic = 2e-3;
    f.state.energies.strain = 2.0 * created;
    f.state.energies.kinetic_defect = -created;
    f.state.energies.external_work = created;  // ETOTAL balanced by the work
    CHECK_NOTHROW(health.check(f.state, ElementTotals{}, 1e-7, 1.0, 1, f.sink));
  }
  CHECK(health.input() == Approx(2e-3 + 0.15).epsilon(1e-9));
}
