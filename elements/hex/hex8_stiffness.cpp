// The linear stiffness product of one C3D8 batch (HexBlock::add_stiffness_product), for the
// global estimate of the highest frequency (solver/increment/global_increment.*).
#include "elements/hex/hex8.hpp"
#include "elements/hex/hex8_geometry.hpp"
#include "elements/hex/hex8_point.hpp"

namespace xpl::elements {

using simd::Vec;

void Hex8Block::stiffness_batch(Index batch, const NodalColumns& c) const {
  const Index* conn = m_batches.conn(batch);
  const Real* cst = m_batches.constants(batch);
  V3<Vec> ax[8], au[8], g[8];
  gather_modes(conn, c.x[0], c.x[1], c.x[2], c.v[0], c.v[1], c.v[2], ax, au);
  Vec vol;
  volume_gradient(ax, g, vol);
  Vec tr = simd::splat(0.0);
  for (int k = 1; k < 7; ++k) tr += dot(au[k], g[k]);
  tr /= vol;
  const Vec lambda = simd::load(cst + LAMBDA * W);
  const Vec two_mu = simd::load(cst + TWO_MU * W);
  V3<Vec> F[8];
  for (int k = 0; k < 8; ++k) F[k] = {simd::splat(0.0), simd::splat(0.0), simd::splat(0.0)};
  for (int q = 0; q < HEX8_POINTS; ++q) {
    const GaussPoint p = gauss_point(q);
    const PointFrame<Vec> f = point_frame(ax, p);
    V3<Vec> du[3];
    jacobian_columns(au, p, du);
    // Displacement gradient H = (1/det J) Σ_a ∂u/∂ξ_a ⊗ n_a; only its deviator is needed.
    Vec H[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) H[i][j] = simd::splat(0.0);
    for (int a = 0; a < 3; ++a) {
      const Vec ui[3] = {du[a].x, du[a].y, du[a].z};
      const Vec nj[3] = {f.n[a].x, f.n[a].y, f.n[a].z};
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) H[i][j] += ui[i] * nj[j];
    }
    const Vec inv_det = 1.0 / f.det;
    const Vec mean = (1.0 / 3.0) * (H[0][0] + H[1][1] + H[2][2]);
    // Deviatoric stress 2μ dev(sym H) (the B-bar volumetric part is in the pressure below).
    const Vec dev[6] = {
        two_mu * inv_det * (H[0][0] - mean),          two_mu * inv_det * (H[1][1] - mean),
        two_mu * inv_det * (H[2][2] - mean),          0.5 * two_mu * inv_det * (H[0][1] + H[1][0]),
        0.5 * two_mu * inv_det * (H[0][2] + H[2][0]), 0.5 * two_mu * inv_det * (H[1][2] + H[2][1])};
    add_deviatoric_forces(dev, f, p, F);
  }
  // Mean stress K tr(ε̄) through the exact volume gradient.
  const Vec pressure = (lambda + (1.0 / 3.0) * two_mu) * tr;
  for (int k = 1; k < 7; ++k) F[k] = F[k] + pressure * g[k];
  Vec Fx[8], Fy[8], Fz[8];
  for (int k = 0; k < 8; ++k) {
    Fx[k] = 0.125 * F[k].x;
    Fy[k] = 0.125 * F[k].y;
    Fz[k] = 0.125 * F[k].z;
  }
  Vec fnx[8], fny[8], fnz[8];
  from_modes(Fx, fnx);
  from_modes(Fy, fny);
  from_modes(Fz, fnz);
  m_batches.scatter_direct(batch, fnx, fny, fnz, c.f[0], c.f[1], c.f[2]);
}

}  // namespace xpl::elements
