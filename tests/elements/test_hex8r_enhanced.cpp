// The enhanced assumed-strain hourglass stabilisation of C3D8R (elements/hex/hex8r_enhanced.hpp,
// issue 32): the patch test, rigid rotation of stored resultants, energy, forces as the
// derivative of an energy, the plastic relaxation and bound (a hinge at M_p), the flow
// projection of a yielding element's hourglass strain, and lanes of
// mixed forms in one batch. Bending against beam theory: test_hex8r_enhanced_bending.cpp.

#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <numeric>
#include <random>
#include <vector>

#include <Eigen/Dense>

#include "elements/hex/hex8_geometry.hpp"
#include "elements/hex/hex8r.hpp"
#include "elements/hex/hex8r_hourglass.hpp"
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

NodalVectors zeros_like(const NodalVectors& x) {
  return NodalVectors::Zero(x.rows(), 3);
}

}  // namespace

TEST_CASE("enhanced: a linear field gives no hourglass force, a rotation turns stored ones",
          "[elements][hex8r][enhanced][patch]") {
  const auto mesh = test::make_block(2, 0.01, 0.2);
  SECTION("patch test") {
    Hex8rBlock block =
        block_of(mesh.coordinates, mesh.connectivity, uniform(8, 0.3, HourglassForm::Enhanced));
    Hex8rBlock reference =
        block_of(mesh.coordinates, mesh.connectivity, uniform(8, 0.3, HourglassForm::Viscous));
    Eigen::Matrix3d L;
    L << 1.0, 0.3, -0.2, 0.1, -0.5, 0.4, 0.25, -0.15, 0.7;
    L *= 1e-3;
    const NodalVectors v = mesh.coordinates * L.transpose();
    NodalVectors f = zeros_like(v), f_ref = zeros_like(v);
    HexStepTotals t, t_ref;
    block.internal_forces(mesh.coordinates, v, 1e-3, 0.0, 0.0, f, t);
    reference.internal_forces(mesh.coordinates, v, 1e-3, 0.0, 0.0, f_ref, t_ref);
    // The hourglass forces of the viscous form vanish as well (q = 0): both give the forces of
    // the uniform stress alone.
    CHECK(std::abs(t.hourglass_energy_increment) < 1e-20);
    CHECK((f - f_ref).norm() <= 1e-10 * f_ref.norm());
  }
  SECTION("rigid rotation of stored resultants") {
    const auto one = test::make_block(1, 0.01, 0.2, 11);
    Hex8rBlock block =
        block_of(one.coordinates, one.connectivity, uniform(1, 0.3, HourglassForm::Enhanced));
    // One increment along the ξη and ξηζ modes stores resultants.
    NodalVectors v = zeros_like(one.coordinates);
    for (int a = 0; a < 8; ++a) {
      v(one.connectivity[a], 0) = 1e-3 * mode_sign(4, a);
      v(one.connectivity[a], 2) = 0.5e-3 * mode_sign(7, a);
    }
    const Real dt = 1e-3;
    NodalVectors x = one.coordinates + dt * v;
    NodalVectors f0 = zeros_like(x);
    HexStepTotals t0;
    block.internal_forces(x, v, dt, 0.0, 0.0, f0, t0);
    REQUIRE(t0.hourglass_energy_increment > 0.0);
    const Real stored = t0.hourglass_energy_increment;
    // Then 90° about (1, 2, 3) in 2000 rigid increments about the centroid.
    const NodalVectors start = x;
    const Eigen::RowVector3d centre = start.colwise().mean();
    const int steps = 2000;
    const Eigen::Vector3d axis = Eigen::Vector3d(1, 2, 3).normalized();
    Real hourglass = 0.0;
    NodalVectors f = zeros_like(x);
    Eigen::Matrix3d R = Eigen::Matrix3d::Identity();
    for (int n = 1; n <= steps; ++n) {
      R = Eigen::AngleAxisd(n * (M_PI / 2) / steps, axis).toRotationMatrix();
      const NodalVectors x_new = ((start.rowwise() - centre) * R.transpose()).rowwise() + centre;
      const NodalVectors vel = (x_new - x) / 1e-6;
      x = x_new;
      f.setZero();
      HexStepTotals t;
      block.internal_forces(x, vel, 1e-6, 0.0, 0.0, f, t);
      hourglass += t.hourglass_energy_increment;
    }
    // The forces turned with the body (the hourglass stresses are kept in the element's frame;
    // the uniform stress of the distorted element follows its Jaumann rate, whose Euler step
    // lengthens it by (1 + (ω dt)²)^(n/2) − 1 = 3e-4 here), and no energy was made or lost.
    const NodalVectors expect = f0 * R.transpose();
    CHECK((f - expect).norm() <= 2e-3 * f0.norm());
    CHECK(std::abs(hourglass) <= 1e-6 * stored);
    // The same stored forces left unturned would be off by the whole rotation.
    CHECK((f0 - expect).norm() > 0.5 * f0.norm());
  }
}

TEST_CASE("enhanced: hourglass energy is the work of the hourglass forces",
          "[elements][hex8r][enhanced][energy]") {
  const auto mesh = test::make_block(1, 0.01, 0.1, 3);
  Hex8rBlock block =
      block_of(mesh.coordinates, mesh.connectivity, uniform(1, 0.3, HourglassForm::Enhanced));
  std::vector<Real> mass(8, 0.0);
  block.add_lumped_mass(mesh.coordinates, mass);
  // Free vibration of the ξη and ηζ modes with central differences: the artificial energy
  // and the kinetic energy exchange, their sum stays put.
  NodalVectors x = mesh.coordinates, v = zeros_like(x), f = zeros_like(x);
  for (int a = 0; a < 8; ++a) {
    v(mesh.connectivity[a], 0) = 0.1 * mode_sign(4, a);
    v(mesh.connectivity[a], 1) = 0.05 * mode_sign(5, a);
  }
  const Real dt = 2e-7;
  Real artificial = 0.0, strain = 0.0;
  Real kinetic0 = 0.0;
  for (Index n = 0; n < 8; ++n) kinetic0 += 0.5 * mass[n] * v.row(n).squaredNorm();
  Real worst = 0.0, max_artificial = 0.0;
  NodalVectors v_prev = v;
  for (int step = 0; step < 400; ++step) {
    x += dt * v;
    f.setZero();
    HexStepTotals t;
    block.internal_forces(x, v, dt, 0.0, 0.0, f, t);
    artificial += t.hourglass_energy_increment;
    strain += t.strain_energy_increment;
    v_prev = v;
    for (Index n = 0; n < 8; ++n) v.row(n) -= dt * f.row(n) / mass[n];
    // ALLKE = ½ v(n−½)·M·v(n+½), as the solver books it.
    Real kinetic = 0.0;
    for (Index n = 0; n < 8; ++n) kinetic += 0.5 * mass[n] * v_prev.row(n).dot(v.row(n));
    worst = std::max(worst, std::abs(kinetic + artificial + strain - kinetic0));
    max_artificial = std::max(max_artificial, artificial);
  }
  CHECK(max_artificial > 0.3 * kinetic0);  // the modes do store energy
  // Central differences conserve a shadow energy within (ω dt)²/4 ≈ 0.4 % of it here.
  CHECK(worst < 1e-2 * kinetic0);
}

TEST_CASE("enhanced: forces are the derivative of a stored energy (one increment from rest)",
          "[elements][hex8r][enhanced][fd]") {
  const auto mesh = test::make_block(1, 0.01, 0.2, 5);
  const NodalVectors X = mesh.coordinates;
  std::mt19937 rng(3);
  std::uniform_real_distribution<Real> d(-1e-9, 1e-9);
  NodalVectors u = zeros_like(X);
  for (Index i = 0; i < u.rows(); ++i)
    for (int c = 0; c < 3; ++c) u(i, c) = d(rng);
  const auto energy = [&](const NodalVectors& uu, NodalVectors* force) {
    Hex8rBlock blk = block_of(X, mesh.connectivity, uniform(1, 0.3, HourglassForm::Enhanced));
    NodalVectors ff = zeros_like(X);
    HexStepTotals t;
    blk.internal_forces(X + uu, uu, 1.0, 0.0, 0.0, ff, t);
    if (force) *force = ff;
    return t.strain_energy_increment + t.hourglass_energy_increment;
  };
  NodalVectors f;
  const Real e = energy(u, &f);
  CHECK(e == Approx(0.5 * (f.array() * u.array()).sum()).epsilon(1e-6));
  for (int trial = 0; trial < 3; ++trial) {
    NodalVectors w = zeros_like(X);
    for (Index i = 0; i < w.rows(); ++i)
      for (int c = 0; c < 3; ++c) w(i, c) = d(rng);
    const Real s = 1e-2;
    const Real fd = (energy(u + s * w, nullptr) - energy(u - s * w, nullptr)) / (2 * s);
    CHECK((f.array() * w.array()).sum() == Approx(fd).epsilon(1e-5));
  }
}

TEST_CASE("enhanced: resultants of a yielding element relax with its stress",
          "[elements][hex8r][enhanced][plastic]") {
  // One cube squeezed in z beyond yield while an ξη hourglass motion goes on: the plastic
  // element keeps a fraction of the elastic element's hourglass resultants, and the energy of
  // the stabilisation still equals the work of its forces (the relaxed part is dissipated).
  const auto mesh = test::make_block(1, 0.01, 0.0);
  Plasticity law;  // perfectly plastic, 250 MPa
  law.yield_stress = {250e6};
  law.plastic_strain = {0.0};
  Real force_norm[2] = {0.0, 0.0}, artificial[2] = {0.0, 0.0}, work[2] = {0.0, 0.0};
  for (int k = 0; k < 2; ++k) {
    Hex8rBlock block = block_of(mesh.coordinates, mesh.connectivity,
                                uniform(1, 0.3, HourglassForm::Enhanced, k == 1 ? &law : nullptr));
    NodalVectors x = mesh.coordinates, v = zeros_like(x), f = zeros_like(x);
    for (int a = 0; a < 8; ++a) {
      const Index n = mesh.connectivity[a];
      v(n, 2) = -1.0 * (mesh.coordinates(n, 2) / 0.01);  // 100 /s compression
      v(n, 0) = 0.02 * mode_sign(4, a);
    }
    const Real dt = 1e-7;
    for (int step = 0; step < 500; ++step) {  // 0.5 % strain: 5 × the yield strain
      x += dt * v;
      NodalVectors f_prev = f;
      f.setZero();
      HexStepTotals t;
      block.internal_forces(x, v, dt, 0.0, 0.0, f, t);
      artificial[k] += t.hourglass_energy_increment;
      // Work of the hourglass part of the forces: the ξη component of the x forces.
      Real fq = 0.0, fq_prev = 0.0;
      for (int a = 0; a < 8; ++a) {
        fq += f(mesh.connectivity[a], 0) * mode_sign(4, a);
        fq_prev += f_prev(mesh.connectivity[a], 0) * mode_sign(4, a);
      }
      work[k] += dt * 0.5 * (fq + fq_prev) * 0.02;
      force_norm[k] = std::abs(fq);
    }
  }
  std::printf("hourglass force after 0.5 %% squeeze: elastic %.4g N, plastic %.4g N\n",
              force_norm[0], force_norm[1]);
  CHECK(force_norm[1] < 0.5 * force_norm[0]);
  CHECK(force_norm[1] > 0.0);
  for (int k = 0; k < 2; ++k) CHECK(artificial[k] == Approx(work[k]).epsilon(0.02));
}

TEST_CASE("enhanced: lanes of different forms in one batch compute their own form",
          "[elements][hex8r][enhanced][mixed]") {
  const auto mesh = test::make_block(3, 0.01, 0.15);
  const std::size_t n = mesh.connectivity.size() / 8;
  std::vector<HexMaterial> mixed = uniform(n, 0.3, HourglassForm::Enhanced);
  for (std::size_t e = 0; e < n; e += 2) mixed[e].hourglass = HourglassForm::Stiffness;
  for (std::size_t e = 1; e < n; e += 6) mixed[e].hourglass = HourglassForm::Viscous;
  // The same elements as three single-form blocks.
  std::vector<Index> rows[3];
  std::vector<Index> conn[3];
  std::vector<HexMaterial> mats[3];
  for (std::size_t e = 0; e < n; ++e) {
    const int k = static_cast<int>(mixed[e].hourglass);
    rows[k].push_back(static_cast<Index>(e));
    conn[k].insert(conn[k].end(), mesh.connectivity.begin() + 8 * e,
                   mesh.connectivity.begin() + 8 * e + 8);
    mats[k].push_back(mixed[e]);
  }
  const Index nodes = static_cast<Index>(mesh.coordinates.rows());
  Hex8rBlock all = block_of(mesh.coordinates, mesh.connectivity, mixed);
  std::mt19937 rng(9);
  std::uniform_real_distribution<Real> d(-1.0, 1.0);
  NodalVectors v = zeros_like(mesh.coordinates);
  for (Index i = 0; i < v.rows(); ++i)
    for (int c = 0; c < 3; ++c) v(i, c) = d(rng);
  const NodalVectors x = mesh.coordinates + 1e-7 * v;
  NodalVectors f_all = zeros_like(x), f_parts = zeros_like(x);
  HexStepTotals t_all, t_parts;
  for (int step = 0; step < 3; ++step) all.internal_forces(x, v, 1e-7, 0.0, 0.0, f_all, t_all);
  for (int k = 0; k < 3; ++k) {
    Hex8rBlock part(rows[k], conn[k], mats[k], nodes);
    HexStepTotals t;
    for (int step = 0; step < 3; ++step) part.internal_forces(x, v, 1e-7, 0.0, 0.0, f_parts, t);
    t_parts.hourglass_energy_increment += t.hourglass_energy_increment;
  }
  CHECK((f_all - f_parts).norm() <= 1e-12 * f_all.norm());
  // Last increment's energies: the sums differ by summation order only.
  CHECK(t_all.hourglass_energy_increment ==
        Approx(t_parts.hourglass_energy_increment).epsilon(1e-10));
}

TEST_CASE("enhanced: a plastic hinge one element thick bends at the fully plastic moment",
          "[elements][hex8r][enhanced][plastic]") {
  // One element 20 × 10 × 4 mm (x, y, z), pure bending about y by u_x = κ x z (ν = 0, so
  // that nothing else moves), κ ramped to 8 times the yield curvature 2σ_y/(E t): the moment
  // rises as E I κ and saturates at the fully plastic σ_y w t²/4 (the centre stays at zero
  // stress and never yields: the bound alone stops the elastic hourglass stress).
  const Real a = 0.01, b = 0.005, c = 0.002, sigma_y = 250e6;
  NodalVectors x0(8, 3);
  std::vector<Index> conn(8);
  for (int n = 0; n < 8; ++n) {
    x0(n, 0) = a * NODE_XI[n];
    x0(n, 1) = b * NODE_ETA[n];
    x0(n, 2) = c * NODE_ZETA[n];
    conn[static_cast<std::size_t>(n)] = n;
  }
  Plasticity law;
  law.yield_stress = {sigma_y};
  law.plastic_strain = {0.0};
  Hex8rBlock block = block_of(x0, conn, uniform(1, 0.0, HourglassForm::Enhanced, &law));
  const Real inertia = 2 * b * std::pow(2 * c, 3) / 12.0;
  const Real m_plastic = sigma_y * 2 * b * 4 * c * c / 4.0;
  const Real kappa_y = 2.0 * sigma_y / (E * 2 * c);
  const int steps = 4000;
  const Real dt = 1e-6, rate = 8.0 * kappa_y / (steps * dt);
  NodalVectors x = x0, v = zeros_like(x0), f = zeros_like(x0);
  for (int n = 0; n < 8; ++n) v(n, 0) = rate * x0(n, 0) * x0(n, 2);
  Real artificial = 0.0, work = 0.0, moment = 0.0, first_slope = 0.0;
  for (int step = 1; step <= steps; ++step) {
    x += dt * v;
    f.setZero();
    HexStepTotals t;
    block.internal_forces(x, v, dt, 0.0, 0.0, f, t);
    artificial += t.hourglass_energy_increment;
    Real m = 0.0;
    for (int n = 0; n < 8; ++n) m += f(n, 0) * x0(n, 0) * x0(n, 2);
    m /= 2 * a;
    work += dt * rate * 2 * a * 0.5 * (m + moment);
    moment = m;
    if (step == steps / 40) first_slope = m / (step * dt * rate);
    for (Real s : block.stress(0)) CHECK(std::abs(s) < 1e-3 * sigma_y);
  }
  std::printf("plastic hinge: initial slope / EI %.4f, final moment / M_p %.4f\n",
              first_slope / (E * inertia), moment / m_plastic);
  CHECK(first_slope == Approx(E * inertia).epsilon(0.01));
  CHECK(moment == Approx(m_plastic).epsilon(0.03));
  CHECK(artificial == Approx(work).epsilon(0.01));
}

TEST_CASE("enhanced: a yielding element's hourglass strain along its flow loads no stress",
          "[elements][hex8r][enhanced][plastic]") {
  // flow_projected() in a frame turned about z by 30°: the flow of uniaxial compression along
  // z, N = (−1, −1, 2)/√6 (a diagonal tensor, so the same in the turned frame).
  using simd::Vec;
  EnhancedFrame<Vec> f;
  const Real c = std::cos(0.5236), s = std::sin(0.5236);
  f.e[0] = {simd::splat(c), simd::splat(s), simd::splat(0.0)};
  f.e[1] = {simd::splat(-s), simd::splat(c), simd::splat(0.0)};
  f.e[2] = {simd::splat(0.0), simd::splat(0.0), simd::splat(1.0)};
  for (Vec& ci : f.c) ci = simd::splat(100.0);
  const Real r6 = 1.0 / std::sqrt(6.0);
  const Vec flow[6] = {simd::splat(-r6), simd::splat(-r6), simd::splat(2.0 * r6),
                       simd::splat(0.0), simd::splat(0.0), simd::splat(0.0)};
  const Vec zero[6] = {simd::splat(0.0), simd::splat(0.0), simd::splat(0.0),
                       simd::splat(0.0), simd::splat(0.0), simd::splat(0.0)};
  const Real ratio = 0.3 / 0.7;  // λ̄/2μ = ν/(1 − ν)
  // Plane η (axes 1, 3; transverse 2): a strain coaxial with the flow, ε11 = −1, ε33 = 2
  // (transverse −ratio·1); plane ζ (axes 1, 2): a shear γ12, orthogonal to N; plane ξ (axes
  // 2, 3): ε22 = ε33 = 1 (transverse ε11 = −2 ratio).
  Vec eps[9] = {simd::splat(1.0),  simd::splat(1.0), simd::splat(0.0),
                simd::splat(-1.0), simd::splat(2.0), simd::splat(0.0),
                simd::splat(0.0),  simd::splat(0.0), simd::splat(3.0)};
  Vec out[9];
  flow_projected(f, zero, simd::splat(ratio), eps, out);
  for (int k = 0; k < 9; ++k) CHECK(out[k][0] == eps[k][0]);  // nothing flows: unchanged
  flow_projected(f, flow, simd::splat(ratio), eps, out);
  // ζ: the shear is orthogonal to the flow and stays.
  CHECK(out[6][0] == Approx(0.0).margin(1e-14));
  CHECK(out[7][0] == Approx(0.0).margin(1e-14));
  CHECK(out[8][0] == Approx(3.0).epsilon(1e-14));
  // η: N:ε = (1 + 4 + ratio)/√6 comes off along (N11, N33) = (−1, 2)/√6.
  const Real along = (1.0 + 4.0 + ratio) * r6;
  CHECK(out[3][0] == Approx(-1.0 + along * r6).epsilon(1e-13));
  CHECK(out[4][0] == Approx(2.0 - 2.0 * along * r6).epsilon(1e-13));
  CHECK(out[5][0] == Approx(0.0).margin(1e-14));
  // The rest of the coaxial strain, completed by its transverse strain, is nearly
  // orthogonal to N (exactly but for the transverse strain's own change).
  const Real a = out[3][0], b = out[4][0];
  CHECK(std::abs(-a + 2.0 * b + ratio * (a + b)) * r6 < 0.25 * along);
  // ξ: N:ε = (−1 + 2 + 2 ratio)/√6 comes off along (N22, N33) = (−1, 2)/√6.
  const Real along_xi = (1.0 + 2.0 * ratio) * r6;
  CHECK(out[0][0] == Approx(1.0 + along_xi * r6).epsilon(1e-13));
  CHECK(out[1][0] == Approx(1.0 - 2.0 * along_xi * r6).epsilon(1e-13));
}
