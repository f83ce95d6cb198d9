#include <catch2/catch.hpp>

#include <cmath>

#include "elements/material/plasticity.hpp"

using namespace xpl;
using namespace xpl::elements;

namespace {

Plasticity table(std::vector<Real> stress, std::vector<Real> strain) {
  Plasticity p;
  p.hardening = Hardening::Tabular;
  p.yield_stress = std::move(stress);
  p.plastic_strain = std::move(strain);
  return p;
}

Plasticity johnson_cook(Real a, Real b, Real n) {
  Plasticity p;
  p.hardening = Hardening::JohnsonCook;
  p.jc_a = a;
  p.jc_b = b;
  p.jc_n = n;
  return p;
}

/// The consistency condition the return solves: q_trial − 3G Δ − σ_y(ε̄ + Δ, Δ/dt).
Real residual(const Plasticity& law, Real q_trial, Real three_g, Real peeq, Real dt,
              const PlasticIncrement& r) {
  const Real rate = law.rate == RateDependence::None ? 0.0 : r.peeq_increment / dt;
  return q_trial - three_g * r.peeq_increment -
         flow_stress(law, peeq + r.peeq_increment, rate).stress;
}

constexpr Real THREE_G = 3.0 * 80e9;  // steel-like shear modulus, Pa

}  // namespace

TEST_CASE("tabular hardening interpolates linearly and is constant beyond the table",
          "[elements][plasticity]") {
  const Plasticity law = table({200e6, 300e6, 350e6}, {0.0, 0.1, 0.3});
  // Exact binary fractions of the segments: the interpolation is exact to round-off.
  CHECK(flow_stress(law, 0.0, 0.0).stress == Approx(200e6).epsilon(1e-14));
  CHECK(flow_stress(law, 0.05, 0.0).stress == Approx(250e6).epsilon(1e-14));
  CHECK(flow_stress(law, 0.1, 0.0).stress == Approx(300e6).epsilon(1e-14));
  CHECK(flow_stress(law, 0.2, 0.0).stress == Approx(325e6).epsilon(1e-14));
  CHECK(flow_stress(law, 0.05, 0.0).d_strain == Approx(1e9).epsilon(1e-12));
  // At a break the slope is the one of the segment that starts there (right derivative).
  CHECK(flow_stress(law, 0.1, 0.0).d_strain == Approx(2.5e8).epsilon(1e-12));
  // Beyond the last point: the last stress, no slope (as Abaqus does).
  CHECK(flow_stress(law, 0.3, 0.0).stress == 350e6);
  CHECK(flow_stress(law, 2.0, 0.0).stress == 350e6);
  CHECK(flow_stress(law, 2.0, 0.0).d_strain == 0.0);
  // One point: perfectly plastic.
  const Plasticity perfect = table({250e6}, {0.0});
  CHECK(flow_stress(perfect, 0.7, 0.0).stress == 250e6);
  CHECK(perfect.initial_yield() == 250e6);
  CHECK_FALSE(law.softens());
  CHECK(table({200e6, 150e6}, {0.0, 0.1}).softens());
}

TEST_CASE("Johnson-Cook hardening and its slope", "[elements][plasticity]") {
  const Plasticity law = johnson_cook(300e6, 500e6, 0.4);
  for (const Real e : {1e-4, 0.01, 0.1, 0.5, 1.0}) {
    const FlowStress f = flow_stress(law, e, 0.0);
    CHECK(f.stress == Approx(300e6 + 500e6 * std::pow(e, 0.4)).epsilon(1e-14));
    CHECK(f.d_strain == Approx(0.4 * 500e6 * std::pow(e, -0.6)).epsilon(1e-13));
  }
  CHECK(flow_stress(law, 0.0, 0.0).stress == 300e6);
  // Unbounded slope at ε̄ = 0 for n < 1: finite (evaluated at a tiny strain), positive.
  const Real slope0 = flow_stress(law, 0.0, 0.0).d_strain;
  CHECK(std::isfinite(slope0));
  CHECK(slope0 > 0.0);
  CHECK(law.initial_yield() == 300e6);
}

TEST_CASE("rate laws: Johnson-Cook logarithm and Cowper-Symonds power law",
          "[elements][plasticity]") {
  Plasticity jc = johnson_cook(300e6, 0.0, 1.0);
  jc.rate = RateDependence::JohnsonCook;
  jc.rate_c = 0.02;
  jc.rate_reference = 1.0;
  CHECK(flow_stress(jc, 0.1, 0.5).stress == 300e6);  // below ε̇_0: no effect
  CHECK(flow_stress(jc, 0.1, 1000.0).stress ==
        Approx(300e6 * (1.0 + 0.02 * std::log(1000.0))).epsilon(1e-14));
  CHECK(flow_stress(jc, 0.1, 1000.0).d_rate == Approx(300e6 * 0.02 / 1000.0).epsilon(1e-14));

  Plasticity cs = table({250e6, 350e6}, {0.0, 0.2});
  cs.rate = RateDependence::PowerLaw;
  cs.power_d = 40.4;
  cs.power_n = 5.0;
  CHECK(flow_stress(cs, 0.1, 0.0).stress == Approx(300e6).epsilon(1e-14));
  const Real r = 1.0 + std::pow(100.0 / 40.4, 0.2);
  CHECK(flow_stress(cs, 0.1, 100.0).stress == Approx(300e6 * r).epsilon(1e-14));
  CHECK(flow_stress(cs, 0.1, 100.0).d_strain == Approx(5e8 * r).epsilon(1e-13));
  CHECK(flow_stress(cs, 0.1, 100.0).d_rate ==
        Approx(300e6 * 0.2 * std::pow(100.0 / 40.4, -0.8) / 40.4).epsilon(1e-13));
}

TEST_CASE("radial return: admissible trial states are left alone", "[elements][plasticity]") {
  const Plasticity law = table({200e6, 300e6}, {0.0, 0.1});
  const PlasticIncrement r = radial_return(law, 150e6, THREE_G, 0.0, 1e-7);
  CHECK(r.peeq_increment == 0.0);
  CHECK(r.yield_stress == 200e6);
  // After hardening the yield stress is the one at the current PEEQ.
  CHECK(radial_return(law, 240e6, THREE_G, 0.05, 1e-7).peeq_increment == 0.0);
}

TEST_CASE("radial return is exact for linear hardening", "[elements][plasticity]") {
  const Real h = 2e9;
  const Plasticity law = table({200e6, 200e6 + h}, {0.0, 1.0});
  for (const Real peeq : {0.0, 0.01, 0.3}) {
    const Real sy = 200e6 + h * peeq;
    const Real q = sy + 50e6;
    const PlasticIncrement r = radial_return(law, q, THREE_G, peeq, 1e-7);
    // Closed form Δ = (q − σ_y)/(3G + H), to round-off.
    CHECK(r.peeq_increment == Approx(50e6 / (THREE_G + h)).epsilon(1e-13));
    CHECK(r.yield_stress == Approx(sy + h * r.peeq_increment).epsilon(1e-14));
    CHECK(std::abs(residual(law, q, THREE_G, peeq, 1e-7, r)) <= 1e-12 * r.yield_stress);
  }
}

TEST_CASE("radial return satisfies the consistency condition for tables, JC and rate laws",
          "[elements][plasticity]") {
  std::vector<Plasticity> laws;
  laws.push_back(table({200e6, 300e6, 320e6, 320e6}, {0.0, 0.002, 0.05, 0.2}));
  laws.push_back(johnson_cook(300e6, 500e6, 0.3));
  Plasticity jc_rate = johnson_cook(300e6, 500e6, 0.3);
  jc_rate.rate = RateDependence::JohnsonCook;
  jc_rate.rate_c = 0.02;
  jc_rate.rate_reference = 1.0;
  laws.push_back(jc_rate);
  Plasticity cs = table({250e6, 400e6}, {0.0, 0.5});
  cs.rate = RateDependence::PowerLaw;
  cs.power_d = 40.4;
  cs.power_n = 5.0;
  laws.push_back(cs);
  laws.push_back(table({250e6, 200e6}, {0.0, 0.1}));  // softening
  int n = 0;
  for (const Plasticity& law : laws)
    for (const Real peeq : {0.0, 0.001, 0.04, 0.3})
      for (const Real excess : {1e3, 1e6, 3e7, 5e8})
        for (const Real dt : {1e-8, 1e-6}) {
          const Real sy0 = flow_stress(law, peeq, 0.0).stress;
          const Real q = sy0 + excess;
          const PlasticIncrement r = radial_return(law, q, THREE_G, peeq, dt);
          INFO("law " << n / 32 << " peeq " << peeq << " excess " << excess << " dt " << dt);
          CHECK(r.peeq_increment > 0.0);
          CHECK(r.peeq_increment < q / THREE_G);
          // The solver's own stopping criterion, 1e-12 of σ_y, with room for the round-off of
          // q − 3GΔ (a few ulp of q).
          CHECK(std::abs(residual(law, q, THREE_G, peeq, dt, r)) <=
                1e-12 * r.yield_stress + 8 * 2.2e-16 * q);
          const Real rate = law.rate == RateDependence::None ? 0.0 : r.peeq_increment / dt;
          CHECK(r.yield_stress == flow_stress(law, peeq + r.peeq_increment, rate).stress);
          ++n;
        }
}
