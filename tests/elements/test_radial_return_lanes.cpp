#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <vector>

#include "elements/material/plasticity.hpp"
#include "elements/material/radial_return_lanes.hpp"

using namespace xpl;
using namespace xpl::elements;
using simd::Vec;
using simd::W;

namespace {

Plasticity table(std::vector<Real> stress, std::vector<Real> strain) {
  Plasticity p;
  p.yield_stress = std::move(stress);
  p.plastic_strain = std::move(strain);
  return p;
}

/// The return of one lane the way the hex kernels did it before the batch return: the
/// scalar radial_return on the trial's von Mises stress, the deviator scaled, PEEQ and the
/// next yield stress from flow_stress. The reference the batch must reproduce.
struct LaneReference {
  Real stress[6];
  Real peeq, dissipation;
};

LaneReference scalar_lane(const Plasticity& law, const Real start[6], const Real trial[6],
                          Real two_mu, Real peeq, Real dt) {
  LaneReference out{};
  for (int c = 0; c < 6; ++c) out.stress[c] = trial[c];
  out.peeq = peeq;
  const Real p = (trial[0] + trial[1] + trial[2]) * (1.0 / 3.0);
  const Real dev[6] = {trial[0] - p, trial[1] - p, trial[2] - p, trial[3], trial[4], trial[5]};
  const Real q2 = 1.5 * (dev[0] * dev[0] + dev[1] * dev[1] + dev[2] * dev[2]) +
                  3.0 * (dev[3] * dev[3] + dev[4] * dev[4] + dev[5] * dev[5]);
  const Real y = flow_stress(law, peeq, 0.0).stress;
  if (!(q2 > y * y)) return out;
  const Real q = std::sqrt(q2);
  const PlasticIncrement r = radial_return(law, q, 1.5 * two_mu, peeq, dt);
  if (!(r.peeq_increment > 0.0)) return out;
  const Real scale = r.yield_stress / q;
  for (int c = 0; c < 3; ++c) out.stress[c] = p + scale * dev[c];
  for (int c = 3; c < 6; ++c) out.stress[c] = scale * dev[c];
  out.peeq = peeq + r.peeq_increment;
  // ½(σ_n + σ_{n+1}) : Δεᵖ, Δεᵖ = (σ_trial − σ_{n+1}) / 2μ (shears twice: Voigt).
  for (int c = 0; c < 6; ++c)
    out.dissipation +=
        (c < 3 ? 0.5 : 1.0) * (start[c] + out.stress[c]) * (trial[c] - out.stress[c]) / two_mu;
  return out;
}

}  // namespace

TEST_CASE("the batch radial return of the hexes matches the scalar return lane by lane",
          "[elements][plasticity]") {
  // Law 0: three segments and a constant end (segment crossings within an increment); law 1:
  // perfectly plastic; law 2: Johnson–Cook with a rate law (always the scalar return).
  std::vector<Plasticity> laws = {table({200e6, 300e6, 350e6}, {0.0, 0.002, 0.01}),
                                  table({250e6}, {0.0}), Plasticity{}};
  laws[2].hardening = Hardening::JohnsonCook;
  laws[2].jc_a = 300e6;
  laws[2].jc_b = 500e6;
  laws[2].jc_n = 0.3;
  laws[2].rate = RateDependence::JohnsonCook;
  laws[2].rate_c = 0.02;
  laws[2].rate_reference = 1.0;
  const int lane_law[W] = {0, 0, 1, -1, 0, 2, 0, 1};
  const Real two_mu = 2.0 * 80e9, dt = 1e-7;

  std::mt19937 rng(7);
  std::uniform_real_distribution<Real> strain(-1.5e-3, 1.5e-3);
  RadialReturnLanes lanes(W);
  for (int l = 0; l < W; ++l)
    if (lane_law[l] >= 0) lanes.reset(static_cast<std::size_t>(l), laws[lane_law[l]], 0.0);
  std::vector<Real> stress(6 * W, 0.0), peeq(W, 0.0);
  int fast = 0, slow = 0, crossings = 0;
  for (int step = 0; step < 400; ++step) {
    // A random strain increment per lane on top of the current stress: loading, unloading
    // and reversed loading, several increments past the yield stress at a time.
    Vec sn[6];
    for (int c = 0; c < 6; ++c)
      for (int l = 0; l < W; ++l) sn[c][l] = stress[6 * l + c] + two_mu * strain(rng);
    LaneReference expected[W];
    for (int l = 0; l < W; ++l) {
      Real trial[6];
      for (int c = 0; c < 6; ++c) trial[c] = sn[c][l];
      if (lane_law[l] >= 0) {
        expected[l] = scalar_lane(laws[lane_law[l]], &stress[6 * l], trial, two_mu, peeq[l], dt);
        continue;
      }
      expected[l] = LaneReference{};  // elastic lane: the trial stays
      for (int c = 0; c < 6; ++c) expected[l].stress[c] = trial[c];
    }
    Real rate[W];
    Vec start[6];
    for (int c = 0; c < 6; ++c)
      for (int l = 0; l < W; ++l) start[c][l] = stress[6 * l + c];
    const Vec dissipation =
        lanes.return_row(0, lane_law, laws, start, sn, simd::splat(two_mu), dt, rate);
    for (int l = 0; l < W; ++l) {
      INFO("step " << step << " lane " << l);
      for (int c = 0; c < 6; ++c) CHECK(sn[c][l] == expected[l].stress[c]);
      CHECK(lanes.peeq(static_cast<std::size_t>(l)) == expected[l].peeq);
      // The same sum in another order: round-off of the stresses' size times Δεᵖ.
      CHECK(dissipation[l] == Approx(expected[l].dissipation).epsilon(1e-12).margin(1e-3));
      // Δε̄ᵖ/dt: the difference of the PEEQs is Δε̄ᵖ to round-off only.
      CHECK(rate[l] == Approx((expected[l].peeq - peeq[l]) / dt).epsilon(1e-9).margin(1e-6));
      if (expected[l].peeq > peeq[l]) {
        (lane_law[l] == 2 ? slow : fast) += 1;
        if (lane_law[l] == 0 && (peeq[l] < 0.002) != (expected[l].peeq < 0.002)) ++crossings;
      }
      for (int c = 0; c < 6; ++c) stress[6 * l + c] = sn[c][l];
      peeq[l] = expected[l].peeq;
    }
  }
  // The sequence exercised both returns and crossed a table break.
  CHECK(fast > 100);
  CHECK(slow > 10);
  CHECK(crossings > 0);
  CHECK(peeq[0] > 0.01);  // past the table's end: the constant part
}
