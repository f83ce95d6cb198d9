// Bad *RIGID BODY, *ELEMENT TYPE=MASS/ROTARYI, *MASS and *ROTARY INERTIA input: every error
// at once, at its line.

#include <catch2/catch.hpp>

#include "deck/deck_test_support.hpp"

using namespace xpl;
using test::at;
using test::deck_errors;
using test::line_of;
using test::shell_plate_model;
using test::simple_step;
using test::two_brick_model;

TEST_CASE("point mass errors are all reported, each at its line", "[io][deck][rigid][errors]") {
  const std::string deck = two_brick_model() +
                           "*NODE\n100, 5, 5, 5\n"
                           "*ELEMENT, TYPE=MASS, ELSET=PM\n"
                           "901, 100\n"
                           "902, 555\n"
                           "903\n"
                           "5000001, 100\n"
                           "*ELEMENT, TYPE=ROTARYI, ELSET=RI\n"
                           "911, 100\n"
                           "*ELEMENT, TYPE=MASS\n"
                           "921, 100\n"
                           "*ELEMENT, TYPE=C3D8R\n"
                           "901, 1000001, 1000002, 1000003, 1000004, 1000007, 1000008, 1000009, "
                           "1000010\n"
                           "*MASS, ELSET=PM\n-1.\n"
                           "*MASS, ELSET=PM\n2.\n"
                           "*MASS, ELSET=BRICKS\n1.\n"
                           "*MASS, ELSET=PM\n1., 2.\n"
                           "*ROTARY INERTIA, ELSET=RI\n1., -2., 3.\n"
                           "*ROTARY INERTIA, ELSET=NOSET\n1., 1., 1.\n"
                           "*ROTARY INERTIA, ELSET=RI\n" +
                           simple_step();
  const auto errors = deck_errors(deck);
  const std::vector<std::string> expected = {
      at(deck, "903\n", "*ELEMENT") + "element 903 has 0 node ids; expected 1 node id for MASS",
      at(deck, "5000001, 100\n", "*ELEMENT") +
          "element 5000001 is defined twice; expected each element id once",
      at(deck, "901, 1000001", "*ELEMENT") +
          "element 901 is defined twice; expected each element id once",
      at(deck, "-1.", "*MASS") + "mass -1 is not positive; expected a mass > 0",
      at(deck, "1., 2.\n", "*MASS") + "too many values (2) on the data line; expected the mass",
      at(deck, "1., -2.", "*ROTARY INERTIA") +
          "rotary inertia I22 = -2 is negative; expected I11, I22, I33 >= 0",
      at(deck, "*ROTARY INERTIA, ELSET=RI\n*STEP", "*ROTARY INERTIA") +
          "found 0 data lines; expected one data line: I11, I22, I33[, I12, I13, I23]",
      // Resolved at the end: nodes, then properties, then elements without one.
      at(deck, "902, 555", "*ELEMENT") +
          "element 902 refers to undefined node 555; expected a *NODE with id 555",
      at(deck, "*MASS, ELSET=PM\n2.", "*MASS") + "element 901 already has the *MASS at t.inp:" +
          std::to_string(line_of(deck, "*MASS, ELSET=PM\n-1.")) +
          "; expected each MASS element in one *MASS",
      at(deck, "*MASS, ELSET=BRICKS", "*MASS") +
          "element set BRICKS has no MASS elements; expected *ELEMENT, TYPE=MASS elements in it",
      at(deck, "*MASS, ELSET=PM\n1., 2.", "*MASS") + "element 901 already has the *MASS at t.inp:" +
          std::to_string(line_of(deck, "*MASS, ELSET=PM\n-1.")) +
          "; expected each MASS element in one *MASS",
      at(deck, "*ROTARY INERTIA, ELSET=NOSET", "*ROTARY INERTIA") +
          "undefined element set NOSET; expected *ELSET, ELSET=NOSET or *ELEMENT, "
          "TYPE=ROTARYI, ELSET=NOSET",
      at(deck, "*ROTARY INERTIA, ELSET=RI\n*STEP", "*ROTARY INERTIA") +
          "element 911 already has the *ROTARY INERTIA at t.inp:" +
          std::to_string(line_of(deck, "*ROTARY INERTIA, ELSET=RI\n1.")) +
          "; expected each ROTARYI element in one *ROTARY INERTIA",
      at(deck, "921, 100", "*ELEMENT") +
          "MASS element 921 has no *MASS; expected a *MASS, ELSET= covering it",
  };
  CHECK(errors == expected);
}

TEST_CASE("rigid body errors are all reported, each at its line", "[io][deck][rigid][errors]") {
  const std::string deck = two_brick_model() + shell_plate_model() +
                           "*NODE\n100, 5, 5, 5\n"
                           "*NSET, NSET=TWO\n100, 1000001\n"
                           "*NSET, NSET=ONE\n100\n"
                           "*ELSET, ELSET=R1\n5000001\n"
                           "*RIGID BODY, ELSET=BRICKS\n"
                           "*RIGID BODY, REF NODE=777, ELSET=PLATE\n"
                           "*RIGID BODY, REF NODE=TWO, ELSET=GONE\n"
                           "*RIGID BODY, REF NODE=100, PIN NSET=NOPE, TIE NSET=ONE\n"
                           "*RIGID BODY, REF NODE=1000002, ELSET=R1\n"
                           "*RIGID BODY, REF NODE=ONE, ELSET=R1\n"
                           "*RIGID BODY, REF NODE=100\n"
                           "*RIGID BODY, REF NODE=100, ELSET=R1, POSITION=CENTER OF MASS\n"
                           "1, 2\n"
                           "*STEP\n*DYNAMIC, EXPLICIT\n, 1e-3\n"
                           "*RIGID BODY, REF NODE=100, ELSET=PLATE\n"
                           "*END STEP\n";
  const auto errors = deck_errors(deck);
  const auto rigid = [&](const std::string& needle) { return at(deck, needle, "*RIGID BODY"); };
  const std::string first_r1 = "at t.inp:" + std::to_string(line_of(deck, "REF NODE=1000002"));
  const std::vector<std::string> expected = {
      rigid("*RIGID BODY, ELSET=BRICKS") +
          "missing parameter REF NODE; expected REF NODE=node id (or a node set of one node)",
      rigid("REF NODE=100\n") +
          "no ELSET, PIN NSET or TIE NSET; expected the elements (ELSET=) or nodes (PIN NSET=, "
          "TIE NSET=) of the rigid body",
      rigid("POSITION") +
          "unknown parameter POSITION; accepted parameters: REF NODE=, ELSET=, PIN NSET=, TIE "
          "NSET=",
      rigid("1, 2\n") + "unexpected data line; expected no data lines after *RIGID BODY",
      rigid("ELSET=PLATE\n*END") +
          "model data cannot appear inside a step; expected it before the first *STEP",
      // Resolved at the end, body by body; then the reference nodes.
      rigid("REF NODE=777") +
          "undefined reference node 777; expected REF NODE= a defined node id or a node set of "
          "one node",
      rigid("REF NODE=TWO") +
          "reference node set TWO has 2 nodes; expected REF NODE= a node id or a node set of "
          "exactly one node",
      rigid("REF NODE=TWO") +
          "undefined element set GONE; expected *ELSET, ELSET=GONE or *ELEMENT, ELSET=",
      rigid("PIN NSET=NOPE") + "undefined node set NOPE (PIN NSET=); expected *NSET, NSET=NOPE",
      rigid("REF NODE=ONE") + "element 5000001 is already in the rigid body " + first_r1 +
          "; expected each element in at most one *RIGID BODY",
      rigid("POSITION") + "element 5000001 is already in the rigid body " + first_r1 +
          "; expected each element in at most one *RIGID BODY",
      rigid("REF NODE=1000002") +
          "reference node 1000002 belongs to deformable element 5000002; expected a reference "
          "node that no element outside a rigid body uses (e.g. a node of its own)",
  };
  CHECK(errors == expected);
}
