// The linear stiffness product of one C3D8R batch (HexBlock::add_stiffness_product): what
// the global estimate of the highest frequency needs (solver/increment/global_increment.*).
#include "elements/hex/hex8_geometry.hpp"
#include "elements/hex/hex8r.hpp"
#include "elements/hex/hex8r_gather.hpp"
#include "elements/hex/hex8r_hourglass.hpp"

namespace xpl::elements {

using simd::Vec;

void Hex8rBlock::stiffness_batch(Index batch, const NodalColumns& c) const {
  // Enhanced and mixed batches take the general instantiation; the Flanagan–Belytschko one is
  // the form's kernel alone (bit for bit the products of the form before).
  if (m_batch_path[batch] == HourglassPath::FlanaganBelytschko)
    stiffness_batch<HourglassPath::FlanaganBelytschko>(batch, c);
  else
    stiffness_batch<HourglassPath::Mixed>(batch, c);
}

template <Hex8rBlock::HourglassPath PATH>
void Hex8rBlock::stiffness_batch(Index batch, const NodalColumns& c) const {
  const Index* conn = m_batches.conn(batch);
  const Real* cst = m_batches.constants(batch);
  V3<Vec> ax[8], au[8];
  gather_modes(conn, c.x[0], c.x[1], c.x[2], c.v[0], c.v[1], c.v[2], ax, au);
  V3<Vec> g[8];
  Vec vol;
  volume_gradient(ax, g, vol);
  const Vec inv_vol = 1.0 / vol;

  // Displacement gradient H = (1/V) Σ_k au_k ⊗ g_k and the stress C : sym(H).
  Vec H[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) H[i][j] = simd::splat(0.0);
  Vec gsum = simd::splat(0.0);
  for (int k = 1; k < 7; ++k) {
    const Vec ui[3] = {au[k].x, au[k].y, au[k].z};
    const Vec gj[3] = {g[k].x, g[k].y, g[k].z};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) H[i][j] += ui[i] * gj[j];
    gsum += dot(g[k], g[k]);
  }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) H[i][j] *= inv_vol;
  const Vec lambda = simd::load(cst + LAMBDA * W);
  const Vec two_mu = simd::load(cst + TWO_MU * W);
  const Vec lt = lambda * (H[0][0] + H[1][1] + H[2][2]);
  Vec P[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) P[i][j] = 0.5 * two_mu * (H[i][j] + H[j][i]);
  for (int i = 0; i < 3; ++i) P[i][i] += lt;

  // Stiffness hourglass forces Q_α = k_hg q_α, q_α = 8 (au_α − H a_α), or the enhanced
  // form's, with the projection term of the force (see compute_batch).
  const Vec k_hg = simd::load(cst + HG_STIFFNESS * W) * two_mu * (gsum * 0.125) * (0.125 * inv_vol);
  V3<Vec> Q[4];
  if constexpr (PATH == HourglassPath::FlanaganBelytschko) {
    for (int m = 0; m < 4; ++m) {
      const V3<Vec>& a = ax[4 + m];
      const V3<Vec> ha = {H[0][0] * a.x + H[0][1] * a.y + H[0][2] * a.z,
                          H[1][0] * a.x + H[1][1] * a.y + H[1][2] * a.z,
                          H[2][0] * a.x + H[2][1] * a.y + H[2][2] * a.z};
      Q[m] = (8.0 * k_hg) * (au[4 + m] - ha);
      const Vec qi[3] = {Q[m].x, Q[m].y, Q[m].z};
      const Vec aj[3] = {a.x, a.y, a.z};
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) P[i][j] -= 8.0 * inv_vol * qi[i] * aj[j];
    }
  } else {
    V3<Vec> q[4], u[4];
    for (int m = 0; m < 4; ++m) {
      const V3<Vec>& a = ax[4 + m];
      q[m] = au[4 + m] - V3<Vec>{H[0][0] * a.x + H[0][1] * a.y + H[0][2] * a.z,
                                 H[1][0] * a.x + H[1][1] * a.y + H[1][2] * a.z,
                                 H[2][0] * a.x + H[2][1] * a.y + H[2][2] * a.z};
    }
    // The enhanced form's K q̂ (hex8r_enhanced.hpp): plane stresses of the strains, their
    // forces, the ξηζ mode's diagonal stiffness; back to global Flanagan–Belytschko scaling.
    const Vec mu = simd::load(cst + HG_MU * W);
    const Vec lambda_bar = simd::load(cst + HG_LAMBDA * W);
    const EnhancedFrame<Vec> f = enhanced_frame(ax, g[3], inv_vol);
    to_frame(f, q, u);
    Vec eps[9], S[9];
    enhanced_strains(f, u, eps);
    enhanced_stress_increment(eps, 2.0 * mu + lambda_bar, lambda_bar, mu, S);
    V3<Vec> qe[4];
    enhanced_forces(f, S, vol * (1.0 / 3.0), qe);
    const V3<Vec> k7 = enhanced_mode7_stiffness(f, vol * (1.0 / 9.0) * mu);
    qe[3] = {k7.x * u[3].x, k7.y * u[3].y, k7.z * u[3].z};
    const simd::Mask use = mu > 0.0;
    for (int m = 0; m < 4; ++m) {
      Q[m] = select3(use, from_frame(f, 0.125 * qe[m]), (8.0 * k_hg) * q[m]);
      const Vec qi[3] = {Q[m].x, Q[m].y, Q[m].z};
      const Vec aj[3] = {ax[4 + m].x, ax[4 + m].y, ax[4 + m].z};
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) P[i][j] -= 8.0 * inv_vol * qi[i] * aj[j];
    }
  }
  Vec Fx[8], Fy[8], Fz[8];
  Fx[0] = Fy[0] = Fz[0] = simd::splat(0.0);
  Fx[7] = Fy[7] = Fz[7] = simd::splat(0.0);
  for (int k = 1; k < 7; ++k) {
    Fx[k] = 0.125 * (P[0][0] * g[k].x + P[0][1] * g[k].y + P[0][2] * g[k].z);
    Fy[k] = 0.125 * (P[1][0] * g[k].x + P[1][1] * g[k].y + P[1][2] * g[k].z);
    Fz[k] = 0.125 * (P[2][0] * g[k].x + P[2][1] * g[k].y + P[2][2] * g[k].z);
  }
  for (int m = 0; m < 4; ++m) {
    Fx[4 + m] += Q[m].x;
    Fy[4 + m] += Q[m].y;
    Fz[4 + m] += Q[m].z;
  }
  Vec fnx[8], fny[8], fnz[8];
  from_modes(Fx, fnx);
  from_modes(Fy, fny);
  from_modes(Fz, fnz);
  m_batches.scatter_direct(batch, fnx, fny, fnz, c.f[0], c.f[1], c.f[2]);
}

}  // namespace xpl::elements
