// Stability stress test (S2): the time-increment scale factor is raised until the run
// fails. Factors up to 1 must be stable; the first failing factor is reported.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <string>

#include "solver/explicit_solver.hpp"
#include "solver_fixtures.hpp"
#include "stability_support.hpp"

using namespace xpl;
using test::check_limit;
using test::deficient_mesh;
using test::first_failing_factor;
using test::stable_at;

TEST_CASE("stability: bar at factors 0.5, 0.9, 1.0 is stable; the limit lies above 1",
          "[solver][stability]") {
  test::BoxSpec spec;    // the steel bar of the wave test, ν = 0
  spec.period = 1.5e-3;  // about 3500 increments at factor 1
  spec.history_dt = 1e-6;
  for (Real f : {0.5, 0.9, 1.0}) {
    Real drift = 0.0;
    INFO("factor " << f);
    REQUIRE(stable_at(spec, f, drift));
    CHECK(drift < 0.01);  // energy bounded: ETOTAL within 1 % of ALLKE(0)
  }
  const Real fail = first_failing_factor(spec);
  std::printf("stability (bar, nu = 0): first failing scale factor %.2f\n", fail);
  CHECK(fail > 1.0);
  CHECK(fail < 3.0);  // the stress test must actually find the limit
}

TEST_CASE("stability: nearly incompressible block (nu = 0.45) is stable at factor 1",
          "[solver][stability]") {
  test::BoxSpec spec;
  spec.nx = spec.ny = spec.nz = 8;
  spec.lx = spec.ly = spec.lz = 0.02;
  spec.poisson = 0.45;
  spec.fix_x0 = false;
  spec.velocity_x = 1.0;
  spec.period = 4e-4;
  spec.history_dt = 1e-6;
  for (Real f : {0.5, 0.9, 1.0}) {
    Real drift = 0.0;
    INFO("factor " << f);
    REQUIRE(stable_at(spec, f, drift));
    CHECK(drift < 0.01);
  }
  const Real fail = first_failing_factor(spec);
  std::printf("stability (block, nu = 0.45): first failing scale factor %.2f\n", fail);
  CHECK(fail > 1.0);
  CHECK(fail < 3.0);
}

TEST_CASE("stability: meshes with few neighbours (global estimate) are stable at factor 1",
          "[solver][stability][global]") {
  // Before the global estimate these failed at 0.85, 0.80, 0.96, 0.90 and 0.90. The stiffness
  // hourglass form of these numbers (the default then); both forms below, "[enhanced]".
  const auto deficient_mesh = [](int nx, int ny, int nz, bool fixed) {
    test::BoxSpec spec = test::deficient_mesh(nx, ny, nz, fixed);
    spec.hourglass = HourglassType::Stiffness;
    return spec;
  };
  SECTION("one element, fixed face") {
    // Pushed onto its fixed face, the element takes all the kinetic energy into its few modes
    // at ω·Δt near 2 within an increment or two. Measured at the whole steps their energy was
    // off by tens of per cent (bound 0.3 here before); ALLKE + ALLKD = ½ v(n−½)·M·v(n+½) and
    // the trapezoidal ALLVD left 1.7 % at factor 1, the shifts of that energy at every change
    // of the increment (the increment follows the element's shape); booked in ALLKD, 3e-4.
    // The first failure moved from 1.1-1.3 to 1.55: those "failures" were the same shifts
    // (drifts above 50 % of ALLKE(0) at the step's short last increment, while the element
    // stayed stable: its largest energy grows by 9 % from factor 1 to 1.5, no more). The fixed
    // face lowers the element's highest frequency below that of the free element, which the
    // global estimate bounds; the first failure of the free element stays at 1.1.
    check_limit("1x1x1 fixed face", deficient_mesh(1, 1, 1, true), 0.002, 1.6);
  }
  SECTION("one element, free") {
    check_limit("1x1x1 free", deficient_mesh(1, 1, 1, false));
  }
  SECTION("free single layer") {
    check_limit("4x4x1 free", deficient_mesh(4, 4, 1, false));
  }
  SECTION("bar, fixed end") {
    check_limit("20x1x1 fixed end", deficient_mesh(20, 1, 1, true));
  }
  SECTION("bar, free") {
    check_limit("20x1x1 free", deficient_mesh(20, 1, 1, false));
  }
}

TEST_CASE("stability: first failing factor to 0.01 (diagnostic table, not run by default)",
          "[.scan]") {
  struct Case {
    const char* name;
    test::BoxSpec spec;
  };
  const Case cases[] = {{"1x1x1 fixed face", deficient_mesh(1, 1, 1, true)},
                        {"1x1x1 free", deficient_mesh(1, 1, 1, false)},
                        {"3x3x1 free", deficient_mesh(3, 3, 1, false)},
                        {"4x4x1 free", deficient_mesh(4, 4, 1, false)},
                        {"12x12x1 free", deficient_mesh(12, 12, 1, false)},
                        {"20x1x1 fixed end", deficient_mesh(20, 1, 1, true)},
                        {"20x1x1 free", deficient_mesh(20, 1, 1, false)},
                        {"4x4x2 free", deficient_mesh(4, 4, 2, false)},
                        {"6x6x6 free", deficient_mesh(6, 6, 6, false)}};
  for (const Case& c : cases) {
    Real first = 0.0;
    for (int i = 0; i < 100 && first == 0.0; ++i) {
      const Real f = 0.7 + 0.01 * i;
      Real drift = 0.0;
      if (!stable_at(c.spec, f, drift) || drift > 0.5) first = f;
    }
    std::printf("stability scan: %-18s first failing scale factor %.2f\n", c.name, first);
  }
}

TEST_CASE("stability: both hourglass stiffness forms keep the increment stable",
          "[solver][stability][enhanced]") {
  // The enhanced form (the default since issue 32) resists the hourglass modes with the
  // material's own moduli: their frequencies rise to those of the uniform modes (a cube's ξη
  // mode at 1.15 c/h with E, the twist triple at 2.3 c_s/h, against the element estimate's
  // 2 c_d/h). The same stress test for it and for the stiffness form: stable at 0.5, 0.9 and
  // 1, the first failure in (1.05, 1.3] (the global estimate covers the meshes with few
  // neighbours).
  struct Case {
    const char* name;
    test::BoxSpec spec;
  };
  test::BoxSpec bar;  // the wave-test bar, ν = 0, 3500 increments
  bar.period = 1.5e-3;
  bar.history_dt = 1e-6;
  test::BoxSpec block;  // 8³, ν = 0.45
  block.nx = block.ny = block.nz = 8;
  block.lx = block.ly = block.lz = 0.02;
  block.poisson = 0.45;
  block.fix_x0 = false;
  block.velocity_x = 1.0;
  block.period = 4e-4;
  block.history_dt = 1e-6;
  test::BoxSpec incompressible = test::deficient_mesh(6, 6, 6, false);
  incompressible.poisson = 0.49;
  const Case cases[] = {{"bar", bar},
                        {"8x8x8 nu 0.45", block},
                        {"6x6x6 nu 0.49", incompressible},
                        {"1x1x1 fixed face", test::deficient_mesh(1, 1, 1, true)},
                        {"1x1x1 free", test::deficient_mesh(1, 1, 1, false)},
                        {"4x4x1 free", test::deficient_mesh(4, 4, 1, false)},
                        {"20x1x1 fixed end", test::deficient_mesh(20, 1, 1, true)},
                        {"6x6x6 free", test::deficient_mesh(6, 6, 6, false)}};
  for (const HourglassType form : {HourglassType::Enhanced, HourglassType::Stiffness})
    for (Case c : cases) {
      c.spec.hourglass = form;
      const std::string name =
          std::string(form == HourglassType::Enhanced ? "enhanced " : "stiffness ") + c.name;
      // The fixed single element trades energy between modes near ω·Δt = 2 (see above), and
      // its increment comes from the global estimate of the free element (constraints only
      // lower ω_max, so the estimate leaves it a margin: measured first failure 1.50).
      const bool fixed_one = c.spec.nx == 1 && c.spec.fix_x0;
      check_limit(name.c_str(), c.spec, fixed_one ? 0.05 : 0.01, fixed_one ? 1.6 : 1.3);
    }
}
