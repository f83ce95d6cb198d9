// C3D8 (Hex8Block): patch test on a distorted block (every integration point of every element
// carries the exact uniform stress, interior nodes are in equilibrium, and the stress agrees
// with the one-point C3D8R), rigid rotation is stress free, the stiffness product is the
// derivative of the internal force, full integration leaves only the 6 rigid-body modes
// (no hourglass modes), the mean dilatation keeps a nearly incompressible element from locking,
// and J2 plasticity returns every point to the yield surface.

#include <catch2/catch.hpp>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <random>

#include "elements/hex/hex8.hpp"
#include "elements/hex/hex8r.hpp"
#include "hex_fixtures.hpp"

using namespace xpl;
using namespace xpl::elements;

namespace {

constexpr Real E = 200e9, RHO = 7850.0, H = 1e-3;

std::vector<Index> iota_rows(const test::HexBlockMesh& mesh) {
  std::vector<Index> rows(mesh.connectivity.size() / 8);
  for (std::size_t i = 0; i < rows.size(); ++i) rows[i] = static_cast<Index>(i);
  return rows;
}

Hex8Block make_c3d8(const test::HexBlockMesh& mesh, Real nu, const Plasticity* plastic = nullptr) {
  HexMaterial m{RHO, E, nu, HourglassForm::Stiffness, 1.0, plastic};
  const std::vector<Index> rows = iota_rows(mesh);
  return Hex8Block(rows, mesh.connectivity, std::vector<HexMaterial>(rows.size(), m),
                   static_cast<Index>(mesh.coordinates.rows()));
}

Hex8rBlock make_c3d8r(const test::HexBlockMesh& mesh, Real nu) {
  HexMaterial m{RHO, E, nu, HourglassForm::Stiffness, 1.0};
  const std::vector<Index> rows = iota_rows(mesh);
  return Hex8rBlock(rows, mesh.connectivity, std::vector<HexMaterial>(rows.size(), m),
                    static_cast<Index>(mesh.coordinates.rows()));
}

NodalVectors random_field(Index rows, unsigned seed, Real scale) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<Real> d(-scale, scale);
  NodalVectors u(rows, 3);
  for (Index i = 0; i < rows; ++i)
    for (int c = 0; c < 3; ++c) u(i, c) = d(rng);
  return u;
}

/// Velocity v = G x of a linear field at every node.
NodalVectors linear_field(const NodalVectors& x, const Real G[3][3]) {
  NodalVectors v(x.rows(), 3);
  for (Index i = 0; i < x.rows(); ++i)
    for (int r = 0; r < 3; ++r) v(i, r) = G[r][0] * x(i, 0) + G[r][1] * x(i, 1) + G[r][2] * x(i, 2);
  return v;
}

bool interior(const test::HexBlockMesh& mesh, Index node) {
  const int m = mesh.n + 1;
  const int i = static_cast<int>(node % m), j = static_cast<int>((node / m) % m),
            k = static_cast<int>(node / (m * m));
  return i > 0 && j > 0 && k > 0 && i < mesh.n && j < mesh.n && k < mesh.n;
}

}  // namespace

TEST_CASE("c3d8: patch test on a distorted block: uniform exact stress, interior equilibrium",
          "[elements][c3d8]") {
  const test::HexBlockMesh mesh = test::make_block(3, H, 0.2);
  const Index n = static_cast<Index>(mesh.coordinates.rows());
  const Real nu = 0.3;
  // A symmetric velocity gradient (pure strain rate: the stress after one increment from zero
  // is dt·C:D exactly, whatever the mid-increment geometry, as long as D is uniform).
  const Real G[3][3] = {{1.0, 0.3, -0.2}, {0.3, -0.5, 0.4}, {-0.2, 0.4, 0.7}};
  const Real dt = 1e-9;  // s: strains ~1e-9
  const NodalVectors v = linear_field(mesh.coordinates, G);
  // Positions at the end of the increment; the mid geometry is then x - dt/2 v.
  const NodalVectors x = mesh.coordinates + dt * v;
  Hex8Block block = make_c3d8(mesh, nu);
  NodalVectors force = NodalVectors::Zero(n, 3);
  HexStepTotals totals;
  block.internal_forces(x, v, dt, 0.0, 0.0, force, totals);

  Hex8rBlock reduced = make_c3d8r(mesh, nu);
  NodalVectors force_r = NodalVectors::Zero(n, 3);
  HexStepTotals totals_r;
  reduced.internal_forces(x, v, dt, 0.0, 0.0, force_r, totals_r);

  // The linear field is exact on the mid geometry too: x_mid = (I + dt/2 G) X, so there
  // L = G (I + dt/2 G)⁻¹.
  Eigen::Matrix3d g;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) g(r, c) = G[r][c];
  const Eigen::Matrix3d L = g * (Eigen::Matrix3d::Identity() + 0.5 * dt * g).inverse();
  const Eigen::Matrix3d D = 0.5 * (L + L.transpose());
  const Real lambda = E * nu / ((1 + nu) * (1 - 2 * nu)), mu = E / (2 * (1 + nu));
  const Eigen::Matrix3d sigma =
      dt * (lambda * D.trace() * Eigen::Matrix3d::Identity() + 2.0 * mu * D);
  const Real expected[6] = {sigma(0, 0), sigma(1, 1), sigma(2, 2),
                            sigma(0, 1), sigma(0, 2), sigma(1, 2)};
  const Real scale = sigma.norm();
  for (Index e = 0; e < block.size(); ++e) {
    const std::array<Real, 6> sr = reduced.stress(e);
    for (int q = 0; q < HEX8_POINTS; ++q) {
      const std::array<Real, 6> s = block.point_stress(e, q);
      for (int c = 0; c < 6; ++c) {
        INFO("element " << e << " point " << q << " component " << c);
        // Round-off of a few operations on strains of 1e-9: 1e-9 of the stress.
        CHECK(std::abs(s[c] - expected[c]) <= 1e-9 * scale);
        CHECK(std::abs(s[c] - sr[c]) <= 1e-9 * scale);
      }
    }
  }
  // Interior nodes: the element forces cancel; boundary nodes carry σ·n·area.
  Real interior_max = 0.0, boundary_max = 0.0;
  for (Index i = 0; i < n; ++i) {
    const Real f = force.row(i).norm();
    (interior(mesh, i) ? interior_max : boundary_max) =
        std::max(interior(mesh, i) ? interior_max : boundary_max, f);
  }
  CHECK(boundary_max > 0.0);
  CHECK(interior_max <= 1e-9 * boundary_max);
  // Same nodal forces as the one-point element: both are exact for a uniform stress.
  CHECK((force - force_r).norm() <= 1e-9 * force.norm());
  CHECK(totals.hourglass_energy_increment == 0.0);
}

TEST_CASE("c3d8: a rigid rotation leaves the stress zero", "[elements][c3d8]") {
  const test::HexBlockMesh mesh = test::make_block(2, H, 0.2);
  const Index n = static_cast<Index>(mesh.coordinates.rows());
  const Real omega = 1e3;  // rad/s about z; 1e-3 rad over the increment
  const Real dt = 1e-6;
  // Exact rotation over the increment, with the mid-increment velocity that produces it.
  NodalVectors x(n, 3), v(n, 3);
  const Real a = omega * dt;
  for (Index i = 0; i < n; ++i) {
    const Real px = mesh.coordinates(i, 0), py = mesh.coordinates(i, 1);
    x(i, 0) = std::cos(a) * px - std::sin(a) * py;
    x(i, 1) = std::sin(a) * px + std::cos(a) * py;
    x(i, 2) = mesh.coordinates(i, 2);
    v.row(i) = (x.row(i) - mesh.coordinates.row(i)) / dt;
  }
  Hex8Block block = make_c3d8(mesh, 0.3);
  NodalVectors force = NodalVectors::Zero(n, 3);
  HexStepTotals totals;
  block.internal_forces(x, v, dt, 0.0, 0.0, force, totals);
  // The mid-increment geometry makes the strain increment of a rotation zero to second order
  // in the angle: |σ| ≲ E a³ = 2e-4 Pa (against E a = 2e8 Pa of a strain of that size).
  for (Index e = 0; e < block.size(); ++e)
    for (int q = 0; q < HEX8_POINTS; ++q)
      for (Real s : block.point_stress(e, q)) CHECK(std::abs(s) <= 1e-3);
}

TEST_CASE("c3d8: the stiffness product is the derivative of the internal force, symmetric",
          "[elements][c3d8]") {
  const test::HexBlockMesh mesh = test::make_block(3, H, 0.15);
  const Index n = static_cast<Index>(mesh.coordinates.rows());
  const NodalVectors u = random_field(n, 11, 1.0);
  const Hex8Block block = make_c3d8(mesh, 0.3);
  NodalVectors ku = NodalVectors::Zero(n, 3);
  block.add_stiffness_product(mesh.coordinates, u, ku);
  const auto force_after = [&](Real eps) {
    Hex8Block b = make_c3d8(mesh, 0.3);
    const Real dt = 1e3;  // s: a long, slow increment (no rate terms)
    NodalVectors f = NodalVectors::Zero(n, 3);
    HexStepTotals t;
    b.internal_forces(mesh.coordinates + eps * u, (eps / dt) * u, dt, 0.0, 0.0, f, t);
    return f;
  };
  const Real eps = 1e-9;  // m: 1e-6 h
  const NodalVectors fd = (force_after(eps) - force_after(-eps)) / (2.0 * eps);
  CHECK((ku - fd).norm() <= 1e-6 * ku.norm());
  const NodalVectors w = random_field(n, 5, 1.0);
  NodalVectors kw = NodalVectors::Zero(n, 3);
  block.add_stiffness_product(mesh.coordinates, w, kw);
  const Real uKw = (u.array() * kw.array()).sum(), wKu = (w.array() * ku.array()).sum();
  CHECK(std::abs(uKw - wKu) <= 1e-12 * std::abs(uKw));
}

namespace {

/// Eigenvalues (ascending) of the stiffness of one element, assembled column by column from
/// the stiffness product.
template <class Block>
Eigen::VectorXd element_spectrum(const Block& block, const NodalVectors& x) {
  Eigen::MatrixXd K(24, 24);
  for (int j = 0; j < 24; ++j) {
    NodalVectors u = NodalVectors::Zero(8, 3), y = NodalVectors::Zero(8, 3);
    u(j / 3, j % 3) = 1.0;
    block.add_stiffness_product(x, u, y);
    for (int i = 0; i < 24; ++i) K(i, j) = y(i / 3, i % 3);
  }
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(0.5 * (K + K.transpose()),
                                                        Eigen::EigenvaluesOnly);
  return solver.eigenvalues();
}

}  // namespace

TEST_CASE("c3d8: full integration leaves the 6 rigid-body modes only (no hourglass modes)",
          "[elements][c3d8]") {
  const test::HexBlockMesh mesh = test::make_block(1, H, 0.15);
  for (Real nu : {0.0, 0.3, 0.499}) {
    INFO("nu " << nu);
    const Eigen::VectorXd k = element_spectrum(make_c3d8(mesh, nu), mesh.coordinates);
    const Real top = k(23);
    int zero = 0;
    for (int i = 0; i < 24; ++i) zero += k(i) < 1e-10 * top ? 1 : 0;
    CHECK(zero == 6);
    // The softest deformation mode is shear-like (μ), not hourglass-soft: above 0.1 % of the top
    // (where the top is not the bulk modulus' uniform dilatation, ν < 0.4).
    if (nu < 0.4) CHECK(k(6) > 1e-3 * top);
  }
}

TEST_CASE("c3d8: mean dilatation: volumetric stiffness in one mode, not in every mode",
          "[elements][c3d8]") {
  // Near incompressibility the stiffness of a locking element grows with the bulk modulus in
  // many modes; with mean dilatation only one mode (the uniform dilatation) does. Between
  // ν = 0.49 and 0.4999 the bulk modulus grows 100-fold: the 17 deformation modes below the
  // top one keep their stiffness to within 3 % (μ changes by 0.7 %).
  const test::HexBlockMesh mesh = test::make_block(1, H, 0.15);
  const Eigen::VectorXd a = element_spectrum(make_c3d8(mesh, 0.49), mesh.coordinates);
  const Eigen::VectorXd b = element_spectrum(make_c3d8(mesh, 0.4999), mesh.coordinates);
  CHECK(b(23) / a(23) > 50.0);
  for (int i = 6; i < 23; ++i) {
    INFO("mode " << i);
    CHECK(b(i) / a(i) == Approx(1.0).margin(0.03));
  }
}

TEST_CASE("c3d8: J2 plasticity: every point returns to the yield surface, pressure kept",
          "[elements][c3d8][plastic]") {
  const test::HexBlockMesh mesh = test::make_block(2, H, 0.1);
  const Index n = static_cast<Index>(mesh.coordinates.rows());
  Plasticity law;
  law.yield_stress = {250e6};
  law.plastic_strain = {0.0};
  Hex8Block block = make_c3d8(mesh, 0.3, &law);
  REQUIRE(block.has_plasticity());
  // A large uniaxial-strain increment (strain 1e-2, far beyond yield at 1.25e-3).
  const Real G[3][3] = {{1e4, 0.0, 0.0}, {0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}};
  const Real dt = 1e-6;
  const NodalVectors v = linear_field(mesh.coordinates, G);
  NodalVectors force = NodalVectors::Zero(n, 3);
  HexStepTotals totals;
  block.internal_forces(mesh.coordinates + dt * v, v, dt, 0.0, 0.0, force, totals);
  CHECK(totals.plastic_energy_increment > 0.0);
  for (Index e = 0; e < block.size(); ++e) {
    for (int q = 0; q < HEX8_POINTS; ++q) {
      const std::array<Real, 6> s = block.point_stress(e, q);
      const Real p = (s[0] + s[1] + s[2]) / 3.0;
      const Real mises =
          std::sqrt(0.5 * ((s[0] - s[1]) * (s[0] - s[1]) + (s[1] - s[2]) * (s[1] - s[2]) +
                           (s[2] - s[0]) * (s[2] - s[0])) +
                    3.0 * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]));
      CHECK(mises == Approx(250e6).epsilon(1e-9));
      // The pressure is the elastic one, K dt tr(D) with D on the mid geometry (the return is
      // deviatoric): tr D = G11 / (1 + dt G11 / 2).
      const Real bulk = E / (3.0 * (1.0 - 2.0 * 0.3));
      CHECK(p == Approx(bulk * dt * G[0][0] / (1.0 + 0.5 * dt * G[0][0])).epsilon(1e-9));
    }
    CHECK(block.plastic_strain(e) > 0.0);
  }
}
