/// \file Shell4rBlock: output and import of the section points' plastic strain.

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "elements/shell/shell4r.hpp"

namespace xpl::elements {

void Shell4rBlock::gather_plastic_strain(std::vector<Real>& peeq) const {
  for (Index i = 0; i < size(); ++i) {
    const std::size_t s = slot_of(i), b = s / W, l = s % W;
    Real largest = 0.0;
    for (int k = 0; k < points_of(b, l); ++k) largest = std::max(largest, m_plastic.peeq(b, k, l));
    peeq[static_cast<std::size_t>(m_element_index[i])] = largest;
  }
}

void Shell4rBlock::gather_section_plastic_strain(std::vector<Real>& bottom,
                                                 std::vector<Real>& middle,
                                                 std::vector<Real>& top) const {
  for (Index i = 0; i < size(); ++i) {
    const std::size_t s = slot_of(i), b = s / W, l = s % W;
    const int points = points_of(b, l);
    const auto e = static_cast<std::size_t>(m_element_index[i]);
    bottom[e] = m_plastic.peeq(b, 0, l);
    middle[e] = m_plastic.peeq(b, (points - 1) / 2, l);
    top[e] = m_plastic.peeq(b, points - 1, l);
  }
}

void Shell4rBlock::set_plastic_strain(std::span<const Real> middle, std::span<const Real> bottom,
                                      std::span<const Real> top) {
  if (!has_plasticity()) return;
  for (Index e : m_element_index) {
    const auto end = static_cast<std::size_t>(e) + 1;
    if (end > middle.size() || end > bottom.size() || end > top.size()) {
      throw std::invalid_argument(
          "Shell4rBlock::set_plastic_strain: the PEEQ arrays do not reach element " +
          std::to_string(e) + "; expected n_elements values each");
    }
  }
  for (Index i = 0; i < size(); ++i) {
    const std::size_t s = slot_of(i), b = s / W, l = s % W;
    const auto e = static_cast<std::size_t>(m_element_index[i]);
    const int points = points_of(b, l);
    const Real mid = middle[e];
    const Real low = points > 1 ? bottom[e] : mid, high = points > 1 ? top[e] : mid;
    for (int k = 0; k < points; ++k) {
      const Real zeta = m_zeta[(b * m_points + k) * W + l];
      const Real f = std::abs(zeta);
      m_plastic.set_peeq(b, k, l, std::max(0.0, (1.0 - f) * mid + f * (zeta < 0.0 ? low : high)));
    }
  }
  // Padding lanes compute a copy of lane 0 of their batch: give them its state as well.
  const auto n_batches = static_cast<std::size_t>(m_color_batches.back());
  for (std::size_t b = 0; b < n_batches; ++b)
    for (std::size_t l = 1; l < W; ++l) {
      if (m_lane_owner[b * W + l] != NO_INDEX) continue;
      for (int k = 0; k < m_points; ++k) m_plastic.set_peeq(b, k, l, m_plastic.peeq(b, k, 0));
    }
}

Real Shell4rBlock::plastic_strain(Index i, int k) const {
  const std::size_t s = slot_of(i);
  return m_plastic.peeq(s / W, k, s % W);
}

}  // namespace xpl::elements
