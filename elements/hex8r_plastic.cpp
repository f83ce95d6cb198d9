/// \file The J2 part of the C3D8R block: its plastic laws and state, the return of a batch's
/// yielding lanes, and the PEEQ output and import.

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "elements/hex8r.hpp"

namespace xpl::elements {

using simd::Vec;

void Hex8rBlock::setup_plasticity(const std::vector<HexMaterial>& materials) {
  HexBatches::PlasticLanes lanes = m_batches.plastic_lanes(materials);
  if (lanes.laws.empty()) return;  // P2: an elastic block holds no plastic state
  m_laws = std::move(lanes.laws);
  m_lane_law = std::move(lanes.lane_law);
  m_batch_plastic = std::move(lanes.batch_plastic);
  const std::size_t n = m_lane_law.size();
  m_peeq.assign(n, 0.0);
  m_peeq_rate.assign(n, 0.0);
  m_yield.assign(n, std::numeric_limits<Real>::infinity());
  for (std::size_t k = 0; k < n; ++k)
    if (m_lane_law[k] >= 0)
      m_yield[k] = flow_stress(m_laws[static_cast<std::size_t>(m_lane_law[k])], 0.0, 0.0).stress;
}

Vec Hex8rBlock::plastic_return(Index batch, Vec sn[6], Real dt) {
  const std::size_t base = static_cast<std::size_t>(batch) * W;
  const Vec p = (sn[0] + sn[1] + sn[2]) * (1.0 / 3.0);
  const Vec dev[6] = {sn[0] - p, sn[1] - p, sn[2] - p, sn[3], sn[4], sn[5]};
  const Vec q2 = 1.5 * (dev[0] * dev[0] + dev[1] * dev[1] + dev[2] * dev[2]) +
                 3.0 * (dev[3] * dev[3] + dev[4] * dev[4] + dev[5] * dev[5]);
  const Vec y = simd::load(&m_yield[base]);
  const simd::Mask yielding = q2 > y * y;
  Vec dissipation = simd::splat(0.0);
  Real* rate = &m_peeq_rate[base];
  if (!simd::any(yielding)) {  // the common case: one test for the whole batch
    simd::store(rate, dissipation);
    return dissipation;
  }
  const Real* two_mu = m_batches.constants(batch) + TWO_MU * W;
  for (int l = 0; l < W; ++l) {
    rate[l] = 0.0;
    if (!yielding[l]) continue;
    const Plasticity& law = m_laws[static_cast<std::size_t>(m_lane_law[base + l])];
    const Real q = std::sqrt(q2[l]);
    const PlasticIncrement r = radial_return(law, q, 1.5 * two_mu[l], m_peeq[base + l], dt);
    // Δε̄ᵖ = 0: q lies on the surface to round-off (the SIMD test squared it); leave it.
    if (!(r.peeq_increment > 0.0)) continue;
    // Radial return: the deviator scaled onto the surface, the pressure unchanged.
    const Real scale = r.yield_stress / q;
    for (int c = 0; c < 3; ++c) sn[c][l] = p[l] + scale * dev[c][l];
    for (int c = 3; c < 6; ++c) sn[c][l] = scale * dev[c][l];
    m_peeq[base + l] += r.peeq_increment;
    rate[l] = dt > 0.0 ? r.peeq_increment / dt : 0.0;
    m_yield[base + l] = flow_stress(law, m_peeq[base + l], 0.0).stress;
    dissipation[l] = r.yield_stress * r.peeq_increment;
  }
  return dissipation;
}

void Hex8rBlock::gather_plastic_strain(std::vector<Real>& peeq) const {
  if (m_laws.empty()) return;  // the caller's array holds zeros for elastic elements
  for (Index i = 0; i < size(); ++i) peeq[m_batches.element_index(i)] = plastic_strain(i);
}

void Hex8rBlock::set_plastic_strain(std::span<const Real> peeq) {
  if (m_laws.empty()) return;
  m_batches.for_imported_peeq(
      peeq, m_lane_law, "Hex8rBlock::set_plastic_strain", [&](Index b, int l, int law, Real value) {
        const std::size_t slot = static_cast<std::size_t>(b) * W + l;
        m_peeq[slot] = value;
        m_peeq_rate[slot] = 0.0;
        m_yield[slot] = flow_stress(m_laws[static_cast<std::size_t>(law)], value, 0.0).stress;
      });
}

Real Hex8rBlock::plastic_strain(Index i) const {
  if (m_laws.empty()) return 0.0;
  const auto slot = static_cast<std::size_t>(m_batches.slot(i));
  return m_lane_law[slot] < 0 ? 0.0 : m_peeq[slot];
}

Real Hex8rBlock::plastic_strain_rate(Index i) const {
  if (m_laws.empty()) return 0.0;
  const auto slot = static_cast<std::size_t>(m_batches.slot(i));
  return m_lane_law[slot] < 0 ? 0.0 : m_peeq_rate[slot];
}

}  // namespace xpl::elements
