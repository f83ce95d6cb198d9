#pragma once
/// \file Gather of one batch of hexes into mode space, shared by the C3D8R and C3D8 force
/// passes (hex8r.cpp, hex8.cpp) and their linear stiffness products.

#include "elements/hex/hex8_geometry.hpp"
#include "elements/parallel/simd.hpp"

namespace xpl::elements {

/// Gathers the 8 corners of a batch (connectivity `conn`, corner-major, simd::W lanes) of two
/// nodal fields given as component arrays (positions p, and v: velocities or displacements)
/// and transforms both into the trilinear modes a_k (hex8_geometry.hpp); the corner positions
/// themselves into `corners` unless it is null.
inline void gather_modes(const Index* conn, const Real* px, const Real* py, const Real* pz,
                         const Real* vx, const Real* vy, const Real* vz, V3<simd::Vec> ap[8],
                         V3<simd::Vec> av[8], V3<simd::Vec>* corners = nullptr) {
  simd::Vec cx[8], cy[8], cz[8], wx[8], wy[8], wz[8];
  for (int a = 0; a < 8; ++a) {
    const Index* idx = conn + a * simd::W;
    cx[a] = simd::gather(px, idx);
    cy[a] = simd::gather(py, idx);
    cz[a] = simd::gather(pz, idx);
    wx[a] = simd::gather(vx, idx);
    wy[a] = simd::gather(vy, idx);
    wz[a] = simd::gather(vz, idx);
  }
  if (corners != nullptr)
    for (int a = 0; a < 8; ++a) corners[a] = {cx[a], cy[a], cz[a]};
  to_modes(cx, cy, cz, ap);
  to_modes(wx, wy, wz, av);
}

}  // namespace xpl::elements
