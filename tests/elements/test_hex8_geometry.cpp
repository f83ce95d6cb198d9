#include <catch2/catch.hpp>

#include <cmath>

#include "elements/hex/hex8_geometry.hpp"
#include "hex_fixtures.hpp"

using namespace xpl;
using namespace xpl::elements;

namespace {

// det J of the trilinear map at natural point (r, s, t).
Real jacobian_det(const Real x[8], const Real y[8], const Real z[8], Real r, Real s, Real t) {
  Real J[3][3] = {};
  for (int a = 0; a < 8; ++a) {
    const Real xi = NODE_XI[a], eta = NODE_ETA[a], zeta = NODE_ZETA[a];
    const Real dn[3] = {0.125 * xi * (1 + eta * s) * (1 + zeta * t),
                        0.125 * eta * (1 + xi * r) * (1 + zeta * t),
                        0.125 * zeta * (1 + xi * r) * (1 + eta * s)};
    const Real p[3] = {x[a], y[a], z[a]};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) J[i][j] += p[i] * dn[j];
  }
  return J[0][0] * (J[1][1] * J[2][2] - J[1][2] * J[2][1]) -
         J[0][1] * (J[1][0] * J[2][2] - J[1][2] * J[2][0]) +
         J[0][2] * (J[1][0] * J[2][1] - J[1][1] * J[2][0]);
}

// 2×2×2 Gauss integration of det J is exact for the trilinear hex.
Real gauss_volume(const Real x[8], const Real y[8], const Real z[8]) {
  const Real g = 1.0 / std::sqrt(3.0);
  Real v = 0.0;
  for (int i = 0; i < 8; ++i)
    v += jacobian_det(x, y, z, (i & 1) ? g : -g, (i & 2) ? g : -g, (i & 4) ? g : -g);
  return v;
}

void element_coords(const test::HexBlockMesh& mesh, int e, Real x[8], Real y[8], Real z[8]) {
  for (int a = 0; a < 8; ++a) {
    const Index p = mesh.connectivity[e * 8 + a];
    x[a] = mesh.coordinates(p, 0);
    y[a] = mesh.coordinates(p, 1);
    z[a] = mesh.coordinates(p, 2);
  }
}

// b_I = ∂V/∂x_I from the mode-space gradient.
void volume_derivatives(const Real x[8], const Real y[8], const Real z[8], Real b[8][3]) {
  V3<Real> a[8], g[8];
  Real vol = 0.0;
  to_modes(x, y, z, a);
  volume_gradient(a, g, vol);
  Real gx[8], gy[8], gz[8], bx[8], by[8], bz[8];
  for (int k = 0; k < 8; ++k) {
    gx[k] = g[k].x / 8.0;
    gy[k] = g[k].y / 8.0;
    gz[k] = g[k].z / 8.0;
  }
  from_modes(gx, bx);
  from_modes(gy, by);
  from_modes(gz, bz);
  for (int i = 0; i < 8; ++i) {
    b[i][0] = bx[i];
    b[i][1] = by[i];
    b[i][2] = bz[i];
  }
}

}  // namespace

TEST_CASE("mode transform and its inverse are consistent with the sign table", "[elements][hex]") {
  const Real p[8] = {1.5, -2.0, 0.25, 4.0, 3.0, -1.0, 0.5, 2.0};
  Real a[8];
  to_modes(p, a);
  for (int k = 0; k < 8; ++k) {
    Real expect = 0.0;
    for (int i = 0; i < 8; ++i) expect += mode_sign(k, i) * p[i] / 8.0;
    CHECK(a[k] == Approx(expect).margin(1e-14));
  }
  Real back[8];
  from_modes(a, back);
  for (int i = 0; i < 8; ++i) CHECK(back[i] == Approx(p[i]).margin(1e-14));
}

TEST_CASE("hex volume is exact for distorted elements", "[elements][hex]") {
  const auto mesh = test::make_block(2, 0.01, 0.2);
  for (int e = 0; e < 8; ++e) {
    Real x[8], y[8], z[8];
    element_coords(mesh, e, x, y, z);
    const Real exact = gauss_volume(x, y, z);
    // Both are exact integrals; they differ only by round-off (relative 1e-12).
    CHECK(hex8_volume(x, y, z) == Approx(exact).epsilon(1e-12));
  }
}

TEST_CASE("volume derivatives match finite differences and reproduce linear fields",
          "[elements][hex]") {
  const auto mesh = test::make_block(1, 0.01, 0.25, 3);
  Real x[8], y[8], z[8];
  element_coords(mesh, 0, x, y, z);
  Real b[8][3];
  volume_derivatives(x, y, z, b);
  const Real vol = hex8_volume(x, y, z);
  const Real h = 1e-7;  // V is cubic: central differences err by O(h²·V/L²) ~ 1e-14 relative
  for (int node = 0; node < 8; ++node) {
    Real* comp[3] = {x, y, z};
    for (int c = 0; c < 3; ++c) {
      const Real keep = comp[c][node];
      comp[c][node] = keep + h;
      const Real vp = hex8_volume(x, y, z);
      comp[c][node] = keep - h;
      const Real vm = hex8_volume(x, y, z);
      comp[c][node] = keep;
      CHECK(b[node][c] == Approx((vp - vm) / (2 * h)).margin(1e-9 * vol / 0.01));
    }
  }
  // Σ_I b_Ii x_Ij = V δ_ij: the uniform gradient differentiates linear fields exactly.
  const Real* p[3] = {x, y, z};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      Real s = 0.0;
      for (int node = 0; node < 8; ++node) s += b[node][i] * p[j][node];
      CHECK(s == Approx(i == j ? vol : 0.0).margin(1e-12 * vol));
    }
}

TEST_CASE("characteristic length of a cube is its side", "[elements][hex]") {
  const Real h = 0.02;
  const Real x[8] = {0, h, h, 0, 0, h, h, 0}, y[8] = {0, 0, h, h, 0, 0, h, h},
             z[8] = {0, 0, 0, 0, h, h, h, h};
  V3<Real> a[8];
  to_modes(x, y, z, a);
  CHECK(std::sqrt(max_face_area_squared(a)) == Approx(h * h).epsilon(1e-12));
  CHECK(hex8_volume(x, y, z) == Approx(h * h * h).epsilon(1e-12));
}

TEST_CASE("the corner fold measure is negative where a scaled corner Jacobian is below -tau",
          "[elements][hex]") {
  // The measure from the columns of J at each corner (shape-function derivatives).
  auto direct = [](const Real x[8], const Real y[8], const Real z[8], Real tau, Real& scaled) {
    Real smallest = 0.0;
    scaled = 1.0;
    for (int c = 0; c < 8; ++c) {
      Real J[3][3] = {};
      const Real r = NODE_XI[c], s = NODE_ETA[c], t = NODE_ZETA[c];
      for (int a = 0; a < 8; ++a) {
        const Real xi = NODE_XI[a], eta = NODE_ETA[a], zeta = NODE_ZETA[a];
        const Real dn[3] = {0.125 * xi * (1 + eta * s) * (1 + zeta * t),
                            0.125 * eta * (1 + xi * r) * (1 + zeta * t),
                            0.125 * zeta * (1 + xi * r) * (1 + eta * s)};
        const Real p[3] = {x[a], y[a], z[a]};
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j) J[i][j] += p[i] * dn[j];
      }
      Real columns = 1.0;
      for (int j = 0; j < 3; ++j)
        columns *= J[0][j] * J[0][j] + J[1][j] * J[1][j] + J[2][j] * J[2][j];
      const Real det = jacobian_det(x, y, z, r, s, t);
      const Real f = det * std::abs(det) + tau * tau * columns;
      smallest = c == 0 ? f : std::min(smallest, f);
      scaled = std::min(scaled, det / std::sqrt(columns));
    }
    return smallest;
  };
  // The measure of the edges, twice J's columns: 2⁶ times that of J.
  auto fold_of = [](const Real x[8], const Real y[8], const Real z[8], Real tau) {
    V3<Real> p[8];
    for (int a = 0; a < 8; ++a) p[a] = {x[a], y[a], z[a]};
    return corner_fold(p, tau) / 64.0;
  };
  const auto mesh = test::make_block(2, 0.01, 0.2);
  for (int e = 0; e < 8; ++e) {
    Real x[8], y[8], z[8], scaled = 0.0;
    element_coords(mesh, e, x, y, z);
    // Every corner positive: the smallest det E, 8 det J.
    direct(x, y, z, 0.5, scaled);
    REQUIRE(scaled > 0.0);
    Real smallest = jacobian_det(x, y, z, -1, -1, -1);
    for (int c = 1; c < 8; ++c)
      smallest = std::min(smallest, jacobian_det(x, y, z, NODE_XI[c], NODE_ETA[c], NODE_ZETA[c]));
    CHECK(fold_of(x, y, z, 0.5) * 64.0 == Approx(8.0 * smallest).epsilon(1e-12));
  }
  // A cube of side h: det J = (h/2)³ and |J_i| = h/2 at every corner (without a negative
  // corner the measure is the smallest det E = 8 det J). Node 7 (index 6) pushed
  // along the diagonal past the plane of its three neighbours (x + y + z = 2h, at s = 2h/3):
  // the volume stays positive while that corner turns over, its scaled Jacobian falling
  // through 0 and below −0.5 as the node goes on.
  const Real h = 0.01;
  Real x[8], y[8], z[8];
  for (int a = 0; a < 8; ++a) {
    x[a] = h * (NODE_XI[a] + 1) / 2;
    y[a] = h * (NODE_ETA[a] + 1) / 2;
    z[a] = h * (NODE_ZETA[a] + 1) / 2;
  }
  CHECK(fold_of(x, y, z, 0.5) == Approx(std::pow(h / 2, 3) / 8).epsilon(1e-12));
  for (const Real s : {0.62, 0.55, 0.5}) {
    x[6] = y[6] = z[6] = s * h;
    Real scaled = 0.0;
    const Real expected = direct(x, y, z, 0.5, scaled);
    INFO("s = " << s << " h, smallest scaled Jacobian " << scaled);
    CHECK(hex8_volume(x, y, z) > 0.0);
    CHECK(scaled < 0.0);
    CHECK(fold_of(x, y, z, 0.5) == Approx(expected).epsilon(1e-12));
    CHECK((fold_of(x, y, z, 0.5) < 0.0) == (scaled < -0.5));
    CHECK((scaled < -0.5) == (s < 0.6));
  }
}
