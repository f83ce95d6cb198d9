// S4R acceptance: a simply supported plate under a suddenly applied pressure (Navier series)
// and a cantilever strip's first frequency, through the whole solver.

#include <catch2/catch.hpp>

#include <omp.h>
#include <cmath>

#include "shell_fixtures.hpp"
#include "solver/explicit_solver.hpp"
#include "solver_fixtures.hpp"

using namespace xpl;
using namespace xpl::test;

namespace {

constexpr Real PI = 3.14159265358979323846;

/// Simply supported square plate 1 m × 1 m × 10 mm, 1 kPa on the SPOS face of every element
/// (pushing along −z), edges w = 0, in-plane rigid motion removed at two corners.
Model make_pressure_plate(int n, Real scale = 1.0) {
  PlateSpec spec;
  spec.nx = spec.ny = n;
  spec.scale_factor = scale;
  Model m = make_plate(spec);
  fix(m, 0, 3, 3);
  m.steps[0].boundaries.push_back(
      {plate_node(spec, 0, 0), 1, 2, 0.0, BoundaryType::Displacement, NO_INDEX, {}});
  m.steps[0].boundaries.push_back(
      {plate_node(spec, n, 0), 2, 2, 0.0, BoundaryType::Displacement, NO_INDEX, {}});
  for (Index e = 0; e < m.element_count(); ++e)
    m.steps[0].pressures.push_back({{e, SHELL_FACE_POS}, 1000.0, NO_INDEX, {}});
  return m;
}

struct Peak {
  Real value = 0.0, time = 0.0;
};

/// First local maximum of −U3 of the series `path` (with parabolic refinement).
Peak first_peak(const CaptureSink& sink, const std::string& path) {
  const Index col = sink.column(path);
  REQUIRE(col != NO_INDEX);
  const std::size_t n = sink.rows.size();
  for (std::size_t k = 1; k + 1 < n; ++k) {
    const Real a = -sink.rows[k - 1][col], b = -sink.rows[k][col], c = -sink.rows[k + 1][col];
    if (b > a && b >= c && b > 0.0) {
      const Real denom = a - 2 * b + c;
      const Real shift = denom != 0.0 ? 0.5 * (a - c) / denom : 0.0;
      const Real h = sink.times[k + 1] - sink.times[k];
      return {b - 0.25 * (a - c) * shift, sink.times[k] + shift * h};
    }
  }
  return {};
}

/// Largest |ETOTAL − ETOTAL(0)| and largest energy (ALLKE, ALLIE, ALLWK) of a run.
std::pair<Real, Real> energy_drift(const CaptureSink& sink) {
  const Index et = sink.column("energy/ETOTAL"), ke = sink.column("energy/ALLKE"),
              ie = sink.column("energy/ALLIE"), wk = sink.column("energy/ALLWK");
  Real drift = 0.0, largest = 0.0;
  for (const auto& row : sink.rows) {
    drift = std::max(drift, std::abs(row[et] - sink.rows.front()[et]));
    largest = std::max({largest, row[ke], row[ie], std::abs(row[wk])});
  }
  return {drift, largest};
}

}  // namespace

TEST_CASE("simply supported plate under sudden pressure: first peak matches Navier",
          "[solver][shell][acceptance]") {
  // Navier series (undamped, step load): first peak of the centre deflection 0.4436 mm at
  // 10.42 ms (twice the static 0.2218 mm; half the fundamental period 20.84 ms).
  const Model m = make_pressure_plate(20);
  CaptureSink sink;
  ExplicitSolver solver(m, sink);
  solver.run();
  const Peak peak = first_peak(sink, "node/CENTER/U3");
  INFO("peak " << peak.value * 1e3 << " mm at " << peak.time * 1e3 << " ms");
  CHECK(peak.value == Approx(0.4436e-3).epsilon(0.03));
  CHECK(peak.time == Approx(10.42e-3).epsilon(0.03));
  const auto [drift, largest] = energy_drift(sink);
  INFO("ETOTAL drift " << drift << " J of " << largest << " J");
  CHECK(drift < 0.01 * largest);
}

TEST_CASE("shell plate results do not depend on the thread count", "[solver][shell][threads]") {
  // Large enough that every colour runs in parallel (see simd::MIN_PARALLEL_BATCHES).
  Model m = make_pressure_plate(48);
  m.steps[0].time_period = 1e-3;
  std::vector<std::vector<Real>> runs;
  for (int threads : {1, 2}) {
    CaptureSink sink;
    SolverOptions options;
    options.threads = threads;
    ExplicitSolver solver(m, sink, options);
    solver.run();
    std::vector<Real> flat;
    for (const auto& row : sink.rows) flat.insert(flat.end(), row.begin(), row.end());
    runs.push_back(flat);
  }
  REQUIRE(runs[0].size() == runs[1].size());
  for (std::size_t k = 0; k < runs[0].size(); ++k) CHECK(runs[0][k] == runs[1][k]);
  omp_set_num_threads(omp_get_num_procs());
}

namespace {

/// Cantilever strip 500 × 50 × 5 mm clamped at x = 0, released from rest with a velocity
/// field in the shape of the static tip-load deflection (mostly the first mode). Returns
/// the frequency from the upward zero crossings of the tip velocity-driven U3 history.
Real cantilever_frequency(bool plate_strip) {
  PlateSpec spec;
  spec.nx = 20;
  spec.ny = 2;
  spec.lx = 0.5;
  spec.ly = 0.05;
  spec.thickness = 0.005;
  spec.period = 0.13;
  spec.history_dt = 5e-5;
  Model m = make_plate(spec);
  m.steps[0].outputs.resize(2);  // energies and TIP U3 only
  m.steps[0].outputs[1].node_set = 3;
  fix(m, 1, 1, 6);  // clamped root
  // Plate strip (cylindrical bending): no lateral strain and no rotation about the axis.
  if (plate_strip) {
    fix(m, 4, 2, 2);
    fix(m, 4, 4, 4);
  }
  for (Index n = 0; n < m.node_count(); ++n) {
    const Real s = m.coordinates(n, 0) / spec.lx;
    m.initial_velocity(n, 2) = 0.05 * 0.5 * s * s * (3.0 - s);
  }
  CaptureSink sink;
  ExplicitSolver solver(m, sink);
  solver.run();
  const Index col = sink.column("node/TIP/U3");
  std::vector<Real> crossings;  // downward crossings of U3 (it starts by rising)
  for (std::size_t k = 1; k < sink.rows.size(); ++k) {
    const Real a = sink.rows[k - 1][col], b = sink.rows[k][col];
    if (a > 0.0 && b <= 0.0)
      crossings.push_back(sink.times[k - 1] + (sink.times[k] - sink.times[k - 1]) * a / (a - b));
  }
  REQUIRE(crossings.size() >= 2);
  return (crossings.size() - 1) / (crossings.back() - crossings.front());
}

}  // namespace

TEST_CASE("cantilever strip: first frequency against plate-strip and beam theory",
          "[solver][shell][acceptance]") {
  const Real E = 200e9, nu = 0.3, rho = 7850.0, t = 0.005, L = 0.5;
  const Real lambda2 = 1.875104 * 1.875104;
  // Plate strip (cylindrical bending, D = E t³ / 12(1 − ν²)): 17.09 Hz.
  const Real f_strip =
      lambda2 / (2 * PI * L * L) * std::sqrt(E * t * t / (12 * (1 - nu * nu) * rho));
  // Euler–Bernoulli beam with free side edges (EI = E b t³ / 12): 16.30 Hz.
  const Real f_beam = lambda2 / (2 * PI * L * L) * std::sqrt(E * t * t / (12 * rho));
  const Real strip = cantilever_frequency(true);
  INFO("plate strip: " << strip << " Hz against " << f_strip << " Hz");
  CHECK(strip == Approx(f_strip).epsilon(0.03));
  const Real beam = cantilever_frequency(false);
  INFO("free edges: " << beam << " Hz against beam " << f_beam << " Hz");
  CHECK(beam == Approx(f_beam).epsilon(0.03));
}
