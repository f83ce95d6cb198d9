// Micro-benchmark of the S4R plane-stress return (issue 14, item 2 of the crash-tube helper):
// ShellPlasticState::point_return on 64 batches x 5 section points, N increments of monotonic
// strain per lane (direction fixed per lane, random), a share of the lanes unloading halfway.
// Usage: shell_return_micro MODE UNLOAD_PERCENT N (MODE 0 perfectly plastic, 1 linear
// hardening); prints the dissipation and PEEQ sums (old and new builds must agree to round-off).
// Built and run by benchmarks/run_shell_return_micro.sh.
#include <cstdio>
#include <cstdlib>
#include <random>
#include <vector>
#include "elements/material/shell_plasticity.hpp"
using namespace xpl;
using namespace xpl::elements;
int main(int argc, char** argv) {
  const int mode = argc > 1 ? std::atoi(argv[1]) : 0;           // 0 perfect, 1 linear hardening
  const int elastic_share = argc > 2 ? std::atoi(argv[2]) : 0;  // % of lanes unloading
  const std::size_t B = 64;
  const int P = 5;
  const int N = argc > 3 ? std::atoi(argv[3]) : 400;
  const Real E = 210e9, nu = 0.3, q11 = E / (1 - nu * nu), q12 = nu * q11, G = E / (2 * (1 + nu));
  Plasticity law;
  if (mode == 0) {
    law.yield_stress = {250e6};
    law.plastic_strain = {0.0};
  } else {
    law.yield_stress = {250e6, 250e6 + 1e9};
    law.plastic_strain = {0.0, 1.0};
  }
  std::vector<const Plasticity*> lanes(B * simd::W, &law);
  ShellPlasticState st(lanes, P);
  std::mt19937 rng(7);
  std::normal_distribution<Real> nd(0.0, 1.0);
  std::uniform_int_distribution<int> pct(0, 99);
  std::vector<Real> dir(B * P * simd::W * 3), s(B * P * simd::W * 3, 0.0);
  std::vector<int> unload(B * simd::W);
  for (auto& d : dir) d = nd(rng);
  for (auto& u : unload) u = pct(rng) < elastic_share;
  const Real rate = 2e-5;  // strain per increment
  Real dissipation = 0.0;
  const simd::Vec vq11 = simd::splat(q11), vq12 = simd::splat(q12), vg = simd::splat(G);
  for (int n = 0; n < N; ++n)
    for (std::size_t b = 0; b < B; ++b)
      for (int k = 0; k < P; ++k) {
        simd::Vec sxx, syy, sxy, th = simd::splat(0.0), start[3];
        for (int l = 0; l < simd::W; ++l) {
          const std::size_t i = ((b * P + k) * simd::W + l) * 3;
          // Unloading lanes reverse after 200 increments (elastic for a while).
          const Real sign = unload[b * simd::W + l] && n >= N / 2 ? -1.0 : 1.0;
          const Real ex = sign * rate * dir[i], ey = sign * rate * dir[i + 1],
                     gxy = sign * rate * dir[i + 2];
          for (int c = 0; c < 3; ++c) start[c][l] = s[i + static_cast<std::size_t>(c)];
          sxx[l] = s[i] + q11 * ex + q12 * ey;
          syy[l] = s[i + 1] + q12 * ex + q11 * ey;
          sxy[l] = s[i + 2] + G * gxy;
        }
        const simd::Vec d =
            st.point_return(b, k, vq11, vq12, vg, 1e-7, simd::splat(0.2), start, sxx, syy, sxy, th);
        for (int l = 0; l < simd::W; ++l) {
          const std::size_t i = ((b * P + k) * simd::W + l) * 3;
          s[i] = sxx[l];
          s[i + 1] = syy[l];
          s[i + 2] = sxy[l];
          dissipation += d[l];
        }
      }
  Real peeq = 0.0;
  for (std::size_t b = 0; b < B; ++b)
    for (int k = 0; k < P; ++k)
      for (std::size_t l = 0; l < simd::W; ++l) peeq += st.peeq(b, k, l);
  std::printf("dissipation %.15e peeq %.15e\n", dissipation, peeq);
}
