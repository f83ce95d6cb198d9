#include "elements/hex/hex8r.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "elements/hex/hex8_geometry.hpp"
#include "elements/hex/hex8r_gather.hpp"
#include "elements/hex/hex8r_hourglass.hpp"
#include "elements/hex/hex_kernel.hpp"

namespace xpl::elements {

using simd::Vec;

// Both families keep 12 values per element in m_hourglass and in HGSTATE rows.
static_assert(ENHANCED_STATE == 12 && ENHANCED_STATE <= HOURGLASS_STATE_WIDTH);

Hex8rBlock::Hex8rBlock(std::vector<Index> element_index, const std::vector<Index>& connectivity,
                       const std::vector<HexMaterial>& materials, Index node_count,
                       const BatchLayout* layout)
    : Hex8rBase(std::move(element_index), connectivity, materials, node_count, N_CONST, layout) {
  const auto nb = static_cast<std::size_t>(m_batches.batch_count());
  m_hourglass.assign(nb * 12 * W, 0.0);
  m_batch_path.assign(nb, HourglassPath::FlanaganBelytschko);
  for (Index b = 0; b < m_batches.batch_count(); ++b) {
    int enhanced = 0;
    for (int l = 0; l < W; ++l) {
      const HexMaterial& m = materials[m_batches.lane_element(b, l)];
      Real* c = m_batches.constants(b) + l;
      const bool stiff = m.hourglass == HourglassForm::Stiffness;
      const bool viscous = m.hourglass == HourglassForm::Viscous;
      c[HG_STIFFNESS * W] = stiff ? HOURGLASS_STIFFNESS * m.hourglass_scale : 0.0;
      c[HG_VISCOSITY * W] = viscous ? HOURGLASS_VISCOSITY * m.hourglass_scale : 0.0;
      // Plane-stress moduli of the enhanced form: μ and λ̄ = 2μλ/(λ + 2μ) = νE/(1 − ν²).
      const Real mu = 0.5 * c[TWO_MU * W], lambda = c[LAMBDA * W];
      const Real scale = m.hourglass == HourglassForm::Enhanced ? m.hourglass_scale : 0.0;
      c[HG_MU * W] = scale * mu;
      c[HG_LAMBDA * W] = scale * 2.0 * mu * lambda / (lambda + 2.0 * mu);
      if (scale > 0.0) ++enhanced;
    }
    if (enhanced == W)
      m_batch_path[b] = HourglassPath::Enhanced;
    else if (enhanced > 0)
      m_batch_path[b] = HourglassPath::Mixed;
  }
  if (has_plasticity()) m_peeq_rate.assign(m_lane_law.size(), 0.0);
}

template <bool PLASTIC>
void Hex8rBlock::batch_forces(Index batch, const NodalColumns& c, Real dt, Real b1, Real b2) {
  switch (m_batch_path[batch]) {
    case HourglassPath::FlanaganBelytschko:
      compute_batch<PLASTIC, HourglassPath::FlanaganBelytschko>(batch, c, dt, b1, b2);
      break;
    case HourglassPath::Enhanced:
      compute_batch<PLASTIC, HourglassPath::Enhanced>(batch, c, dt, b1, b2);
      break;
    case HourglassPath::Mixed:
      compute_batch<PLASTIC, HourglassPath::Mixed>(batch, c, dt, b1, b2);
      break;
  }
}

namespace {

constexpr int W = simd::W;

/// The hourglass coefficients of a batch's lanes: κ_s 2μ, κ_v ρ c_d A_max (Flanagan–Belytschko,
/// without their ⅛ factors) and κμ, κλ̄ of the enhanced form (0 in lanes of the other forms).
struct HourglassLanes {
  Vec stiffness;
  Vec viscosity;
  Vec mu;
  Vec lambda;
};

/// The hourglass resultants Q_α (α = modes 4..7) of a batch applied on x_{n+1} (`ax`, `av`,
/// `g`, `vol` there; `L` the mid velocity gradient), their power, and the state they leave
/// in `hgq` ([12][W]): the Flanagan–Belytschko forms (FB), the enhanced form (ENHANCED), or
/// both, each lane taking the enhanced one where its κμ > 0. `relax` and `hg_limit` bound the
/// enhanced resultants of plastic lanes (hex8r.hpp).
template <bool PLASTIC, bool FB, bool ENHANCED>
XPL_KERNEL_INLINE void hourglass_resultants(const V3<Vec> ax[8], const V3<Vec> av[8],
                                            const V3<Vec> g[8], const Vec L[3][3], Vec vol,
                                            Vec inv_vol, const HourglassLanes& lanes, Real dt,
                                            const Vec& relax, const Vec& hg_limit,
                                            const Vec flow[6], Real* hgq, V3<Vec> Q[4],
                                            Vec& hg_power) {
  [[maybe_unused]] Vec stored[12];
  if constexpr (FB) {
    // Flanagan–Belytschko: q_α = γ_α·v = 8 (av_α − L_{n+1} a_α) on x_{n+1}.
    Vec Ln[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) Ln[i][j] = simd::splat(0.0);
    Vec gsum = simd::splat(0.0);
    for (int k = 1; k < 7; ++k) {
      const Vec vi[3] = {av[k].x, av[k].y, av[k].z};
      const Vec gj[3] = {g[k].x, g[k].y, g[k].z};
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) Ln[i][j] += vi[i] * gj[j];
      gsum += dot(g[k], g[k]);
    }
    V3<Vec> old[4];
    for (int m = 0; m < 4; ++m) {
      const Real* qs = hgq + m * 3 * W;
      old[m] = {simd::load(qs), simd::load(qs + W), simd::load(qs + 2 * W)};
    }
    const Vec k_hg = lanes.stiffness * (gsum * 0.125) * (0.125 * inv_vol);
    const Vec c_hg = lanes.viscosity * 0.125;
    HourglassStep hg;
    flanagan_belytschko_step(ax, av, Ln, inv_vol, k_hg, c_hg, dt, old, hg);
    for (int m = 0; m < 4; ++m) {
      stored[3 * m] = hg.stored[m].x;
      stored[3 * m + 1] = hg.stored[m].y;
      stored[3 * m + 2] = hg.stored[m].z;
      Q[m] = hg.force[m];
    }
    hg_power = hg.power;
  }
  if constexpr (ENHANCED) {
    // The enhanced form, its state in the element's frame (L: the mid velocity gradient).
    const Vec mu = lanes.mu;
    Vec old[ENHANCED_STATE], next[ENHANCED_STATE];
    for (int k = 0; k < ENHANCED_STATE; ++k) old[k] = simd::load(hgq + k * W);
    V3<Vec> force[4];
    Vec power;
    enhanced_step<PLASTIC>(ax, av, g[3], L, vol, inv_vol, mu, lanes.lambda, dt,
                           PLASTIC ? &relax : nullptr, PLASTIC ? &hg_limit : nullptr, flow, old,
                           next, force, power);
    if constexpr (!FB) {
      for (int k = 0; k < ENHANCED_STATE; ++k) stored[k] = next[k];
      for (int m = 0; m < 4; ++m) Q[m] = force[m];
      hg_power = power;
    } else {
      const simd::Mask use = mu > 0.0;
      for (int k = 0; k < ENHANCED_STATE; ++k) stored[k] = simd::select(use, next[k], stored[k]);
      for (int m = 0; m < 4; ++m) Q[m] = select3(use, force[m], Q[m]);
      hg_power = simd::select(use, power, hg_power);
    }
  }
  for (int k = 0; k < 12; ++k) simd::store(hgq + k * W, stored[k]);
}

/// The mean velocity gradient L = (1/V) Σ_k av_k ⊗ g_k over the geometry (g, V) of one point.
XPL_KERNEL_INLINE void mean_velocity_gradient(const V3<Vec> av[8], const V3<Vec> g[8], Vec volume,
                                              Vec L[3][3]) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) L[i][j] = simd::splat(0.0);
  for (int k = 1; k < 7; ++k) {
    const Vec vi[3] = {av[k].x, av[k].y, av[k].z};
    const Vec gj[3] = {g[k].x, g[k].y, g[k].z};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) L[i][j] += vi[i] * gj[j];
  }
  const Vec inv_volume = 1.0 / volume;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) L[i][j] *= inv_volume;
}

/// Corner forces (fnx, fny, fnz, N) of the stress `sn`, the bulk-viscosity pressure `sv` and
/// the hourglass resultants `Q` on x_{n+1} (modes `ax`, volume gradient `g`, 1/V).
XPL_KERNEL_INLINE void corner_forces(const Vec sn[6], Vec sv, const V3<Vec> Q[4],
                                     const V3<Vec> ax[8], const V3<Vec> g[8], Vec inv_vol,
                                     Vec fnx[8], Vec fny[8], Vec fnz[8]) {
  // Forces: f_I = P b_I + Σ_α Γ_αI Q_α with P = σ + s_v I − (8/V) Σ_α Q_α ⊗ a_α, and
  // b_I = ⅛ Σ_k Λ_kI g_k, so in mode space F_k = ⅛ P g_k (+ Q_α for k = 4..7).
  Vec P[3][3] = {
      {sn[0] + sv, sn[3], sn[4]}, {sn[3], sn[1] + sv, sn[5]}, {sn[4], sn[5], sn[2] + sv}};
  for (int m = 0; m < 4; ++m) {
    const Vec qi[3] = {Q[m].x, Q[m].y, Q[m].z};
    const Vec aj[3] = {ax[4 + m].x, ax[4 + m].y, ax[4 + m].z};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) P[i][j] -= 8.0 * inv_vol * qi[i] * aj[j];
  }
  Vec Fx[8], Fy[8], Fz[8];
  Fx[0] = Fy[0] = Fz[0] = simd::splat(0.0);
  for (int k = 1; k < 7; ++k) {
    Fx[k] = 0.125 * (P[0][0] * g[k].x + P[0][1] * g[k].y + P[0][2] * g[k].z);
    Fy[k] = 0.125 * (P[1][0] * g[k].x + P[1][1] * g[k].y + P[1][2] * g[k].z);
    Fz[k] = 0.125 * (P[2][0] * g[k].x + P[2][1] * g[k].y + P[2][2] * g[k].z);
  }
  Fx[7] = Fy[7] = Fz[7] = simd::splat(0.0);
  for (int m = 0; m < 4; ++m) {
    Fx[4 + m] += Q[m].x;
    Fy[4 + m] += Q[m].y;
    Fz[4 + m] += Q[m].z;
  }
  from_modes(Fx, fnx);
  from_modes(Fy, fny);
  from_modes(Fz, fnz);
}

}  // namespace

template <bool PLASTIC, Hex8rBlock::HourglassPath PATH>
void Hex8rBlock::compute_batch(Index batch, const NodalColumns& c, Real dt, Real b1, Real b2) {
  const Index* conn = m_batches.conn(batch);
  const Real* cst = m_batches.constants(batch);
  Real* sig = &m_stress[static_cast<std::size_t>(batch) * 6 * W];
  Real* hgq = &m_hourglass[static_cast<std::size_t>(batch) * 12 * W];

  // Gather and go to mode space (positions x_{n+1}, velocities v_{n+1/2}).
  V3<Vec> ax[8], av[8], corners[8];
  gather_modes(conn, c.x[0], c.x[1], c.x[2], c.v[0], c.v[1], c.v[2], ax, av, corners);
  // One point sees the mean gradient only: a corner node pushed through the element leaves the
  // volume positive (and the stress finite) while the element is turned inside out at that
  // corner. A corner counts as turned over past HEX_FOLD_LIMIT (hex8r.hpp says why not at 0).
  const Vec fold = simd::any_negative(corner_screen(ax)) ? corner_fold(corners, HEX_FOLD_LIMIT)
                                                         : simd::splat(1.0);

  // Geometry at x_{n+1} (forces, hourglass) and at x_{n+1/2} (strain increment).
  V3<Vec> g[8], gm[8];
  Vec vol, volm;
  volume_gradient(ax, g, vol);
  {
    V3<Vec> am[8];
    const Real half_dt = 0.5 * dt;
    for (int k = 0; k < 8; ++k) am[k] = ax[k] - half_dt * av[k];
    volume_gradient(am, gm, volm);
  }

  // Velocity gradient on the mid geometry.
  Vec L[3][3];
  mean_velocity_gradient(av, gm, volm, L);

  const Vec lambda = simd::load(cst + LAMBDA * W);
  const Vec two_mu = simd::load(cst + TWO_MU * W);
  const Vec density = simd::load(cst + DENSITY * W);
  const Vec wave = simd::load(cst + WAVE_SPEED * W);

  // Jaumann-rate elastic update: σ̇ = λ tr(D) I + 2μ D + Wσ − σW.
  const hex_kernel::Rates rate = hex_kernel::rates(L);
  const Vec tr = rate.d[0] + rate.d[1] + rate.d[2];
  Vec s[6];
  for (int c = 0; c < 6; ++c) s[c] = simd::load(sig + c * W);
  Vec sn[6];
  hex_kernel::jaumann_update(s, rate, lambda * tr, two_mu, dt, sn);
  // The elastic update is the trial state of the J2 return (its plastic work per lane, Pa).
  [[maybe_unused]] Vec dissipation = simd::splat(0.0);
  // The enhanced resultants of a yielding lane relax with its stress, stay within its flow
  // stress and take no strain along its flow (see hex8r.hpp).
  [[maybe_unused]] PlasticHourglass yielding = elastic_hourglass();
  // No flow without an increment (dt = 0 at the start: an imported state stays as it is).
  if constexpr (PLASTIC) {
    if (dt > 0.0) {
      if constexpr (PATH == HourglassPath::FlanaganBelytschko) {
        dissipation = plastic_return(batch, s, sn, dt);
      } else {
        const Vec trial = deviator_norm2(sn);
        dissipation = plastic_return(batch, s, sn, dt);
        const Vec yield = simd::load(m_points.yield_row(static_cast<std::size_t>(batch) * W));
        yielding = plastic_hourglass(sn, trial, deviator_norm2(sn), yield);
      }
    }
  }
  for (int c = 0; c < 6; ++c) simd::store(sig + c * W, sn[c]);
  const Vec strain_power = 0.5 * hex_kernel::stress_power2(s, sn, rate);

  // Characteristic length L_e = V / A_max, bulk viscosity and the stable increment.
  const hex_kernel::BulkViscosity bulk = hex_kernel::bulk_viscosity(
      ax, vol, tr, density, wave, simd::load(cst + DT_FACTOR * W), b1, b2);
  const Vec sv = bulk.sv;

  // Hourglass resultants Q_α (α = modes 4..7) applied on x_{n+1} and the state they leave.
  const Vec inv_vol = 1.0 / vol;
  V3<Vec> Q[4];
  Vec hg_power;
  {
    const HourglassLanes lanes{simd::load(cst + HG_STIFFNESS * W) * two_mu,
                               simd::load(cst + HG_VISCOSITY * W) * density * wave * bulk.area,
                               simd::load(cst + HG_MU * W), simd::load(cst + HG_LAMBDA * W)};
    constexpr bool FB = PATH != HourglassPath::Enhanced;
    constexpr bool ENHANCED = PATH != HourglassPath::FlanaganBelytschko;
    hourglass_resultants<PLASTIC, FB, ENHANCED>(ax, av, g, L, vol, inv_vol, lanes, dt,
                                                yielding.relax, yielding.limit, yielding.flow, hgq,
                                                Q, hg_power);
  }

  Vec fnx[8], fny[8], fnz[8];
  corner_forces(sn, sv, Q, ax, g, inv_vol, fnx, fny, fnz);

  simd::store(&m_volume[static_cast<std::size_t>(batch) * W], vol);
  // Stress work minus plastic work: ALLSE is the elastic energy of the stress state.
  Vec strain_inc = dt * volm * strain_power;
  Vec plastic_inc = simd::splat(0.0);
  if constexpr (PLASTIC) {
    plastic_inc = volm * dissipation;
    strain_inc -= plastic_inc;
  }
  const Vec visc_inc = hex_kernel::viscous_work(
      &m_viscous_before[static_cast<std::size_t>(batch) * W], sv, dt, volm, tr);
  const Vec hg_inc = dt * hg_power;

  // Scatter (lanes of a batch share no node) and the per-batch sums over real lanes.
  m_batches.scatter(batch, fnx, fny, fnz, c.f[0], c.f[1], c.f[2]);
  bool ok[W];
  for (int l = 0; l < W; ++l) ok[l] = vol[l] > 0.0 && volm[l] > 0.0 && !(fold[l] < 0.0);
  record_batch(batch, {strain_inc, hg_inc, visc_inc, plastic_inc}, bulk.dt_e, ok);
}

// The kinds' force pass (HexBlock::forces_of_part()) runs both forms.
template void Hex8rBlock::batch_forces<false>(Index, const NodalColumns&, Real, Real, Real);
template void Hex8rBlock::batch_forces<true>(Index, const NodalColumns&, Real, Real, Real);

void Hex8rBlock::gather_hourglass_state(std::vector<Real>& rows) const {
  gather_lane_rows(m_hourglass, 12, W, m_batches.element_indices(), m_batches.slots(), rows);
}

void Hex8rBlock::set_hourglass_state(std::span<const Real> rows) {
  set_lane_rows(rows, 12, W, m_batches.element_indices(), m_batches.slots(),
                m_batches.lane_owners(), m_hourglass);
}

}  // namespace xpl::elements
