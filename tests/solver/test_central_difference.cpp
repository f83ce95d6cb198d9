#include <catch2/catch.hpp>

#include "common/timer.hpp"
#include "solver/forces/element_set.hpp"
#include "solver/motion/central_difference.hpp"
#include "solver/motion/nodal_increment.hpp"
#include "solver/motion/rigid_bodies.hpp"
#include "solver_fixtures.hpp"

using namespace xpl;

TEST_CASE("nodal increment: the weights of the velocities it pairs", "[solver][integration]") {
  const Real dt = 1e-6;
  const NodalIncrement start = NodalIncrement::make(0.0, dt, 0.0, 0.0, 0.5 * dt, dt);
  CHECK(start.dt_avg == 0.5 * dt);
  CHECK(start.w_new == 0.0);      // v_0 is the initial velocity itself
  CHECK(start.w_before == -1.0);  // 2 v_0 - v(1/2)
  const NodalIncrement steady = NodalIncrement::make(dt, dt, 3 * dt, 5 * dt, 5.5 * dt, 6 * dt);
  CHECK(steady.w_new == 0.5);
  CHECK(steady.w_before == 0.0);  // v(n-1/2)
  CHECK(steady.step_next_half == 3.5 * dt);
  CHECK(steady.step_next_end == 4 * dt);
  CHECK(steady.time_next_half == 5.5 * dt);
  const NodalIncrement shorter = NodalIncrement::make(2 * dt, dt, 0.0, 0.0, 0.0, 0.0);
  CHECK(shorter.dt_avg == 1.5 * dt);
  CHECK(shorter.w_before == Approx(1.0 / 3.0).epsilon(1e-15));
}

TEST_CASE(
    "central difference: a node under a constant force moves as x = a t^2 / 2 and the "
    "work is its kinetic energy",
    "[solver][integration]") {
  // One free C3D8R cube at rest with a CLOAD F on node 1; no element pass runs, so the
  // element forces stay 0 and node 1 accelerates at a = F / m alone.
  test::BoxSpec spec;
  spec.nx = spec.ny = spec.nz = 1;
  spec.lx = spec.ly = spec.lz = 0.01;
  spec.fix_x0 = false;
  spec.velocity_x = 0.0;
  Model model = test::make_box(spec);
  const Real force = 40.0, dt = 1e-6;
  model.steps[0].loads.push_back({1, 1, force, NO_INDEX, {}});
  const Index n = model.node_count();
  State state;
  state.reference = state.position = model.coordinates;
  state.velocity = state.velocity_half = state.acceleration = NodalVectors::Zero(n, 3);
  state.reaction = NodalVectors::Zero(n, 3);
  state.mass.assign(n, 0.0);
  PhaseTimers timers;
  RigidBodies rigid;
  ElementSet elements(model, rigid, state, timers);
  const Real m = state.mass[1];
  REQUIRE(m == Approx(7850.0 * 1e-6 / 8.0).epsilon(1e-12));
  const Real a = force / m;

  CentralDifference nodes(model, timers, false);
  nodes.begin_step(0, state, rigid);
  CHECK(nodes.prescribed().empty());
  nodes.apply_loads(state, 0.0, 0.0);
  nodes.update_nodes(state, elements, rigid, 0.0, dt, 0.5 * dt, dt);
  CHECK(state.velocity_half(1, 0) == Approx(0.5 * dt * a).epsilon(1e-14));
  CHECK(state.acceleration(1, 0) == Approx(a).epsilon(1e-14));
  CHECK(state.velocity(1, 0) == 0.0);  // v_0
  CHECK(state.velocity_half(0, 0) == 0.0);
  CHECK(state.velocity_half(1, 1) == 0.0);
  CHECK(state.energies.kinetic == 0.0);  // at rest at t = 0
  const Real v_half = state.velocity_half(1, 0);
  CHECK(state.energies.kinetic_defect == Approx(-0.5 * m * v_half * v_half).epsilon(1e-14));
  CHECK(state.energies.external_work == 0.0);

  nodes.advance_positions(state, elements, dt);
  CHECK(state.position(1, 0) - state.reference(1, 0) == Approx(0.5 * a * dt * dt).epsilon(1e-9));
  state.time = state.step_time = dt;
  nodes.apply_loads(state, dt, dt);
  nodes.update_nodes(state, elements, rigid, dt, dt, 1.5 * dt, 2 * dt);
  const Real v1 = a * dt;  // exact for a constant force
  CHECK(state.velocity_half(1, 0) == Approx(1.5 * v1).epsilon(1e-14));
  CHECK(state.velocity(1, 0) == Approx(v1).epsilon(1e-14));
  CHECK(state.energies.kinetic == Approx(0.5 * m * v1 * v1).epsilon(1e-13));
  CHECK(state.energies.external_work == Approx(0.5 * m * v1 * v1).epsilon(1e-13));
  CHECK(state.energies.kinetic_defect == Approx(-0.125 * m * v1 * v1).epsilon(1e-13));
  CHECK(nodes.largest_speed() == Approx(1.5 * v1).epsilon(1e-14));
}
