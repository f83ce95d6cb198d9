/// \file ShellPlasticState: the section points' plastic state of a shell block (its laws, one
/// copy each, and the per-point arrays) and its accessors; the return is in shell_plasticity.cpp.

#include <algorithm>
#include <limits>
#include <utility>

#include "elements/material/shell_plasticity.hpp"

namespace xpl::elements {

ShellPlasticState::ShellPlasticState(std::span<const Plasticity* const> lane_law, int points)
    : m_points(points) {
  const std::size_t n_batches = lane_law.size() / W;
  std::vector<const Plasticity*> seen;
  m_lane_law.assign(lane_law.size(), -1);
  m_batch_plastic.assign(n_batches, 0);
  for (std::size_t s = 0; s < lane_law.size(); ++s) {
    const Plasticity* law = lane_law[s];
    if (law == nullptr) continue;
    auto it = std::find(seen.begin(), seen.end(), law);
    if (it == seen.end()) {
      seen.push_back(law);
      m_laws.push_back(*law);
      it = seen.end() - 1;
    }
    m_lane_law[s] = static_cast<int>(it - seen.begin());
    m_batch_plastic[s / W] = 1;
  }
  if (m_laws.empty()) {
    m_lane_law.clear();
    m_batch_plastic.clear();
    return;
  }
  for (const Plasticity& law : m_laws) {
    std::vector<Real> slopes;
    if (law.hardening == Hardening::Tabular)
      for (std::size_t i = 0; i + 1 < law.yield_stress.size(); ++i)
        slopes.push_back((law.yield_stress[i + 1] - law.yield_stress[i]) /
                         (law.plastic_strain[i + 1] - law.plastic_strain[i]));
    m_slopes.push_back(std::move(slopes));
  }
  const std::size_t n = n_batches * static_cast<std::size_t>(points) * W;
  m_segment.assign(n, 0);
  m_peeq.assign(n, 0.0);
  m_rate.assign(n, 0.0);
  m_yield.assign(n, std::numeric_limits<Real>::infinity());
  for (std::size_t b = 0; b < n_batches; ++b)
    for (std::size_t l = 0; l < W; ++l) {
      const int law = m_lane_law[b * W + l];
      if (law < 0) continue;
      const Real y = m_laws[static_cast<std::size_t>(law)].initial_yield();
      for (int k = 0; k < points; ++k) m_yield[row(b, k) + l] = y;
    }
}

Real ShellPlasticState::peeq(std::size_t b, int k, std::size_t l) const {
  return empty() ? 0.0 : m_peeq[row(b, k) + l];
}

Real ShellPlasticState::peeq_rate(std::size_t b, int k, std::size_t l) const {
  return empty() ? 0.0 : m_rate[row(b, k) + l];
}

}  // namespace xpl::elements
