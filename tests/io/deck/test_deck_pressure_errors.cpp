// Bad *DLOAD / *DSLOAD input and shell output requests; every error of a shell deck at once.

#include <catch2/catch.hpp>

#include "deck/deck_test_support.hpp"

using namespace xpl;
using test::at;
using test::deck_errors;
using test::has_message;
using test::shell_plate_model;
using test::simple_step;
using test::two_brick_model;

namespace {

const std::string DLOAD_SUPPORTED =
    "supported: P on S4R elements (face SPOS), P1..P6 on C3D8R elements (faces S1..S6), GRAV "
    "(gravity)";

}  // namespace

TEST_CASE("*DLOAD and *DSLOAD errors are all reported, each at its line",
          "[io][deck][shell][errors]") {
  const std::string deck = two_brick_model() + shell_plate_model() +
                           "*SURFACE, NAME=TOP\nPLATE, SPOS\n"
                           "*SURFACE, NAME=PTS, TYPE=NODE\nPLATE_NODES\n"
                           "*DLOAD\nPLATE, P, 1.\n"
                           "*STEP\n*DYNAMIC, EXPLICIT\n, 1e-3\n"
                           "*DLOAD\n"
                           "BRICKS, P, 1e5\n"
                           "11, P3, 1e5\n"
                           "PLATE, GRAV, 9.81, 0, 0, 0\n"
                           "PLATE, BZ, 1e3\n"
                           "PLATE, P, lots\n"
                           "NOPE, P, 1\n"
                           "99, P, 1\n"
                           "PLATE\n"
                           "PLATE, P\n"
                           "*DLOAD, AMPLITUDE=GONE\n"
                           "12, P, 1\n"
                           "*DSLOAD\n"
                           "MISSING, P, 1\n"
                           "PTS, P, 1\n"
                           "TOP, TRSHR, 1, 0, 0, 1\n"
                           "TOP, P, 1, 2\n"
                           "*DSLOAD, OP=REPLACE\n"
                           "TOP, P, 1\n"
                           "*END STEP\n";
  const auto errors = deck_errors(deck);
  auto dload = [&](const std::string& needle) { return at(deck, needle, "*DLOAD"); };
  auto dsload = [&](const std::string& needle) { return at(deck, needle, "*DSLOAD"); };
  const std::vector<std::string> expected = {
      at(deck, "*DLOAD\nPLATE, P, 1.", "*DLOAD") +
          "history data outside a step; expected it between *STEP and *END STEP",
      dload("PLATE, GRAV") +
          "gravity direction 0, 0, 0 has no length; expected a nonzero direction dx, dy, dz (it "
          "is normalised)",
      dload("PLATE, BZ") + "load type BZ is not supported yet; " + DLOAD_SUPPORTED,
      dload("PLATE, P, lots") +
          "bad number 'lots' for magnitude; expected a real number such as 2, -1.5, 1e3 or 1.0D3",
      dload("PLATE\nPLATE, P\n") +
          "missing load type; expected element or element set, load type, magnitude",
      dload("PLATE, P\n*DLOAD") + "missing magnitude; expected a number",
      dsload("TOP, TRSHR") +
          "load type TRSHR is not supported yet; supported: P (pressure on an element-based "
          "surface)",
      dsload("TOP, P, 1, 2") +
          "too many values (4) on the data line; expected surface, P, "
          "magnitude",
      at(deck, "*DSLOAD, OP=REPLACE", "*DSLOAD") + "bad OP=REPLACE; expected OP=MOD or OP=NEW",
      // Resolved at the end: sets, surfaces, amplitudes and element types.
      dload("BRICKS, P") +
          "load type P does not fit C3D8R element 5000001 of set BRICKS; "
          "expected P1..P6 on C3D8R solid elements (faces S1..S6)",
      dload("11, P3") +
          "load type P3 does not fit S4R element 11; expected P on S4R shell "
          "elements",
      dload("NOPE, P") + "undefined element set NOPE; expected *ELSET, ELSET=NOPE",
      dload("99, P") +
          "undefined element 99; expected a defined element id or an element set "
          "name",
      dload("12, P, 1") + "undefined amplitude GONE; expected *AMPLITUDE, NAME=GONE",
      dsload("MISSING, P") + "undefined surface MISSING; expected *SURFACE, NAME=MISSING",
      dsload("PTS, P") +
          "surface PTS is node-based; expected an element-based surface "
          "(*SURFACE, TYPE=ELEMENT) under a pressure",
  };
  CHECK(errors == expected);
}

TEST_CASE("unknown rotational output variables", "[io][deck][shell][errors]") {
  const std::string deck = shell_plate_model() +
                           "*STEP\n*DYNAMIC, EXPLICIT\n, 1.\n"
                           "*OUTPUT, FIELD\n*NODE OUTPUT\nUR1\n*ELEMENT OUTPUT\nSTH, SF\n"
                           "*OUTPUT, HISTORY\n*NODE OUTPUT, NSET=PLATE_NODES\nUR4\n"
                           "*END STEP\n";
  const auto errors = deck_errors(deck);
  REQUIRE(errors.size() == 3);
  CHECK(errors[0] == at(deck, "UR1", "*NODE OUTPUT") +
                         "unknown output variable UR1; expected one of U, V, A, RF, UR, VR, RM");
  CHECK(errors[1] == at(deck, "STH, SF", "*ELEMENT OUTPUT") +
                         "unknown output variable SF; expected one of S, EVOL, MISES, STH, PEEQ");
  CHECK(errors[2] == at(deck, "UR4", "*NODE OUTPUT") +
                         "unknown output variable UR4; expected one of U, V, A, RF, UR, VR, RM "
                         "or a component such as U1, RF3, UR2, RM1");
}

TEST_CASE("every shell error of a deck is reported together", "[io][deck][shell][errors]") {
  std::string deck = two_brick_model() + shell_plate_model() +
                     "*ELEMENT, TYPE=S3R\n81, 1, 2, 5\n"
                     "*ELEMENT, TYPE=S4, ELSET=PLATE\n82, 1, 2, 2, 4\n"
                     "*SURFACE, NAME=S\nPLATE, S2\n"
                     "*STEP\n*DYNAMIC, EXPLICIT\n, 1e-3\n"
                     "*DLOAD\nBRICKS, P, 1.\n"
                     "*DSLOAD\nS, P, 1.\n"
                     "*END STEP\n";
  deck.replace(deck.find("0.002\n"), 6, "0.002, 2\n");
  deck.replace(deck.find("*SOLID SECTION, ELSET=BRICKS"), 28, "*SOLID SECTION, ELSET=ALLN");
  deck.insert(deck.find("*MATERIAL, NAME=STEEL"), "*ELSET, ELSET=ALLN\n5000001, 11\n");
  const auto errors = deck_errors(deck);
  const std::vector<std::string> expected = {
      at(deck, "0.002, 2", "*SHELL SECTION") +
          "number of integration points 2 is even; "
          "expected an odd number of points from 1 to 99 "
          "(Simpson's rule through the thickness), e.g. 5",
      at(deck, "*ELEMENT, TYPE=S3R", "*ELEMENT") +
          "element type S3R is not supported; nearest supported: S4R (four-node quadrilateral "
          "shell, reduced integration); supported: C3D8R, C3D8, S4R (S4 is run as S4R), MASS, "
          "ROTARYI; CPS4, CPS3, T3D2, T3D3 without a section are read as geometry",
      at(deck, "*SOLID SECTION", "*SOLID SECTION") +
          "element 11 is an S4R shell element; expected a *SHELL SECTION for it (*SOLID SECTION "
          "is for C3D8R and C3D8 elements)",
      at(deck, "5000002,", "*ELEMENT") +
          "element 5000002 has no section; expected a *SOLID SECTION covering it",
      at(deck, "PLATE, S2", "*SURFACE") +
          "face S2 does not fit S4R element 11 of set PLATE; "
          "expected SPOS or SNEG on S4R shell elements",
      at(deck, "BRICKS, P", "*DLOAD") +
          "load type P does not fit C3D8R element 5000001 of set BRICKS; expected P1..P6 on "
          "C3D8R solid elements (faces S1..S6)",
      at(deck, "82, 1", "*ELEMENT") +
          "degenerate element 82: node 2 appears twice; expected 4 "
          "distinct corner nodes (triangles and collapsed "
          "quadrilaterals are not supported)",
  };
  CHECK(errors == expected);
}
