#include <catch2/catch.hpp>

#include "solver/loads/boundary_state.hpp"
#include "solver/motion/nodal_increment.hpp"
#include "solver/motion/prescribed_motion.hpp"
#include "solver/motion/rigid_bodies.hpp"
#include "solver_fixtures.hpp"

using namespace xpl;

TEST_CASE(
    "rigid bodies: a body driven from rest by a velocity BC on its reference node moves "
    "as one and books the jump as an impulse",
    "[solver][rigid]") {
  // One cube of 10 mm made rigid, reference node 0 (a corner), its x velocity prescribed at
  // v from t = 0 (step amplitude: a jump from rest) and its rotations held (driven at a
  // corner, a free body would also spin); 8 nodes of `mass` each, no forces.
  test::BoxSpec spec;
  spec.nx = spec.ny = spec.nz = 1;
  spec.lx = spec.ly = spec.lz = 0.01;
  spec.fix_x0 = false;
  spec.velocity_x = 0.0;
  Model model = test::make_box(spec);
  model.rigid_bodies.push_back({0, 0, NO_INDEX, NO_INDEX, {}});
  const Real v = 2.0, mass = 1e-3, dt = 1e-6;
  model.steps[0].boundaries.push_back({0, 1, 1, v, BoundaryType::Velocity, NO_INDEX, {}});
  model.steps[0].boundaries.push_back({0, 4, 6, 0.0, BoundaryType::Velocity, NO_INDEX, {}});
  const Index n = model.node_count();
  State state;
  state.reference = state.position = model.coordinates;
  state.velocity = state.velocity_half = state.acceleration = NodalVectors::Zero(n, 3);
  state.reaction = state.rotation = state.angular_velocity = NodalVectors::Zero(n, 3);
  state.angular_velocity_half = state.reaction_moment = NodalVectors::Zero(n, 3);
  state.mass.assign(n, mass);
  RigidBodies rigid(model);
  rigid.setup(model, state.mass, state);
  BoundaryState boundary;
  boundary.begin_step(model, 0, NodalVectors::Zero(n, 3), state.velocity, state.rotation,
                      state.angular_velocity);
  PrescribedMotion motion(model, boundary, false);
  motion.begin_step(rigid, state);
  CHECK(motion.prescribed().empty());  // the body took its reference node's BC

  const NodalVectors force_internal = NodalVectors::Zero(n, 3);
  const RigidUpdate update = rigid.update(motion, state, force_internal, nullptr,
                                          NodalIncrement::make(0.0, dt, 0.0, 0.0, 0.5 * dt, dt));
  const Real body_mass = 8 * mass;
  for (Index i = 0; i < n; ++i) {
    CHECK(state.velocity_half(i, 0) == Approx(v).epsilon(1e-9));
    CHECK(state.velocity_half(i, 1) == Approx(0.0).margin(1e-9));
    CHECK(state.velocity_half(i, 2) == Approx(0.0).margin(1e-9));
  }
  // The whole body is accelerated through the reference node: m a with a = v / (dt / 2).
  CHECK(state.reaction(0, 0) == Approx(body_mass * v / (0.5 * dt)).epsilon(1e-12));
  CHECK(update.jumps.dofs == 1);  // the held rotations do not jump
  CHECK(update.jumps.energy == Approx(0.5 * body_mass * v * v).epsilon(1e-12));
  CHECK(update.jumps.pending == Approx(0.5 * body_mass * v * v).epsilon(1e-12));
  CHECK(update.work == 0.0);  // at t = 0 the state before the jump: its work comes next
}
