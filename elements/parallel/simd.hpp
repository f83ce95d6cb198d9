#pragma once
/// \file A batch of W element lanes as one SIMD value (GCC vector extension), so that the
/// element kernels read like scalar code while every operation runs across W elements.
/// Without AVX-512 the compiler splits the vectors; results are identical lane by lane.

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

/// Loads a mask row (0 or −1 per lane).
inline Mask load_mask(const std::int64_t* p) {
  Mask r;
  for (int l = 0; l < W; ++l) r[l] = p[l];
  return r;
}

#if !defined(__AVX512F__) && defined(__AVX__)
/// With AVX but without AVX-512, GCC splits the 8-lane arithmetic into two 4-lane halves but
/// lowers an 8-lane comparison and `m ? a : b` lane by lane (a scalar compare, set, negate and
/// insert per lane, ~40 instructions each; ~85 % of the plastic S4R return's instructions,
/// issue 38). The comparisons, selects, min, max and `any` below take the two halves through
/// GCC's builtins behind _mm256_cmp_pd, _mm256_blendv_pd, _mm256_min_pd, _mm256_max_pd and
/// _mm256_testz_si256 instead (without the header, whose GCC 12 version warns under -Wall).
/// Each gives the same bits as the lane loop: the comparisons are the C ones (ordered,
/// signalling), vminpd/vmaxpd return the second operand unless the first is less/greater,
/// exactly `a < b ? a : b`, and the masks are 0 or −1 per lane.
#define XPL_SIMD_HALVES 1
namespace halves {
typedef Real Half __attribute__((vector_size(W / 2 * sizeof(Real))));
typedef long long HalfBits __attribute__((vector_size(W / 2 * sizeof(Real))));
inline Half low(Vec a) {
  return __builtin_shufflevector(a, a, 0, 1, 2, 3);
}
inline Half high(Vec a) {
  return __builtin_shufflevector(a, a, 4, 5, 6, 7);
}
inline Vec join(Half l, Half h) {
  return __builtin_shufflevector(l, h, 0, 1, 2, 3, 4, 5, 6, 7);
}
/// `PREDICATE`: _CMP_LT_OS 1, _CMP_LE_OS 2, _CMP_GE_OS 13, _CMP_GT_OS 14.
template <int PREDICATE>
inline Mask compare(Vec a, Vec b) {
  return __builtin_bit_cast(Mask, join(__builtin_ia32_cmppd256(low(a), low(b), PREDICATE),
                                       __builtin_ia32_cmppd256(high(a), high(b), PREDICATE)));
}
}  // namespace halves
#endif

/// Lane-wise a < b, a <= b, a > b, a >= b (the vector extension's operators; on AVX without
/// AVX-512 through the halves above).
inline Mask less(Vec a, Vec b) {
#ifdef XPL_SIMD_HALVES
  return halves::compare<1>(a, b);
#else
  return a < b;
#endif
}
inline Mask less_equal(Vec a, Vec b) {
#ifdef XPL_SIMD_HALVES
  return halves::compare<2>(a, b);
#else
  return a <= b;
#endif
}
inline Mask greater(Vec a, Vec b) {
#ifdef XPL_SIMD_HALVES
  return halves::compare<14>(a, b);
#else
  return a > b;
#endif
}
inline Mask greater_equal(Vec a, Vec b) {
#ifdef XPL_SIMD_HALVES
  return halves::compare<13>(a, b);
#else
  return a >= b;
#endif
}
inline Mask less(Vec a, Real b) {
  return less(a, splat(b));
}
inline Mask greater(Vec a, Real b) {
  return greater(a, splat(b));
}

/// Whether any lane of `m` is true.
inline bool any(Mask m) {
#ifdef XPL_SIMD_HALVES
  const halves::HalfBits bits =
      __builtin_bit_cast(halves::HalfBits, halves::low(__builtin_bit_cast(Vec, m))) |
      __builtin_bit_cast(halves::HalfBits, halves::high(__builtin_bit_cast(Vec, m)));
  return !__builtin_ia32_ptestz256(bits, bits);
#else
  bool r = false;
  for (int l = 0; l < W; ++l) r |= m[l] != 0;
  return r;
#endif
}

/// a where `m` is true, else b.
inline Vec select(Mask m, Vec a, Vec b) {
#ifdef XPL_SIMD_HALVES
  const Vec bits = __builtin_bit_cast(Vec, m);
  return halves::join(
      __builtin_ia32_blendvpd256(halves::low(b), halves::low(a), halves::low(bits)),
      __builtin_ia32_blendvpd256(halves::high(b), halves::high(a), halves::high(bits)));
#else
  return m ? a : b;
#endif
}
inline Vec min(Vec a, Vec b) {
#ifdef XPL_SIMD_HALVES
  return halves::join(__builtin_ia32_minpd256(halves::low(a), halves::low(b)),
                      __builtin_ia32_minpd256(halves::high(a), halves::high(b)));
#else
  return a < b ? a : b;
#endif
}
inline Vec max(Vec a, Vec b) {
#ifdef XPL_SIMD_HALVES
  return halves::join(__builtin_ia32_maxpd256(halves::low(a), halves::low(b)),
                      __builtin_ia32_maxpd256(halves::high(a), halves::high(b)));
#else
  return a > b ? a : b;
#endif
}
/// Whether any lane of `a` is below 0.
inline bool any_negative(Vec a) {
  return any(less(a, 0.0));
}
inline Vec abs(Vec a) {
  return select(less(a, 0.0), -a, a);
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
