#pragma once
/// \file The plate and plastic modes of shell4r_element_micro (issue 38 item 1): the production
/// S4R kernel alone on a flat plate stretched as make_plate_benchmark.py --load drive stretches
/// the benchmark plate, so that callgrind can count the plastic pass on an AVX2 build of
/// xpl_elements alone (22 files) rather than of the whole program:
///   cmake -S . -B build/avx2 -DCMAKE_BUILD_TYPE=Release -DXPL_NATIVE=OFF
///     -DCMAKE_CXX_FLAGS=-march=x86-64-v3 -DXPL_BUILD_BENCHMARKS=ON
///   cmake --build build/avx2 -j2 --target shell4r_element_micro
///   valgrind --tool=callgrind --toggle-collect='*Shell4rBlock::forces_of_part*'
///     build/avx2/shell4r_element_micro plastic 32 400
/// and the count over 400 × 1024 is the instructions per element-increment (2026-12-07: 1018.6
/// elastic, 1947.0 plastic, against 1021.1 and 1949.8 of the driven deck through xpl).

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "common/types.hpp"
#include "elements/material/plasticity.hpp"
#include "elements/shell/shell4r.hpp"

namespace xpl::elements::micro {

/// The flat N × N plate of the plate and plastic modes, nodes moving with the stretch.
struct StretchedPlate {
  NodalVectors x, v, w;
  std::vector<Index> conn;
  Real dt;
  explicit StretchedPlate(int n) {
    const int row = n + 1;
    const Real side = 0.2025 * n / 64.0, h = side / n, rate = 20.0;
    x.resize(row * row, 3);
    v.resize(row * row, 3);
    w = NodalVectors::Zero(row * row, 3);
    for (int j = 0; j < row; ++j)
      for (int i = 0; i < row; ++i) {
        const int k = i + row * j;
        x(k, 0) = i * h;
        x(k, 1) = j * h;
        x(k, 2) = 0.0;
        v(k, 0) = rate * (i * h - 0.5 * side);
        v(k, 1) = rate * (j * h - 0.5 * side);
        v(k, 2) = 0.0;
      }
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const Index k = i + row * j;
        conn.insert(conn.end(), {k, k + 1, k + 1 + row, k + row});
      }
    const Real nu = 0.3,
               speed = std::sqrt(200e9 / (7850.0 * (1.0 - nu * nu))) * std::sqrt(1.0 + nu);
    dt = 0.9 * h / speed;
  }
};

/// The plate and plastic modes: INCREMENTS passes of the production kernel on StretchedPlate.
inline int run_stretched(bool plastic, int n, int increments, Real yield) {
  StretchedPlate plate(n);
  Plasticity law;
  law.yield_stress = {yield};
  law.plastic_strain = {0.0};
  ShellProperties prop;
  prop.density = 7850.0;
  prop.young = 200e9;
  prop.poisson = 0.3;
  prop.thickness = 0.01;
  prop.integration_points = 5;
  if (plastic) prop.plastic = &law;
  const Index nn = static_cast<Index>(plate.x.rows());
  const Index ne = static_cast<Index>(plate.conn.size() / 4);
  std::vector<Index> index(ne);
  for (Index e = 0; e < ne; ++e) index[e] = e;
  Shell4rBlock block(index, plate.conn, std::vector<ShellProperties>(ne, prop), nn);
  NodalVectors f(nn, 3), m(nn, 3), x = plate.x;
  Real plastic_energy = 0.0;
  for (int inc = 0; inc < increments; ++inc) {
    x += plate.dt * plate.v;
    ShellStepTotals totals;
    f.setZero();
    m.setZero();
    block.internal_forces(x, plate.v, plate.w, plate.dt, f, m, totals);
    plastic_energy += totals.plastic_energy_increment;
  }
  std::vector<Real> peeq;
  if (plastic) {
    peeq.assign(static_cast<std::size_t>(ne), 0.0);
    block.gather_plastic_strain(peeq);
  }
  std::printf("%s: %d elements, %d increments, f[0] %.17g, plastic work %.17g J, PEEQ[0] %.6g\n",
              plastic ? "plastic" : "plate", static_cast<int>(ne), increments, f(0, 0),
              plastic_energy, peeq.empty() ? 0.0 : peeq[0]);
  if (const char* dump = std::getenv("XPL_MICRO_DUMP")) {
    if (std::FILE* out = std::fopen(dump, "wb")) {
      std::fwrite(f.data(), sizeof(Real), f.size(), out);
      std::fwrite(m.data(), sizeof(Real), m.size(), out);
      std::fclose(out);
    }
  }
  return 0;
}

}  // namespace xpl::elements::micro
