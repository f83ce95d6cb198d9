#include "elements/shell_plasticity.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace xpl::elements {

using simd::Vec;

namespace {

/// A trial this little outside the yield surface (relative, on σ²) counts as inside: the
/// stress of a point returned in the last increment lies on the surface to round-off, and a
/// zero-strain pass (dt = 0) must not send it through the return again.
constexpr Real YIELD_TOLERANCE = 1e-12;

/// Whether any lane of `m` is set.
bool any_lane(simd::Mask m) {
  bool r = false;
  for (int l = 0; l < simd::W; ++l) r |= m[l] != 0;
  return r;
}

}  // namespace

PlaneStressReturn plane_stress_return(const Plasticity& law, Real q11, Real q12, Real shear,
                                      Real sxx, Real syy, Real sxy, Real peeq, Real dt) {
  PlaneStressReturn r;
  r.sxx = sxx;
  r.syy = syy;
  r.sxy = sxy;
  const FlowStress start = flow_stress(law, peeq, 0.0);
  r.yield_stress = r.static_yield = start.stress;
  const Real vm2_trial = sxx * sxx - sxx * syy + syy * syy + 3.0 * sxy * sxy;
  if (vm2_trial <= start.stress * start.stress * (1.0 + YIELD_TOLERANCE)) return r;

  // Eigen-components of the trial: Σ = σxx+σyy (eigenvalue of C: E/(1−ν) = q11+q12, of
  // P: 1/3), D = σxx−σyy and σxy (C: 2G, P: 1 and 2 with engineering shear). Along the
  // return Σ scales by f1 = 1/(1 + aΔγ), D and σxy by f2 = 1/(1 + cΔγ), and
  // ‖σ‖²_vM = ¼Σ² f1² + (¾D² + 3σxy²) f2².
  const Real sum = sxx + syy, diff = sxx - syy;
  const Real a = (q11 + q12) / 3.0, c = 2.0 * shear;
  const Real p1_trial = 0.25 * sum * sum, p2_trial = 0.75 * diff * diff + 3.0 * sxy * sxy;
  const bool rate = law.rate != RateDependence::None && dt > 0.0;
  const Real inv_dt = rate ? 1.0 / dt : 0.0;

  // g(Δγ) = ‖σ(Δγ)‖_vM − σ_y(ε̄ᵖ_n + Δε̄ᵖ, Δε̄ᵖ/dt), Δε̄ᵖ = ⅔Δγ‖σ‖_vM: positive at 0 and
  // −σ_y < 0 as Δγ → ∞ (the stress vanishes, Δε̄ᵖ stays bounded). ‖σ(Δγ)‖_vM is convex
  // and decreasing, so Newton from 0 approaches the root from below; a step that leaves the
  // bracket (softening) bisects, or doubles while no upper bound is known.
  Real lo = 0.0, hi = std::numeric_limits<Real>::infinity(), dg = 0.0;
  Real f1 = 1.0, f2 = 1.0, vm = std::sqrt(vm2_trial), dpeeq = 0.0;
  FlowStress flow = start;
  for (int iteration = 0; iteration < 200; ++iteration) {
    f1 = 1.0 / (1.0 + a * dg);
    f2 = 1.0 / (1.0 + c * dg);
    const Real p1 = p1_trial * f1 * f1, p2 = p2_trial * f2 * f2;
    vm = std::sqrt(p1 + p2);
    const Real dvm = -(a * p1 * f1 + c * p2 * f2) / vm;
    dpeeq = (2.0 / 3.0) * dg * vm;
    flow = flow_stress(law, peeq + dpeeq, dpeeq * inv_dt);
    const Real g = vm - flow.stress;
    if (std::abs(g) <= 1e-13 * flow.stress) break;
    if (g > 0.0)
      lo = dg;
    else
      hi = dg;
    if (std::isfinite(hi) && hi - lo <= 1e-15 * hi) break;
    const Real slope = dvm - (flow.d_strain + flow.d_rate * inv_dt) * (2.0 / 3.0) * (vm + dg * dvm);
    Real next = slope < 0.0 ? dg - g / slope : -1.0;
    if (!(next > lo && next < hi))
      next = std::isfinite(hi) ? 0.5 * (lo + hi) : (lo > 0.0 ? 2.0 * lo : 1.0 / c);
    dg = next;
  }
  r.sxx = 0.5 * (sum * f1 + diff * f2);
  r.syy = 0.5 * (sum * f1 - diff * f2);
  r.sxy = sxy * f2;
  r.peeq_increment = dpeeq;
  r.yield_stress = flow.stress;
  r.static_yield = flow_stress(law, peeq + dpeeq, 0.0).stress;
  // Δεᵖ = Δγ P σ: Δε11ᵖ + Δε22ᵖ = Δγ (σxx + σyy)/3.
  r.thickness_strain = -dg * (r.sxx + r.syy) / 3.0;
  r.dissipation = flow.stress * dpeeq;
  return r;
}

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
  const std::size_t n = n_batches * static_cast<std::size_t>(points) * W;
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

Vec ShellPlasticState::point_return(std::size_t b, int k, Vec q11, Vec q12, Vec shear, Real dt,
                                    Vec weight, Vec& sxx, Vec& syy, Vec& sxy,
                                    Vec& thickness_strain) {
  const std::size_t r = row(b, k);
  const Vec y = simd::load(&m_yield[r]);
  const Vec vm2 = sxx * sxx - sxx * syy + syy * syy + 3.0 * (sxy * sxy);
  const simd::Mask yielding = vm2 > (y * y) * (1.0 + YIELD_TOLERANCE);
  Vec dissipation = simd::splat(0.0);
  if (!any_lane(yielding)) {
    simd::store(&m_rate[r], dissipation);
    return dissipation;
  }
  for (std::size_t l = 0; l < W; ++l) {
    m_rate[r + l] = 0.0;
    if (!yielding[l]) continue;
    const Plasticity& law = m_laws[static_cast<std::size_t>(m_lane_law[b * W + l])];
    const PlaneStressReturn p = plane_stress_return(law, q11[l], q12[l], shear[l], sxx[l], syy[l],
                                                    sxy[l], m_peeq[r + l], dt);
    sxx[l] = p.sxx;
    syy[l] = p.syy;
    sxy[l] = p.sxy;
    m_peeq[r + l] += p.peeq_increment;
    if (dt > 0.0) m_rate[r + l] = p.peeq_increment / dt;
    m_yield[r + l] = p.static_yield;
    dissipation[l] = p.dissipation;
    thickness_strain[l] += weight[l] * p.thickness_strain;
  }
  return dissipation;
}

Real ShellPlasticState::peeq(std::size_t b, int k, std::size_t l) const {
  return empty() ? 0.0 : m_peeq[row(b, k) + l];
}

Real ShellPlasticState::peeq_rate(std::size_t b, int k, std::size_t l) const {
  return empty() ? 0.0 : m_rate[row(b, k) + l];
}

void ShellPlasticState::set_peeq(std::size_t b, int k, std::size_t l, Real value) {
  if (empty() || m_lane_law[b * W + l] < 0) return;
  const Plasticity& law = m_laws[static_cast<std::size_t>(m_lane_law[b * W + l])];
  m_peeq[row(b, k) + l] = value;
  m_yield[row(b, k) + l] = flow_stress(law, value, 0.0).stress;
}

}  // namespace xpl::elements
