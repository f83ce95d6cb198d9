#pragma once
// A cantilever of hexes for bending tests (test_hex8_bending.cpp, test_hex8r_enhanced.cpp):
// the mesh and the static tip deflection under a tip load, solved by conjugate gradients on a
// block's linear stiffness product.

#include <catch2/catch.hpp>

#include <vector>

#include "common/types.hpp"

namespace xpl::test {

struct Beam {
  NodalVectors x;
  std::vector<Index> connectivity;
  std::vector<bool> fixed;  // per node: the clamped end x = 0
  std::vector<Index> tip;   // nodes of x = L
};

/// Clamped at x = 0; LENGTH × WIDTH × DEPTH (x, y, z), nx × 1 × nz elements.
inline Beam make_beam(int nx, int nz, Real length, Real width, Real depth) {
  Beam b;
  const int px = nx + 1, pz = nz + 1;
  auto node = [&](int i, int j, int k) { return static_cast<Index>(i + px * (j + 2 * k)); };
  b.x.resize(px * 2 * pz, 3);
  b.fixed.assign(static_cast<std::size_t>(px * 2 * pz), false);
  for (int k = 0; k < pz; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < px; ++i) {
        const Index n = node(i, j, k);
        b.x(n, 0) = length * i / nx;
        b.x(n, 1) = width * j;
        b.x(n, 2) = depth * k / nz;
        b.fixed[n] = i == 0;
        if (i == nx) b.tip.push_back(n);
      }
  for (int k = 0; k < nz; ++k)
    for (int i = 0; i < nx; ++i) {
      const Index c[8] = {node(i, 0, k),         node(i + 1, 0, k), node(i + 1, 1, k),
                          node(i, 1, k),         node(i, 0, k + 1), node(i + 1, 0, k + 1),
                          node(i + 1, 1, k + 1), node(i, 1, k + 1)};
      b.connectivity.insert(b.connectivity.end(), c, c + 8);
    }
  return b;
}

/// Mean z displacement of the tip nodes under `load` (N) shared by them, by conjugate gradients on
/// the free DOFs (Jacobi-preconditioned if `jacobi`) to a relative residual of 1e-10.
template <class Block>
Real tip_deflection(const Block& block, const Beam& b, Real load, bool jacobi = true) {
  const Index n = b.x.rows();
  NodalVectors f = NodalVectors::Zero(n, 3), u = NodalVectors::Zero(n, 3);
  for (Index t : b.tip) f(t, 2) = load / static_cast<Real>(b.tip.size());
  const auto apply = [&](const NodalVectors& v) {
    NodalVectors y = NodalVectors::Zero(n, 3);
    block.add_stiffness_product(b.x, v, y);
    for (Index i = 0; i < n; ++i)
      if (b.fixed[i]) y.row(i).setZero();
    return y;
  };
  NodalVectors diag = NodalVectors::Zero(n, 3);
  for (Index i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) {
      if (b.fixed[i]) continue;
      if (!jacobi) {
        diag(i, c) = 1.0;
        continue;
      }
      NodalVectors e = NodalVectors::Zero(n, 3);
      e(i, c) = 1.0;
      diag(i, c) = apply(e)(i, c);
    }
  const auto precondition = [&](const NodalVectors& r) {
    NodalVectors z = NodalVectors::Zero(n, 3);
    for (Index i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c)
        if (diag(i, c) > 0.0) z(i, c) = r(i, c) / diag(i, c);
    return z;
  };
  NodalVectors r = f, z = precondition(r), p = z;
  Real rz = (r.array() * z.array()).sum();
  const Real f_norm = f.norm();
  for (int it = 0; it < 50000 && r.norm() > 1e-10 * f_norm; ++it) {
    const NodalVectors q = apply(p);
    const Real alpha = rz / (p.array() * q.array()).sum();
    u += alpha * p;
    r -= alpha * q;
    z = precondition(r);
    const Real rz_new = (r.array() * z.array()).sum();
    p = z + (rz_new / rz) * p;
    rz = rz_new;
  }
  REQUIRE(r.norm() <= 1e-10 * f_norm);
  Real sum = 0.0;
  for (Index t : b.tip) sum += u(t, 2);
  return sum / static_cast<Real>(b.tip.size());
}

inline std::vector<Index> rows_of(const Beam& b) {
  std::vector<Index> rows(b.connectivity.size() / 8);
  for (std::size_t i = 0; i < rows.size(); ++i) rows[i] = static_cast<Index>(i);
  return rows;
}

}  // namespace xpl::test
