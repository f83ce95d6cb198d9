#include <catch2/catch.hpp>

#include <cmath>
#include <numeric>

#include <omp.h>
#include <Eigen/Dense>

#include "elements/hex/hex8_geometry.hpp"
#include "elements/hex/hex8r.hpp"
#include "hex_fixtures.hpp"

using namespace xpl;
using namespace xpl::elements;

namespace {

constexpr Real E = 200e9, NU = 0.3, RHO = 7850.0;

Hex8rBlock make_hex_block(const test::HexBlockMesh& mesh,
                          HourglassForm form = HourglassForm::Stiffness) {
  const auto n = static_cast<Index>(mesh.connectivity.size() / 8);
  std::vector<Index> ids(n);
  std::iota(ids.begin(), ids.end(), 0);
  std::vector<HexMaterial> mats(n, HexMaterial{RHO, E, NU, form, 1.0});
  return Hex8rBlock(ids, mesh.connectivity, mats, static_cast<Index>(mesh.coordinates.rows()));
}

NodalVectors zeros_like(const NodalVectors& x) {
  return NodalVectors::Zero(x.rows(), 3);
}

}  // namespace

TEST_CASE("patch test: a linear velocity field gives the exact uniform stress",
          "[elements][hex][patch]") {
  const auto mesh = test::make_block(2, 0.01, 0.2);
  auto block = make_hex_block(mesh);
  Eigen::Matrix3d L;
  L << 1.0, 0.3, -0.2, 0.1, -0.5, 0.4, 0.25, -0.15, 0.7;
  L *= 1e-3;  // 1/s
  const Real dt = 1e-3;
  const NodalVectors x = mesh.coordinates;
  const NodalVectors v = x * L.transpose();  // v_I = L x_I
  NodalVectors f = zeros_like(x);
  HexStepTotals totals;
  block.internal_forces(x, v, dt, 0.0, 0.0, f, totals);

  // The strain increment is taken on the mid geometry x_m = (I − dt/2 L) x, where the
  // velocity field is still linear with gradient L (I − dt/2 L)⁻¹.
  const Eigen::Matrix3d Lm = L * (Eigen::Matrix3d::Identity() - 0.5 * dt * L).inverse();
  const Eigen::Matrix3d D = 0.5 * (Lm + Lm.transpose());
  const Real lambda = E * NU / ((1 + NU) * (1 - 2 * NU)), mu = E / (2 * (1 + NU));
  const Eigen::Matrix3d sigma =
      dt * (lambda * D.trace() * Eigen::Matrix3d::Identity() + 2 * mu * D);
  const Real expect[6] = {sigma(0, 0), sigma(1, 1), sigma(2, 2),
                          sigma(0, 1), sigma(0, 2), sigma(1, 2)};
  const Real scale = sigma.norm();
  for (Index e = 0; e < block.size(); ++e) {
    const auto s = block.stress(e);
    for (int c = 0; c < 6; ++c) CHECK(s[c] == Approx(expect[c]).margin(1e-10 * scale));
  }
  // Hourglass rates vanish for linear fields: no hourglass energy.
  CHECK(std::abs(totals.hourglass_energy_increment) < 1e-20);
  // Uniform stress is in equilibrium at the interior node (forces cancel to round-off).
  const Index centre = mesh.node(1, 1, 1);
  const Real force_scale = scale * 0.01 * 0.01;
  for (int c = 0; c < 3; ++c) CHECK(std::abs(f(centre, c)) < 1e-10 * force_scale);
}

TEST_CASE("an hourglass mode is resisted and its energy is artificial energy",
          "[elements][hex][hourglass]") {
  const auto mesh = test::make_block(1, 0.01, 0.0);
  auto block = make_hex_block(mesh);
  NodalVectors x = mesh.coordinates;
  NodalVectors v = zeros_like(x);
  for (int a = 0; a < 8; ++a) v(mesh.connectivity[a], 0) = 0.1 * mode_sign(4, a);  // ξη mode in x
  const Real dt = 1e-7;
  Real artificial = 0.0, work = 0.0;
  NodalVectors f = zeros_like(x);
  for (int step = 0; step < 10; ++step) {
    x += dt * v;
    f.setZero();
    HexStepTotals totals;
    block.internal_forces(x, v, dt, 0.0, 0.0, f, totals);
    artificial += totals.hourglass_energy_increment;
    CHECK(std::abs(totals.strain_energy_increment) <
          1e-6 * std::abs(totals.hourglass_energy_increment));
    work += dt * (f.array() * v.array()).sum();
  }
  CHECK(artificial > 0.0);
  // The internal force points along the hourglass motion: it resists it.
  CHECK((f.array() * v.array()).sum() > 0.0);
  // Energy is consistent with the work of the hourglass forces (trapezoidal vs end-point rule).
  CHECK(artificial == Approx(work).epsilon(0.15));
  // No stress from a pure hourglass mode.
  for (Real s : block.stress(0)) CHECK(std::abs(s) < 1e-6);
}

TEST_CASE("viscous hourglass control damps the mode without stiffness",
          "[elements][hex][hourglass]") {
  const auto mesh = test::make_block(1, 0.01, 0.0);
  auto block = make_hex_block(mesh, HourglassForm::Viscous);
  NodalVectors x = mesh.coordinates;
  NodalVectors v = zeros_like(x);
  for (int a = 0; a < 8; ++a) v(mesh.connectivity[a], 1) = 0.1 * mode_sign(7, a);
  NodalVectors f = zeros_like(x);
  HexStepTotals totals;
  block.internal_forces(x, v, 1e-7, 0.0, 0.0, f, totals);
  CHECK(totals.hourglass_energy_increment > 0.0);
  CHECK((f.array() * v.array()).sum() > 0.0);
}

TEST_CASE("a rigid rotation of 90 degrees produces no stress", "[elements][hex][objectivity]") {
  const auto mesh = test::make_block(1, 0.01, 0.2, 11);
  auto block = make_hex_block(mesh);
  const NodalVectors X = mesh.coordinates;
  NodalVectors x = X;
  const int steps = 400;
  const Real dt = 1e-6, dtheta = (M_PI / 2) / steps;
  Real strain_energy = 0.0, hourglass = 0.0;
  for (int n = 1; n <= steps; ++n) {
    const Eigen::Matrix3d R =
        Eigen::AngleAxisd(n * dtheta, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
    const NodalVectors x_new = X * R.transpose();
    const NodalVectors v = (x_new - x) / dt;
    x = x_new;
    NodalVectors f = zeros_like(x);
    HexStepTotals totals;
    block.internal_forces(x, v, dt, 0.06, 1.2, f, totals);
    strain_energy += totals.strain_energy_increment;
    hourglass += totals.hourglass_energy_increment;
  }
  // Round-off only: the strain increment on the mid geometry is exactly skew for rotations.
  for (Real s : block.stress(0)) CHECK(std::abs(s) < 1e-9 * E);
  CHECK(std::abs(hourglass) < 1e-12);
}

TEST_CASE("element forces are the gradient of the element energy", "[elements][hex][fd]") {
  // From rest, one increment with displacement u = dt·v gives σ = C:ε(u) and hourglass forces
  // k γ (γ·u); the forces must equal ∂Π/∂u of Π = ½ V ε:C:ε + ½ k Σ |γ_α·u|².
  const auto mesh = test::make_block(1, 0.01, 0.2, 5);
  auto block = make_hex_block(mesh);
  const NodalVectors X = mesh.coordinates;
  NodalVectors u = zeros_like(X);
  std::mt19937 rng(3);
  std::uniform_real_distribution<Real> d(-1e-9, 1e-9);  // tiny: geometry change negligible
  for (Index i = 0; i < u.rows(); ++i)
    for (int c = 0; c < 3; ++c) u(i, c) = d(rng);
  NodalVectors f = zeros_like(X);
  HexStepTotals totals;
  block.internal_forces(X + u, u, 1.0, 0.0, 0.0, f, totals);

  // The energy increment reported equals the work ½ f·u of a linear spring system.
  const Real work = 0.5 * (f.array() * u.array()).sum();
  CHECK(totals.strain_energy_increment + totals.hourglass_energy_increment ==
        Approx(work).epsilon(1e-6));

  // Finite differences of Π along random directions w: dΠ(u + s w)/ds at s = 0 = f·w.
  auto energy = [&](const NodalVectors& uu) {
    auto blk = make_hex_block(mesh);
    NodalVectors ff = zeros_like(X);
    HexStepTotals t;
    blk.internal_forces(X + uu, uu, 1.0, 0.0, 0.0, ff, t);
    return t.strain_energy_increment + t.hourglass_energy_increment;
  };
  for (int trial = 0; trial < 3; ++trial) {
    NodalVectors w = zeros_like(X);
    for (Index i = 0; i < w.rows(); ++i)
      for (int c = 0; c < 3; ++c) w(i, c) = d(rng);
    const Real s = 1e-2;
    const Real fd = (energy(u + s * w) - energy(u - s * w)) / (2 * s);
    CHECK((f.array() * w.array()).sum() == Approx(fd).epsilon(1e-5));
  }
}

TEST_CASE("internal forces do not depend on the thread count", "[elements][hex][threads]") {
  const auto mesh = test::make_block(6, 0.01, 0.2);
  NodalVectors v = zeros_like(mesh.coordinates);
  std::mt19937 rng(1);
  std::uniform_real_distribution<Real> d(-1.0, 1.0);
  for (Index i = 0; i < v.rows(); ++i)
    for (int c = 0; c < 3; ++c) v(i, c) = d(rng);
  NodalVectors f1 = zeros_like(v), f2 = zeros_like(v);
  HexStepTotals t1, t2;
  const int saved = omp_get_max_threads();
  omp_set_num_threads(1);
  auto b1 = make_hex_block(mesh);
  b1.internal_forces(mesh.coordinates + 1e-7 * v, v, 1e-7, 0.06, 1.2, f1, t1);
  omp_set_num_threads(2);
  auto b2 = make_hex_block(mesh);
  b2.internal_forces(mesh.coordinates + 1e-7 * v, v, 1e-7, 0.06, 1.2, f2, t2);
  omp_set_num_threads(saved);
  // Colour-ordered assembly: bitwise identical, not just equal to round-off.
  CHECK((f1 - f2).cwiseAbs().maxCoeff() == 0.0);
  CHECK(t1.strain_energy_increment == t2.strain_energy_increment);
  CHECK(t1.stable_dt == t2.stable_dt);
  CHECK(t1.critical_element == t2.critical_element);
}

TEST_CASE("stable increment of a cube is its side over the wave speed", "[elements][hex][dt]") {
  const auto mesh = test::make_block(1, 0.01, 0.0);
  auto block = make_hex_block(mesh);
  NodalVectors f = zeros_like(mesh.coordinates);
  HexStepTotals totals;
  block.internal_forces(mesh.coordinates, zeros_like(f), 0.0, 0.0, 0.0, f, totals);
  const Real cd = std::sqrt(E * (1 - NU) / (RHO * (1 + NU) * (1 - 2 * NU)));
  CHECK(totals.stable_dt == Approx(0.01 / cd).epsilon(1e-12));
  CHECK(totals.critical_element == 0);
  // Linear bulk viscosity b1 lowers it by √(1+b1²) − b1.
  HexStepTotals damped;
  block.internal_forces(mesh.coordinates, zeros_like(f), 0.0, 0.06, 1.2, f, damped);
  CHECK(damped.stable_dt == Approx(0.01 / cd * (std::sqrt(1 + 0.06 * 0.06) - 0.06)).epsilon(1e-12));
}

TEST_CASE("an inverted element is reported", "[elements][hex]") {
  auto mesh = test::make_block(1, 0.01, 0.0);
  auto block = make_hex_block(mesh);
  NodalVectors x = mesh.coordinates;
  for (int a = 4; a < 8; ++a) x(mesh.connectivity[a], 2) = -0.01;  // top face below bottom
  NodalVectors f = zeros_like(x);
  HexStepTotals totals;
  block.internal_forces(x, zeros_like(x), 0.0, 0.0, 0.0, f, totals);
  CHECK(totals.failed_element == 0);
}

TEST_CASE("a corner node pushed through the element is reported though the volume stays positive",
          "[elements][hex]") {
  // One point sees the mean gradient only: node 7 (index 6) of a cube pushed along the
  // diagonal past its three neighbours' plane (x + y + z = 0.02 m, s = 6.67 mm) leaves a
  // positive volume (and a finite stress) while the element turns inside out at that corner.
  // Just past the plane the corner is nearly flat (scaled Jacobian −0.25 at 6.2 mm, below the
  // limit −0.5 from 5.7 mm on).
  const auto mesh = test::make_block(1, 0.01, 0.0);
  auto block = make_hex_block(mesh, HourglassForm::Enhanced);
  NodalVectors x = mesh.coordinates;
  const Index corner = mesh.connectivity[6];
  for (const Real s : {0.007, 0.0062, 0.0055, 0.0}) {
    for (int c = 0; c < 3; ++c) x(corner, c) = s;
    Real cx[8], cy[8], cz[8];
    for (int a = 0; a < 8; ++a) {
      cx[a] = x(mesh.connectivity[a], 0);
      cy[a] = x(mesh.connectivity[a], 1);
      cz[a] = x(mesh.connectivity[a], 2);
    }
    INFO("s = " << s);
    REQUIRE(hex8_volume(cx, cy, cz) > 0.0);
    NodalVectors f = zeros_like(x);
    HexStepTotals totals;
    block.internal_forces(x, zeros_like(x), 0.0, 0.0, 0.0, f, totals);
    CHECK(totals.failed_element == (s < 0.006 ? 0 : NO_INDEX));
  }
}

TEST_CASE("lumped mass is rho V / 8 per node", "[elements][hex]") {
  const auto mesh = test::make_block(2, 0.01, 0.2);
  auto block = make_hex_block(mesh);
  std::vector<Real> mass(mesh.coordinates.rows(), 0.0);
  block.add_lumped_mass(mesh.coordinates, mass);
  Real total = 0.0;
  for (Real m : mass) total += m;
  // Total volume of the distorted block from the element volumes (exact integrals).
  Real volume = 0.0;
  for (int e = 0; e < 8; ++e) {
    Real x[8], y[8], z[8];
    for (int a = 0; a < 8; ++a) {
      const Index p = mesh.connectivity[e * 8 + a];
      x[a] = mesh.coordinates(p, 0);
      y[a] = mesh.coordinates(p, 1);
      z[a] = mesh.coordinates(p, 2);
    }
    volume += hex8_volume(x, y, z);
  }
  CHECK(total == Approx(RHO * volume).epsilon(1e-12));
}
