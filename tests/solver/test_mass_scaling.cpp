// *FIXED MASS SCALING in the solver (SPEC S4): the increment rises by the requested factor, the
// added mass is reported (and matches ρV by hand), counts in the kinetic energy, and the
// energy balance holds; DT= with TYPE=BELOW MIN scales only the small elements.
#include <catch2/catch.hpp>

#include <cmath>
#include <string>

#include "solver/explicit_solver.hpp"
#include "solver_fixtures.hpp"

using namespace xpl;

namespace {

struct Run {
  RunSummary summary;
  test::CaptureSink sink;
  Real ke0 = 0.0;
};

void run(const Model& model, Run& r) {
  ExplicitSolver solver(model, r.sink, {});
  r.summary = solver.run();
  r.ke0 = r.sink.rows.front()[r.sink.column("energy/ALLKE")];
}

/// A free steel box (ν = 0.3) moving at 1 m/s along x plus a small shear, about 300 increments.
test::BoxSpec free_box() {
  test::BoxSpec spec;
  spec.nx = 12;
  spec.ny = spec.nz = 3;
  spec.lx = 0.012;
  spec.ly = spec.lz = 0.003;
  spec.poisson = 0.3;
  spec.fix_x0 = false;
  spec.velocity_x = 1.0;
  spec.period = 5e-5;
  spec.history_dt = 1e-6;
  return spec;
}

/// The number after `key` in the first message that contains it.
Real number_after(const std::vector<std::string>& messages, const std::string& key) {
  for (const std::string& m : messages) {
    const std::size_t at = m.find(key);
    if (at != std::string::npos) return std::stod(m.substr(at + key.size()));
  }
  return -1.0;
}

}  // namespace

TEST_CASE("fixed mass scaling: FACTOR=4 doubles the increment, adds 3 rho V, keeps ETOTAL",
          "[solver][mass-scaling]") {
  const test::BoxSpec spec = free_box();
  Model base = test::make_box(spec);
  // A shear component so that the block deforms and the energies exchange.
  for (Index n = 0; n < base.node_count(); ++n)
    base.initial_velocity(n, 1) = 2.0 * base.coordinates(n, 0) / spec.lx - 1.0;
  Model scaled = base;
  FixedMassScaling s;
  s.factor = 4.0;
  scaled.steps[0].mass_scaling.push_back(s);
  Run a, b;
  run(base, a);
  run(scaled, b);
  // The stable increment doubles: half the increments (±1 for the last one that lands on the end).
  CHECK(std::abs(2.0 * static_cast<Real>(b.summary.increments) -
                 static_cast<Real>(a.summary.increments)) <= 2.0);
  const Real rho_v = spec.density * spec.lx * spec.ly * spec.lz;
  // Reported with 4 significant digits: the added mass 3 ρV and the model mass ρV.
  CHECK(number_after(b.sink.messages, "model mass ") == Approx(rho_v).epsilon(1e-3));
  CHECK(number_after(b.sink.messages, "kg, added ") == Approx(3.0 * rho_v).epsilon(1e-3));
  CHECK(number_after(b.sink.messages, "kg (+") == Approx(300.0).epsilon(1e-3));
  // The added mass moves with the nodes: four times the kinetic energy at the start.
  CHECK(b.ke0 == Approx(4.0 * a.ke0).epsilon(1e-12));
  CHECK(b.summary.energy_drift < 0.01);
  CHECK(a.summary.energy_drift < 0.01);
}

TEST_CASE("fixed mass scaling: DT= UNIFORM lifts the smallest element increment to DT",
          "[solver][mass-scaling]") {
  Model base = test::make_box(free_box());
  Run a;
  run(base, a);
  // Without scaling there is no report.
  REQUIRE(number_after(a.sink.messages, "smallest element increment ") < 0.0);
  Model scaled = base;
  FixedMassScaling s;
  s.dt = 3e-7;  // about 1.9 × the element estimate of a 1 mm steel cube (1.608e-7 s)
  s.type = FixedMassScaling::Type::Uniform;
  scaled.steps[0].mass_scaling.push_back(s);
  Run b;
  run(scaled, b);
  const Real before = number_after(b.sink.messages, "smallest element increment ");
  const Real after = number_after(b.sink.messages, " s -> ");
  CHECK(after == Approx(3e-7).epsilon(1e-3));
  const Real gain = after / before;
  CHECK(gain > 1.3);
  // The increment of the run rises by the same factor.
  CHECK(static_cast<Real>(a.summary.increments) / static_cast<Real>(b.summary.increments) ==
        Approx(gain).epsilon(0.01));
  CHECK(b.summary.energy_drift < 0.01);
}

TEST_CASE("fixed mass scaling: DT= BELOW MIN scales only the elements below DT",
          "[solver][mass-scaling]") {
  test::BoxSpec spec = free_box();
  Model base = test::make_box(spec);
  // A thin first slice: the nodes of x = h moved to x = h/4 (elements 4 times shorter there).
  const Real h = spec.lx / spec.nx;
  for (Index n = 0; n < base.node_count(); ++n)
    if (std::abs(base.coordinates(n, 0) - h) < 1e-9) base.coordinates(n, 0) = 0.25 * h;
  Run a;
  run(base, a);
  Model scaled = base;
  FixedMassScaling s;
  s.dt = 0.9 * h / std::sqrt(200e9 * 0.7 / (1.3 * 0.4 * 7850.0));  // below the regular elements
  scaled.steps[0].mass_scaling.push_back(s);
  Run b;
  run(scaled, b);
  bool listed = false;
  for (const std::string& m : b.sink.messages)
    listed |= m.find("(all elements): 9 of 108 elements scaled") != std::string::npos;
  CHECK(listed);  // the 3 × 3 elements of the thin slice
  CHECK(static_cast<Real>(a.summary.increments) > 2.5 * static_cast<Real>(b.summary.increments));
  CHECK(b.summary.energy_drift < 0.01);
}
