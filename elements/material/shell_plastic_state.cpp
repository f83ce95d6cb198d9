/// \file ShellPlasticState: the section points' plastic state of a shell block (its laws, one
/// copy each, and the per-point arrays) and its accessors; the return is in shell_plasticity.cpp.

#include <algorithm>
#include <cmath>
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
  m_batch_yielded.assign(n_batches, 0);
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
    m_batch_yielded.clear();
    return;
  }
  m_segment_slope.assign(1, 0.0);
  m_segment_end.assign(1, std::numeric_limits<Real>::infinity());
  for (const Plasticity& law : m_laws) {
    if (law.hardening != Hardening::Tabular) {
      m_law_segment.push_back(0);
      continue;
    }
    m_law_segment.push_back(static_cast<Index>(m_segment_slope.size()));
    const std::vector<Real>& eps = law.plastic_strain;
    const std::vector<Real>& sig = law.yield_stress;
    for (std::size_t i = 0; i + 1 < sig.size(); ++i) {
      m_segment_slope.push_back((sig[i + 1] - sig[i]) / (eps[i + 1] - eps[i]));
      m_segment_end.push_back(eps[i + 1]);
    }
    m_segment_slope.push_back(0.0);
    m_segment_end.push_back(std::numeric_limits<Real>::infinity());
  }
  m_lane_linear.assign(lane_law.size(), 0);
  const std::size_t n = n_batches * static_cast<std::size_t>(points) * W;
  m_peeq.assign(n, 0.0);
  // Batches perfectly plastic at one yield stress in every lane (padding lanes carry lane 0's
  // law) need no yield stress or segment rows; the arrays exist when another batch needs them.
  m_constant_yield.assign(n_batches, std::numeric_limits<Real>::quiet_NaN());
  bool rows = false;
  for (std::size_t b = 0; b < n_batches; ++b) {
    Real constant = std::numeric_limits<Real>::quiet_NaN();
    for (std::size_t l = 0; l < W; ++l) {
      const int law = m_lane_law[b * W + l];
      const Plasticity* p = law < 0 ? nullptr : &m_laws[static_cast<std::size_t>(law)];
      const bool perfect = p != nullptr && p->hardening == Hardening::Tabular &&
                           p->rate == RateDependence::None && p->yield_stress.size() == 1;
      if (!perfect || (l > 0 && !(p->yield_stress[0] == constant))) {
        constant = std::numeric_limits<Real>::quiet_NaN();
        break;
      }
      constant = p->yield_stress[0];
    }
    m_constant_yield[b] = constant;
    rows |= m_batch_plastic[b] != 0 && std::isnan(constant);
  }
  if (rows) {
    m_segment.assign(n, 0);
    m_yield.assign(n, std::numeric_limits<Real>::infinity());
  }
  for (std::size_t b = 0; b < n_batches; ++b)
    for (std::size_t l = 0; l < W; ++l) {
      const int law = m_lane_law[b * W + l];
      if (law < 0) continue;
      const Plasticity& p = m_laws[static_cast<std::size_t>(law)];
      if (p.hardening == Hardening::Tabular && p.rate == RateDependence::None)
        m_lane_linear[b * W + l] = -1;
      if (!rows) continue;
      const Real y = p.initial_yield();
      for (int k = 0; k < points; ++k) {
        m_yield[row(b, k) + l] = y;
        m_segment[row(b, k) + l] = m_law_segment[static_cast<std::size_t>(law)];
      }
    }
}

Real ShellPlasticState::peeq(std::size_t b, int k, std::size_t l) const {
  return empty() ? 0.0 : m_peeq[row(b, k) + l];
}

}  // namespace xpl::elements
