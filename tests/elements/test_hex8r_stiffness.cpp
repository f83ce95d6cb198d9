// Hex8rBlock::add_stiffness_product is the derivative of the internal force: checked against
// central finite differences of internal_forces() on a distorted block, with both hourglass
// forms, and for symmetry (the global frequency estimate relies on it).

#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include "elements/hex/hex8r.hpp"
#include "hex_fixtures.hpp"

using namespace xpl;
using namespace xpl::elements;

namespace {

constexpr Real E = 200e9, NU = 0.3, RHO = 7850.0, H = 1e-3;

Hex8rBlock make_block(const test::HexBlockMesh& mesh, HourglassForm form) {
  const auto n = static_cast<Index>(mesh.connectivity.size() / 8);
  std::vector<Index> rows(static_cast<std::size_t>(n));
  for (Index i = 0; i < n; ++i) rows[static_cast<std::size_t>(i)] = i;
  std::vector<HexMaterial> materials(n, HexMaterial{RHO, E, NU, form, 1.0});
  return Hex8rBlock(rows, mesh.connectivity, materials,
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

/// Internal force of a fresh (stress-free) block after one long, slow increment that moves
/// the nodes by eps·u: to first order eps·K u (no bulk viscosity; the viscous hourglass
/// forces, ∝ eps·u/dt, vanish with the long increment).
NodalVectors force_after(const test::HexBlockMesh& mesh, HourglassForm form, const NodalVectors& u,
                         Real eps) {
  Hex8rBlock block = make_block(mesh, form);
  const NodalVectors position = mesh.coordinates + eps * u;
  const Real dt = 1e3;  // s
  const NodalVectors velocity = (eps / dt) * u;
  NodalVectors force = NodalVectors::Zero(u.rows(), 3);
  HexStepTotals totals;
  block.internal_forces(position, velocity, dt, 0.0, 0.0, force, totals);
  return force;
}

}  // namespace

TEST_CASE("hex8r: the stiffness product is the derivative of the internal force",
          "[elements][hex8r]") {
  const test::HexBlockMesh mesh = test::make_block(3, H, 0.15);
  const Index n = static_cast<Index>(mesh.coordinates.rows());
  const NodalVectors u = random_field(n, 11, 1.0);
  for (HourglassForm form :
       {HourglassForm::Stiffness, HourglassForm::Viscous, HourglassForm::Enhanced}) {
    INFO("hourglass form " << static_cast<int>(form));
    const Hex8rBlock block = make_block(mesh, form);
    NodalVectors ku = NodalVectors::Zero(n, 3);
    block.add_stiffness_product(mesh.coordinates, u, ku);
    const Real eps = 1e-9;  // m: displacement 1e-6 h
    const NodalVectors fd =
        (force_after(mesh, form, u, eps) - force_after(mesh, form, u, -eps)) / (2.0 * eps);
    CHECK((ku - fd).norm() <= 1e-6 * ku.norm());
    CHECK(ku.norm() > 0.0);
  }
}

TEST_CASE("hex8r: the stiffness product is symmetric and positive semi-definite",
          "[elements][hex8r]") {
  const test::HexBlockMesh mesh = test::make_block(2, H, 0.2);
  const Index n = static_cast<Index>(mesh.coordinates.rows());
  const HourglassForm form = GENERATE(HourglassForm::Stiffness, HourglassForm::Enhanced);
  INFO("hourglass form " << static_cast<int>(form));
  const Hex8rBlock block = make_block(mesh, form);
  const NodalVectors u = random_field(n, 3, 1e-6), v = random_field(n, 5, 1e-6);
  NodalVectors ku = NodalVectors::Zero(n, 3), kv = NodalVectors::Zero(n, 3);
  block.add_stiffness_product(mesh.coordinates, u, ku);
  block.add_stiffness_product(mesh.coordinates, v, kv);
  const Real vku = (v.array() * ku.array()).sum(), ukv = (u.array() * kv.array()).sum();
  CHECK(std::abs(vku - ukv) <= 1e-10 * std::abs(vku));
  CHECK((u.array() * ku.array()).sum() > 0.0);
  // A rigid translation has no stiffness.
  NodalVectors t = NodalVectors::Zero(n, 3), kt = NodalVectors::Zero(n, 3);
  t.col(1).setConstant(1e-6);
  block.add_stiffness_product(mesh.coordinates, t, kt);
  CHECK(kt.norm() <= 1e-9 * ku.norm());
}
