#pragma once
/// \file The plane-stress J2 return of section points whose flow stress is linear in ε̄ᵖ over
/// the increment (a rate-free table on one segment: σ_y = s + h Δε̄ᵖ), as the root of a
/// polynomial in Δγ: one square root and one division to start, one division per iteration
/// (shell_plasticity.hpp has the return and its notation).
///
/// With u1 = 1 + aΔγ, u2 = 1 + cΔγ (a = E/(3(1−ν)), c = 2G), P1 = ¼Σ², P2 = ¾D² + 3σxy² of the
/// trial, the returned stress has ‖σ‖²_vM = P1/u1² + P2/u2² and Δε̄ᵖ = ⅔Δγ‖σ‖_vM. With
/// w = 1 − βΔγ, β = ⅔h, the consistency ‖σ‖_vM = s + h Δε̄ᵖ reads w‖σ‖_vM = s, and multiplied
/// out by (u1 u2)²:
///   Q(Δγ) = s² A² − w² B = 0,   A = u1 u2,   B = P1 u2² + P2 u1²,
/// a polynomial of degree 4 (6 with hardening). Q(0) = s² − ‖σ_trial‖²_vM < 0 at a yielding
/// trial; for w > 0 the sign of Q is that of σ_y − ‖σ‖_vM, so the root sought is the first
/// one where w > 0; in (0, 1/β) it is the only root, Q < 0 below it and Q > 0 above.
/// Householder's third-order step on Q (the error raised to the 4th power, one division; Q'''
/// costs a few products) starts from the root of the one-rate approximation (below; one root
/// and one division). Trials up to POLYNOMIAL_ONE_STEP_OVERSHOOT outside the surface take
/// exactly one step, without a stop test: the yield condition then holds to ≤ 4e-11 (1.5e-13
/// at 7 %). The others (larger overshoots, softening segments) iterate out of line
/// (polynomial_iterate) to |‖σ‖_vM/σ_y − 1| ≤ 1e-12; there, over 3,000 random trials per case
/// (perfectly plastic, h = 1 GPa and 20 GPa; E = 200 GPa, ν = 0.3, σ_y = 50 MPa), at most 2
/// steps up to 4 × σ_y. A lane whose step leaves the bracket of Δγ its residuals have shown or
/// that has not converged after POLYNOMIAL_ITERATIONS steps is marked `failed`: the caller
/// returns it by the safeguarded Newton instead.

#include <limits>

#include "common/types.hpp"
#include "elements/parallel/kernel_inline.hpp"
#include "elements/parallel/simd.hpp"

namespace xpl::elements {

/// |‖σ‖_vM/σ_y − 1| at which the iterated polynomial return stops (the Newton return's 1e-12).
inline constexpr Real POLYNOMIAL_TOLERANCE = 1e-12;
/// Steps of the iterated polynomial return before a lane is handed to the Newton return.
inline constexpr int POLYNOMIAL_ITERATIONS = 8;
/// Trials up to this far outside the yield surface, ‖σ_trial‖_vM ≤ (1 + this) σ_y, on segments
/// that do not soften, take exactly one Householder step from the one-rate start, without a
/// stop test: the start's error is second order in the overshoot and the step raises it to the
/// 4th power, so the yield condition holds to ≤ 4e-11 (perfectly plastic at 15 %; 1.5e-13 at
/// 7 %, 4e-16 at 2 %; hardening only lowers it: worst of 20,000 random trials per case, E =
/// 200 GPa, ν = 0.3, σ_y = 50 MPa, h = 0 to 1 TPa), inside the bound of 1e-8.
inline constexpr Real POLYNOMIAL_ONE_STEP_OVERSHOOT = 0.15;

/// The end of the polynomial return of a batch's lanes.
struct PolynomialReturn {
  simd::Vec f1, f2;   ///< factors of Σ and of (D, σxy): 1/u1, 1/u2 (1 where not returned)
  simd::Vec dgamma;   ///< Δγ (0 where not returned)
  simd::Vec dpeeq;    ///< Δε̄ᵖ = ⅔Δγ‖σ‖_vM, -
  simd::Vec yield;    ///< σ_y = s + h Δε̄ᵖ at the end, Pa
  simd::Mask failed;  ///< lanes of `active` to be returned by the Newton return instead
};

/// The polynomial Q of a return and its pieces (notation above) at Δγ = x.
struct PolynomialTerms {
  simd::Vec a, c, p1, p2, s2, beta, ac2, b2;  ///< a, c, P1, P2, s², β, A'' = 2ac, B''
  simd::Vec u1, u2, w, A, dA, B, dB, sA2, Q;  ///< at x: Q = s²A² − w²B, dA = A', dB = B'

  XPL_KERNEL_INLINE void evaluate(simd::Vec x) {
    u1 = 1.0 + a * x;
    u2 = 1.0 + c * x;
    w = 1.0 - beta * x;
    A = u1 * u2;
    dA = a * u2 + c * u1;
    B = p1 * (u2 * u2) + p2 * (u1 * u1);
    dB = 2.0 * (c * p1 * u2 + a * p2 * u1);
    sA2 = s2 * (A * A);
    Q = sA2 - (w * w) * B;
  }
  /// Householder's third-order step from x (evaluated), x − Q(6Q'² − 3QQ'')/(6Q'³ − 6QQ'Q'' +
  /// Q²Q'''): the next Δγ; Q' and the step's denominator into `dQ`, `denominator`.
  XPL_KERNEL_INLINE simd::Vec step(simd::Vec x, simd::Vec& dQ, simd::Vec& denominator) const {
    dQ = 2.0 * s2 * (A * dA) + 2.0 * beta * (w * B) - (w * w) * dB;
    const simd::Vec ddQ = 2.0 * s2 * (dA * dA + ac2 * A) - 2.0 * (beta * beta) * B +
                          4.0 * beta * (w * dB) - (w * w) * b2;
    const simd::Vec d3Q = 6.0 * s2 * (dA * ac2) - 6.0 * (beta * beta) * dB + 6.0 * beta * (w * b2);
    denominator = 6.0 * (dQ * dQ * dQ) - 6.0 * (Q * dQ * ddQ) + (Q * Q) * d3Q;
    return x - (Q * (6.0 * (dQ * dQ) - 3.0 * (Q * ddQ))) / denominator;
  }
};

/// The lanes `open` of a return that the single step does not take (overshoots beyond
/// POLYNOMIAL_ONE_STEP_OVERSHOOT, softening segments, a start or step outside (0, 1/β)):
/// Householder's steps from their Δγ in `x` until |Q| ≤ 2 tol s²A², i.e. |‖σ‖_vM/σ_y − 1| ≤
/// tol to first order, without a root (‖σ‖_vM σ_y⁻¹ = w‖σ‖_vM/s = √(1 − Q/(s²A²))). Returns the
/// lanes whose step leaves the bracket of Δγ their residuals have shown (a step's denominator
/// ≤ 0, w ≤ 0) or that have not converged after POLYNOMIAL_ITERATIONS steps: the caller
/// returns them by the safeguarded Newton instead. Out of line: explicit increments overshoot
/// by a few per cent, so it runs at first yield of fast impacts and on softening segments only.
[[gnu::noinline]] inline simd::Mask polynomial_iterate(simd::Mask open, PolynomialTerms& q,
                                                       simd::Vec& x) {
  using simd::Vec;
  Vec lo = simd::splat(0.0), hi = simd::splat(std::numeric_limits<Real>::infinity());
  const Vec tolerance = simd::splat(2.0 * POLYNOMIAL_TOLERANCE);
  simd::Mask failed{};  // all clear
  q.evaluate(x);
  for (int iteration = 0;; ++iteration) {
    open &= ~simd::less_equal(simd::abs(q.Q), tolerance * q.sA2);
    if (!simd::any(open)) break;
    if (iteration == POLYNOMIAL_ITERATIONS) {
      failed |= open;
      break;
    }
    lo = simd::select(open & simd::less(q.Q, 0.0), x, lo);
    hi = simd::select(open & simd::greater(q.Q, 0.0), x, hi);
    Vec dQ, denominator;
    const Vec next = q.step(x, dQ, denominator);
    const simd::Mask ok = simd::greater(dQ, 0.0) & simd::greater(denominator, 0.0) &
                          simd::greater(next, lo) & simd::less(next, hi) &
                          simd::greater(1.0 - q.beta * next, 0.0);
    failed |= open & ~ok;
    open &= ok;
    x = simd::select(open, next, x);
    q.evaluate(x);
  }
  return failed;
}

/// The return of the lanes in `active` on the segment σ_y = s + h Δε̄ᵖ (s, h in Pa), plane-
/// stress moduli q11, q12, shear (Pa), trial stress (sxx, syy, sxy) (Pa). Every lane's result
/// is its own.
XPL_KERNEL_INLINE PolynomialReturn polynomial_return(simd::Mask active, simd::Vec s, simd::Vec h,
                                                     simd::Vec q11, simd::Vec q12, simd::Vec shear,
                                                     simd::Vec sxx, simd::Vec syy, simd::Vec sxy) {
  using simd::Vec;
  const Vec zero = simd::splat(0.0), one = simd::splat(1.0);
  const Vec sum = sxx + syy, diff = sxx - syy;
  PolynomialTerms q;
  q.a = (q11 + q12) * (1.0 / 3.0);
  q.c = 2.0 * shear;
  q.p1 = 0.25 * sum * sum;
  q.p2 = 0.75 * diff * diff + 3.0 * (sxy * sxy);
  q.s2 = s * s;
  q.beta = (2.0 / 3.0) * h;
  q.ac2 = 2.0 * q.a * q.c;
  q.b2 = 2.0 * (q.c * q.c * q.p1 + q.a * q.a * q.p2);
  // The start: the root if both parts of the stress scaled at one rate k = (aP1 + cP2)/P, P =
  // P1 + P2 = ‖σ_trial‖²_vM, i.e. (1 − βΔγ)√P = s(1 + kΔγ) (exact where P1 or P2 is 0); its
  // error is second order in the overshoot. Lanes where it is not inside (0, 1/β) start from 0.
  const Vec p = q.p1 + q.p2, root = simd::sqrt(p);
  const Vec guess = (p * (root - s)) / (s * (q.a * q.p1 + q.c * q.p2) + q.beta * (p * root));
  const simd::Mask started =
      active & simd::greater(guess, 0.0) & simd::greater(1.0 - q.beta * guess, 0.0);
  Vec x = simd::select(started, guess, zero);
  // One step from the start where the overshoot allows (POLYNOMIAL_ONE_STEP_OVERSHOOT).
  constexpr Real BOUND =
      (1.0 + POLYNOMIAL_ONE_STEP_OVERSHOOT) * (1.0 + POLYNOMIAL_ONE_STEP_OVERSHOOT);
  q.evaluate(x);
  Vec dQ, denominator;
  const Vec next = q.step(x, dQ, denominator);
  const simd::Mask stepped = started & simd::less_equal(p, BOUND * q.s2) &
                             simd::greater_equal(h, zero) & simd::greater(dQ, 0.0) &
                             simd::greater(denominator, 0.0) & simd::greater(next, 0.0) &
                             simd::greater(1.0 - q.beta * next, 0.0);
  x = simd::select(stepped, next, x);
  const simd::Mask rest = active & ~stepped;
  simd::Mask failed{};  // all clear
  if (simd::any(rest)) [[unlikely]]
    failed = polynomial_iterate(rest, q, x);
  // One division for 1/u1, 1/u2 and ‖σ‖_vM = s/w (failed lanes: anything, the caller
  // overwrites them).
  const Vec u1 = 1.0 + q.a * x, u2 = 1.0 + q.c * x, w = 1.0 - q.beta * x;
  const Vec A = u1 * u2;
  const Vec t = 1.0 / (A * w);
  const Vec vm = s * (A * t);
  PolynomialReturn r;
  r.f1 = simd::select(active, u2 * (w * t), one);
  r.f2 = simd::select(active, u1 * (w * t), one);
  r.dgamma = simd::select(active, x, zero);
  r.dpeeq = simd::select(active, (2.0 / 3.0) * x * vm, zero);
  r.yield = s + h * r.dpeeq;
  r.failed = failed;
  return r;
}

}  // namespace xpl::elements
