#include <catch2/catch.hpp>

#include <vector>

#include "solver/loads/boundary_state.hpp"
#include "solver/loads/external_loads.hpp"
#include "solver_fixtures.hpp"

using namespace xpl;

namespace {

/// One C3D8R cube of 10 mm at rest with, in its only step, a CLOAD of `force` N in x on node 1
/// (step amplitude: constant over the step).
Model loaded_cube(Real force) {
  test::BoxSpec spec;
  spec.nx = spec.ny = spec.nz = 1;
  spec.lx = spec.ly = spec.lz = 0.01;
  spec.fix_x0 = false;
  spec.velocity_x = 0.0;
  Model model = test::make_box(spec);
  model.steps[0].loads.push_back({1, 1, force, NO_INDEX, {}});
  return model;
}

/// The BCs and loads of step 0 of `model`, taken in on its reference state.
BoundaryState boundary_of(const Model& model) {
  const NodalVectors zero = NodalVectors::Zero(model.node_count(), 3);
  BoundaryState boundary;
  boundary.begin_step(model, 0, zero, zero, NodalVectors(), NodalVectors());
  return boundary;
}

}  // namespace

TEST_CASE("external loads: the CLOAD's force at its node and its work by the trapezoidal rule",
          "[solver][loads]") {
  const Real force = 40.0, dt = 1e-6, v = 2.0;
  const Model model = loaded_cube(force);
  const Index n = model.node_count();
  const BoundaryState boundary = boundary_of(model);
  const std::vector<Real> mass(n, 1e-3);
  ExternalLoads loads;
  loads.begin_step(model, 0, boundary, model.coordinates, mass, {});
  CHECK(loads.has_free_loads());
  CHECK(loads.force() == nullptr);  // no array before the first apply()
  loads.apply(model, boundary, 0.0, 0.0);
  REQUIRE(loads.force() != nullptr);
  CHECK(loads.pending());

  NodalVectors previous_force = NodalVectors::Zero(n, 3);
  NodalVectors velocity_half = NodalVectors::Constant(n, 3, v);
  // The first update (t = 0, dt_prev = 0): the force is set, no work yet.
  loads.evaluate(0, n, model.coordinates, velocity_half.data(), 0.0, previous_force);
  CHECK((*loads.force())(1, 0) == force);
  CHECK((*loads.force())(1, 1) == 0.0);
  CHECK((*loads.force())(0, 0) == 0.0);
  CHECK(previous_force(1, 0) == force);
  Real work = 0.0;
  loads.add_work(work);
  CHECK(work == 0.0);
  CHECK_FALSE(loads.pending());

  // The next update: ½(f_prev + f) Δt v(n−½) = F Δt v for a constant force.
  loads.apply(model, boundary, dt, dt);
  loads.evaluate(0, n, model.coordinates, velocity_half.data(), dt, previous_force);
  loads.add_work(work);
  CHECK(work == Approx(force * dt * v).epsilon(1e-15));

  // Not due: add_work() adds nothing.
  const Real before = work;
  loads.add_work(work);
  CHECK(work == before);
}

TEST_CASE("external loads: a loaded DOF that is prescribed does no work here", "[solver][loads]") {
  const Model model = loaded_cube(40.0);
  const Index n = model.node_count();
  const BoundaryState boundary = boundary_of(model);
  const std::vector<Real> mass(n, 1e-3);
  PrescribedDof held;
  held.node = 1;
  held.component = 0;
  ExternalLoads loads;
  loads.begin_step(model, 0, boundary, model.coordinates, mass, {held});
  CHECK_FALSE(loads.has_free_loads());
  loads.apply(model, boundary, 0.0, 0.0);
  NodalVectors previous_force = NodalVectors::Zero(n, 3);
  const NodalVectors velocity_half = NodalVectors::Constant(n, 3, 2.0);
  loads.evaluate(0, n, model.coordinates, velocity_half.data(), 1e-6, previous_force);
  CHECK((*loads.force())(1, 0) == 40.0);  // the force still acts (its reaction pairs with it)
  CHECK(previous_force(1, 0) == 0.0);     // the prescribed motion keeps this DOF's
  Real work = 0.0;
  loads.add_work(work);
  CHECK(work == 0.0);
}

TEST_CASE("external loads: a model without loads has no force array (P2)", "[solver][loads]") {
  Model model = loaded_cube(1.0);
  model.steps[0].loads.clear();
  const BoundaryState boundary = boundary_of(model);
  const std::vector<Real> mass(model.node_count(), 1e-3);
  ExternalLoads loads;
  loads.begin_step(model, 0, boundary, model.coordinates, mass, {});
  loads.apply(model, boundary, 0.0, 0.0);
  CHECK(loads.force() == nullptr);
  CHECK_FALSE(loads.pending());
  CHECK_FALSE(loads.has_free_loads());
}
