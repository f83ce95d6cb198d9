#include "elements/hex/hex8.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "elements/hex/hex8_geometry.hpp"
#include "elements/hex/hex8_point.hpp"
#include "elements/hex/hex_kernel.hpp"

namespace xpl::elements {

using simd::Vec;

Hex8Block::Hex8Block(std::vector<Index> element_index, const std::vector<Index>& connectivity,
                     const std::vector<HexMaterial>& materials, Index node_count,
                     const BatchLayout* layout)
    : HexBlock(std::move(element_index), connectivity, materials, node_count, N_CONST, layout) {
  const auto nb = static_cast<std::size_t>(m_batches.batch_count());
  m_stress.assign(nb * HEX8_POINTS * 6 * W, 0.0);
  m_point_volume.assign(nb * HEX8_POINTS * W, 0.0);
  m_volume.assign(nb * W, 0.0);
  m_viscous_before.assign(nb * W, 0.0);
  m_batch_energy.assign(nb * 3, 0.0);
  setup_plasticity(materials);
}

void Hex8Block::internal_forces(const NodalVectors& position, const NodalVectors& velocity_half,
                                Real dt, Real bulk_linear, Real bulk_quadratic, NodalVectors& force,
                                HexStepTotals& totals) {
  m_batches.own_pass(force, [&](int p) {
    forces_of_part(p, position, velocity_half, dt, bulk_linear, bulk_quadratic, force);
  });
  add_totals(totals);
}

void Hex8Block::forces_of_part(int part, const NodalVectors& position,
                               const NodalVectors& velocity_half, Real dt, Real bulk_linear,
                               Real bulk_quadratic, NodalVectors& force) {
  const Index n_nodes = static_cast<Index>(position.rows());
  const Real* px = position.data();
  const Real* vx = velocity_half.data();
  Real* fx = force.data();
  m_batches.for_part_batches(part, m_batch_plastic, [&](Index b, auto plastic) {
    compute_batch<decltype(plastic)::value>(b, px, px + n_nodes, px + 2 * n_nodes, vx, vx + n_nodes,
                                            vx + 2 * n_nodes, dt, bulk_linear, bulk_quadratic, fx,
                                            fx + n_nodes, fx + 2 * n_nodes);
  });
}

void Hex8Block::add_totals(HexStepTotals& totals) const {
  for (Index b = 0; b < m_batches.batch_count(); ++b) {
    totals.strain_energy_increment += m_batch_energy[b * 3 + 0];
    totals.viscous_energy_increment += m_batch_energy[b * 3 + 1];
    totals.plastic_energy_increment += m_batch_energy[b * 3 + 2];
  }
  m_batches.merge_limits(totals);
}

template <bool PLASTIC>
void Hex8Block::compute_batch(Index batch, const Real* px, const Real* py, const Real* pz,
                              const Real* vx, const Real* vy, const Real* vz, Real dt, Real b1,
                              Real b2, Real* fx, Real* fy, Real* fz) {
  const Index* conn = m_batches.conn(batch);
  const Real* cst = m_batches.constants(batch);
  V3<Vec> ax[8], av[8];
  gather_modes(conn, px, py, pz, vx, vy, vz, ax, av);

  // Element geometry at x_{n+1} (forces, volume, stable increment) and x_{n+1/2} (rates).
  V3<Vec> am[8], g[8], gm[8];
  Vec vol, volm;
  volume_gradient(ax, g, vol);
  const Real half_dt = 0.5 * dt;
  for (int k = 0; k < 8; ++k) am[k] = ax[k] - half_dt * av[k];
  volume_gradient(am, gm, volm);
  // Mean dilatation rate (1/V) dV/dt on the mid geometry, the volumetric rate of every point.
  Vec tr = simd::splat(0.0);
  for (int k = 1; k < 7; ++k) tr += dot(av[k], gm[k]);
  tr /= volm;

  const Vec lambda = simd::load(cst + LAMBDA * W);
  const Vec two_mu = simd::load(cst + TWO_MU * W);
  const Vec density = simd::load(cst + DENSITY * W);
  const Vec wave = simd::load(cst + WAVE_SPEED * W);
  const Vec lt = lambda * tr;

  Real* sig = &m_stress[static_cast<std::size_t>(batch) * HEX8_POINTS * 6 * W];
  Real* pvol = &m_point_volume[static_cast<std::size_t>(batch) * HEX8_POINTS * W];
  V3<Vec> F[8];
  for (int k = 0; k < 8; ++k) F[k] = {simd::splat(0.0), simd::splat(0.0), simd::splat(0.0)};
  Vec pressure_volume = simd::splat(0.0);  // Σ_q det J_q tr(σ_q)/3
  Vec strain_power = simd::splat(0.0);     // Σ_q det J^m_q σ̄_q : D̄_q
  [[maybe_unused]] Vec dissipation = simd::splat(0.0);
  Vec min_det = simd::splat(std::numeric_limits<Real>::infinity());
  for (int q = 0; q < HEX8_POINTS; ++q) {
    const GaussPoint p = gauss_point(q);
    // Velocity gradient on the mid geometry: L = (1/det J) Σ_a ∂v/∂ξ_a ⊗ n_a.
    const PointFrame<Vec> mid = point_frame(am, p);
    V3<Vec> dv[3];
    jacobian_columns(av, p, dv);
    const Vec inv_det = 1.0 / mid.det;
    Vec L[3][3];
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) L[i][j] = simd::splat(0.0);
    for (int a = 0; a < 3; ++a) {
      const Vec vi[3] = {dv[a].x, dv[a].y, dv[a].z};
      const Vec nj[3] = {mid.n[a].x, mid.n[a].y, mid.n[a].z};
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) L[i][j] += vi[i] * nj[j];
    }
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) L[i][j] *= inv_det;
    // B-bar: the point's own dilatation replaced by the element's mean dilatation.
    const Vec shift = (1.0 / 3.0) * (tr - (L[0][0] + L[1][1] + L[2][2]));
    const hex_kernel::Rates rate = hex_kernel::rates(L, shift);
    Real* sq = sig + q * 6 * W;
    Vec s[6];
    for (int c = 0; c < 6; ++c) s[c] = simd::load(sq + c * W);
    // Jaumann-rate update σ̇ = λ tr(D̄) I + 2μ D̄ + Wσ − σW (as Hex8rBlock).
    Vec sn[6];
    hex_kernel::jaumann_update(s, rate, lt, two_mu, dt, sn);
    if constexpr (PLASTIC)
      if (dt > 0.0) dissipation += mid.det * plastic_return(batch, q, s, sn, dt);
    for (int c = 0; c < 6; ++c) simd::store(sq + c * W, sn[c]);
    strain_power += mid.det * 0.5 * hex_kernel::stress_power2(s, sn, rate);

    // Forces on x_{n+1}: the deviator through the cofactor columns, the pressure below.
    const PointFrame<Vec> end = point_frame(ax, p);
    simd::store(pvol + q * W, end.det);
    min_det = simd::min(min_det, simd::min(end.det, mid.det));
    const Vec pq = (1.0 / 3.0) * (sn[0] + sn[1] + sn[2]);
    pressure_volume += end.det * pq;
    const Vec dev[6] = {sn[0] - pq, sn[1] - pq, sn[2] - pq, sn[3], sn[4], sn[5]};
    add_deviatoric_forces(dev, end, p, F);
  }

  // Characteristic length, bulk viscosity and stable increment as Hex8rBlock.
  const hex_kernel::BulkViscosity bulk = hex_kernel::bulk_viscosity(
      ax, vol, tr, density, wave, simd::load(cst + DT_FACTOR * W), b1, b2);
  const Vec sv = bulk.sv;

  // Volumetric forces: the mean stress (and bulk viscosity) through the exact volume gradient.
  const Vec mean = pressure_volume / vol + sv;
  for (int k = 1; k < 7; ++k) F[k] = F[k] + mean * g[k];
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
  simd::store(&m_volume[static_cast<std::size_t>(batch) * W], vol);

  Vec strain_inc = dt * strain_power;
  [[maybe_unused]] Vec plastic_inc = simd::splat(0.0);
  if constexpr (PLASTIC) {
    plastic_inc = dissipation;
    strain_inc -= plastic_inc;
  }
  const Vec visc_inc = hex_kernel::viscous_work(
      &m_viscous_before[static_cast<std::size_t>(batch) * W], sv, dt, volm, tr);

  m_batches.scatter(batch, fnx, fny, fnz, fx, fy, fz);
  Real e_strain = 0.0, e_visc = 0.0, e_plastic = 0.0;
  bool ok[W];
  for (int l = 0; l < W; ++l) {
    // A fully integrated element also fails where a Gauss point's Jacobian turns over.
    ok[l] = vol[l] > 0.0 && volm[l] > 0.0 && min_det[l] > 0.0;
    if (m_batches.lane_owner(batch, l) == NO_INDEX) continue;
    e_strain += strain_inc[l];
    e_visc += visc_inc[l];
    if constexpr (PLASTIC) e_plastic += plastic_inc[l];
  }
  m_batch_energy[batch * 3 + 0] = e_strain;
  m_batch_energy[batch * 3 + 1] = e_visc;
  m_batch_energy[batch * 3 + 2] = e_plastic;
  m_batches.record_limit(batch, bulk.dt_e, ok);
}

void Hex8Block::gather_output(std::vector<Real>& stress, std::vector<Real>& volume) const {
  for (Index i = 0; i < size(); ++i) {
    const Index e = m_batches.element_index(i);
    if (!stress.empty()) {
      const std::array<Real, 6> s = this->stress(i);
      for (int c = 0; c < 6; ++c) stress[e * 6 + c] = s[c];
    }
    const Index b = m_batches.slot(i) / W, l = m_batches.slot(i) % W;
    if (!volume.empty()) volume[e] = m_volume[b * W + l];
  }
}

void Hex8Block::set_stress(std::span<const Real> stress) {
  m_batches.check_model_rows(stress.size(), 6, "Hex8Block::set_stress");
  for (Index b = 0; b < m_batches.batch_count(); ++b)
    for (int l = 0; l < W; ++l) {
      // Padding lanes take lane 0's stress, whose copy they compute.
      const auto e =
          static_cast<std::size_t>(m_batches.element_index(m_batches.lane_element(b, l)));
      for (int q = 0; q < HEX8_POINTS; ++q)
        for (int c = 0; c < 6; ++c)
          m_stress[((static_cast<std::size_t>(b) * HEX8_POINTS + q) * 6 + c) * W + l] =
              stress[e * 6 + c];
    }
}

std::array<Real, 6> Hex8Block::point_stress(Index i, int q) const {
  const Index b = m_batches.slot(i) / W, l = m_batches.slot(i) % W;
  std::array<Real, 6> s{};
  for (int c = 0; c < 6; ++c)
    s[c] = m_stress[((static_cast<std::size_t>(b) * HEX8_POINTS + q) * 6 + c) * W + l];
  return s;
}

std::array<Real, 6> Hex8Block::stress(Index i) const {
  const Index b = m_batches.slot(i) / W, l = m_batches.slot(i) % W;
  std::array<Real, 6> s{};
  Real weight = 0.0;
  for (int q = 0; q < HEX8_POINTS; ++q) {
    // Before the first force pass the point volumes are 0: a plain mean then.
    const Real w = m_point_volume[(static_cast<std::size_t>(b) * HEX8_POINTS + q) * W + l];
    weight += w;
  }
  for (int q = 0; q < HEX8_POINTS; ++q) {
    const Real w =
        weight > 0.0
            ? m_point_volume[(static_cast<std::size_t>(b) * HEX8_POINTS + q) * W + l] / weight
            : 1.0 / HEX8_POINTS;
    const std::array<Real, 6> sq = point_stress(i, q);
    for (int c = 0; c < 6; ++c) s[c] += w * sq[c];
  }
  return s;
}

}  // namespace xpl::elements
