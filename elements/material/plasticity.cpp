#include "elements/material/plasticity.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "elements/material/plasticity_root.hpp"

namespace xpl::elements {

namespace {

/// Smallest argument at which unbounded derivatives (ε^(n−1), rate^(1/n−1)) are evaluated.
/// Far below any increment of a return (a small overstress on a power law gives Δε̄ᵖ/dt of
/// 1e-25 /s and less), so that Newton sees the true slope there; large enough that the
/// slope stays finite for exponents down to 0.01.
constexpr Real TINY_STRAIN = 1e-100;

constexpr Real INFINITE = std::numeric_limits<Real>::infinity();

/// Relative residual |g|/σ_y at which a return has converged.
constexpr Real TOLERANCE = 1e-12;
/// Newton iterations before the bisection takes over (plasticity_root.hpp).
constexpr int NEWTON_ITERATIONS = 100;

/// σ_0(ε̄ᵖ) and its slope.
void static_curve(const Plasticity& law, Real peeq, Real& stress, Real& slope) {
  if (law.hardening == Hardening::JohnsonCook) {
    const Real e = std::max(peeq, 0.0);
    stress = law.jc_a + law.jc_b * std::pow(e, law.jc_n);
    slope = law.jc_n * law.jc_b * std::pow(std::max(e, TINY_STRAIN), law.jc_n - 1.0);
    return;
  }
  const std::vector<Real>& eps = law.plastic_strain;
  const std::vector<Real>& sig = law.yield_stress;
  const std::size_t n = sig.size();
  if (n == 1 || peeq >= eps[n - 1]) {
    stress = sig[n - 1];
    slope = 0.0;
    return;
  }
  // Segment [eps[i], eps[i+1]) holding peeq (peeq < eps[0] = 0 is clamped to the first).
  const auto upper = std::upper_bound(eps.begin(), eps.end(), peeq);
  const std::size_t i =
      upper == eps.begin() ? 0 : static_cast<std::size_t>(upper - eps.begin()) - 1;
  slope = (sig[i + 1] - sig[i]) / (eps[i + 1] - eps[i]);
  stress = sig[i] + slope * (std::max(peeq, eps[0]) - eps[i]);
}

/// R(ε̇ᵖ) and its derivative.
void rate_factor(const Plasticity& law, Real rate, Real& factor, Real& slope) {
  factor = 1.0;
  slope = 0.0;
  switch (law.rate) {
    case RateDependence::None:
      return;
    case RateDependence::JohnsonCook:
      if (rate > law.rate_reference) {
        factor = 1.0 + law.rate_c * std::log(rate / law.rate_reference);
        slope = law.rate_c / rate;
      }
      return;
    case RateDependence::PowerLaw: {
      const Real x = std::max(rate, 0.0) / law.power_d;
      const Real p = 1.0 / law.power_n;
      factor = 1.0 + std::pow(x, p);
      slope = p * std::pow(std::max(x, TINY_STRAIN), p - 1.0) / law.power_d;
      return;
    }
  }
}

}  // namespace

Real Plasticity::initial_yield() const {
  return hardening == Hardening::JohnsonCook ? jc_a
                                             : (yield_stress.empty() ? 0.0 : yield_stress[0]);
}

Real Plasticity::largest_flow_stress() const {
  // σ_0 rises with ε̄ᵖ for Johnson–Cook (B ≥ 0) and R with ε̇ᵖ (C ≥ 0, D, n > 0): the largest
  // σ_y is the largest static stress times the largest rate factor.
  Real static_largest = 0.0, slope = 0.0;
  if (hardening == Hardening::JohnsonCook)
    static_curve(*this, PLAUSIBLE_PLASTIC_STRAIN, static_largest, slope);
  else
    for (const Real s : yield_stress) static_largest = std::max(static_largest, s);
  Real factor = 1.0;
  rate_factor(*this, PLAUSIBLE_STRAIN_RATE, factor, slope);
  return static_largest * factor;
}

bool Plasticity::softens() const {
  if (hardening == Hardening::JohnsonCook) return jc_b < 0.0;
  for (std::size_t i = 1; i < yield_stress.size(); ++i)
    if (yield_stress[i] < yield_stress[i - 1]) return true;
  return false;
}

FlowStress flow_stress(const Plasticity& law, Real peeq, Real peeq_rate) {
  Real s0 = 0.0, h = 0.0, r = 1.0, dr = 0.0;
  static_curve(law, peeq, s0, h);
  rate_factor(law, peeq_rate, r, dr);
  return {s0 * r, h * r, s0 * dr};
}

PlasticIncrement radial_return(const Plasticity& law, Real q_trial, Real three_g, Real peeq,
                               Real dt) {
  const bool rate = law.rate != RateDependence::None && dt > 0.0;
  const Real inv_dt = rate ? 1.0 / dt : 0.0;
  const FlowStress start = flow_stress(law, peeq, 0.0);
  if (q_trial <= start.stress) return {0.0, start.stress};

  // g(Δ) = q_trial − 3G Δ − σ_y(ε̄ᵖ_n + Δ, Δ/dt): positive at 0, equal to −σ_y < 0 at
  // q_trial/3G, so a root lies in between; Newton keeps inside the bracket or bisects.
  Real lo = 0.0, hi = q_trial / three_g;
  Real delta = (q_trial - start.stress) / (three_g + std::max(start.d_strain, 0.0));
  delta = std::min(delta, hi);
  PlasticIncrement result{delta, start.stress};
  for (int iteration = 0; iteration < NEWTON_ITERATIONS; ++iteration) {
    const FlowStress f = flow_stress(law, peeq + delta, delta * inv_dt);
    const Real g = q_trial - three_g * delta - f.stress;
    result = {delta, f.stress};
    // (An overflowing flow stress is no solution: |−inf| ≤ 1e-12 · inf would hold.)
    if (std::abs(g) <= TOLERANCE * f.stress && f.stress < INFINITE) return result;
    if (g > 0.0)
      lo = delta;
    else
      hi = delta;
    if (hi - lo <= 1e-15 * hi) return result;
    const Real slope = three_g + f.d_strain + f.d_rate * inv_dt;
    Real next = slope > 0.0 ? delta + g / slope : -1.0;
    if (!(next > lo && next < hi)) {
      // Bisection, geometric while the bracket spans decades: the root of a power law with
      // a small overstress lies many decades below q_trial/3G.
      if (hi <= 16.0 * lo)
        next = 0.5 * (lo + hi);
      else
        next = lo > 0.0 ? std::sqrt(lo * hi) : hi / 16.0;
    }
    delta = next;
  }
  // Newton did not converge (a steep law: it creeps, see plasticity_root.hpp): bisect the
  // bracket it leaves. The stress is the one on the surface, q_trial − 3GΔ, which at a jump
  // of the flow stress between two adjacent doubles lies between the flow stresses there.
  const auto residual = [&](Real x, Real& scale) {
    scale = flow_stress(law, peeq + x, x * inv_dt).stress;
    return q_trial - three_g * x - scale;
  };
  const BracketedRoot root = bisect_root(residual, lo, hi, TOLERANCE);
  if (root.converged) return {root.x, flow_stress(law, peeq + root.x, root.x * inv_dt).stress};
  return {root.x, q_trial - three_g * root.x};
}

}  // namespace xpl::elements
