#include "elements/material/shell_plasticity.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "elements/material/plane_stress_polynomial.hpp"
#include "elements/material/plasticity_root.hpp"

namespace xpl::elements {

using simd::Vec;

namespace {

/// |g| / σ_y at which a return has converged.
constexpr Real NEWTON_TOLERANCE = 1e-12;
/// Newton iterations before the bisection takes over (plasticity_root.hpp).
constexpr int NEWTON_ITERATIONS = 200;

/// Whether any lane of `m` is set.
bool any_lane(simd::Mask m) {
  bool r = false;
  for (int l = 0; l < simd::W; ++l) r |= m[l] != 0;
  return r;
}

/// Result of the return of the lanes of a batch point.
struct LaneReturn {
  Vec sxx, syy, sxy;  ///< returned stress (the trial in lanes not returned)
  Vec dpeeq;          ///< Δε̄ᵖ (0 in lanes not returned)
  Vec yield;          ///< σ_y at the end, with the rate factor
  Vec dgamma;         ///< Δγ
  /// Lanes whose Newton did not converge, and the bracket [lo, hi] of Δγ it left them
  /// (finish_unconverged completes them).
  simd::Mask unconverged;
  Vec lo, hi;
};

/// The state of one lane at the end of its return.
struct LaneEnd {
  Real dgamma, f1, f2, dpeeq, yield;
};

/// The plane-stress return of one lane by bisection on Δγ (plasticity_root.hpp), for a lane
/// whose Newton did not converge: [lo, hi] is the bracket Newton left (hi may be +inf: it is
/// found by doubling, g → −σ_y < 0 as Δγ grows). Eigen-components and the flow stress as in
/// return_lanes (`linear`: the table segment σ_y = seg_stress + seg_slope Δε̄ᵖ). At a jump of
/// the flow stress between two adjacent doubles the stress is the one at the lower end and
/// σ_y its von Mises norm (on the surface, between the flow stresses of the two ends).
[[gnu::noinline]] LaneEnd bisect_lane(const Plasticity& law, bool linear, Real seg_stress,
                                      Real seg_slope, Real a, Real c, Real p1_trial, Real p2_trial,
                                      Real peeq, Real inv_dt, Real lo, Real hi) {
  const auto state = [&](Real dg) {
    LaneEnd e{dg, 1.0 / (1.0 + a * dg), 1.0 / (1.0 + c * dg), 0.0, 0.0};
    const Real vm = std::sqrt(p1_trial * e.f1 * e.f1 + p2_trial * e.f2 * e.f2);
    e.dpeeq = (2.0 / 3.0) * dg * vm;
    e.yield = linear ? seg_stress + seg_slope * e.dpeeq
                     : flow_stress(law, peeq + e.dpeeq, e.dpeeq * inv_dt).stress;
    return std::pair<LaneEnd, Real>(e, vm);
  };
  const auto residual = [&](Real dg, Real& scale) {
    const auto [e, vm] = state(dg);
    scale = e.yield;
    return vm - e.yield;
  };
  if (!(hi < std::numeric_limits<Real>::infinity())) {
    // Doubling from 1/c (the Δγ that halves the deviatoric stress) reaches the largest double
    // within ~1100 steps; g < 0 long before.
    Real x = std::max(2.0 * lo, 1.0 / c);
    for (int k = 0; k < 1100; ++k, x *= 2.0) {
      Real scale = 0.0;
      const Real g = residual(x, scale);
      if (!(g > 0.0)) break;
      lo = x;
    }
    hi = std::max(x, lo);
  }
  const BracketedRoot root = bisect_root(residual, lo, hi, NEWTON_TOLERANCE);
  auto [end, vm] = state(root.x);
  if (!root.converged) end.yield = vm;
  return end;
}

/// The plane-stress return of the lanes in `active`, all lanes at once: Newton on Δγ with
/// SIMD arithmetic, the flow stress per active lane (laws[l], ε̄ᵖ_n = peeq[l]). Lanes that
/// converge keep their Δγ while the others iterate, so every lane gets its own solution.
///
/// Eigen-components of the trial: Σ = σxx+σyy (eigenvalue of C: E/(1−ν) = q11+q12, of P:
/// 1/3), D = σxx−σyy and σxy (C: 2G, P: 1 and 2 with engineering shear). Along the return Σ
/// scales by f1 = 1/(1 + aΔγ), D and σxy by f2 = 1/(1 + cΔγ), and
/// ‖σ‖²_vM = ¼Σ² f1² + (¾D² + 3σxy²) f2².
///
/// g(Δγ) = ‖σ(Δγ)‖_vM − σ_y(ε̄ᵖ_n + Δε̄ᵖ, Δε̄ᵖ/dt), Δε̄ᵖ = ⅔Δγ‖σ‖_vM: positive at 0 and −σ_y
/// < 0 as Δγ → ∞ (the stress vanishes, Δε̄ᵖ stays bounded). Newton runs on the equivalent
/// σ_y/‖σ‖_vM − 1 = 0, which is nearly linear in Δγ (exactly, for perfect plasticity, when
/// one eigen-component carries the stress); a step that leaves the bracket (softening)
/// bisects, or doubles while no upper bound is known.
///
/// Cost per iteration: one division for f1 and f2 together (1/((1 + aΔγ)(1 + cΔγ))), one
/// square root and one division for 1/‖σ‖_vM, one for the Newton step. The evaluation at
/// Δγ = 0 is the trial itself (no division for f1, f2), and its step is Halley's in the
/// piecewise-linear lanes (below): 3.3 evaluations per return instead of 4.0 on monotonic
/// loading at 1–2 % overshoot per increment (benchmarks/RESULTS.md).
/// Lanes in `linear` take σ_y = seg_stress + seg_slope Δε̄ᵖ in SIMD arithmetic instead of the
/// law (see segment_at); the others call flow_stress.
LaneReturn return_lanes(const Plasticity* const* laws, simd::Mask active, simd::Mask linear,
                        Vec seg_stress, Vec seg_slope, Vec q11, Vec q12, Vec shear, Vec sxx,
                        Vec syy, Vec sxy, Vec peeq, Real dt) {
  constexpr Real TOLERANCE = NEWTON_TOLERANCE;
  const Real inv_dt = dt > 0.0 ? 1.0 / dt : 0.0;  // rate-free laws ignore the rate
  const Vec sum = sxx + syy, diff = sxx - syy;
  const Vec a = (q11 + q12) * (1.0 / 3.0), c = 2.0 * shear;
  const Vec p1_trial = 0.25 * sum * sum, p2_trial = 0.75 * diff * diff + 3.0 * (sxy * sxy);
  const Vec zero = simd::splat(0.0), one = simd::splat(1.0);
  const Vec inf = simd::splat(std::numeric_limits<Real>::infinity());
  Vec dg = zero, lo = zero, hi = inf, f1 = one, f2 = one, dpeeq = zero;
  Vec yield = zero, hardening = zero;
  const simd::Mask nonlinear = active & ~linear;
  const bool any_nonlinear = any_lane(nonlinear);
  simd::Mask open = active;                         // lanes still iterating
  simd::Mask unconverged = active & (active == 0);  // all clear
  for (int iteration = 0; iteration < NEWTON_ITERATIONS; ++iteration) {
    Vec p1 = p1_trial, p2 = p2_trial;
    if (iteration > 0) {
      const Vec u1 = 1.0 + a * dg, u2 = 1.0 + c * dg;
      const Vec r = 1.0 / (u1 * u2);
      f1 = u2 * r;
      f2 = u1 * r;
      p1 = p1_trial * f1 * f1;
      p2 = p2_trial * f2 * f2;
    }
    const Vec vm2 = p1 + p2;
    const Vec inv_vm = 1.0 / simd::sqrt(vm2);
    const Vec vm = vm2 * inv_vm;
    const Vec dvm = -(a * p1 * f1 + c * p2 * f2) * inv_vm;
    dpeeq = (2.0 / 3.0) * dg * vm;
    yield = simd::select(linear, seg_stress + seg_slope * dpeeq, yield);
    hardening = simd::select(linear, seg_slope, hardening);
    if (any_nonlinear)
      for (int l = 0; l < simd::W; ++l) {
        if (!(open[l] & nonlinear[l])) continue;
        const FlowStress f = flow_stress(*laws[l], peeq[l] + dpeeq[l], dpeeq[l] * inv_dt);
        // An overflowing flow stress is no solution (|−inf| ≤ 1e-12 · inf would hold): the
        // largest double keeps the stop test honest and the bracket on the right side.
        yield[l] = std::min(f.stress, std::numeric_limits<Real>::max());
        hardening[l] = f.d_strain + f.d_rate * inv_dt;
      }
    const Vec g = vm - yield;
    const simd::Mask bracketed = hi < inf;
    const simd::Mask done = ((g <= TOLERANCE * yield) & (g >= -TOLERANCE * yield)) |
                            (bracketed & (hi - lo <= 1e-15 * hi));
    open &= ~done;
    if (!any_lane(open)) break;
    lo = simd::select(open & (g > 0.0), dg, lo);
    hi = simd::select(open & (g <= 0.0), dg, hi);
    if (iteration == NEWTON_ITERATIONS - 1) [[unlikely]] {
      unconverged = open;  // finish_unconverged bisects their bracket
      break;
    }
    // vm · d(σ_y/vm − 1)/dΔγ, positive but where the law softens.
    const Vec slope = hardening * (2.0 / 3.0) * (vm + dg * dvm) - (yield * inv_vm) * dvm;
    const Vec inv_slope = 1.0 / slope;
    const Vec newton_step = g * inv_slope;
    Vec next = simd::select(slope > 0.0, dg + newton_step, zero - 1.0);
    if (iteration == 0) {
      // Halley's first step in the piecewise-linear lanes, where F = s·φ + ⅔hΔγ − 1 with
      // φ = 1/‖σ‖_vM, F' = slope/vm and F'' = s·φ'', φ'' = 3φ³(A1²φ² − A2) at Δγ = 0 (A1 =
      // aP1 + cP2, A2 = a²P1 + c²P2 of the trial): the step's error is O(g³) instead of O(g²),
      // one evaluation less at overshoots of a few per cent.
      const Vec a1 = a * p1_trial + c * p2_trial, a2 = a * a * p1_trial + c * c * p2_trial;
      const Vec phi3 = inv_vm * inv_vm * inv_vm;
      const Vec f_second = 3.0 * seg_stress * phi3 * (a1 * a1 * inv_vm * inv_vm - a2);
      // 1 − F F''/(2F'²) with F = −g/vm and F' = slope/vm.
      const Vec denominator = 1.0 + 0.5 * newton_step * f_second * vm * inv_slope;
      const Vec halley = newton_step / denominator;
      next = simd::select(linear & (slope > 0.0) & (denominator > 0.5), halley, next);
    }
    const simd::Mask newton = (next > lo) & (next < hi);
    const Vec fallback =
        simd::select(hi < inf, 0.5 * (lo + hi), simd::select(lo > 0.0, 2.0 * lo, 1.0 / c));
    next = simd::select(newton, next, fallback);
    dg = simd::select(open, next, dg);
  }
  LaneReturn r;
  r.sxx = simd::select(active, 0.5 * (sum * f1 + diff * f2), sxx);
  r.syy = simd::select(active, 0.5 * (sum * f1 - diff * f2), syy);
  r.sxy = simd::select(active, sxy * f2, sxy);
  r.dpeeq = simd::select(active, dpeeq, zero);
  r.yield = yield;
  r.dgamma = simd::select(active, dg, zero);
  r.unconverged = unconverged;
  r.lo = lo;
  r.hi = hi;
  return r;
}

/// Completes the lanes of `r` whose Newton did not converge by bisect_lane, from the trial
/// (sxx, syy, sxy), moduli and segments return_lanes had.
[[gnu::noinline]] void finish_unconverged(LaneReturn& r, const Plasticity* const* laws,
                                          simd::Mask linear, Vec seg_stress, Vec seg_slope, Vec q11,
                                          Vec q12, Vec shear, Vec sxx, Vec syy, Vec sxy, Vec peeq,
                                          Real dt) {
  const Real inv_dt = dt > 0.0 ? 1.0 / dt : 0.0;
  for (int l = 0; l < simd::W; ++l) {
    if (!r.unconverged[l]) continue;
    const Real sum = sxx[l] + syy[l], diff = sxx[l] - syy[l];
    const LaneEnd end = bisect_lane(*laws[l], linear[l] != 0, seg_stress[l], seg_slope[l],
                                    (q11[l] + q12[l]) * (1.0 / 3.0), 2.0 * shear[l],
                                    0.25 * sum * sum, 0.75 * diff * diff + 3.0 * (sxy[l] * sxy[l]),
                                    peeq[l], inv_dt, r.lo[l], r.hi[l]);
    r.sxx[l] = 0.5 * (sum * end.f1 + diff * end.f2);
    r.syy[l] = 0.5 * (sum * end.f1 - diff * end.f2);
    r.sxy[l] = sxy[l] * end.f2;
    r.dpeeq[l] = end.dpeeq;
    r.yield[l] = end.yield;
    r.dgamma[l] = end.dgamma;
  }
}

/// Whether the flow stress of `law` is piecewise linear in ε̄ᵖ alone (tabular, rate-free).
bool piecewise_linear(const Plasticity& law) {
  return law.hardening == Hardening::Tabular && law.rate == RateDependence::None;
}

/// The table segment of a piecewise-linear law holding ε̄ᵖ = peeq: σ_y = stress + slope
/// (ε̄ᵖ − peeq) for ε̄ᵖ ≤ end (+inf on the last, constant part).
struct Segment {
  Real stress, slope, end;
};

Segment segment_at(const Plasticity& law, Real peeq) {
  const FlowStress f = flow_stress(law, peeq, 0.0);
  const std::vector<Real>& eps = law.plastic_strain;
  const auto upper = std::upper_bound(eps.begin(), eps.end(), peeq);
  return {f.stress, f.d_strain,
          upper == eps.end() ? std::numeric_limits<Real>::infinity() : *upper};
}

/// Index of the table segment holding ε̄ᵖ = peeq: the last i with ε_i ≤ peeq (n − 1 on the
/// constant part after the last point), as segment_at finds it.
int segment_index(const Plasticity& law, Real peeq) {
  const std::vector<Real>& eps = law.plastic_strain;
  const auto upper = std::upper_bound(eps.begin(), eps.end(), peeq);
  return upper == eps.begin() ? 0 : static_cast<int>(upper - eps.begin()) - 1;
}

}  // namespace

void newton_return_lanes(const Plasticity* const* laws, simd::Mask rest, simd::Mask linear,
                         Vec seg_stress, Vec seg_slope, Vec seg_end, Vec q11, Vec q12, Vec shear,
                         Vec sxx, Vec syy, Vec sxy, Vec peeq, Real dt, PlaneStressLanes& r) {
  LaneReturn n = return_lanes(laws, rest, linear, seg_stress, seg_slope, q11, q12, shear, sxx, syy,
                              sxy, peeq, dt);
  if (any_lane(n.unconverged)) [[unlikely]]
    finish_unconverged(n, laws, linear, seg_stress, seg_slope, q11, q12, shear, sxx, syy, sxy, peeq,
                       dt);
  const simd::Mask crossed = linear & (peeq + n.dpeeq > seg_end);
  if (any_lane(crossed)) {
    const simd::Mask none = crossed & (crossed == 0);
    LaneReturn again = return_lanes(laws, crossed, none, seg_stress, seg_slope, q11, q12, shear,
                                    sxx, syy, sxy, peeq, dt);
    if (any_lane(again.unconverged)) [[unlikely]]
      finish_unconverged(again, laws, none, seg_stress, seg_slope, q11, q12, shear, sxx, syy, sxy,
                         peeq, dt);
    n.sxx = simd::select(crossed, again.sxx, n.sxx);
    n.syy = simd::select(crossed, again.syy, n.syy);
    n.sxy = simd::select(crossed, again.sxy, n.sxy);
    n.dpeeq = simd::select(crossed, again.dpeeq, n.dpeeq);
    n.yield = simd::select(crossed, again.yield, n.yield);
    n.dgamma = simd::select(crossed, again.dgamma, n.dgamma);
  }
  r.sxx = simd::select(rest, n.sxx, r.sxx);
  r.syy = simd::select(rest, n.syy, r.syy);
  r.sxy = simd::select(rest, n.sxy, r.sxy);
  r.dpeeq = simd::select(rest, n.dpeeq, r.dpeeq);
  r.yield = simd::select(rest, n.yield, r.yield);
  r.dgamma = simd::select(rest, n.dgamma, r.dgamma);
}

PlaneStressReturn plane_stress_return(const Plasticity& law, Real q11, Real q12, Real shear,
                                      Real sxx, Real syy, Real sxy, Real peeq, Real dt) {
  PlaneStressReturn r;
  r.sxx = sxx;
  r.syy = syy;
  r.sxy = sxy;
  const FlowStress start = flow_stress(law, peeq, 0.0);
  r.yield_stress = r.static_yield = start.stress;
  const Real vm2_trial = sxx * sxx - sxx * syy + syy * syy + 3.0 * sxy * sxy;
  if (vm2_trial <= start.stress * start.stress * (1.0 + SHELL_YIELD_TOLERANCE)) return r;
  // The batch return with lane 0 alone: one implementation for the kernel and this.
  const Plasticity* laws[simd::W];
  for (const Plasticity*& l : laws) l = &law;
  const simd::Mask none = simd::splat(0.0) != 0.0;
  simd::Mask active = none, linear = none;
  active[0] = -1;
  Vec seg_stress = simd::splat(0.0), seg_slope = seg_stress, seg_end = seg_stress;
  if (piecewise_linear(law)) {
    const Segment segment = segment_at(law, peeq);
    linear[0] = -1;
    seg_stress[0] = segment.stress;
    seg_slope[0] = segment.slope;
    seg_end[0] = segment.end;
  }
  const PlaneStressLanes lanes =
      plane_stress_lanes([&] { return laws; }, active, linear, seg_stress, seg_slope, seg_end,
                         simd::splat(q11), simd::splat(q12), simd::splat(shear), simd::splat(sxx),
                         simd::splat(syy), simd::splat(sxy), simd::splat(peeq), dt);
  r.sxx = lanes.sxx[0];
  r.syy = lanes.syy[0];
  r.sxy = lanes.sxy[0];
  r.peeq_increment = lanes.dpeeq[0];
  r.yield_stress = lanes.yield[0];
  r.static_yield = flow_stress(law, peeq + r.peeq_increment, 0.0).stress;
  // Δεᵖ = Δγ P σ: Δε11ᵖ + Δε22ᵖ = Δγ (σxx + σyy)/3.
  r.thickness_strain = -lanes.dgamma[0] * (r.sxx + r.syy) / 3.0;
  r.dissipation = r.yield_stress * r.peeq_increment;
  return r;
}

void ShellPlasticState::finish_point(std::size_t b, std::size_t r, simd::Mask other,
                                     simd::Mask passed, Vec peeq_end) {
  for (std::size_t l = 0; l < W; ++l) {
    if (other[l]) {
      const Plasticity& law = m_laws[static_cast<std::size_t>(m_lane_law[b * W + l])];
      if (law.rate != RateDependence::None)
        m_yield[r + l] = flow_stress(law, peeq_end[l], 0.0).stress;
    }
    // ε̄ᵖ only grows: the segment index moves up past the table points it passed (the last
    // segment of a law ends at +inf).
    if (passed[l])
      while (peeq_end[l] >= m_segment_end[static_cast<std::size_t>(m_segment[r + l])])
        ++m_segment[r + l];
  }
}

void ShellPlasticState::set_peeq(std::size_t b, int k, std::size_t l, Real value) {
  if (empty() || m_lane_law[b * W + l] < 0) return;
  const Plasticity& law = m_laws[static_cast<std::size_t>(m_lane_law[b * W + l])];
  m_peeq[row(b, k) + l] = value;
  if (batch_constant(b)) return;  // σ_y does not follow ε̄ᵖ, and the batch has no rows
  m_yield[row(b, k) + l] = flow_stress(law, value, 0.0).stress;
  if (law.hardening == Hardening::Tabular)
    m_segment[row(b, k) + l] =
        m_law_segment[static_cast<std::size_t>(m_lane_law[b * W + l])] + segment_index(law, value);
}

}  // namespace xpl::elements
