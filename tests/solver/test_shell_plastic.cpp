// S4R plasticity through the whole solver: the plastic hinge of a strip in pure bending, the
// membrane-only warning, and thread independence of a plastic run.
//
// The hinge and thread tests are hidden ([.]) until the plastic dissipation is part of ALLIE
// (issue 14, solver plumbing: Energies::plastic, ElementTotals::plastic_energy_increment):
// without it the energy check stops a plastic run. Remove the [.] then; both pass with
// that plumbing applied (measured numbers below).

#include <catch2/catch.hpp>

#include <omp.h>
#include <cmath>

#include "shell_fixtures.hpp"
#include "solver/explicit_solver.hpp"
#include "solver_fixtures.hpp"

using namespace xpl;
using namespace xpl::test;

namespace {

constexpr Real E = 200e9, SY = 250e6;

elements::Plasticity perfectly_plastic(Real yield) {
  elements::Plasticity p;
  p.yield_stress = {yield};
  p.plastic_strain = {0.0};
  return p;
}

/// Strip 100 × 10 × 4 mm (10 × 1 S4R), elastic–perfectly plastic steel (σy = 250 MPa).
/// Root: u1, u3, θy, θz held at both nodes, u2 at one, so that the root does not stop the
/// lateral contraction and anticlastic curvature (the strip stays in uniaxial bending
/// stress). Tip: a rotation rate about y on both nodes, ramped over the first fifth of the
/// 40 ms step (clamped-guided first mode ≈ 0.8 ms: quasi-static), to θ = 6 κ_y L.
struct Hinge {
  Real moment_at_4 = 0.0;  ///< mean root moment over κ ∈ [4, 6] κ_y, N·m
  Real plastic_moment = 0.0;
  Real elastic_slope = 0.0;  ///< root moment / tip rotation early in the ramp, N·m/rad
  Real beam_slope = 0.0;     ///< E I / L
  std::vector<std::string> messages;
};

Hinge run_hinge(int points) {
  PlateSpec spec;
  spec.nx = 10;
  spec.ny = 1;
  spec.lx = 0.1;
  spec.ly = 0.01;
  spec.thickness = 0.004;
  spec.integration_points = points;
  spec.period = 40e-3;
  spec.history_dt = 2e-4;
  Model m = make_plate(spec);
  m.materials[0].plastic = perfectly_plastic(SY);
  const Index root[2] = {plate_node(spec, 0, 0), plate_node(spec, 0, 1)};
  for (Index n : root)
    for (int dof : {1, 3, 5, 6})
      m.steps[0].boundaries.push_back({n, dof, dof, 0.0, BoundaryType::Displacement, NO_INDEX, {}});
  m.steps[0].boundaries.push_back({root[0], 2, 2, 0.0, BoundaryType::Displacement, NO_INDEX, {}});
  const Real ky = 2.0 * SY / (E * spec.thickness), theta = 6.0 * ky * spec.lx;
  const Real ramp = 0.2 * spec.period;
  const Real rate = theta / (spec.period - 0.5 * ramp);  // θ(T) = rate (T − ramp/2)
  Amplitude amplitude;
  amplitude.name = "RAMP";
  amplitude.time = {0.0, ramp, spec.period};
  amplitude.value = {0.0, 1.0, 1.0};
  m.amplitudes.push_back(amplitude);
  for (Index n : m.node_sets[3].members)
    m.steps[0].boundaries.push_back({n, 5, 5, rate, BoundaryType::Velocity, 0, {}});
  m.steps[0].outputs.resize(2);
  m.steps[0].outputs[1].node_set = 1;  // X0: the root
  m.steps[0].outputs[1].node_variables = {"RM2"};
  CaptureSink sink;
  ExplicitSolver solver(m, sink);
  solver.run();
  REQUIRE(sink.run_status == RunStatus::Completed);

  Hinge h;
  h.messages = sink.messages;
  h.plastic_moment = SY * spec.ly * spec.thickness * spec.thickness / 4.0;
  h.beam_slope = E * spec.ly * std::pow(spec.thickness, 3) / 12.0 / spec.lx;
  const Index col = sink.column("node/X0/RM2");
  REQUIRE(col != NO_INDEX);
  Real sum = 0.0;
  int count = 0;
  for (std::size_t k = 0; k < sink.rows.size(); ++k) {
    const Real t = sink.times[k];
    const Real angle = t < ramp ? 0.5 * rate * t * t / ramp : rate * (t - 0.5 * ramp);
    const Real moment = std::abs(sink.rows[k][col] + sink.rows[k][col + 1]);
    const Real kappa = angle / spec.lx / ky;
    if (kappa >= 4.0 && kappa <= 6.0) {
      sum += moment;
      ++count;
    }
    if (kappa > 0.3 && kappa < 0.5 && h.elastic_slope == 0.0) h.elastic_slope = moment / angle;
  }
  REQUIRE(count > 10);
  h.moment_at_4 = sum / count;
  return h;
}

}  // namespace

/// 2 Σ w_k |ζ_k| of Simpson's rule with `points` points on ζ ∈ [−1, 1] (Σ w = 1): the
/// fully plastic moment the rule integrates (σ = ±σy), as a fraction of σy b t²/4.
Real simpson_plastic_fraction(int points) {
  const Real h = 2.0 / (points - 1);
  Real sum = 0.0;
  for (int k = 0; k < points; ++k) {
    const Real w = (k == 0 || k == points - 1) ? 1.0 : (k % 2 == 1 ? 4.0 : 2.0);
    sum += 0.5 * w * h / 3.0 * std::abs(-1.0 + k * h);
  }
  return 2.0 * sum;
}

TEST_CASE("plastic hinge: the root moment of an S4R strip plateaus at sigma_y b t^2 / 4",
          "[.][solver][shell][plasticity][acceptance]") {
  // Measured M/Mp at 4–6 κ_y : 3 points 0.6667, 5 points 0.99996,
  // 7 points 0.9627, 9 points 0.9993, 15 points 0.9856. Simpson's rule is exact for the
  // fully plastic section when the mid-point has weight 2/3 of its neighbours' (5, 9, 13
  // points); 7, 11, 15 points integrate 0.963, 0.985, 0.993 of Mp, 3 points 2/3 (the elastic
  // limit moment). The exact section gives 1 − (κ_y/κ)²/3 = 0.979–0.991 Mp at 4–6 κ_y; 15
  // points follow it (their inner points yield at 7 κ_y).
  for (int points : {3, 5, 7, 9, 15}) {
    const Hinge h = run_hinge(points);
    const Real rule = simpson_plastic_fraction(points);
    INFO(points << " points: plateau " << h.moment_at_4 << " N m, Mp " << h.plastic_moment
                << " (ratio " << h.moment_at_4 / h.plastic_moment << ", the rule's " << rule
                << "); elastic slope " << h.elastic_slope << " against EI/L " << h.beam_slope);
    // The integrated plateau is the rule's fully plastic moment, at most 2 % below it (the
    // elastic core at 4 κ_y) and not above it but for the quasi-static ringing.
    CHECK(h.moment_at_4 / h.plastic_moment == Approx(rule).epsilon(0.02));
    // The acceptance: within 2 % of σy b t²/4 with enough points.
    if (points == 5 || points == 9 || points == 15)
      CHECK(h.moment_at_4 == Approx(h.plastic_moment).epsilon(0.02));
    // Elastic bending of the free-edged strip (uniaxial stress): EI/L with E; 3 % covers the
    // one-point element's bending of a 10-element strip and the dynamics of the ramp.
    CHECK(h.elastic_slope == Approx(h.beam_slope).epsilon(0.03));
  }
}

TEST_CASE("a plastic shell section with one point is warned as membrane-only",
          "[solver][shell][plasticity]") {
  for (int points : {1, 5}) {
    PlateSpec spec;
    spec.nx = spec.ny = 2;
    spec.integration_points = points;
    Model m = make_plate(spec);
    m.materials[0].plastic = perfectly_plastic(SY);
    m.shell_sections[0].where = {"plate.inp", 12};
    CaptureSink sink;
    ExplicitSolver solver(m, sink);
    solver.check();
    int warned = 0;
    for (const std::string& text : sink.messages)
      if (text.find("plate.inp:12: *SHELL SECTION: 1 section point on the plastic material "
                    "STEEL: a membrane-only section") != std::string::npos)
        ++warned;
    CHECK(warned == (points == 1 ? 1 : 0));
  }
}

TEST_CASE("plastic shell results do not depend on the thread count",
          "[.][solver][shell][plasticity][threads]") {
  // 48 × 48 plate (every colour runs in parallel, see simd::MIN_PARALLEL_BATCHES), simply
  // supported, 300 kPa suddenly applied: the bending stresses pass σy = 100 MPa within the
  // first millisecond, so most section points return.
  PlateSpec spec;
  spec.nx = spec.ny = 48;
  spec.period = 1e-3;
  Model m = make_plate(spec);
  m.materials[0].plastic = perfectly_plastic(100e6);
  fix(m, 0, 3, 3);
  m.steps[0].boundaries.push_back(
      {plate_node(spec, 0, 0), 1, 2, 0.0, BoundaryType::Displacement, NO_INDEX, {}});
  m.steps[0].boundaries.push_back(
      {plate_node(spec, 48, 0), 2, 2, 0.0, BoundaryType::Displacement, NO_INDEX, {}});
  for (Index e = 0; e < m.element_count(); ++e)
    m.steps[0].pressures.push_back({{e, SHELL_FACE_POS}, 3e5, NO_INDEX, {}});
  std::vector<std::vector<Real>> runs;
  for (int threads : {1, 2}) {
    CaptureSink sink;
    SolverOptions options;
    options.threads = threads;
    ExplicitSolver solver(m, sink, options);
    solver.run();  // with the plumbing: also CHECK(run().energies.plastic > 0)
    std::vector<Real> flat;
    for (const auto& row : sink.rows) flat.insert(flat.end(), row.begin(), row.end());
    runs.push_back(flat);
  }
  REQUIRE(runs[0].size() == runs[1].size());
  for (std::size_t k = 0; k < runs[0].size(); ++k) CHECK(runs[0][k] == runs[1][k]);
  omp_set_num_threads(omp_get_num_procs());
}
