/// \file The J2 part of the C3D8R block: its plastic laws and state, the return of a batch's
/// yielding lanes, and the PEEQ output and import.

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "elements/hex/hex8r.hpp"

namespace xpl::elements {

using simd::Vec;

void Hex8rBlock::setup_plasticity(const std::vector<HexMaterial>& materials) {
  HexBatches::PlasticLanes lanes = m_batches.plastic_lanes(materials);
  if (lanes.laws.empty()) return;  // P2: an elastic block holds no plastic state
  m_laws = std::move(lanes.laws);
  m_lane_law = std::move(lanes.lane_law);
  m_batch_plastic = std::move(lanes.batch_plastic);
  const std::size_t n = m_lane_law.size();
  m_points = RadialReturnLanes(n);
  m_peeq_rate.assign(n, 0.0);
  for (std::size_t k = 0; k < n; ++k)
    if (m_lane_law[k] >= 0) m_points.reset(k, m_laws[static_cast<std::size_t>(m_lane_law[k])], 0.0);
}

Vec Hex8rBlock::plastic_return(Index batch, const Vec start[6], Vec sn[6], Real dt) {
  const std::size_t base = static_cast<std::size_t>(batch) * W;
  const Vec two_mu = simd::load(m_batches.constants(batch) + TWO_MU * W);
  return m_points.return_row(base, &m_lane_law[base], m_laws, start, sn, two_mu, dt,
                             &m_peeq_rate[base]);
}

void Hex8rBlock::gather_plastic_strain(std::vector<Real>& peeq) const {
  if (m_laws.empty()) return;  // the caller's array holds zeros for elastic elements
  for (Index i = 0; i < size(); ++i) peeq[m_batches.element_index(i)] = plastic_strain(i);
}

void Hex8rBlock::set_plastic_strain(std::span<const Real> peeq) {
  if (m_laws.empty()) return;
  m_batches.for_imported_peeq(peeq, m_lane_law, "Hex8rBlock::set_plastic_strain",
                              [&](Index b, int l, int law, Real value) {
                                const std::size_t slot = static_cast<std::size_t>(b) * W + l;
                                m_points.reset(slot, m_laws[static_cast<std::size_t>(law)], value);
                                m_peeq_rate[slot] = 0.0;
                              });
}

Real Hex8rBlock::plastic_strain(Index i) const {
  if (m_laws.empty()) return 0.0;
  const auto slot = static_cast<std::size_t>(m_batches.slot(i));
  return m_lane_law[slot] < 0 ? 0.0 : m_points.peeq(slot);
}

Real Hex8rBlock::plastic_strain_rate(Index i) const {
  if (m_laws.empty()) return 0.0;
  const auto slot = static_cast<std::size_t>(m_batches.slot(i));
  return m_lane_law[slot] < 0 ? 0.0 : m_peeq_rate[slot];
}

}  // namespace xpl::elements
