#include <catch2/catch.hpp>

#include <cstring>
#include <limits>

#include "elements/parallel/simd.hpp"

using xpl::Real;
using xpl::simd::Mask;
using xpl::simd::Vec;
using xpl::simd::W;

namespace {

bool same_bits(Real a, Real b) {
  return std::memcmp(&a, &b, sizeof(Real)) == 0;
}

}  // namespace

// min, max, abs and select have the bits of their lane-wise ternaries on every pair of special
// values (±0, NaN of both signs, ±inf, tiny and ordinary numbers), whichever instructions the
// build uses for them (AVX-512, the two AVX halves, or the generic lanes).
TEST_CASE("simd min, max, abs and select equal the lane-wise ternaries bit for bit",
          "[elements][simd]") {
  const Real nan = std::numeric_limits<Real>::quiet_NaN();
  const Real inf = std::numeric_limits<Real>::infinity();
  const Real values[] = {0.0, -0.0, 1.0, -1.0, nan, -nan, inf, -inf, 1e-300, -2.5, 3.0};
  constexpr int N = sizeof(values) / sizeof(values[0]);
  int compared = 0, differ = 0;
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) {
      Vec a, b;
      for (int l = 0; l < W; ++l) {
        a[l] = values[(i + l) % N];
        b[l] = values[(j + 3 * l) % N];
      }
      const Mask less = a < b;
      const Vec lo = xpl::simd::min(a, b), hi = xpl::simd::max(a, b);
      const Vec mag = xpl::simd::abs(a), pick = xpl::simd::select(less, a, b);
      for (int l = 0; l < W; ++l) {
        const Real x = a[l], y = b[l];
        differ += !same_bits(lo[l], x < y ? x : y);
        differ += !same_bits(hi[l], x > y ? x : y);
        differ += !same_bits(mag[l], x < 0.0 ? -x : x);
        differ += !same_bits(pick[l], less[l] != 0 ? x : y);
        compared += 4;
      }
    }
  CHECK(compared == N * N * W * 4);
  CHECK(differ == 0);
}
