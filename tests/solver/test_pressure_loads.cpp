// Pressure loads (*DLOAD/*DSLOAD) and shell diagnostics through the solver.

#include <catch2/catch.hpp>

#include <cmath>

#include "shell_fixtures.hpp"
#include "solver/explicit_solver.hpp"
#include "solver_fixtures.hpp"

using namespace xpl;
using namespace xpl::test;

namespace {

/// One free C3D8R cube (side 10 mm) with a pressure on one face for a short time.
State push_cube(int face, Real pressure) {
  BoxSpec spec;
  spec.nx = spec.ny = spec.nz = 1;
  spec.lx = spec.ly = spec.lz = 0.01;
  spec.fix_x0 = false;
  spec.velocity_x = 0.0;
  spec.period = 3e-5;  // ~20 increments
  Model m = make_box(spec);
  m.steps[0].boundaries.clear();
  m.steps[0].pressures.push_back({{0, static_cast<std::uint8_t>(face)}, pressure, NO_INDEX, {}});
  CaptureSink sink;
  ExplicitSolver solver(m, sink);
  solver.run();
  return solver.state();
}

}  // namespace

TEST_CASE("a positive pressure on a hex face pushes into the element", "[solver][pressure]") {
  // Faces S1..S6: z = 0, z = h, y = 0, x = h, y = h, x = 0; inward direction of each.
  const int axis[6] = {2, 2, 1, 0, 1, 0};
  const Real inward[6] = {1, -1, 1, -1, -1, 1};
  for (int face = 0; face < 6; ++face) {
    INFO("face S" << face + 1);
    const State s = push_cube(face, 1e6);
    Real momentum[3] = {0, 0, 0};
    for (Index n = 0; n < 8; ++n)
      for (int c = 0; c < 3; ++c) momentum[c] += s.mass[n] * s.velocity(n, c);
    // Impulse = p A t along the inward normal (the face stays flat and square here).
    const Real impulse = 1e6 * 1e-4 * s.time;
    CHECK(momentum[axis[face]] == Approx(inward[face] * impulse).epsilon(1e-6));
    CHECK(std::abs(momentum[(axis[face] + 1) % 3]) < 1e-9 * impulse);
    // Work of the pressure equals the kinetic plus internal energy. One element rings in its
    // highest mode here, where whole-step kinetic energy is measured to O((ω Δt)²): 1 %.
    CHECK(s.energies.external_work > 0.0);
    INFO("ETOTAL " << s.energies.total() << " J, ALLWK " << s.energies.external_work << " J");
    CHECK(std::abs(s.energies.total()) < 1e-2 * s.energies.external_work);
  }
}

TEST_CASE("shell pressure: SPOS pushes along -n, SNEG along +n", "[solver][pressure][shell]") {
  for (std::uint8_t face : {SHELL_FACE_POS, SHELL_FACE_NEG}) {
    PlateSpec spec;
    spec.nx = spec.ny = 2;
    spec.lx = spec.ly = 0.1;
    spec.period = 1e-5;
    Model m = make_plate(spec);
    for (Index e = 0; e < m.element_count(); ++e)
      m.steps[0].pressures.push_back({{e, face}, 1000.0, NO_INDEX, {}});
    CaptureSink sink;
    ExplicitSolver solver(m, sink);
    solver.run();
    const State& s = solver.state();
    Real pz = 0.0;
    for (Index n = 0; n < m.node_count(); ++n) pz += s.mass[n] * s.velocity(n, 2);
    const Real impulse = 1000.0 * 0.01 * s.time;
    CHECK(pz == Approx(face == SHELL_FACE_POS ? -impulse : impulse).epsilon(1e-6));
  }
}

TEST_CASE("warped shell elements are reported in the message file", "[solver][shell]") {
  PlateSpec spec;
  spec.nx = spec.ny = 2;
  spec.lx = spec.ly = 0.1;
  spec.period = 1e-6;
  Model m = make_plate(spec);
  m.coordinates(plate_node(spec, 1, 1), 2) = 0.02;  // lift the centre node: ~30° warp
  CaptureSink sink;
  ExplicitSolver solver(m, sink);
  solver.run();
  int warned = 0;
  for (const std::string& text : sink.messages)
    if (text.find("plate.inp:1: *ELEMENT: S4R element") != std::string::npos &&
        text.find("is warped by") != std::string::npos)
      ++warned;
  CHECK(warned == 4);
  // A flat plate is not reported.
  CaptureSink quiet;
  ExplicitSolver flat(make_plate(spec), quiet);
  for (const std::string& text : quiet.messages) CHECK(text.find("warped") == std::string::npos);
}

TEST_CASE("rotations prescribed on solid nodes are dropped with a note", "[solver][shell]") {
  BoxSpec spec;
  spec.nx = spec.ny = spec.nz = 1;
  spec.period = 1e-7;
  Model m = make_box(spec);
  m.steps[0].boundaries.push_back({0, 4, 6, 0.0, BoundaryType::Displacement, NO_INDEX, {}});
  CaptureSink sink;
  ExplicitSolver solver(m, sink);
  solver.run();
  bool noted = false;
  for (const std::string& text : sink.messages)
    noted = noted || text.find("DOFs 4-6 of nodes that belong to no shell") != std::string::npos;
  CHECK(noted);
}

TEST_CASE("gravity accelerates a free block at g and its work is kinetic energy",
          "[solver][gravity]") {
  BoxSpec spec;
  spec.nx = spec.ny = spec.nz = 2;
  spec.lx = spec.ly = spec.lz = 0.02;
  spec.fix_x0 = false;
  spec.velocity_x = 0.0;
  spec.period = 1e-4;
  for (bool whole_model : {true, false}) {
    Model m = make_box(spec);
    m.steps[0].boundaries.clear();
    GravityLoad g;
    g.element_set = whole_model ? NO_INDEX : 0;  // set 0 is ALL: the same elements
    g.magnitude = 9.81;
    g.direction[0] = 0.6;
    g.direction[1] = 0.0;
    g.direction[2] = -0.8;
    m.steps[0].gravity.push_back(g);
    CaptureSink sink;
    ExplicitSolver solver(m, sink);
    solver.run();
    const State& s = solver.state();
    Real mass = 0.0, p[3] = {0, 0, 0};
    for (Index n = 0; n < m.node_count(); ++n) {
      mass += s.mass[n];
      for (int c = 0; c < 3; ++c) p[c] += s.mass[n] * s.velocity(n, c);
    }
    CHECK(p[0] / mass == Approx(9.81 * 0.6 * s.time).epsilon(1e-9));
    CHECK(p[2] / mass == Approx(-9.81 * 0.8 * s.time).epsilon(1e-9));
    // ½ v⁻·M·v(n+½) = ALLKE + ALLKD is ½ m v(n)² − ⅛ m Δt² g² under a constant load
    // (docs/theory/energy.md, "What ALLKE measures"): ALLKE(0) = 0 for the block at rest, ALLKD(0)
    // = −⅛ m Δt² g², and ETOTAL keeps that value, the step's shortened last increment included
    // (ALLKD books the shift ⅛ m g² (Δt² − Δt'²)). The kinetic energy is the work of gravity
    // to ALLKD (7e-5 here).
    const Index ke = sink.column("energy/ALLKE"), kd = sink.column("energy/ALLKD"),
                et = sink.column("energy/ETOTAL");
    CHECK(sink.rows[0][ke] == 0.0);
    CHECK(sink.rows[0][kd] < 0.0);
    CHECK(std::abs(s.energies.total() - sink.rows[0][et]) <= 1e-9 * s.energies.kinetic);
    CHECK(s.energies.kinetic == Approx(s.energies.external_work).epsilon(1e-4));
  }
}

TEST_CASE("a pressure removed in a later step (OP=NEW) stops acting", "[solver][pressure]") {
  // Step 1 pushes a free cube on face S6 (x = 0) along +x; step 2 (*DLOAD, OP=NEW with no
  // lines) has no load: the momentum at its end is that of step 1's end. A force left behind
  // in the external force array would keep pushing and double it.
  BoxSpec spec;
  spec.nx = spec.ny = spec.nz = 1;
  spec.lx = spec.ly = spec.lz = 0.01;
  spec.fix_x0 = false;
  spec.velocity_x = 0.0;
  spec.period = 3e-5;
  Model m = make_box(spec);
  m.steps[0].boundaries.clear();
  m.steps[0].pressures.push_back({{0, 5}, 1e6, NO_INDEX, {}});
  Step second = m.steps[0];
  second.name = "free";
  second.pressures.clear();
  second.pressures_reset = true;
  m.steps.push_back(second);
  CaptureSink sink;
  ExplicitSolver solver(m, sink);
  solver.run();
  const State& s = solver.state();
  Real px = 0.0;
  for (Index n = 0; n < 8; ++n) px += s.mass[n] * s.velocity(n, 0);
  // Step 1's impulse p A T (the face stays flat and square), plus the half increment over
  // which central differences let the force of t = T act: at most 1/10 more on this ~20-
  // increment step. A force left acting in step 2 would double it.
  const Real impulse = 1e6 * 1e-4 * spec.period;
  CHECK(s.time == Approx(2.0 * spec.period).epsilon(1e-9));
  CHECK(px > impulse * (1.0 - 1e-6));
  CHECK(px < 1.1 * impulse);
}
