// One C3D8R element in uniaxial stress through the whole solver: the face x = H is pulled at
// a prescribed velocity, the faces x = 0, y = 0 and z = 0 are symmetry planes, the faces
// y = H and z = H are free. The stress-strain curve, PEEQ, the volume, the unloading slope
// and the energies are compared with the hardening law (issue 14, acceptance 1, hexes).

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "elements/material/plasticity.hpp"
#include "solver/explicit_solver.hpp"
#include "solver_fixtures.hpp"

using namespace xpl;
using elements::Plasticity;

namespace {

constexpr Real H = 0.01;  // element edge, m
constexpr Real E = 200e9, NU = 0.3, RHO = 7850.0;

/// What a frame of the single element holds.
struct Sample {
  Real time = 0.0;
  Real strain = 0.0;   ///< logarithmic axial strain ln(L/H)
  Real stress = 0.0;   ///< S11, Pa
  Real lateral = 0.0;  ///< largest |S22|, |S33|, |S12|, |S13|, |S23|, Pa
  Real peeq = 0.0;
  Real log_volume = 0.0;  ///< ln(V/H³)
};

/// Keeps the single element's frames and the energy history.
class UniaxialSink : public test::CaptureSink {
 public:
  std::vector<Sample> samples;
  Index loaded_node = 1;  // node (H, 0, 0)
  void write_frame(const Model& model, const State& state, const FrameFields& fields,
                   const FrameRequest& what) override {
    CaptureSink::write_frame(model, state, fields, what);
    Sample s;
    s.time = state.time;
    s.strain = std::log((H + state.displacement(loaded_node, 0)) / H);
    std::vector<Real> buffer;
    const std::vector<Real>& stress = fields.element_rows(ElementField::Stress, buffer);
    s.stress = stress[0];
    for (int c = 1; c < 6; ++c) s.lateral = std::max(s.lateral, std::abs(stress[c]));
    s.peeq = fields.peeq.empty() ? -1.0 : fields.peeq[0];
    s.log_volume = std::log(fields.element_rows(ElementField::Volume, buffer)[0] / (H * H * H));
    samples.push_back(s);
  }
  Real energy(const std::string& name, std::size_t row) const {
    return rows[row][static_cast<std::size_t>(column("energy/" + name))];
  }
};

/// Pulled at `velocity` (m/s, ramped up over 20 µs) until `load_time`, then pushed back at
/// the same speed (ramped over 20 µs) until `end_time`.
Model make_uniaxial(const Plasticity& law, Real velocity, Real load_time, Real end_time) {
  Model m;
  m.job_name = "uniaxial";
  m.coordinates.resize(8, 3);
  const Real corners[8][3] = {{0, 0, 0}, {H, 0, 0}, {H, H, 0}, {0, H, 0},
                              {0, 0, H}, {H, 0, H}, {H, H, H}, {0, H, H}};
  for (Index n = 0; n < 8; ++n) {
    m.node_ids.push_back(n + 1);
    for (int c = 0; c < 3; ++c) m.coordinates(n, c) = corners[n][c];
  }
  m.element_ids.push_back(1);
  m.element_types.push_back(ElementType::C3D8R);
  for (Index n = 0; n < 8; ++n) m.element_nodes.push_back(n);
  m.element_offsets.push_back(8);
  m.element_section.push_back(0);
  Material metal;
  metal.name = "METAL";
  metal.density = RHO;
  metal.young = E;
  metal.poisson = NU;
  metal.has_density = metal.has_elastic = true;
  metal.plastic = law;
  m.materials.push_back(metal);
  m.element_sets.push_back({"ALL", {0}, {}});
  m.solid_sections.push_back({0, 0, NO_INDEX, {}});
  m.initial_velocity = NodalVectors::Zero(8, 3);

  const Real rise = 20e-6;
  Amplitude pull;
  pull.name = "PULL";
  pull.time = {0.0, rise, load_time, load_time + rise, end_time};
  pull.value = {0.0, 1.0, 1.0, -1.0, -1.0};
  m.amplitudes.push_back(pull);

  Step step;
  step.name = "PULL";
  step.time_period = end_time;
  for (Index n = 0; n < 8; ++n) {
    for (int c = 0; c < 3; ++c)
      if (m.coordinates(n, c) == 0.0)
        step.boundaries.push_back({n, c + 1, c + 1, 0.0, BoundaryType::Displacement, NO_INDEX, {}});
    if (m.coordinates(n, 0) == H)
      step.boundaries.push_back({n, 1, 1, velocity, BoundaryType::Velocity, 0, {}});
  }
  OutputRequest field;
  field.kind = OutputRequest::Kind::Field;
  field.number_interval = 400;
  field.node_variables = {"U"};
  field.element_variables = {"S", "EVOL", "PEEQ"};
  step.outputs.push_back(field);
  OutputRequest history;
  history.kind = OutputRequest::Kind::History;
  history.number_interval = 400;
  history.energy = true;
  step.outputs.push_back(history);
  m.steps.push_back(step);
  return m;
}

struct Run {
  UniaxialSink sink;
  Real load_time = 0.0;
};

void run(const Plasticity& law, Real velocity, Real load_time, Real end_time, UniaxialSink& sink) {
  const Model model = make_uniaxial(law, velocity, load_time, end_time);
  ExplicitSolver solver(model, sink);
  solver.run();
  REQUIRE(sink.run_status == RunStatus::Completed);
}

/// Checks the loading branch against σ = σ_y(ε̄ᵖ, ε̇ᵖ) with ε̄ᵖ = ε − σ/E from the measured
/// strain and stress; returns the number of plastic frames checked.
int check_loading(const UniaxialSink& sink, const Plasticity& law, Real load_time, bool rate) {
  const std::vector<Sample>& s = sink.samples;
  int checked = 0;
  Real max_plastic = 0.0;
  for (std::size_t i = 1; i + 1 < s.size() && s[i + 1].time <= load_time; ++i) {
    const Real plastic = s[i].strain - s[i].stress / E;
    // Past the elastic-plastic transition (and the 20 µs ramp).
    if (plastic < 2e-3) continue;
    const Real plastic_before = s[i - 1].strain - s[i - 1].stress / E;
    const Real plastic_after = s[i + 1].strain - s[i + 1].stress / E;
    const Real plastic_rate = (plastic_after - plastic_before) / (s[i + 1].time - s[i - 1].time);
    const Real expected = elements::flow_stress(law, plastic, rate ? plastic_rate : 0.0).stress;
    INFO("t = " << s[i].time << " strain " << s[i].strain << " plastic " << plastic << " rate "
                << plastic_rate);
    // Acceptance: the curve to 0.1 % (rate laws: the rate factor's formula to 0.5 %).
    CHECK(s[i].stress == Approx(expected).epsilon(rate ? 5e-3 : 1e-3));
    // PEEQ is the plastic strain: the same to 1e-4 of it (the measured ε − σ/E carries the
    // round-off of a 1e-3 elastic strain over a few hundred increments).
    CHECK(s[i].peeq == Approx(plastic).epsilon(1e-4));
    // Uniaxial: the other components vanish but for the free faces' inertia.
    CHECK(s[i].lateral <= 1e-3 * std::abs(s[i].stress));
    // Plastic flow keeps the volume: ln(V/V0) is the elastic tr(σ)/3K = (1 − 2ν) σ/E.
    CHECK(s[i].log_volume == Approx((1.0 - 2.0 * NU) * s[i].stress / E).margin(1e-6));
    max_plastic = std::max(max_plastic, plastic);
    if (std::getenv("XPL_TEST_REPORT"))
      std::printf("REPORT %g stress_err %.3e peeq_err %.3e lateral %.3e dvol %.3e\n", plastic,
                  s[i].stress / expected - 1.0, s[i].peeq / plastic - 1.0,
                  s[i].lateral / s[i].stress, s[i].log_volume - (1.0 - 2.0 * NU) * s[i].stress / E);
    ++checked;
  }
  INFO("largest plastic strain checked " << max_plastic);
  CHECK(max_plastic > 0.05);
  return checked;
}

/// Unloading: the slope dσ/dε is E and PEEQ does not change while the stress falls from 90 %
/// to 10 % of its peak.
void check_unloading(const UniaxialSink& sink, Real load_time) {
  const std::vector<Sample>& s = sink.samples;
  Real peak = 0.0;
  for (const Sample& x : s) peak = std::max(peak, x.stress);
  std::vector<Sample> branch;
  for (const Sample& x : s)
    if (x.time > load_time && x.stress < 0.9 * peak && x.stress > 0.1 * peak) branch.push_back(x);
  REQUIRE(branch.size() >= 3);
  const Sample& a = branch.front();
  const Sample& b = branch.back();
  // Slope to 0.1 %: the Jaumann rate of a uniaxial state is exactly σ̇ = E d(ln L)/dt.
  CHECK((a.stress - b.stress) / (a.strain - b.strain) == Approx(E).epsilon(1e-3));
  if (std::getenv("XPL_TEST_REPORT"))
    std::printf("REPORT unloading slope/E - 1 = %.3e\n",
                (a.stress - b.stress) / (a.strain - b.strain) / E - 1.0);
  CHECK(b.peeq == a.peeq);
}

}  // namespace

TEST_CASE("uniaxial stress, tabular hardening (4 points)", "[solver][plasticity]") {
  Plasticity law;
  law.yield_stress = {250e6, 300e6, 340e6, 350e6};
  law.plastic_strain = {0.0, 0.02, 0.06, 0.2};
  UniaxialSink sink;
  const Real load_time = 10e-3, end_time = 11e-3;
  run(law, 0.1, load_time, end_time, sink);
  CHECK(check_loading(sink, law, load_time, false) >= 5);
  check_unloading(sink, load_time);
}

TEST_CASE("uniaxial stress, linear hardening: dissipation and energy balance",
          "[solver][plasticity]") {
  const Real sy = 250e6, hardening = 2e9;
  Plasticity law;
  law.yield_stress = {sy, sy + hardening};
  law.plastic_strain = {0.0, 1.0};
  UniaxialSink sink;
  const Real load_time = 10e-3, end_time = 11e-3;
  run(law, 0.1, load_time, end_time, sink);
  CHECK(check_loading(sink, law, load_time, false) >= 5);
  check_unloading(sink, load_time);

  // ALLPD = ∫ σ_y(ε̄ᵖ) V dε̄ᵖ along the frames (trapezoid; V changes by 1e-3 between tension
  // and the reverse yield in compression at the end); ALLSE at the end is the elastic energy
  // left at the last stress, σ²/2E V.
  const std::size_t last = sink.rows.size() - 1;
  REQUIRE(sink.times[last] == sink.samples.back().time);
  Real allpd = 0.0;
  for (std::size_t i = 1; i < sink.samples.size(); ++i) {
    const Sample& a = sink.samples[i - 1];
    const Sample& b = sink.samples[i];
    const auto density = [&](const Sample& x) {
      return (sy + hardening * x.peeq) * H * H * H * std::exp(x.log_volume);
    };
    allpd += 0.5 * (density(a) + density(b)) * (b.peeq - a.peeq);
  }
  const Sample& end = sink.samples.back();
  const Real volume = H * H * H * std::exp(end.log_volume);
  // 1e-3: the trapezoid over 400 frames of a quadratic integrand is exact to 1e-6; the rest
  // is the frames' sampling of the yield transition.
  CHECK(sink.energy("ALLPD", last) == Approx(allpd).epsilon(1e-3));
  if (std::getenv("XPL_TEST_REPORT"))
    std::printf("REPORT ALLPD %g integral %g\n", sink.energy("ALLPD", last), allpd);
  CHECK(sink.energy("ALLSE", last) ==
        Approx(end.stress * end.stress / (2.0 * E) * volume).epsilon(2e-2));
  CHECK(sink.energy("ALLIE", last) ==
        Approx(sink.energy("ALLSE", last) + sink.energy("ALLPD", last) + sink.energy("ALLAE", last))
            .epsilon(1e-12));
  // The work of the prescribed face goes into ALLIE (+ the kinetic and viscous parts):
  // ETOTAL stays at zero to 1e-4 of the work.
  const Real work = sink.energy("ALLWK", last);
  CHECK(work > 0.9 * sink.energy("ALLPD", last));
  for (std::size_t r = 0; r < sink.rows.size(); ++r)
    CHECK(std::abs(sink.energy("ETOTAL", r)) <= 1e-4 * work);
}

TEST_CASE("uniaxial stress, Johnson-Cook hardening", "[solver][plasticity]") {
  Plasticity law;
  law.hardening = elements::Hardening::JohnsonCook;
  law.jc_a = 300e6;
  law.jc_b = 500e6;
  law.jc_n = 0.3;
  UniaxialSink sink;
  const Real load_time = 10e-3, end_time = 11e-3;
  run(law, 0.1, load_time, end_time, sink);
  CHECK(check_loading(sink, law, load_time, false) >= 5);
  check_unloading(sink, load_time);
}

TEST_CASE("uniaxial stress, Johnson-Cook rate law at 100/s", "[solver][plasticity]") {
  Plasticity law;
  law.hardening = elements::Hardening::JohnsonCook;
  law.jc_a = 300e6;
  law.jc_b = 500e6;
  law.jc_n = 0.3;
  law.rate = elements::RateDependence::JohnsonCook;
  law.rate_c = 0.02;
  law.rate_reference = 1.0;
  UniaxialSink sink;
  const Real load_time = 1.0e-3, end_time = 1.1e-3;
  run(law, 1.0, load_time, end_time, sink);
  CHECK(check_loading(sink, law, load_time, true) >= 5);
  // The rate raises the flow stress: R = 1 + C ln(100) = 1.092 at the nominal rate.
  const Sample& s = sink.samples[sink.samples.size() * 8 / 10];
  const Real plastic = s.strain - s.stress / E;
  CHECK(s.stress / elements::flow_stress(law, plastic, 0.0).stress > 1.08);
}

TEST_CASE("uniaxial stress, Cowper-Symonds power law at 100/s", "[solver][plasticity]") {
  Plasticity law;
  law.yield_stress = {250e6, 250e6 + 1e9};
  law.plastic_strain = {0.0, 1.0};
  law.rate = elements::RateDependence::PowerLaw;
  law.power_d = 40.4;
  law.power_n = 5.0;
  UniaxialSink sink;
  const Real load_time = 1.0e-3, end_time = 1.1e-3;
  run(law, 1.0, load_time, end_time, sink);
  CHECK(check_loading(sink, law, load_time, true) >= 5);
  const Sample& s = sink.samples[sink.samples.size() * 8 / 10];
  const Real plastic = s.strain - s.stress / E;
  // R = 1 + (ε̇/D)^(1/n) ≈ 2.2 at 100/s.
  CHECK(s.stress / elements::flow_stress(law, plastic, 0.0).stress > 2.1);
}
