#include <catch2/catch.hpp>

#include <string>
#include <utility>
#include <vector>

#include "solver/loads/boundary_state.hpp"
#include "solver/motion/nodal_increment.hpp"
#include "solver/motion/prescribed_motion.hpp"
#include "solver/motion/rigid_bodies.hpp"
#include "solver_fixtures.hpp"

using namespace xpl;

namespace {

constexpr Real PERIOD = 1e-3;  // s
constexpr Real MASS = 2e-3;    // kg per node

/// One C3D8R cube at rest whose node 1 is prescribed in x by `type` (value `value`, the
/// step's amplitude RAMP when `ramp`, STEP otherwise) in one step of PERIOD.
Model driven_cube(BoundaryType type, Real value, bool ramp) {
  test::BoxSpec spec;
  spec.nx = spec.ny = spec.nz = 1;
  spec.lx = spec.ly = spec.lz = 0.01;
  spec.fix_x0 = false;
  spec.velocity_x = 0.0;
  spec.period = PERIOD;
  Model model = test::make_box(spec);
  model.steps[0].ramp_amplitude = ramp;
  model.steps[0].boundaries.push_back({1, 1, 1, value, type, NO_INDEX, {}});
  return model;
}

/// The prescribed motion of step 0 of a model, with the state and arrays one update needs.
struct Driven {
  const Model model;
  State state;
  BoundaryState boundary;
  PrescribedMotion motion;
  RigidBodies rigid;  // none
  std::vector<Real> inverse_mass;
  NodalVectors force_internal, previous_force;

  explicit Driven(Model m) : model(std::move(m)), motion(model, boundary, false) {
    const Index n = model.node_count();
    state.reference = state.position = model.coordinates;
    state.velocity = state.velocity_half = state.acceleration = NodalVectors::Zero(n, 3);
    state.reaction = NodalVectors::Zero(n, 3);
    state.mass.assign(n, MASS);
    inverse_mass.assign(n, 1.0 / MASS);
    force_internal = previous_force = NodalVectors::Zero(n, 3);
    boundary.begin_step(model, 0, NodalVectors::Zero(n, 3), state.velocity, NodalVectors(),
                        NodalVectors());
    motion.begin_step(rigid, state);
  }
  NodalField translation() {
    return {state.velocity_half.data(), state.velocity.data(), state.acceleration.data(),
            force_internal.data(),      force_internal.data(), 0.0,
            inverse_mass.data(),        state.mass.data()};
  }
  /// One update with the free update's velocity `v_free` at the driven DOF and the free
  /// update's kinetic sums `free`; returns the update's sums.
  NodalSums update(const NodalIncrement& inc, Real v_free, KineticSums free) {
    const NodalField field = translation();
    motion.keep_old_velocities(field, NodalField{}, model.node_count());
    state.velocity_half(1, 0) = v_free;
    NodalSums sums;
    sums.kinetic = free;
    motion.update(state, field, NodalField{}, inc, RigidJumps{}, previous_force, sums);
    return sums;
  }
};

}  // namespace

TEST_CASE("prescribed motion: v(n+1/2) of velocity and displacement BCs", "[solver][prescribed]") {
  const Real dt = 1e-5;
  const NodalIncrement inc = NodalIncrement::make(dt, dt, 0.25 * PERIOD, 0.25 * PERIOD,
                                                  0.25 * PERIOD + 0.5 * dt, 0.25 * PERIOD + dt);
  SECTION("a ramped velocity at t_n + dt/2") {
    Driven d(driven_cube(BoundaryType::Velocity, 3.0, true));
    REQUIRE(d.motion.prescribed().size() == 1);
    const PrescribedDof& dof = d.motion.prescribed()[0];
    CHECK(d.motion.velocity_half(dof, 0.0, inc) ==
          Approx(3.0 * (0.25 * PERIOD + 0.5 * dt) / PERIOD).epsilon(1e-14));
  }
  SECTION("a ramped displacement: the rate from the current value to that at t_n + dt") {
    Driven d(driven_cube(BoundaryType::Displacement, 1e-3, true));
    const PrescribedDof& dof = d.motion.prescribed()[0];
    const Real current = 0.2e-3;
    const Real target = 1e-3 * (0.25 * PERIOD + dt) / PERIOD;
    CHECK(d.motion.velocity_half(dof, current, inc) ==
          Approx((target - current) / dt).epsilon(1e-12));
    NodalIncrement last = inc;
    last.dt_next = 0.0;  // no next increment: no rate
    CHECK(d.motion.velocity_half(dof, current, last) == 0.0);
  }
}

TEST_CASE("prescribed motion: a step amplitude jumps, a ramp does not", "[solver][prescribed]") {
  const Real dt = 1e-5;
  const NodalIncrement first = NodalIncrement::make(0.0, dt, 0.0, 0.0, 0.5 * dt, dt);
  Driven step(driven_cube(BoundaryType::Velocity, 3.0, false));
  Driven ramp(driven_cube(BoundaryType::Velocity, 3.0, true));
  CHECK(step.motion.first_update());
  const PrescribedDof& a = step.motion.prescribed()[0];
  const PrescribedDof& b = ramp.motion.prescribed()[0];
  CHECK(step.motion.is_jump(a, first, 0.0, step.motion.velocity_half(a, 0.0, first)));
  CHECK_FALSE(ramp.motion.is_jump(b, first, 0.0, ramp.motion.velocity_half(b, 0.0, first)));
}

TEST_CASE(
    "prescribed motion: reaction m a - (f_ext - f_int), trapezoidal work, and a jump "
    "booked as an impulse",
    "[solver][prescribed]") {
  const Real v = 3.0, f_int = 5.0, dt = 1e-5;
  Driven d(driven_cube(BoundaryType::Velocity, v, false));
  d.force_internal(1, 0) = f_int;

  // t = 0: from rest to v at once. The reaction carries the impulse m v / dt_avg; ALLKE is
  // the state before the jump (0) and the work of the jump, ½ m v², falls in the next update.
  const NodalSums first =
      d.update(NodalIncrement::make(0.0, dt, 0.0, 0.0, 0.5 * dt, dt), 0.0, KineticSums{});
  CHECK(d.state.velocity_half(1, 0) == v);
  CHECK(d.state.acceleration(1, 0) == Approx(v / (0.5 * dt)).epsilon(1e-14));
  CHECK(d.state.reaction(1, 0) == Approx(MASS * v / (0.5 * dt) + f_int).epsilon(1e-14));
  CHECK(first.work == 0.0);
  CHECK(first.kinetic.centred == Approx(0.0).margin(1e-18));
  CHECK(first.kinetic.spread == Approx(0.0).margin(1e-18));
  CHECK_FALSE(d.motion.first_update());
  test::CaptureSink sink;
  d.motion.report_jump(0, sink);
  REQUIRE(sink.messages.size() == 1);
  CHECK(sink.messages[0].find("prescribed velocity jump") != std::string::npos);
  d.motion.report_jump(0, sink);  // reported once
  CHECK(sink.messages.size() == 1);

  // The next update at a constant velocity: no acceleration, the reaction balances f_int, the
  // work is the impulse's ½ m v² plus f_int Δt v; ALLKE takes the free update's count back
  // to ½ m v² (8 ALLKE = m (2v)²).
  const Real v_free = 3.5;
  KineticSums free;
  free.add(MASS, v, v_free);
  const NodalSums next =
      d.update(NodalIncrement::make(dt, dt, dt, dt, 1.5 * dt, 2.0 * dt), v_free, free);
  CHECK(d.state.velocity_half(1, 0) == v);
  CHECK(d.state.velocity(1, 0) == v);
  CHECK(d.state.reaction(1, 0) == Approx(f_int).epsilon(1e-14));
  CHECK(next.work == Approx(0.5 * MASS * v * v + f_int * dt * v).epsilon(1e-14));
  CHECK(next.kinetic.centred == Approx(MASS * 4.0 * v * v).epsilon(1e-14));
  CHECK(next.kinetic.spread == Approx(0.0).margin(1e-18));
  d.motion.report_jump(0, sink);
  CHECK(sink.messages.size() == 1);  // no new jump
}
