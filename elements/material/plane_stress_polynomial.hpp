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
/// Householder's third-order iteration on Q (the error raised to the 4th power per step, one
/// division; Q''' costs a few products) starts from the root of the one-rate approximation
/// (below; one root and one division): over 3,000 random trials per case (perfectly plastic,
/// h = 1 GPa and 20 GPa; E = 200 GPa, ν = 0.3, σ_y = 50 MPa) it stops after 1 step at
/// overshoots up to 7 %, after 1.03–1.06 steps on average up to 15 % and after at most 2 up to
/// 4 × σ_y. From Δγ = 0 it took 2 steps at 2–7 %, 3–4 at 20–30 %, and beyond ~1.3 × σ_y
/// (Q'(0) < 0) the lane went to the Newton return.
/// The stop test |Q| ≤ 2 tol s²A² is |‖σ‖_vM/σ_y − 1| ≤ tol to first
/// order, without a root: ‖σ‖_vM σ_y⁻¹ = w‖σ‖_vM/s = √(1 − Q/(s²A²)).
///
/// A lane whose step leaves the bracket of Δγ its residuals have shown (softening segments, a
/// step's denominator ≤ 0, w ≤ 0) or that has not converged after POLYNOMIAL_ITERATIONS
/// steps is marked `failed`: the caller returns it by the safeguarded Newton instead.

#include <limits>

#include "common/types.hpp"
#include "elements/parallel/kernel_inline.hpp"
#include "elements/parallel/simd.hpp"

namespace xpl::elements {

/// |‖σ‖_vM/σ_y − 1| at which the polynomial return stops (the Newton return's 1e-12).
inline constexpr Real POLYNOMIAL_TOLERANCE = 1e-12;
/// Steps of the polynomial return before a lane is handed to the Newton return.
inline constexpr int POLYNOMIAL_ITERATIONS = 8;

/// The end of the polynomial return of a batch's lanes.
struct PolynomialReturn {
  simd::Vec f1, f2;   ///< factors of Σ and of (D, σxy): 1/u1, 1/u2 (1 where not returned)
  simd::Vec dgamma;   ///< Δγ (0 where not returned)
  simd::Vec dpeeq;    ///< Δε̄ᵖ = ⅔Δγ‖σ‖_vM, -
  simd::Vec yield;    ///< σ_y = s + h Δε̄ᵖ at the end, Pa
  simd::Mask failed;  ///< lanes of `active` to be returned by the Newton return instead
};

/// The return of the lanes in `active` on the segment σ_y = s + h Δε̄ᵖ (s, h in Pa), plane-
/// stress moduli q11, q12, shear (Pa), trial stress (sxx, syy, sxy) (Pa). Lanes converge and
/// then keep their Δγ while others iterate: every lane's result is its own.
XPL_KERNEL_INLINE PolynomialReturn polynomial_return(simd::Mask active, simd::Vec s, simd::Vec h,
                                                     simd::Vec q11, simd::Vec q12, simd::Vec shear,
                                                     simd::Vec sxx, simd::Vec syy, simd::Vec sxy) {
  using simd::Vec;
  const Vec zero = simd::splat(0.0), one = simd::splat(1.0);
  const Vec sum = sxx + syy, diff = sxx - syy;
  const Vec a = (q11 + q12) * (1.0 / 3.0), c = 2.0 * shear;
  const Vec p1 = 0.25 * sum * sum, p2 = 0.75 * diff * diff + 3.0 * (sxy * sxy);
  const Vec s2 = s * s, beta = (2.0 / 3.0) * h;
  const Vec ac2 = 2.0 * a * c, b2 = 2.0 * (c * c * p1 + a * a * p2);  // A'', B''
  const Vec tolerance = simd::splat(2.0 * POLYNOMIAL_TOLERANCE);
  // The start: the root if both parts of the stress scaled at one rate k = (aP1 + cP2)/P, P =
  // P1 + P2 = ‖σ_trial‖²_vM, i.e. (1 − βΔγ)√P = s(1 + kΔγ) (exact where P1 or P2 is 0). Its
  // error is second order in the overshoot: one step takes the yield condition to ≤ 2e-13 at
  // 7 % overshoot, 4e-11 at 15 %, 4e-9 at 30 % (from Δγ = 0 it takes two, 1e-12 at 7 %). Lanes
  // where it is not inside (0, 1/β) start from 0.
  const Vec p = p1 + p2, root = simd::sqrt(p);
  const Vec guess = (p * (root - s)) / (s * (a * p1 + c * p2) + beta * (p * root));
  Vec x = simd::select(active & simd::greater(guess, 0.0) & simd::greater(1.0 - beta * guess, 0.0),
                       guess, zero);
  Vec lo = zero, hi = simd::splat(std::numeric_limits<Real>::infinity());
  simd::Mask open = active;
  simd::Mask failed{};  // all clear
  // Q at Δγ = x and the pieces of its derivatives.
  Vec u1, u2, w, A, dA, B, dB, sA2, Q;
  auto evaluate = [&] {
    u1 = 1.0 + a * x;
    u2 = 1.0 + c * x;
    w = 1.0 - beta * x;
    A = u1 * u2;
    dA = a * u2 + c * u1;
    B = p1 * (u2 * u2) + p2 * (u1 * u1);
    dB = 2.0 * (c * p1 * u2 + a * p2 * u1);
    sA2 = s2 * (A * A);
    Q = sA2 - (w * w) * B;
  };
  evaluate();
  for (int iteration = 0;; ++iteration) {
    open &= ~simd::less_equal(simd::abs(Q), tolerance * sA2);
    if (!simd::any(open)) break;
    if (iteration == POLYNOMIAL_ITERATIONS) {
      failed |= open;
      break;
    }
    lo = simd::select(open & simd::less(Q, 0.0), x, lo);
    hi = simd::select(open & simd::greater(Q, 0.0), x, hi);
    // Householder's third-order step x − Q(6Q'² − 3QQ'')/(6Q'³ − 6QQ'Q'' + Q²Q''').
    const Vec dQ = 2.0 * s2 * (A * dA) + 2.0 * beta * (w * B) - (w * w) * dB;
    const Vec ddQ = 2.0 * s2 * (dA * dA + ac2 * A) - 2.0 * (beta * beta) * B +
                    4.0 * beta * (w * dB) - (w * w) * b2;
    const Vec d3Q = 6.0 * s2 * (dA * ac2) - 6.0 * (beta * beta) * dB + 6.0 * beta * (w * b2);
    const Vec denominator = 6.0 * (dQ * dQ * dQ) - 6.0 * (Q * dQ * ddQ) + (Q * Q) * d3Q;
    const Vec next = x - (Q * (6.0 * (dQ * dQ) - 3.0 * (Q * ddQ))) / denominator;
    const simd::Mask ok = simd::greater(dQ, 0.0) & simd::greater(denominator, 0.0) &
                          simd::greater(next, lo) & simd::less(next, hi) &
                          simd::greater(1.0 - beta * next, 0.0);
    failed |= open & ~ok;
    open &= ok;
    x = simd::select(open, next, x);
    evaluate();
  }
  // One division for 1/u1, 1/u2 and ‖σ‖_vM = s/w (failed lanes: anything, the caller
  // overwrites them).
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
