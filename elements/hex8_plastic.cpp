/// \file The J2 part of the C3D8 block: its plastic laws and state (per integration point),
/// the return of the yielding lanes of one point of a batch, and the PEEQ output and import.

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "elements/hex8.hpp"

namespace xpl::elements {

using simd::Vec;

void Hex8Block::setup_plasticity(const std::vector<HexMaterial>& materials) {
  HexBatches::PlasticLanes lanes = m_batches.plastic_lanes(materials);
  if (lanes.laws.empty()) return;  // P2: an elastic block holds no plastic state
  m_laws = std::move(lanes.laws);
  m_lane_law = std::move(lanes.lane_law);
  m_batch_plastic = std::move(lanes.batch_plastic);
  const std::size_t n = m_lane_law.size();
  m_peeq.assign(n * HEX8_POINTS, 0.0);
  m_yield.assign(n * HEX8_POINTS, std::numeric_limits<Real>::infinity());
  for (std::size_t k = 0; k < n; ++k) {
    if (m_lane_law[k] < 0) continue;
    const Real y0 = flow_stress(m_laws[static_cast<std::size_t>(m_lane_law[k])], 0.0, 0.0).stress;
    const std::size_t b = k / W, l = k % W;
    for (int q = 0; q < HEX8_POINTS; ++q) m_yield[(b * HEX8_POINTS + q) * W + l] = y0;
  }
}

Vec Hex8Block::plastic_return(Index batch, int q, Vec sn[6], Real dt) {
  const std::size_t base = (static_cast<std::size_t>(batch) * HEX8_POINTS + q) * W;
  const Vec p = (sn[0] + sn[1] + sn[2]) * (1.0 / 3.0);
  const Vec dev[6] = {sn[0] - p, sn[1] - p, sn[2] - p, sn[3], sn[4], sn[5]};
  const Vec q2 = 1.5 * (dev[0] * dev[0] + dev[1] * dev[1] + dev[2] * dev[2]) +
                 3.0 * (dev[3] * dev[3] + dev[4] * dev[4] + dev[5] * dev[5]);
  const Vec y = simd::load(&m_yield[base]);
  const simd::Mask yielding = q2 > y * y;
  Vec dissipation = simd::splat(0.0);
  if (!simd::any(yielding)) return dissipation;
  const Real* two_mu = m_batches.constants(batch) + TWO_MU * W;
  const std::size_t lane0 = static_cast<std::size_t>(batch) * W;
  for (int l = 0; l < W; ++l) {
    if (!yielding[l]) continue;
    const Plasticity& law = m_laws[static_cast<std::size_t>(m_lane_law[lane0 + l])];
    const Real qt = std::sqrt(q2[l]);
    const PlasticIncrement r = radial_return(law, qt, 1.5 * two_mu[l], m_peeq[base + l], dt);
    if (!(r.peeq_increment > 0.0)) continue;
    // Radial return of the deviator; the pressure (the element's, shared by all points) stays.
    const Real scale = r.yield_stress / qt;
    for (int c = 0; c < 3; ++c) sn[c][l] = p[l] + scale * dev[c][l];
    for (int c = 3; c < 6; ++c) sn[c][l] = scale * dev[c][l];
    m_peeq[base + l] += r.peeq_increment;
    m_yield[base + l] = flow_stress(law, m_peeq[base + l], 0.0).stress;
    dissipation[l] = r.yield_stress * r.peeq_increment;
  }
  return dissipation;
}

void Hex8Block::gather_plastic_strain(std::vector<Real>& peeq) const {
  if (m_laws.empty()) return;
  for (Index i = 0; i < size(); ++i) peeq[m_batches.element_index(i)] = plastic_strain(i);
}

void Hex8Block::set_plastic_strain(std::span<const Real> peeq) {
  if (m_laws.empty()) return;
  m_batches.for_imported_peeq(
      peeq, m_lane_law, "Hex8Block::set_plastic_strain", [&](Index b, int l, int law, Real value) {
        const Real y = flow_stress(m_laws[static_cast<std::size_t>(law)], value, 0.0).stress;
        for (int q = 0; q < HEX8_POINTS; ++q) {
          const std::size_t k = (static_cast<std::size_t>(b) * HEX8_POINTS + q) * W + l;
          m_peeq[k] = value;
          m_yield[k] = y;
        }
      });
}

Real Hex8Block::plastic_strain(Index i) const {
  if (m_laws.empty()) return 0.0;
  const auto s = static_cast<std::size_t>(m_batches.slot(i));
  if (m_lane_law[s] < 0) return 0.0;
  const std::size_t b = s / W, l = s % W;
  Real weight = 0.0, sum = 0.0;
  for (int q = 0; q < HEX8_POINTS; ++q) {
    const std::size_t k = (b * HEX8_POINTS + q) * W + l;
    weight += m_point_volume[k];
    sum += m_point_volume[k] * m_peeq[k];
  }
  if (weight > 0.0) return sum / weight;
  Real mean = 0.0;
  for (int q = 0; q < HEX8_POINTS; ++q) mean += m_peeq[(b * HEX8_POINTS + q) * W + l];
  return mean / HEX8_POINTS;
}

}  // namespace xpl::elements
