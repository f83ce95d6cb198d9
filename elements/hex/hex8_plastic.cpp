/// \file The J2 part of the C3D8 block (its laws and state per integration point are
/// HexBlock's): the return of the yielding lanes of one point of a batch, and the element's
/// volume-averaged PEEQ.

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "elements/hex/hex8.hpp"

namespace xpl::elements {

using simd::Vec;

Vec Hex8Block::plastic_return(Index batch, int q, const Vec start[6], Vec sn[6], Real dt) {
  // The pressure (the element's, shared by all points) is left as it is by the return.
  const std::size_t base = (static_cast<std::size_t>(batch) * HEX8_POINTS + q) * W;
  const Vec two_mu = simd::load(m_batches.constants(batch) + TWO_MU * W);
  return m_points.return_row(base, &m_lane_law[static_cast<std::size_t>(batch) * W], m_laws, start,
                             sn, two_mu, dt, nullptr);
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
