// A frame's element fields made one at a time (ElementSet::fill_output, what a one-process run's
// writer pulls) are bitwise those gathered all at once (ElementSet::gather_output, what a
// distributed run gathers), on a bent and stretched S4R plate and a sheared C3D8R box after
// two force passes (stresses and hourglass state not zero).

#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <utility>
#include <vector>

#include "common/timer.hpp"
#include "shell_fixtures.hpp"
#include "solver/forces/element_set.hpp"
#include "solver/motion/rigid_bodies.hpp"
#include "solver_fixtures.hpp"

using namespace xpl;

namespace {

/// Same size and the same bits (NaN rows included).
bool same_bits(const std::vector<Real>& a, const std::vector<Real>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Real)) == 0;
}

/// Deforms `model`'s mesh (a smooth stretch, shear and bend of every node and a velocity),
/// runs two force passes and checks fill_output of every element field against gather_output.
void check_fields_alone(const Model& model) {
  const Index n = model.node_count();
  State state;
  state.reference = state.position = model.coordinates;
  state.velocity = state.velocity_half = state.acceleration = NodalVectors::Zero(n, 3);
  state.reaction = NodalVectors::Zero(n, 3);
  state.mass.assign(static_cast<std::size_t>(n), 0.0);
  PhaseTimers timers;
  RigidBodies rigid;
  ElementSet elements(model, rigid, state, timers);
  const Real dt = 1e-8;
  for (int pass = 1; pass <= 2; ++pass) {
    for (Index i = 0; i < n; ++i) {
      const Real x = model.coordinates(i, 0), y = model.coordinates(i, 1);
      const Real z = model.coordinates(i, 2);
      state.velocity_half.row(i) << 1e-2 * y, -2e-2 * x, 3e-2 * std::sin(3.0 * x + y);
      state.position(i, 0) = x + pass * (1e-4 * x + 2e-4 * y + 1e-4 * z);
      state.position(i, 1) = y + pass * (-1e-4 * y + 5e-5 * x * x);
      state.position(i, 2) = z + pass * 1e-3 * std::sin(2.0 * x) * std::cos(y);
    }
    ElementTotals totals;
    elements.compute_forces(state, dt, totals);
  }
  REQUIRE(elements.fills_fields_alone());
  FrameRequest what;
  what.stress = what.volume = what.thickness = true;
  FrameFields all;
  elements.gather_output(state, what, all);
  REQUIRE(!all.stress.empty());
  std::vector<Real> rows;
  bool stressed = false;
  for (const Real s : all.stress) stressed = stressed || s != 0.0;
  CHECK(stressed);
  const std::pair<ElementField, const std::vector<Real>*> fields[] = {
      {ElementField::Stress, &all.stress},
      {ElementField::Volume, &all.volume},
      {ElementField::StressBottom, &all.stress_bottom},
      {ElementField::StressTop, &all.stress_top},
      {ElementField::Thickness, &all.thickness},
      {ElementField::HourglassState, &all.hourglass_state}};
  for (const auto& [field, whole] : fields) {
    elements.fill_output(state, field, rows);
    CHECK(same_bits(rows, *whole));
  }
  bool hourglass = false;
  for (const Real h : rows) hourglass = hourglass || h != 0.0;
  CHECK(hourglass);

  // Through FrameFields: held members, or pulled from a source that leaves them empty.
  std::vector<Real> buffer;
  CHECK(&all.element_rows(ElementField::StressTop, buffer) == &all.stress_top);
  struct Pull final : ElementFieldSource {
    const ElementSet& elements;
    const State& state;
    Pull(const ElementSet& e, const State& s) : elements(e), state(s) {}
    void fill(ElementField field, std::vector<Real>& out) const override {
      elements.fill_output(state, field, out);
    }
  } pull(elements, state);
  FrameFields pulled;
  pulled.source = &pull;
  CHECK(same_bits(pulled.element_rows(ElementField::Stress, buffer), all.stress));
  CHECK(pulled.stress.empty());
}

}  // namespace

TEST_CASE("frame fields: one at a time bitwise as gathered together, S4R plate",
          "[solver][output]") {
  test::PlateSpec spec;
  spec.nx = 6;
  spec.ny = 4;
  const Model model = test::make_plate(spec);
  check_fields_alone(model);
}

TEST_CASE("frame fields: one at a time bitwise as gathered together, C3D8R box",
          "[solver][output]") {
  test::BoxSpec spec;
  spec.nx = 4;
  spec.ny = spec.nz = 2;
  const Model model = test::make_box(spec);
  check_fields_alone(model);
}
