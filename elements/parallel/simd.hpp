#pragma once
/// \file A batch of W element lanes as one SIMD value (GCC vector extension), so that the
/// element kernels read like scalar code while every operation runs across W elements.
/// Without AVX-512 the compiler splits the vectors; results are identical lane by lane.

#include <bit>
#include <cmath>
#include <cstdint>

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

#if defined(__AVX__) && !defined(__AVX512F__)
/// Without AVX-512, GCC 12 lowers a comparison or `?:` of two W-lane vectors lane by lane
/// (a scalar compare, min or blend and a store per lane); on the two 4-lane halves of the batch
/// the same operations are one instruction each (issue 38 item 3: about a tenth of the S4R
/// element pass's instructions on an AVX2 build). The instructions have the ternaries' exact
/// semantics: vminpd(a, b) is a < b ? a : b and vmaxpd(a, b) a > b ? a : b, NaN and ±0
/// included (the second operand unless the comparison holds), and vcmppd's ordered "less
/// than" is false on NaN as `<` is, so the bits are those of the generic forms below.
namespace avx {
typedef Real Half __attribute__((vector_size(W / 2 * sizeof(Real))));
typedef std::int64_t HalfMask __attribute__((vector_size(W / 2 * sizeof(Real))));
inline Half low(Vec a) {
  return __builtin_shufflevector(a, a, 0, 1, 2, 3);
}
inline Half high(Vec a) {
  return __builtin_shufflevector(a, a, 4, 5, 6, 7);
}
inline Vec join(Half a, Half b) {
  return __builtin_shufflevector(a, b, 0, 1, 2, 3, 4, 5, 6, 7);
}
/// m ? b : a per lane of 4 (the sign bit of each mask lane decides; masks are 0 or all bits).
inline Half blend(Half a, Half b, Half m) {
  return __builtin_ia32_blendvpd256(a, b, m);
}
constexpr int LESS_ORDERED_QUIET = 0x11;  // _CMP_LT_OQ
}  // namespace avx

inline Vec select(Mask m, Vec a, Vec b) {
  const avx::HalfMask lo = __builtin_shufflevector(m, m, 0, 1, 2, 3);
  const avx::HalfMask hi = __builtin_shufflevector(m, m, 4, 5, 6, 7);
  return avx::join(avx::blend(avx::low(b), avx::low(a), std::bit_cast<avx::Half>(lo)),
                   avx::blend(avx::high(b), avx::high(a), std::bit_cast<avx::Half>(hi)));
}
inline Vec min(Vec a, Vec b) {
  return avx::join(__builtin_ia32_minpd256(avx::low(a), avx::low(b)),
                   __builtin_ia32_minpd256(avx::high(a), avx::high(b)));
}
inline Vec max(Vec a, Vec b) {
  return avx::join(__builtin_ia32_maxpd256(avx::low(a), avx::low(b)),
                   __builtin_ia32_maxpd256(avx::high(a), avx::high(b)));
}
inline Vec abs(Vec a) {
  const avx::Half zero = {}, lo = avx::low(a), hi = avx::high(a);
  return avx::join(avx::blend(lo, -lo, __builtin_ia32_cmppd256(lo, zero, avx::LESS_ORDERED_QUIET)),
                   avx::blend(hi, -hi, __builtin_ia32_cmppd256(hi, zero, avx::LESS_ORDERED_QUIET)));
}
#else
inline Vec select(Mask m, Vec a, Vec b) {
  return m ? a : b;
}
inline Vec min(Vec a, Vec b) {
  return a < b ? a : b;
}
inline Vec max(Vec a, Vec b) {
  return a > b ? a : b;
}
inline Vec abs(Vec a) {
  return a < 0.0 ? -a : a;
}
#endif
/// Whether any lane of `a` is below 0.
inline bool any_negative(Vec a) {
  return any(a < 0.0);
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
