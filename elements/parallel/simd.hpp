#pragma once
/// \file A batch of W element lanes as one SIMD value (GCC vector extension), so that the
/// element kernels read like scalar code while every operation runs across W elements.
/// Without AVX-512 the compiler splits the vectors; results are identical lane by lane.

#include <cmath>

#include "common/types.hpp"

namespace xpl::simd {

/// Lanes per batch: 8 doubles = one AVX-512 register.
inline constexpr int W = 8;

/// Colours with fewer batches than this run on one thread: forking a team and meeting at
/// its barrier costs more than a few batches' work, and far more on an oversubscribed
/// machine (small models in a parallel test run).
inline constexpr int MIN_PARALLEL_BATCHES = 16;

/// W doubles processed together.
typedef Real Vec __attribute__((vector_size(W * sizeof(Real))));
/// Lane-wise comparison result (all bits set where true).
typedef std::int64_t Mask __attribute__((vector_size(W * sizeof(Real))));

inline Vec splat(Real s) {
  return Vec{} + s;
}

/// Loads base[index[l]] into lane l.
inline Vec gather(const Real* base, const Index* index) {
  Vec r;
  for (int l = 0; l < W; ++l) r[l] = base[index[l]];
  return r;
}

/// Contiguous load/store of one batch row.
inline Vec load(const Real* p) {
  Vec r;
  for (int l = 0; l < W; ++l) r[l] = p[l];
  return r;
}
inline void store(Real* p, Vec v) {
  for (int l = 0; l < W; ++l) p[l] = v[l];
}

/// Whether any lane of `m` is true.
inline bool any(Mask m) {
  bool r = false;
  for (int l = 0; l < W; ++l) r |= m[l] != 0;
  return r;
}

inline Vec select(Mask m, Vec a, Vec b) {
  return m ? a : b;
}
inline Vec min(Vec a, Vec b) {
  return a < b ? a : b;
}
inline Vec max(Vec a, Vec b) {
  return a > b ? a : b;
}
/// Whether any lane of `a` is below 0.
inline bool any_negative(Vec a) {
  return any(a < 0.0);
}
inline Vec abs(Vec a) {
  return a < 0.0 ? -a : a;
}
/// With AVX-512 one vsqrtpd, with AVX two of 4 lanes (GCC's builtins behind _mm512_sqrt_pd
/// and _mm256_sqrt_pd, without the header, whose GCC 12 version warns under -Wall): under the
/// default -fmath-errno the lane loop compiles to a root, a compare and a call per lane and is
/// never vectorised. Roots are correctly rounded either way, so the bits are those of the loop.
inline Vec sqrt(Vec a) {
#if defined(__AVX512F__)
  constexpr int CURRENT_ROUNDING = 4;  // _MM_FROUND_CUR_DIRECTION
  return __builtin_ia32_sqrtpd512_mask(a, a, static_cast<unsigned char>(0xff), CURRENT_ROUNDING);
#elif defined(__AVX__)
  typedef Real Half __attribute__((vector_size(W / 2 * sizeof(Real))));
  const Half low = __builtin_ia32_sqrtpd256(__builtin_shufflevector(a, a, 0, 1, 2, 3));
  const Half high = __builtin_ia32_sqrtpd256(__builtin_shufflevector(a, a, 4, 5, 6, 7));
  return __builtin_shufflevector(low, high, 0, 1, 2, 3, 4, 5, 6, 7);
#else
  Vec r;
  for (int l = 0; l < W; ++l) r[l] = std::sqrt(a[l]);
  return r;
#endif
}

// Scalar overloads so that geometry templates also run on plain doubles (tests, setup).
inline Real min(Real a, Real b) {
  return a < b ? a : b;
}
inline Real max(Real a, Real b) {
  return a > b ? a : b;
}
inline Real sqrt(Real a) {
  return std::sqrt(a);
}
inline Real abs(Real a) {
  return std::abs(a);
}
inline bool any_negative(Real a) {
  return a < 0.0;
}

}  // namespace xpl::simd
