// The increment control (solver/increment/increment_control.hpp): which cause governs the
// increment, how ties are broken (the earlier cause of the sequence keeps it), the floor, and that
// a run reports the cause on every status line.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <string>

#include "common/error.hpp"
#include "solver/explicit_solver.hpp"
#include "solver/increment/increment_control.hpp"
#include "solver_fixtures.hpp"

using namespace xpl;

namespace {

constexpr Real INF = std::numeric_limits<Real>::infinity();

ElementEstimate estimate(Real dt, Real ratio = 1.0) {
  ElementEstimate e;
  e.stable_dt = dt;
  e.critical_element = 7;
  e.global_ratio = ratio;
  return e;
}

}  // namespace

TEST_CASE("increment control: the elements' increment and its cause", "[solver][increment]") {
  IncrementControls c;
  c.scale_factor = 0.5;
  SECTION("the element estimate, scaled and with the safety factor") {
    const ElementIncrement e = element_increment(c, 0.9, estimate(2e-7));
    CHECK(e.cause == IncrementCause::Element);
    CHECK(e.raw_dt == 2e-7);
    CHECK(e.dt == 2e-7 * 0.5 * 0.9);  // bit for bit: the order of the products is the rule's
    CHECK(e.critical_element == 7);
  }
  SECTION("the global estimate governs below a ratio of 1, and only then") {
    const ElementIncrement e = element_increment(c, 0.9, estimate(2e-7, 0.75));
    CHECK(e.cause == IncrementCause::Global);
    CHECK(e.raw_dt == 2e-7 * 0.75);
    CHECK(e.dt == 2e-7 * 0.75 * 0.5 * 0.9);
    CHECK(element_increment(c, 0.9, estimate(2e-7, 1.0)).cause == IncrementCause::Element);
  }
  SECTION("a maximum increment governs when it is shorter; a tie keeps the estimate") {
    c.max = 1e-8;
    ElementIncrement e = element_increment(c, 0.9, estimate(2e-7, 0.75));
    CHECK(e.cause == IncrementCause::Maximum);
    CHECK(e.dt == 1e-8);
    CHECK(e.raw_dt == 2e-7 * 0.75);  // the contact rule still sees the element estimate
    c.max = 2e-7 * 0.5 * 0.9;
    e = element_increment(c, 0.9, estimate(2e-7));
    CHECK(e.cause == IncrementCause::Element);
    CHECK(e.dt == *c.max);
  }
  SECTION("a fixed increment replaces everything else") {
    c.max = 1e-9;
    c.fixed = 3e-8;
    const ElementIncrement e = element_increment(c, 0.9, estimate(2e-7, 0.5));
    CHECK(e.cause == IncrementCause::Fixed);
    CHECK(e.dt == 3e-8);
  }
}

TEST_CASE("increment control: contact and the end of the step", "[solver][increment]") {
  ElementIncrement e;
  e.raw_dt = 2e-7;
  e.dt = 1e-7;
  e.cause = IncrementCause::Global;
  e.critical_element = 7;
  SECTION("the shorter of elements and springs; a tie keeps the elements") {
    IncrementDecision d = choose_increment(e, {5e-8, 3}, 1.0);
    CHECK(d.cause == IncrementCause::Contact);
    CHECK(d.dt == 5e-8);
    CHECK(d.critical_node == 3);
    CHECK(d.critical_element == 7);
    d = choose_increment(e, {1e-7, 3}, 1.0);
    CHECK(d.cause == IncrementCause::Global);
    CHECK(d.critical_node == NO_INDEX);
    d = choose_increment(e, {}, 1.0);  // no springs
    CHECK(d.cause == IncrementCause::Global);
    CHECK(d.dt == 1e-7);
  }
  SECTION("the end of the step: shortened onto it, or stretched past a sliver") {
    IncrementDecision d = choose_increment(e, {}, 4e-8);
    CHECK(d.cause == IncrementCause::StepEnd);
    CHECK(d.dt == 4e-8);
    d = choose_increment(e, {}, 1.0005e-7);  // 5e-4 dt beyond: no sliver increment after it
    CHECK(d.cause == IncrementCause::StepEnd);
    CHECK(d.dt == 1.0005e-7);
    d = choose_increment(e, {}, 1.01e-7);  // 1 % beyond: an increment of its own follows
    CHECK(d.cause == IncrementCause::Global);
    CHECK(d.dt == 1e-7);
    d = choose_increment(e, {}, 1e-7);  // exactly on it: the elements keep it
    CHECK(d.cause == IncrementCause::Global);
  }
  SECTION("no elements: one increment to the end of the step") {
    const IncrementDecision d = choose_increment(ElementIncrement{}, {}, 2.5e-3);
    CHECK(d.cause == IncrementCause::StepEnd);
    CHECK(d.dt == 2.5e-3);
  }
  SECTION("a later step starts with the increment carried over, cut to its period") {
    IncrementDecision carried;
    carried.dt = 1e-7;
    carried.cause = IncrementCause::Contact;
    CHECK(carry_increment(carried, 1.0).cause == IncrementCause::Contact);
    CHECK(carry_increment(carried, 1e-7).cause == IncrementCause::Contact);
    const IncrementDecision cut = carry_increment(carried, 5e-8);
    CHECK(cut.cause == IncrementCause::StepEnd);
    CHECK(cut.dt == 5e-8);
  }
  CHECK(std::string(cause_name(IncrementCause::StepEnd)) == "step-end");
}

TEST_CASE("increment control: the floor", "[solver][increment]") {
  CHECK(increment_floor(1e-4, 2e-7, 1e-5) == 1e-4 * 2e-7);
  CHECK(increment_floor(1e-4, 2e-7, 1.0) == DT_TRANSIT_FLOOR * 1.0);  // the transit time's

  test::BoxSpec spec;
  spec.nx = spec.ny = spec.nz = 1;
  Model model = test::make_box(spec);
  test::CaptureSink sink;
  IncrementControl control(model, sink, 0.9, 1e-4, 1e-5);
  control.start(2e-7);
  State state;
  state.increment = 12;
  const Real floor = 1e-4 * 2e-7;
  CHECK_NOTHROW(control.check_floor(state, floor, 5));  // at the floor: still allowed
  CHECK_THROWS_AS(control.check_floor(state, 0.0, 5), SolverError);
  try {
    control.check_floor(state, 0.5 * floor, 5);
    FAIL("no error below the floor");
  } catch (const SolverError& e) {
    CHECK(std::string(e.what()).find("stable increment collapsed to 1e-11 s") != std::string::npos);
    CHECK(e.increment() == 12);
  }
  model.steps[0].increment.fixed = 1e-12;  // a fixed increment is the user's: never checked
  CHECK_NOTHROW(control.check_floor(state, 1e-12, 5));
  // The springs never shorten a fixed increment.
  ElementIncrement e;
  e.raw_dt = 2e-7;
  e.dt = 1e-12;
  CHECK(std::isinf(control.contact(0, e, 1e30, 0).dt));
  model.steps[0].increment.fixed.reset();
  e.dt = 1.8e-7;
  CHECK(control.contact(0, e, 1e30, 0).dt == contact_increment(2e-7, 1.8e-7, 1.0, 1e30));
  CHECK(control.contact(0, e, 1e30, 0).node == 0);
}

TEST_CASE("increment control: every status line names the governing cause", "[solver][increment]") {
  test::BoxSpec spec;
  spec.nx = 10;
  spec.ny = spec.nz = 1;
  spec.period = 2e-6;
  Model model = test::make_box(spec);
  SECTION("the element estimate, and the end of the step") {
    test::CaptureSink sink;
    SolverOptions options;
    options.threads = 1;
    ExplicitSolver solver(model, sink, options);
    solver.run();
    REQUIRE(sink.statuses.size() > 2);
    // The last increments land on the end of the step (the last line shows the one taken).
    CHECK(sink.statuses.front().governing == "element");
    CHECK(sink.statuses.back().governing == "step-end");
    for (const StatusLine& line : sink.statuses)
      CHECK((line.governing == "element" || line.governing == "step-end"));
    bool summary = false;
    for (const std::string& m : sink.messages)
      summary = summary || m.find("increment(s) governed by: element") != std::string::npos;
    CHECK(summary);
  }
  SECTION("the global estimate: one free element") {
    spec.nx = 1;
    spec.lx = spec.ly = spec.lz = 0.01;
    spec.fix_x0 = false;
    spec.poisson = 0.3;  // its linear limit is 0.734 h/c_d (README, Stable increment)
    spec.period = 2e-5;
    model = test::make_box(spec);
    test::CaptureSink sink;
    SolverOptions options;
    options.threads = 1;
    ExplicitSolver solver(model, sink, options);
    solver.run();
    REQUIRE(sink.statuses.size() > 2);
    CHECK(sink.statuses.front().governing == "global");
  }
  SECTION("a step's maximum increment") {
    model.steps[0].increment.max = 5e-8;
    test::CaptureSink sink;
    SolverOptions options;
    options.threads = 1;
    ExplicitSolver solver(model, sink, options);
    solver.run();
    REQUIRE(sink.statuses.size() > 2);
    CHECK(sink.statuses.front().governing == "maximum");
    CHECK(sink.statuses.front().dt == 5e-8);
  }
}
