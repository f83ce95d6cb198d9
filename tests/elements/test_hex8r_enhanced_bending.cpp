// Bending with the enhanced assumed-strain hourglass stabilisation of C3D8R
// (elements/hex/hex8r_enhanced.hpp, issue 32): a cantilever with one element through the thickness
// against beam theory, static (from the stiffness product; element aspect ratios 4 to 0.25,
// ν = 0 and 0.3, skewed and tapered meshes) and dynamic (its first bending period from the
// explicit force pass), beside the stiffness form. Prints the tables of benchmarks/RESULTS.md.

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <numeric>
#include <random>
#include <vector>

#include <Eigen/Dense>

#include "cantilever_fixture.hpp"
#include "elements/hex/hex8.hpp"
#include "elements/hex/hex8_geometry.hpp"
#include "elements/hex/hex8r.hpp"
#include "hex_fixtures.hpp"

using namespace xpl;
using namespace xpl::elements;

namespace {

constexpr Real E = 200e9, RHO = 7850.0;

std::vector<HexMaterial> uniform(std::size_t n, Real nu, HourglassForm form,
                                 const Plasticity* plastic = nullptr) {
  return std::vector<HexMaterial>(n, HexMaterial{RHO, E, nu, form, 1.0, plastic});
}

Hex8rBlock block_of(const NodalVectors& x, const std::vector<Index>& connectivity,
                    const std::vector<HexMaterial>& materials) {
  std::vector<Index> rows(connectivity.size() / 8);
  std::iota(rows.begin(), rows.end(), 0);
  return Hex8rBlock(rows, connectivity, materials, static_cast<Index>(x.rows()));
}

/// Timoshenko cantilever under a tip load P: P L³ / (3 E I) + P L / (κ G A), κ = 5/6.
Real beam_deflection(Real length, Real width, Real depth, Real nu, Real load) {
  const Real inertia = width * depth * depth * depth / 12.0;
  const Real g = E / (2.0 * (1.0 + nu));
  return load * length * length * length / (3.0 * E * inertia) +
         load * length / (5.0 / 6.0 * g * width * depth);
}

NodalVectors zeros_like(const NodalVectors& x) {
  return NodalVectors::Zero(x.rows(), 3);
}

}  // namespace

TEST_CASE("enhanced: one element through the thickness bends as beam theory says",
          "[elements][hex8r][enhanced][bending]") {
  // Square section 10 mm, tip load 1 kN, clamped end; element aspect ratios (length over
  // thickness) from 4 to 0.25, beams of L/h = 4, 10 and 25, ν = 0 and 0.3.
  const Real depth = 0.01, width = 0.01, load = 1000.0;
  std::printf("| L/h | nu | elements | element length / h | ENHANCED tip / beam | STIFFNESS |\n");
  struct Case {
    Real slenderness;
    int nx;
  };
  const Case cases[] = {{4, 1},   {4, 2},   {4, 4},   {10, 5}, {10, 10},
                        {10, 20}, {10, 40}, {25, 25}, {25, 50}};
  for (const Real nu : {0.0, 0.3}) {
    for (const Case& c : cases) {
      const Real length = c.slenderness * depth;
      const test::Beam b = test::make_beam(c.nx, 1, length, width, depth);
      const std::vector<Index> rows = test::rows_of(b);
      const Hex8rBlock enhanced =
          block_of(b.x, b.connectivity, uniform(rows.size(), nu, HourglassForm::Enhanced));
      const Hex8rBlock stiffness =
          block_of(b.x, b.connectivity, uniform(rows.size(), nu, HourglassForm::Stiffness));
      const Real beam = beam_deflection(length, width, depth, nu, load);
      const Real ratio = test::tip_deflection(enhanced, b, load) / beam;
      const Real old_ratio = test::tip_deflection(stiffness, b, load) / beam;
      std::printf("| %.0f | %.1f | %d x 1 | %.2f | %.3f | %.3f |\n", c.slenderness, nu, c.nx,
                  length / c.nx / depth, ratio, old_ratio);
      INFO("L/h " << c.slenderness << ", nu " << nu << ", " << c.nx << " elements");
      // A single element (L/h = 4, 1 × 1) carries one mean curvature for a linear moment: the
      // midpoint rule of ∫M(L−x)dx/EI, 1 − 1/(4n²) = 0.75 of the deflection (measured 0.75,
      // 0.74); 2 elements: 0.94 by that rule, measured 0.93 (ν = 0) and 0.90 (ν = 0.3, the
      // clamped root's Poisson restraint counts on so short a beam). From 4 elements on, the
      // acceptance's 5 % applies.
      if (c.nx >= 4) CHECK(ratio == Approx(1.0).margin(0.05));
      if (c.nx == 2) CHECK(ratio == Approx(0.92).margin(0.04));
      if (c.nx == 1) CHECK(ratio == Approx(0.75).margin(0.03));
      // The stiffness form is far too soft wherever elements are not longer than thick.
      if (length / c.nx <= depth) CHECK(old_ratio > 1.5);
    }
  }
}

TEST_CASE("enhanced: skewed and tapered elements still bend",
          "[elements][hex8r][enhanced][bending]") {
  // L/h = 10, 10 elements, the interior cross sections leaning by ±s h along x (parallelogram
  // elements, s = 0.3 and 0.6: 17° and 31°) or tapered (trapezoids alternating). The form is
  // built in the element's frame with diagonal gradients (hex8r_enhanced.hpp): exact on
  // rectangular elements, stiffer on skewed ones, as the fully integrated hex (printed
  // beside; it is 20 % soft on the straight mesh through its mean dilatation).
  const Real depth = 0.01, width = 0.01, length = 0.1, load = 1000.0;
  const Real beam = beam_deflection(length, width, depth, 0.3, load);
  for (const Real lean : {0.0, 0.3, 0.6}) {
    for (const bool alternate : {false, true}) {
      test::Beam b = test::make_beam(10, 1, length, width, depth);
      for (Index n = 0; n < b.x.rows(); ++n) {
        const int i = static_cast<int>(std::lround(b.x(n, 0) / (length / 10)));
        if (i == 0 || i == 10) continue;
        const Real sign = alternate && i % 2 == 1 ? -1.0 : 1.0;
        b.x(n, 0) += sign * lean * depth * (b.x(n, 2) / depth - 0.5);
      }
      const std::vector<HexMaterial> materials = uniform(10, 0.3, HourglassForm::Enhanced);
      const Hex8rBlock block = block_of(b.x, b.connectivity, materials);
      const Real ratio = test::tip_deflection(block, b, load) / beam;
      const Hex8Block full(test::rows_of(b), b.connectivity, materials, b.x.rows());
      const Real full_ratio = test::tip_deflection(full, b, load) / beam;
      std::printf("skew %.1f h, %s: tip / beam C3D8R ENHANCED %.3f, C3D8 %.3f\n", lean,
                  alternate ? "trapezoids" : "parallelograms", ratio, full_ratio);
      INFO("lean " << lean << (alternate ? " trapezoids" : " parallelograms"));
      // Measured: parallelograms 0.91 (17°) and 0.74 (31°), trapezoids 0.85 and 0.61 (C3D8:
      // 1.05, 0.77, 0.98, 0.65). Stiffer than beam theory, never softer, and bending still:
      // the stiffness form's 2.9 on this mesh is the failure this bounds.
      if (lean == 0.0) CHECK(ratio == Approx(1.0).margin(0.05));
      if (lean == 0.3) CHECK(ratio > (alternate ? 0.8 : 0.87));
      CHECK(ratio > 0.55);
      CHECK(ratio < 1.05);
    }
  }
}

TEST_CASE("enhanced: first bending period of a free-vibrating cantilever",
          "[elements][hex8r][enhanced][dynamic]") {
  // The explicit force pass itself (rate form, stored resultants), not the stiffness product:
  // L/h = 10, 10 × 1 elements, the tip given an initial velocity in z; the period of the tip
  // motion against Euler–Bernoulli, T = 2π/ω, ω = 1.875² √(EI/(ρ A L⁴)), corrected for shear
  // and rotary inertia (Timoshenko, ≈ 1 % at L/h = 10: measured within 5 % in all).
  const Real depth = 0.01, width = 0.01, length = 0.1;
  for (const HourglassForm form : {HourglassForm::Enhanced, HourglassForm::Stiffness}) {
    const test::Beam b = test::make_beam(10, 1, length, width, depth);
    Hex8rBlock block = block_of(b.x, b.connectivity, uniform(10, 0.0, form));
    std::vector<Real> mass(b.x.rows(), 0.0);
    block.add_lumped_mass(b.x, mass);
    NodalVectors x = b.x, v = zeros_like(x), f = zeros_like(x);
    // First-mode-like start: velocity ∝ (x/L)² in z.
    for (Index n = 0; n < x.rows(); ++n) v(n, 2) = 0.1 * std::pow(x(n, 0) / length, 2);
    const Real c = std::sqrt(E / RHO);
    const Real dt = 0.5 * (length / 10) / c;
    const Index tip = b.tip[0];
    // Downward zero crossings of the tip deflection, interpolated within the increment.
    Real prev = 0.0, first = -1.0, last = -1.0;
    int crossings = 0;
    for (int step = 1; step <= 40000 && crossings < 5; ++step) {
      x += dt * v;
      f.setZero();
      HexStepTotals totals;
      block.internal_forces(x, v, dt, 0.0, 0.0, f, totals);
      for (Index n = 0; n < x.rows(); ++n) {
        if (b.fixed[n]) continue;
        for (int k = 0; k < 3; ++k) v(n, k) -= dt * f(n, k) / mass[n];
      }
      const Real w = x(tip, 2) - b.x(tip, 2);
      if (prev > 0.0 && w <= 0.0) {
        const Real t = (step - 1 + prev / (prev - w)) * dt;
        if (first < 0.0) first = t;
        last = t;
        ++crossings;
      }
      prev = w;
    }
    REQUIRE(crossings >= 2);
    const Real period = (last - first) / (crossings - 1);
    const Real inertia = width * depth * depth * depth / 12.0, area = width * depth;
    const Real omega = 1.875 * 1.875 * std::sqrt(E * inertia / (RHO * area * std::pow(length, 4)));
    const Real ratio = period / (2.0 * M_PI / omega);
    std::printf("cantilever 10 x 1, %s: first bending period / Euler-Bernoulli %.3f\n",
                form == HourglassForm::Enhanced ? "ENHANCED" : "STIFFNESS", ratio);
    if (form == HourglassForm::Enhanced) {
      CHECK(ratio == Approx(1.0).margin(0.05));
    } else {
      CHECK(ratio > 1.3);  // √2.2: the stiffness form's soft bending
    }
  }
}
