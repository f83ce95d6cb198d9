#pragma once
/// \file The fallback of the plastic returns (plasticity.cpp, shell_plasticity.cpp): a root of
/// a consistency condition by bisection on the bit patterns of non-negative doubles, which
/// ends for every law in at most 64 evaluations.
///
/// Newton on the consistency condition converges in a few iterations for the common laws, but
/// creeps for steep ones: a Cowper–Symonds law with n = 0.05 raises the overstress to the 20th
/// power, so that from above Newton gains a few per cent per iteration (and 100 iterations end
/// far from the root, with a flow stress many decades above the trial stress), and a
/// Johnson–Cook hardening with n = 0.01 at ε̄ᵖ = 0 is a jump in double precision. The returns
/// therefore run their Newton first (its results are unchanged where it converges) and hand
/// the bracket it leaves to this bisection when it does not converge.
///
/// Bisection on the bits halves the number of doubles between the ends at every step (the
/// bit pattern of a double ≥ 0 is monotone in its value): geometric steps while the bracket
/// spans decades, arithmetic ones once it is narrow, and a bracket of adjacent doubles after
/// 63 steps at most. It ends earlier at |g| ≤ tolerance · scale. When the root lies between
/// two adjacent doubles (the flow stress jumps there in double precision), the end `lo`
/// (g > 0) is the answer: the caller then takes the stress on the surface, q_trial − 3G Δ,
/// which lies between the flow stresses at the two ends.

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

#include "common/types.hpp"

namespace xpl::elements {

/// The end of a bracketed solve.
struct BracketedRoot {
  Real x = 0.0;  ///< the root (|g| small), or the lower end of a bracket of adjacent doubles
  bool converged = false;  ///< |g(x)| ≤ tolerance · scale (else x is the lower end of the bracket)
};

/// Root of a residual g that is positive at `lo` and not positive at `hi` (0 ≤ lo < hi,
/// finite). `residual(x, scale)` returns g(x) and sets `scale` (> 0, the flow stress there)
/// for the stop test |g| ≤ tolerance · scale; a NaN residual counts as not positive.
template <class Residual>
BracketedRoot bisect_root(Residual residual, Real lo, Real hi, Real tolerance) {
  std::uint64_t low = std::bit_cast<std::uint64_t>(lo);
  std::uint64_t high = std::bit_cast<std::uint64_t>(hi);
  while (high - low > 1) {
    const std::uint64_t middle = low + (high - low) / 2;
    const Real x = std::bit_cast<Real>(middle);
    Real scale = 0.0;
    const Real g = residual(x, scale);
    if (std::abs(g) <= tolerance * scale && scale < std::numeric_limits<Real>::infinity())
      return {x, true};
    if (g > 0.0)
      low = middle;
    else
      high = middle;
  }
  return {std::bit_cast<Real>(low), false};
}

}  // namespace xpl::elements
