// The plastic returns end on the yield surface for every law the deck reader accepts
// (issue 33, item 4): a sweep of hardening and rate-law parameters, overstresses, plastic
// strains and increments through the J2 return of the solids (radial_return, and the batch
// return of the hex lanes) and the plane-stress return of the shells.
//
// Before, Newton crept from above on steep laws (Cowper–Symonds n ≤ 0.2, Johnson–Cook
// hardening n = 0.01) and stopped after 100 iterations with a flow stress up to 1e120 times
// the trial stress, or overshot it by 0.2–20 %.

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "elements/material/plasticity.hpp"
#include "elements/material/radial_return_lanes.hpp"
#include "elements/material/shell_plasticity.hpp"

using namespace xpl;
using namespace xpl::elements;

namespace {

constexpr Real E = 200e9, NU = 0.3;
constexpr Real G = E / (2 * (1 + NU)), THREE_G = 3.0 * G;
constexpr Real Q11 = E / (1 - NU * NU), Q12 = NU * Q11;

/// A law of the sweep: exponents, constants and hardening from far below to far above the
/// usual ones, with the parameters of the issue (n = 0.05, D = 40; Johnson–Cook n = 0.01).
struct NamedLaw {
  std::string name;
  Plasticity law;
};

/// The laws of the sweep the reader accepts: all 60 Johnson–Cook ones and 49 of the 54
/// Cowper–Symonds ones (n = 0.01, an exponent of 100, overflows at 1e8 /s unless D = 1e8).
constexpr std::size_t ACCEPTED_LAWS = 109;

/// Whether the deck reader accepts `law` (io/deck/deck_plastic.cpp): its flow stress is
/// finite up to the plausible plastic strain and strain rate.
bool accepted(const Plasticity& law) {
  return std::isfinite(law.largest_flow_stress());
}

/// The laws of the sweep that the reader accepts (of 54 Cowper–Symonds and 60 Johnson–Cook).
std::vector<NamedLaw> sweep_laws() {
  std::vector<NamedLaw> laws;
  const auto describe = [](const char* what, Real a, Real b) {
    std::ostringstream text;
    text << what << " " << a << ", " << b;
    return text.str();
  };
  for (const Real n : {0.01, 0.05, 0.1, 0.2, 0.5, 1.0, 5.0, 20.0, 100.0})
    for (const Real d : {1e-6, 0.01, 1.0, 40.0, 1e4, 1e8}) {
      Plasticity p;
      p.yield_stress = {250e6, 350e6};
      p.plastic_strain = {0.0, 0.2};
      p.rate = RateDependence::PowerLaw;
      p.power_d = d;
      p.power_n = n;
      if (accepted(p)) laws.push_back({describe("table, Cowper-Symonds n, D", n, d), p});
    }
  for (const Real n : {0.01, 0.05, 0.3, 1.0, 5.0})
    for (const Real b : {0.0, 100e6, 1e9})
      for (const Real c : {0.0, 1e-4, 0.02, 1.0}) {
        Plasticity p;
        p.hardening = Hardening::JohnsonCook;
        p.jc_a = 300e6;
        p.jc_b = b;
        p.jc_n = n;
        if (c > 0.0) {
          p.rate = RateDependence::JohnsonCook;
          p.rate_c = c;
          p.rate_reference = c < 0.01 ? 1e-3 : 1.0;
        }
        if (accepted(p))
          laws.push_back({describe("Johnson-Cook n, B", n, b) + ", C " + std::to_string(c), p});
      }
  return laws;
}

/// Whether σ_y = `yield` lies on the flow stress curve at Δε̄ᵖ = `dpeeq` to round-off: between
/// the flow stresses just below and just above it (a steep law rises by many ulps between
/// neighbouring doubles, and at ε̄ᵖ = 0 with n = 0.01 it jumps there).
bool on_flow_curve(const Plasticity& law, Real peeq, Real dpeeq, Real dt, Real yield) {
  const auto flow = [&](Real x) {
    return flow_stress(law, peeq + x, law.rate == RateDependence::None ? 0.0 : x / dt).stress;
  };
  // Above: 1e-13 relative, or 1e-300 absolute (a plastic strain of 1e-300 is none; the
  // shell return brackets Δγ, whose neighbouring doubles at 0 give Δε̄ᵖ ~ 1e-315, where a
  // flat power law with n = 100 already jumps by 0.1 %).
  const Real below = dpeeq * (1.0 - 1e-13);
  const Real above = std::max(
      std::nextafter(dpeeq * (1.0 + 1e-13), std::numeric_limits<Real>::infinity()), dpeeq + 1e-300);
  const Real slack = 1e-11 * yield;
  return flow(below) <= yield + slack && flow(above) >= yield - slack;
}

}  // namespace

TEST_CASE("the J2 return ends on the yield surface for steep rate laws and hardening",
          "[elements][plasticity][sweep]") {
  const std::vector<NamedLaw> laws = sweep_laws();
  CHECK(laws.size() == ACCEPTED_LAWS);
  int returns = 0;
  for (const NamedLaw& named : laws)
    for (const Real peeq : {0.0, 1e-4, 0.1})
      for (const Real overstress : {1e-9, 1e-4, 0.01, 0.3, 3.0})
        for (const Real dt : {1e-8, 1e-6}) {
          const Plasticity& law = named.law;
          const Real q = flow_stress(law, peeq, 0.0).stress * (1.0 + overstress);
          const PlasticIncrement r = radial_return(law, q, THREE_G, peeq, dt);
          INFO(named.name << ", peeq " << peeq << ", overstress " << overstress << ", dt " << dt
                          << ": dpeeq " << r.peeq_increment << ", yield " << r.yield_stress
                          << ", q " << q);
          REQUIRE(std::isfinite(r.yield_stress));
          CHECK(r.peeq_increment >= 0.0);
          CHECK(r.peeq_increment <= q / THREE_G);
          // The stress written is σ_y (the deviator scaled by σ_y/q): it must be the stress
          // on the surface, q − 3GΔ, to the solver's tolerance and the round-off of q − 3GΔ.
          CHECK(std::abs(r.yield_stress - (q - THREE_G * r.peeq_increment)) <=
                1e-12 * r.yield_stress + 8 * 2.2e-16 * q);
          CHECK(on_flow_curve(law, peeq, r.peeq_increment, dt, r.yield_stress));
          ++returns;
        }
  CHECK(returns == static_cast<int>(ACCEPTED_LAWS) * 30);
}

TEST_CASE("the batch return of the hex lanes ends on the yield surface for steep laws",
          "[elements][plasticity][sweep]") {
  // The lanes send rate laws and Johnson–Cook to radial_return: one row per law, lanes at
  // several overstresses in a uniaxial trial state.
  constexpr int W = RadialReturnLanes::W;
  const std::vector<NamedLaw> named = sweep_laws();
  std::vector<Plasticity> laws;
  for (const NamedLaw& n : named) laws.push_back(n.law);
  RadialReturnLanes lanes(laws.size() * W);
  int checked = 0;
  for (std::size_t k = 0; k < laws.size(); ++k) {
    int lane_law[W];
    simd::Vec sn[6];
    for (auto& c : sn) c = simd::splat(0.0);
    const Real sy = flow_stress(laws[k], 0.0, 0.0).stress;
    Real q[W];
    for (int l = 0; l < W; ++l) {
      lane_law[l] = static_cast<int>(k);
      lanes.reset(k * W + static_cast<std::size_t>(l), laws[k], 0.0);
      q[l] = sy * (1.0 + std::pow(10.0, -1.0 - 2.0 * l));  // uniaxial: q = |σ11|
      sn[0][l] = q[l];
    }
    Real rate[W];
    simd::Vec start[6];
    for (auto& c : start) c = simd::splat(0.0);
    lanes.return_row(k * W, lane_law, laws, start, sn, simd::splat(2.0 * G), 1e-6, rate);
    for (int l = 0; l < W; ++l) {
      const Real p = (sn[0][l] + sn[1][l] + sn[2][l]) / 3.0;
      const Real d0 = sn[0][l] - p, d1 = sn[1][l] - p, d2 = sn[2][l] - p;
      const Real vm = std::sqrt(1.5 * (d0 * d0 + d1 * d1 + d2 * d2));
      const Real dpeeq = lanes.peeq(k * W + static_cast<std::size_t>(l));
      INFO(named[k].name << ", lane " << l << ": q " << q[l] << ", vm " << vm << ", dpeeq "
                         << dpeeq);
      CHECK(std::abs(vm - (q[l] - THREE_G * dpeeq)) <= 1e-11 * q[l]);
      CHECK(on_flow_curve(laws[k], 0.0, dpeeq, 1e-6, vm));
      ++checked;
    }
  }
  CHECK(checked == static_cast<int>(laws.size()) * W);
}

TEST_CASE("the plane-stress return ends on the yield surface for steep laws",
          "[elements][plasticity][shell][sweep]") {
  int returns = 0;
  for (const NamedLaw& named : sweep_laws())
    for (const Real peeq : {0.0, 1e-4, 0.1})
      for (const Real overstress : {1e-9, 1e-4, 0.01, 0.3, 3.0})
        for (const Real dt : {1e-8, 1e-6}) {
          const Plasticity& law = named.law;
          // A biaxial trial with shear, scaled to the overstress.
          const Real sy = flow_stress(law, peeq, 0.0).stress;
          const Real bxx = 1.0, byy = -0.4, bxy = 0.3;
          const Real unit = std::sqrt(bxx * bxx - bxx * byy + byy * byy + 3.0 * bxy * bxy);
          const Real s = sy * (1.0 + overstress) / unit;
          const PlaneStressReturn r =
              plane_stress_return(law, Q11, Q12, G, s * bxx, s * byy, s * bxy, peeq, dt);
          const Real vm =
              std::sqrt(r.sxx * r.sxx - r.sxx * r.syy + r.syy * r.syy + 3.0 * r.sxy * r.sxy);
          INFO(named.name << ", peeq " << peeq << ", overstress " << overstress << ", dt " << dt
                          << ": dpeeq " << r.peeq_increment << ", yield " << r.yield_stress
                          << ", vm " << vm);
          REQUIRE(std::isfinite(r.yield_stress));
          CHECK(r.peeq_increment >= 0.0);
          CHECK(std::abs(vm - r.yield_stress) <= 1e-11 * r.yield_stress);
          CHECK(vm <= sy * (1.0 + overstress) * (1.0 + 1e-12));
          CHECK(on_flow_curve(law, peeq, r.peeq_increment, dt, r.yield_stress));
          ++returns;
        }
  CHECK(returns == static_cast<int>(ACCEPTED_LAWS) * 30);
}
