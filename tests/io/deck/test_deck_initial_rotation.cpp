// *INITIAL CONDITIONS with rotations (issue 21): TYPE=VELOCITY dofs 4–6 on shell nodes,
// TYPE=ROTATING VELOCITY (a rigid spin), *SECTION CONTROLS, HOURGLASS=ENHANCED, and the
// errors for misuse.

#include <catch2/catch.hpp>

#include "deck/deck_test_support.hpp"

using namespace xpl;
using test::at;
using test::deck_errors;
using test::has_error;
using test::shell_plate_model;
using test::simple_step;
using test::two_brick_model;

TEST_CASE("initial angular velocities of shell nodes and a rigid spin",
          "[io][deck][shell][initial]") {
  const std::string deck = shell_plate_model() +
                           "*INITIAL CONDITIONS, TYPE=VELOCITY\n"
                           "2, 4, 1.5\n"
                           "PLATE_NODES, 6, -2.\n"
                           "3, 3, 0.25\n"
                           "*INITIAL CONDITIONS, TYPE=ROTATING VELOCITY\n"
                           "6, 10., 0, 1, 0\n"
                           "1, 1, 0\n" +
                           simple_step();
  const Model m = io::read_deck_text(deck, "t.inp");
  REQUIRE(m.initial_angular_velocity.rows() == 6);
  CHECK(m.initial_angular_velocity(1, 0) == 1.5);  // node 2, dof 4
  for (Index n = 0; n < 5; ++n) CHECK(m.initial_angular_velocity(n, 2) == -2.0);
  CHECK(m.initial_velocity(2, 2) == 0.25);
  // Node 6 (2, 1, 0) spins at 10 rad/s about the axis from (0, 1, 0) to (1, 1, 0), ê = x:
  // r = (2, 0, 0) is on the axis, so no velocity; its angular velocity adds 10 along x.
  CHECK(m.initial_angular_velocity(5, 0) == 10.0);
  CHECK(m.initial_angular_velocity(5, 2) == -2.0);
  CHECK(m.initial_velocity.row(5).norm() == 0.0);
}

TEST_CASE("a rotating velocity gives v = omega e x (x - a), on one or two data lines",
          "[io][deck][initial]") {
  for (const std::string& data :
       {std::string("ALLN, 3., 0, 0, 0, 0, 0, 2\n"), std::string("ALLN, 3., 0, 0, 0\n0, 0, 2\n")}) {
    const std::string deck =
        two_brick_model() + "*INITIAL CONDITIONS, TYPE=ROTATING VELOCITY\n" + data + simple_step();
    const Model m = io::read_deck_text(deck, "t.inp");
    // Node 1000003 at (1, 1, 0), spin 3 rad/s about +z through the origin: v = (−3, 3, 0).
    CHECK(m.initial_velocity(2, 0) == Approx(-3.0));
    CHECK(m.initial_velocity(2, 1) == Approx(3.0));
    CHECK(m.initial_velocity(2, 2) == 0.0);
    // Node 1000005 at (2, 0, 0): v = (0, 6, 0). No rotations on a hex model.
    CHECK(m.initial_velocity(4, 1) == Approx(6.0));
    CHECK(m.initial_angular_velocity.norm() == 0.0);
  }
}

TEST_CASE("bad rotational initial conditions: exact messages", "[io][deck][initial][errors]") {
  SECTION("dof 4 on a node without rotations") {
    const std::string deck = two_brick_model() + shell_plate_model() +
                             "*INITIAL CONDITIONS, TYPE=VELOCITY\n1000002, 5, 1.\n" + simple_step();
    const auto errors = deck_errors(deck);
    CHECK(has_error(errors, at(deck, "1000002, 5, 1.", "*INITIAL CONDITIONS"),
                    "dof 5 on node 1000002, which has no rotational dofs (it is on no shell "
                    "element); expected dofs 4-6 on shell nodes only"));
  }
  SECTION("dof 7") {
    const std::string deck =
        shell_plate_model() + "*INITIAL CONDITIONS, TYPE=VELOCITY\n2, 7, 1.\n" + simple_step();
    CHECK(has_error(deck_errors(deck), at(deck, "2, 7, 1.", "*INITIAL CONDITIONS"),
                    "dof 7 is out of range; expected dof 1, 2 or 3 (translation, m/s) or 4, 5 "
                    "or 6"));
  }
  SECTION("coincident axis points, missing point b, bad number") {
    const std::string deck = shell_plate_model() +
                             "*INITIAL CONDITIONS, TYPE=ROTATING VELOCITY\n"
                             "1, 2., 0, 0, 0, 0, 0, 0\n"
                             "2, 2., 1, 1, 1\n"
                             "3, fast, 0, 0, 0, 1, 0, 0\n" +
                             simple_step();
    const auto errors = deck_errors(deck);
    CHECK(has_error(errors, at(deck, "1, 2., 0, 0, 0, 0, 0, 0", "*INITIAL CONDITIONS"),
                    "axis points a and b coincide"));
    CHECK(has_error(errors, at(deck, "2, 2., 1, 1, 1", "*INITIAL CONDITIONS"),
                    "found 5 values and no line with point b"));
    CHECK(has_error(errors, at(deck, "3, fast", "*INITIAL CONDITIONS"), "angular velocity"));
  }
}

TEST_CASE("*SECTION CONTROLS, HOURGLASS=ENHANCED is read", "[io][deck][shell]") {
  std::string deck = shell_plate_model() + simple_step();
  const std::string old = "*SHELL SECTION, ELSET=PLATE, MATERIAL=ALU\n";
  deck.replace(deck.find(old), old.size(),
               "*SECTION CONTROLS, NAME=HG, HOURGLASS=ENHANCED\n"
               "*SHELL SECTION, ELSET=PLATE, MATERIAL=ALU, CONTROLS=HG\n");
  const Model m = io::read_deck_text(deck, "t.inp");
  REQUIRE(m.section_controls.size() == 1);
  CHECK(m.section_controls[0].hourglass == HourglassType::Enhanced);
  CHECK(m.section_controls[0].hourglass_given);
}
