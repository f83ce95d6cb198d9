// Element state setters for imported states: Hex8rBlock::set_stress and
// Shell4rBlock::set_output_stress are the inverses of gather_output, and the state set acts
// in the next internal-force pass.

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

#include <Eigen/Geometry>

#include "elements/hex/hex8r.hpp"
#include "elements/shell/shell4r.hpp"
#include "hex_fixtures.hpp"

using namespace xpl;
using namespace xpl::elements;

namespace {

constexpr Real E = 200e9, NU = 0.3, RHO = 7850.0, T = 0.01;
constexpr Real NaN = std::numeric_limits<Real>::quiet_NaN();

/// Model index of block element i: every other row, so that rows outside the block exist.
Index model_row(Index i) {
  return 2 * i + 1;
}

std::vector<Index> model_rows(Index n) {
  std::vector<Index> rows(static_cast<std::size_t>(n));
  for (Index i = 0; i < n; ++i) rows[static_cast<std::size_t>(i)] = model_row(i);
  return rows;
}

Hex8rBlock make_hex_block(const test::HexBlockMesh& mesh) {
  const auto n = static_cast<Index>(mesh.connectivity.size() / 8);
  std::vector<HexMaterial> materials(n, HexMaterial{RHO, E, NU, HourglassForm::Stiffness, 1.0});
  return Hex8rBlock(model_rows(n), mesh.connectivity, materials,
                    static_cast<Index>(mesh.coordinates.rows()));
}

/// A flat 2 × 2 patch of distorted quads (3 × 3 nodes, side ~ 0.1 m) in its own x'y'-plane,
/// turned by `rotation` and moved by (0.3, −0.2, 0.1) m.
struct Plate {
  NodalVectors local;  ///< node coordinates in the plate's own axes
  NodalVectors x;      ///< placed coordinates
  Eigen::Matrix3d rotation;
  std::vector<Index> conn;
};

Plate make_plate(const Eigen::Matrix3d& rotation) {
  Plate p;
  p.rotation = rotation;
  p.local = NodalVectors::Zero(9, 3);
  const Real h = 0.05;
  const Real jitter[9][2] = {{0, 0},        {0.004, 0.0},    {0, 0},
                             {0.0, -0.006}, {0.007, -0.005}, {0.0, 0.003},
                             {0, 0},        {-0.005, 0.0},   {0, 0}};
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      const int n = i + 3 * j;
      p.local(n, 0) = i * h + jitter[n][0];
      p.local(n, 1) = j * h + jitter[n][1];
    }
  p.x = p.local * rotation.transpose();
  p.x.rowwise() += Eigen::RowVector3d(0.3, -0.2, 0.1);
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const Index a = i + 3 * j;
      for (Index n : {a, a + 1, a + 4, a + 3}) p.conn.push_back(n);
    }
  return p;
}

Shell4rBlock make_shell_block(const Plate& p, int points) {
  const auto n = static_cast<Index>(p.conn.size() / 4);
  const ShellProperties properties{RHO, E, NU, T, points, 0.0, 1.0};
  return Shell4rBlock(model_rows(n), p.conn, std::vector<ShellProperties>(n, properties),
                      static_cast<Index>(p.x.rows()));
}

/// Plate orientations: a general one, and one with the normal along global x, where the
/// output 1-axis is global z projected instead of global x.
std::vector<Eigen::Matrix3d> orientations() {
  return {
      Eigen::AngleAxisd(0.7, Eigen::Vector3d(0.3, -0.5, 0.8).normalized()).toRotationMatrix(),
      Eigen::AngleAxisd(0.5 * 3.14159265358979323846, Eigen::Vector3d::UnitY()).toRotationMatrix()};
}

Real max_abs(const NodalVectors& a) {
  Real m = 0.0;
  for (Eigen::Index i = 0; i < a.rows(); ++i)
    for (int c = 0; c < 3; ++c) m = std::max(m, std::abs(a(i, c)));
  return m;
}

}  // namespace

TEST_CASE("hex set_stress: gather_output returns the stresses set", "[elements][hex][import]") {
  const auto mesh = test::make_block(2, 0.01, 0.2);
  Hex8rBlock block = make_hex_block(mesh);
  const auto rows = static_cast<std::size_t>(2 * block.size() + 1);
  std::vector<Real> set(rows * 6, NaN);  // rows outside the block must not be read
  for (Index i = 0; i < block.size(); ++i) {
    const auto e = static_cast<std::size_t>(model_row(i));
    const Real s[6] = {1.0, -2.0, 3.0, 0.5, -0.25, 0.125};
    for (int c = 0; c < 6; ++c) set[e * 6 + c] = 1e6 * (i + 1) * s[c] + c;
  }
  block.set_stress(set);
  std::vector<Real> stress(rows * 6, NaN), volume(rows, NaN);
  block.gather_output(stress, volume);
  for (std::size_t e = 0; e < rows; ++e) {
    for (int c = 0; c < 6; ++c) {
      if (e % 2 == 1) {
        CHECK(stress[e * 6 + c] == set[e * 6 + c]);  // a copy: bit for bit
      } else {
        CHECK(std::isnan(stress[e * 6 + c]));
      }
    }
  }
}

TEST_CASE("hex set_stress: the stress set gives its nodal forces", "[elements][hex][import]") {
  // A cube of side h under a uniform stress σ: f_I = σ ∂V/∂x_I = σ (h²/4) s_I, with s_I the
  // signs of the corner's position relative to the centre. No strain rate (v = 0, dt = 0): no
  // bulk viscosity, no hourglass force.
  const Real h = 0.02;
  test::HexBlockMesh mesh;  // one cube, Abaqus node order
  mesh.n = 1;
  mesh.coordinates.resize(8, 3);
  mesh.coordinates << 0, 0, 0, h, 0, 0, h, h, 0, 0, h, 0, 0, 0, h, h, 0, h, h, h, h, 0, h, h;
  mesh.connectivity.resize(8);
  std::iota(mesh.connectivity.begin(), mesh.connectivity.end(), 0);
  Hex8rBlock block = make_hex_block(mesh);
  const Real s[6] = {3e8, -1e8, 2e8, 5e7, -4e7, 6e7};
  std::vector<Real> set(3 * 6, 0.0);
  std::copy(s, s + 6, set.begin() + 6);
  block.set_stress(set);
  NodalVectors force = NodalVectors::Zero(8, 3);
  const NodalVectors zero = NodalVectors::Zero(8, 3);
  HexStepTotals totals;
  block.internal_forces(mesh.coordinates, zero, 0.0, 0.06, 1.2, force, totals);
  Eigen::Matrix3d sigma;
  sigma << s[0], s[3], s[4], s[3], s[1], s[5], s[4], s[5], s[2];
  for (Index n = 0; n < 8; ++n) {
    Eigen::Vector3d sign;
    for (int c = 0; c < 3; ++c) sign(c) = mesh.coordinates(n, c) > 0.5 * h ? 1.0 : -1.0;
    const Eigen::Vector3d expected = sigma * sign * (0.25 * h * h);
    // Round-off of the mode transforms: 1e-12 of the force.
    for (int c = 0; c < 3; ++c)
      CHECK(force(n, c) == Approx(expected(c)).margin(1e-12 * 3e8 * h * h));
  }
  for (int c = 0; c < 6; ++c) CHECK(block.stress(0)[c] == s[c]);  // dt = 0: unchanged
  CHECK(totals.hourglass_energy_increment == 0.0);
}

TEST_CASE("hex set_stress: too few rows are refused", "[elements][hex][import]") {
  const auto mesh = test::make_block(2, 0.01, 0.0);
  Hex8rBlock block = make_hex_block(mesh);
  // The last block element is model row 2 n − 1: 2 n rows are needed.
  const std::vector<Real> short_rows(static_cast<std::size_t>(2 * block.size() - 1) * 6, 0.0);
  const std::vector<Real> enough(static_cast<std::size_t>(2 * block.size()) * 6, 0.0);
  CHECK_THROWS_AS(block.set_stress(short_rows), std::invalid_argument);
  CHECK_NOTHROW(block.set_stress(enough));
}

TEST_CASE("shell set_output_stress: gather_output returns the stresses set on a rotated plate",
          "[elements][shell][import]") {
  for (const Eigen::Matrix3d& rotation : orientations()) {
    const Plate p = make_plate(rotation);
    for (int points : {1, 3, 5, 7}) {
      CAPTURE(points);
      Shell4rBlock block = make_shell_block(p, points);
      const auto rows = static_cast<std::size_t>(2 * block.size() + 1);
      std::vector<Real> middle(rows * 6, NaN), bottom(rows * 6, NaN), top(rows * 6, NaN);
      for (Index i = 0; i < block.size(); ++i) {
        const auto e = static_cast<std::size_t>(model_row(i)) * 6;
        const Real k = 1e6 * (i + 1);
        // S11 S22 S33 S12 S13 S23; S33 = 0 and one transverse shear at all three points, as
        // the element holds them; a membrane-only element has one in-plane state.
        const Real mid[6] = {3 * k, -k, 0.0, 0.7 * k, 0.2 * k, -0.3 * k};
        const Real low[6] = {-5 * k, 2 * k, 0.0, 1.3 * k, 0.2 * k, -0.3 * k};
        const Real high[6] = {9 * k, 4 * k, 0.0, -2.1 * k, 0.2 * k, -0.3 * k};
        for (int c = 0; c < 6; ++c) {
          middle[e + c] = mid[c];
          bottom[e + c] = points > 1 ? low[c] : mid[c];
          top[e + c] = points > 1 ? high[c] : mid[c];
        }
      }
      block.set_output_stress(p.x, middle, bottom, top);
      std::vector<Real> s(rows * 6, NaN), sb(rows * 6, NaN), st(rows * 6, NaN),
          thickness(rows, NaN);
      block.gather_output(p.x, s, sb, st, thickness);
      for (std::size_t e = 0; e < rows; ++e) {
        if (e % 2 == 0) {
          CHECK(std::isnan(s[e * 6]));
          continue;
        }
        // Two plane rotations of values up to 9e7 Pa: round-off ~1e-8 Pa.
        for (int c = 0; c < 6; ++c) {
          CHECK(s[e * 6 + c] == Approx(middle[e * 6 + c]).margin(1e-7));
          CHECK(sb[e * 6 + c] == Approx(bottom[e * 6 + c]).margin(1e-7));
          CHECK(st[e * 6 + c] == Approx(top[e * 6 + c]).margin(1e-7));
        }
        CHECK(thickness[e] == T);  // left as it was
      }
    }
  }
}

TEST_CASE(
    "shell set_output_stress: an imported membrane + bending + shear state acts as the "
    "original",
    "[elements][shell][import]") {
  // Block A gets a linear-through-thickness state from one increment of membrane, bending
  // and transverse shear rates (traceless, so that the thickness stays); block B gets A's
  // output stresses set. The forces and moments of a further pass without motion must agree:
  // they integrate every through-thickness point, not only the three section points.
  for (const Eigen::Matrix3d& rotation : orientations()) {
    const Plate p = make_plate(rotation);
    NodalVectors v_local = NodalVectors::Zero(9, 3), w_local = NodalVectors::Zero(9, 3);
    for (Index n = 0; n < 9; ++n) {
      const Real x = p.local(n, 0), y = p.local(n, 1);
      // θx = a x + b y, θy = c x + d y: κxx = c, κyy = −b (κxx + κyy = 0); d = −a and the
      // quadratic part of the normal velocity make it a Kirchhoff field plus a constant
      // shear, which stores no hourglass resultants in either hourglass form.
      v_local.row(n) << 1e-2 * (x + 0.4 * y), 1e-2 * (-0.3 * x - y),
          0.01 * x + 0.02 * y + 0.015 * x * x + 0.02 * x * y - 0.015 * y * y;
      w_local.row(n) << 0.02 * x - 0.03 * y, -0.03 * x - 0.02 * y, 0.0;
    }
    const NodalVectors v = v_local * rotation.transpose(), w = w_local * rotation.transpose();
    for (int points : {3, 5, 7}) {
      CAPTURE(points);
      Shell4rBlock original = make_shell_block(p, points);
      Shell4rBlock imported = make_shell_block(p, points);
      const NodalVectors zero = NodalVectors::Zero(9, 3);
      NodalVectors f = zero, m = zero;
      ShellStepTotals totals;
      // Rates are taken on the mid-increment geometry: make it p.x, where the fields above
      // are defined (else the shear-free field has an O(dt |L|) shear there, which the
      // physical hourglass form stores in resultants that an import does not carry).
      original.internal_forces(p.x + 0.5e-3 * v, v, w, 1e-3, f, m, totals);

      const auto rows = static_cast<std::size_t>(2 * original.size() + 1);
      std::vector<Real> s(rows * 6, NaN), sb(rows * 6, NaN), st(rows * 6, NaN), th(rows, NaN);
      original.gather_output(p.x, s, sb, st, th);
      imported.set_output_stress(p.x, s, sb, st);

      NodalVectors f_original = zero, m_original = zero, f_imported = zero, m_imported = zero;
      ShellStepTotals ignored;
      original.internal_forces(p.x, zero, zero, 0.0, f_original, m_original, ignored);
      imported.internal_forces(p.x, zero, zero, 0.0, f_imported, m_imported, ignored);
      const Real f_scale = max_abs(f_original), m_scale = max_abs(m_original);
      REQUIRE(f_scale > 0.0);
      REQUIRE(m_scale > 0.0);
      // Round-off of the rotations and of the interpolation, and A's hourglass resultants
      // (zero for these linear fields, up to round-off): below 1e-14 of the largest value
      // here; giving the points between the section points (ζ = ±1/2, ±1/3, ±2/3) the middle
      // values instead would halve the moments.
      for (Index n = 0; n < 9; ++n)
        for (int c = 0; c < 3; ++c) {
          CHECK(f_imported(n, c) == Approx(f_original(n, c)).margin(1e-12 * f_scale));
          CHECK(m_imported(n, c) == Approx(m_original(n, c)).margin(1e-12 * m_scale));
        }
    }
  }
}

TEST_CASE("shell set_output_stress: too few rows are refused", "[elements][shell][import]") {
  const Plate p = make_plate(Eigen::Matrix3d::Identity());
  Shell4rBlock block = make_shell_block(p, 5);
  const std::vector<Real> full(static_cast<std::size_t>(2 * block.size()) * 6, 0.0);
  const std::vector<Real> short_rows(static_cast<std::size_t>(2 * block.size() - 1) * 6, 0.0);
  CHECK_THROWS_AS(block.set_output_stress(p.x, full, short_rows, full), std::invalid_argument);
  CHECK_NOTHROW(block.set_output_stress(p.x, full, full, full));
}
