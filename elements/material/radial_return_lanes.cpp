#include "elements/material/radial_return_lanes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace xpl::elements {

using simd::Vec;

namespace {

constexpr Real INF = std::numeric_limits<Real>::infinity();

}  // namespace

RadialReturnLanes::RadialReturnLanes(std::size_t slots)
    : m_peeq(slots, 0.0),
      m_yield(slots, INF),
      m_seg_strain(slots, 0.0),
      m_seg_stress(slots, 0.0),
      m_seg_slope(slots, 0.0),
      m_seg_end(slots, -INF) {}

void RadialReturnLanes::reset(std::size_t slot, const Plasticity& law, Real peeq) {
  m_peeq[slot] = peeq;
  m_yield[slot] = flow_stress(law, peeq, 0.0).stress;
  m_seg_end[slot] = -INF;
  if (law.hardening != Hardening::Tabular || law.rate != RateDependence::None) return;
  const std::vector<Real>& eps = law.plastic_strain;
  const std::vector<Real>& sig = law.yield_stress;
  const std::size_t n = sig.size();
  if (n == 1 || peeq >= eps[n - 1]) {  // constant after the table
    m_seg_strain[slot] = eps[n - 1];
    m_seg_stress[slot] = sig[n - 1];
    m_seg_slope[slot] = 0.0;
    m_seg_end[slot] = INF;
    return;
  }
  // The segment flow_stress uses: the last point at or below ε̄ᵖ (the first below 0).
  const auto upper = std::upper_bound(eps.begin(), eps.end(), peeq);
  const std::size_t i =
      upper == eps.begin() ? 0 : static_cast<std::size_t>(upper - eps.begin()) - 1;
  const Real slope = (sig[i + 1] - sig[i]) / (eps[i + 1] - eps[i]);
  if (!(slope >= 0.0) || peeq < eps[0]) return;  // softening: the scalar return's safeguards
  m_seg_strain[slot] = eps[i];
  m_seg_stress[slot] = sig[i];
  m_seg_slope[slot] = slope;
  m_seg_end[slot] = eps[i + 1];
}

Vec RadialReturnLanes::return_row(std::size_t row, const int* lane_law,
                                  const std::vector<Plasticity>& laws, const Vec start[6],
                                  Vec sn[6], Vec two_mu, Real dt, Real* rate) {
  const Vec p = (sn[0] + sn[1] + sn[2]) * (1.0 / 3.0);
  const Vec dev[6] = {sn[0] - p, sn[1] - p, sn[2] - p, sn[3], sn[4], sn[5]};
  const Vec q2 = 1.5 * (dev[0] * dev[0] + dev[1] * dev[1] + dev[2] * dev[2]) +
                 3.0 * (dev[3] * dev[3] + dev[4] * dev[4] + dev[5] * dev[5]);
  const Vec y = simd::load(&m_yield[row]);
  const simd::Mask yielding = q2 > y * y;
  const Vec zero = simd::splat(0.0);
  if (!simd::any(yielding)) {  // the common case: one test for the whole batch
    if (rate != nullptr) simd::store(rate, zero);
    return zero;
  }

  Vec trial[6];
  for (int c = 0; c < 6; ++c) trial[c] = sn[c];

  // Every lane computes the segment solution; masks keep it where it is valid. Elastic lanes
  // (σ_y = +inf) produce infinities and NaNs that the masks drop.
  const Vec q = simd::sqrt(q2);
  const Vec three_g = 1.5 * two_mu;
  const Vec slope = simd::load(&m_seg_slope[row]);
  const Vec peeq0 = simd::load(&m_peeq[row]);
  const Vec delta = (q - y) / (three_g + slope);
  const Vec peeq1 = peeq0 + delta;
  // Δε̄ᵖ > 0 also leaves alone a q on the surface to round-off (the test squared it).
  const simd::Mask fast = yielding & (delta > 0.0) & (peeq1 < simd::load(&m_seg_end[row]));
  const Vec y1 = simd::load(&m_seg_stress[row]) + slope * (peeq1 - simd::load(&m_seg_strain[row]));
  const Vec scale = y1 / q;
  for (int c = 0; c < 3; ++c) sn[c] = simd::select(fast, p + scale * dev[c], sn[c]);
  for (int c = 3; c < 6; ++c) sn[c] = simd::select(fast, scale * dev[c], sn[c]);
  simd::store(&m_peeq[row], simd::select(fast, peeq1, peeq0));
  simd::store(&m_yield[row], simd::select(fast, y1, y));
  if (rate != nullptr) simd::store(rate, simd::select(fast, delta / dt, zero));

  // Yielding lanes the segment solution does not cover: the scalar return.
  const simd::Mask slow = yielding & ~fast;
  for (int l = 0; l < W; ++l) {
    if (!slow[l]) continue;
    const Plasticity& law = laws[static_cast<std::size_t>(lane_law[l])];
    const std::size_t slot = row + static_cast<std::size_t>(l);
    const PlasticIncrement r = radial_return(law, q[l], three_g[l], m_peeq[slot], dt);
    if (!(r.peeq_increment > 0.0)) continue;
    const Real s = r.yield_stress / q[l];
    for (int c = 0; c < 3; ++c) sn[c][l] = p[l] + s * dev[c][l];
    for (int c = 3; c < 6; ++c) sn[c][l] = s * dev[c][l];
    reset(slot, law, m_peeq[slot] + r.peeq_increment);
    if (rate != nullptr) rate[l] = r.peeq_increment / dt;
  }
  return return_work(start, trial, sn, two_mu);
}

}  // namespace xpl::elements
