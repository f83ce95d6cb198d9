/// \file The J2 part of the C3D8 block: its plastic laws and state (per integration point),
/// the return of the yielding lanes of one point of a batch, and the PEEQ output and import.

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "elements/hex/hex8.hpp"

namespace xpl::elements {

using simd::Vec;

void Hex8Block::setup_plasticity(const std::vector<HexMaterial>& materials) {
  HexBatches::PlasticLanes lanes = m_batches.plastic_lanes(materials);
  if (lanes.laws.empty()) return;  // P2: an elastic block holds no plastic state
  m_laws = std::move(lanes.laws);
  m_lane_law = std::move(lanes.lane_law);
  m_batch_plastic = std::move(lanes.batch_plastic);
  const std::size_t n = m_lane_law.size();
  m_points = RadialReturnLanes(n * HEX8_POINTS);
  for (std::size_t k = 0; k < n; ++k) {
    if (m_lane_law[k] < 0) continue;
    const std::size_t b = k / W, l = k % W;
    for (int q = 0; q < HEX8_POINTS; ++q)
      m_points.reset((b * HEX8_POINTS + q) * W + l, m_laws[static_cast<std::size_t>(m_lane_law[k])],
                     0.0);
  }
}

Vec Hex8Block::plastic_return(Index batch, int q, const Vec start[6], Vec sn[6], Real dt) {
  // The pressure (the element's, shared by all points) is left as it is by the return.
  const std::size_t base = (static_cast<std::size_t>(batch) * HEX8_POINTS + q) * W;
  const Vec two_mu = simd::load(m_batches.constants(batch) + TWO_MU * W);
  return m_points.return_row(base, &m_lane_law[static_cast<std::size_t>(batch) * W], m_laws, start,
                             sn, two_mu, dt, nullptr);
}

void Hex8Block::gather_plastic_strain(std::vector<Real>& peeq) const {
  if (m_laws.empty()) return;
  for (Index i = 0; i < size(); ++i) peeq[m_batches.element_index(i)] = plastic_strain(i);
}

void Hex8Block::set_plastic_strain(std::span<const Real> peeq) {
  if (m_laws.empty()) return;
  m_batches.for_imported_peeq(
      peeq, m_lane_law, "Hex8Block::set_plastic_strain", [&](Index b, int l, int law, Real value) {
        for (int q = 0; q < HEX8_POINTS; ++q)
          m_points.reset((static_cast<std::size_t>(b) * HEX8_POINTS + q) * W + l,
                         m_laws[static_cast<std::size_t>(law)], value);
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
    sum += m_point_volume[k] * m_points.peeq(k);
  }
  if (weight > 0.0) return sum / weight;
  Real mean = 0.0;
  for (int q = 0; q < HEX8_POINTS; ++q) mean += m_points.peeq((b * HEX8_POINTS + q) * W + l);
  return mean / HEX8_POINTS;
}

}  // namespace xpl::elements
