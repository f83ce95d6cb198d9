// Elastic wave in a bar driven against a fixed end: the spine's accuracy acceptance test.
#include <catch2/catch.hpp>

#include <cmath>

#include "solver/explicit_solver.hpp"
#include "solver_fixtures.hpp"

using namespace xpl;

namespace {

struct BarResult {
  std::vector<Real> time, reaction, etotal;
  Real ke0 = 0.0;
};

BarResult run_bar(const test::BoxSpec& spec, int threads = 0) {
  const Model model = test::make_box(spec);
  test::CaptureSink sink;
  SolverOptions options;
  options.threads = threads;
  ExplicitSolver solver(model, sink, options);
  solver.run();
  BarResult r;
  const Index rf = sink.column("node/FIXED/RF1"), width = sink.width("node/FIXED/RF1");
  const Index et = sink.column("energy/ETOTAL"), ke = sink.column("energy/ALLKE");
  REQUIRE(rf != NO_INDEX);
  REQUIRE(et != NO_INDEX);
  for (std::size_t i = 0; i < sink.times.size(); ++i) {
    Real sum = 0.0;
    for (Index c = 0; c < width; ++c) sum += sink.rows[i][rf + c];
    r.time.push_back(sink.times[i]);
    r.reaction.push_back(sum);
    r.etotal.push_back(sink.rows[i][et]);
  }
  r.ke0 = sink.rows.front()[ke];
  return r;
}

}  // namespace

TEST_CASE("bar against a fixed end: impact force, wave return time, energy balance",
          "[solver][accuracy][wave]") {
  test::BoxSpec spec;  // 100×10×10 mm steel, 40×4×4 elements, 10 m/s, ν = 0
  const BarResult r = run_bar(spec);
  const Real c0 = std::sqrt(spec.young / spec.density);
  const Real area = spec.ly * spec.lz;
  const Real force = spec.density * c0 * std::abs(spec.velocity_x) * area;  // 39.6 kN
  const Real t_return = 2.0 * spec.lx / c0;                                 // 39.6 µs

  // Plateau: mean reaction between the arrival transient and the return of the wave.
  Real sum = 0.0;
  int count = 0;
  for (std::size_t i = 0; i < r.time.size(); ++i)
    if (r.time[i] > 0.1 * t_return && r.time[i] < 0.9 * t_return) {
      sum += r.reaction[i];
      ++count;
    }
  REQUIRE(count > 50);
  const Real plateau = sum / count;
  INFO("plateau reaction " << plateau << " N, analytic " << force << " N");
  CHECK(plateau == Approx(force).epsilon(0.02));  // acceptance: 2 %

  // Return of the wave: the reaction changes sign (compression -> tension) at 2L/c0.
  Real crossing = 0.0;
  for (std::size_t i = 1; i < r.time.size(); ++i)
    if (r.time[i] > 0.5 * t_return && r.reaction[i - 1] > 0.0 && r.reaction[i] <= 0.0) {
      const Real s = r.reaction[i - 1] / (r.reaction[i - 1] - r.reaction[i]);
      crossing = r.time[i - 1] + s * (r.time[i] - r.time[i - 1]);
      break;
    }
  INFO("wave return at " << crossing << " s, analytic " << t_return << " s");
  CHECK(crossing == Approx(t_return).epsilon(0.02));  // acceptance: 2 %

  // Energy balance: ETOTAL drift under 1 % of the initial kinetic energy.
  Real drift = 0.0;
  for (Real e : r.etotal) drift = std::max(drift, std::abs(e - r.etotal.front()));
  INFO("ETOTAL drift " << drift << " J, ALLKE(0) " << r.ke0 << " J");
  CHECK(r.ke0 > 0.0);
  CHECK(drift < 0.01 * r.ke0);
}

TEST_CASE("one and two threads give the same history", "[solver][threads]") {
  test::BoxSpec spec;
  spec.nx = 20;
  spec.period = 30e-6;
  const BarResult one = run_bar(spec, 1);
  const BarResult two = run_bar(spec, 2);
  REQUIRE(one.time.size() == two.time.size());
  // Colour-ordered assembly and chunked sums make the runs bitwise identical.
  for (std::size_t i = 0; i < one.time.size(); ++i) {
    CHECK(one.reaction[i] == two.reaction[i]);
    CHECK(one.etotal[i] == two.etotal[i]);
  }
}
