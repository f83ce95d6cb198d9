/// \file The J2 part of the C3D8R block (its laws and state are HexBlock's): the return of a
/// batch's yielding lanes, PEEQ and its rate.

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "elements/hex/hex8r.hpp"

namespace xpl::elements {

using simd::Vec;

Vec Hex8rBlock::plastic_return(Index batch, const Vec start[6], Vec sn[6], Real dt) {
  const std::size_t base = static_cast<std::size_t>(batch) * W;
  const Vec two_mu = simd::load(m_batches.constants(batch) + TWO_MU * W);
  return m_points.return_row(base, &m_lane_law[base], m_laws, start, sn, two_mu, dt,
                             &m_peeq_rate[base]);
}

void Hex8rBlock::set_plastic_strain(std::span<const Real> peeq) {
  Hex8rBase::set_plastic_strain(peeq);
  // An imported state starts at rest: the rate of every plastic lane (padding ones too) is 0.
  for (std::size_t k = 0; k < m_peeq_rate.size(); ++k)
    if (m_lane_law[k] >= 0) m_peeq_rate[k] = 0.0;
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
