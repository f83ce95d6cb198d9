// Bad input: every error is reported as `file:LINE: *KEYWORD: problem; expected`, all at once.

#include <catch2/catch.hpp>

#include "deck/deck_test_support.hpp"

using namespace xpl;
using test::at;
using test::deck_errors;
using test::has_error;
using test::line_of;
using test::simple_step;
using test::two_brick_model;

TEST_CASE("the valid base deck reads without errors", "[io][deck][errors]") {
  CHECK(deck_errors(two_brick_model() + simple_step()).empty());
}

TEST_CASE("unknown keyword", "[io][deck][errors]") {
  const auto errors =
      deck_errors("*HEADING\nx\n*FOO, BAR=1\n1, 2\n" + two_brick_model() + simple_step());
  CHECK(has_error(errors,
                  "t.inp:3: *FOO: unknown keyword *FOO; supported keywords: ", "*SOLID SECTION"));
  CHECK(errors.size() == 1);
}

TEST_CASE("a part left open is one error, *PREPRINT is ignored", "[io][deck][errors]") {
  // Parts and assemblies themselves: test_deck_assembly.cpp.
  const std::string deck =
      "*PREPRINT, ECHO=NO\n*PART, NAME=P\n" + two_brick_model() + simple_step();
  const auto errors = deck_errors(deck);
  REQUIRE(errors.size() == 1);
  CHECK(has_error(errors, at(deck, "*STEP", "*STEP") +
                              "part P is not closed; expected *END PART before *STEP"));
}

TEST_CASE("a refused element type is one error, not also its sets, sections and surfaces",
          "[io][deck][errors]") {
  // CalculiX decks with C3D20R: the elements are refused, and everything that names them
  // (their ELSET=, an *ELSET over their ids, a section, a surface) would otherwise repeat that
  // one cause as "undefined" errors.
  const std::string deck = two_brick_model() +
                           "*ELEMENT, TYPE=C3D20R, ELSET=QUAD\n"
                           "7000001, 1000001, 1000002, 1000003, 1000004, 1000007, 1000008, "
                           "1000009, 1000010, 1000001, 1000002, 1000003, 1000004, 1000007, "
                           "1000008, 1000009, 1000010, 1000001, 1000002, 1000003, 1000004\n"
                           "*ELSET, ELSET=RANGE, GENERATE\n"
                           "7000001, 7000001\n"
                           "*ELSET, ELSET=NAMED\n"
                           "QUAD, 7000001\n"
                           "*NSET, NSET=OF_QUAD, ELSET=QUAD\n"
                           "*SOLID SECTION, ELSET=QUAD, MATERIAL=STEEL\n"
                           "*SURFACE, NAME=QS\n"
                           "7000001, S1\n"
                           "QUAD, S2\n"
                           "*ELSET, ELSET=TYPO\n"
                           "7000002\n" +
                           simple_step();
  const auto errors = deck_errors(deck);
  INFO(errors.size() << " errors, first: " << (errors.empty() ? "" : errors.front()));
  CHECK(has_error(errors, at(deck, "TYPE=C3D20R", "*ELEMENT"), "C3D20R is not supported"));
  // An id that no block defined is still an error of its own.
  CHECK(has_error(errors, at(deck, "7000002", "*ELSET"), "undefined element 7000002"));
  CHECK(errors.size() == 2);
}

TEST_CASE("bad numbers name the token", "[io][deck][errors]") {
  std::string deck = two_brick_model() + simple_step();
  deck.replace(deck.find("1000002, 1, 0, 0"), 16, "1000002, 1.0e, 0, 0");
  deck.replace(deck.find("7800."), 5, "abc");
  const auto errors = deck_errors(deck);
  CHECK(has_error(errors, at(deck, "1000002, 1.0e", "*NODE") + "bad number '1.0e'"));
  CHECK(has_error(errors, at(deck, "abc", "*DENSITY") + "bad number 'abc'"));
}

TEST_CASE("a bad coordinate is one error, not also an inverted element", "[io][deck][errors]") {
  std::string deck = two_brick_model() + simple_step();
  deck.replace(deck.find("1000002, 1, 0, 0"), 16, "1000002, 1.0x, 0, 0");
  const auto errors = deck_errors(deck);
  CHECK(has_error(errors, at(deck, "1000002, 1.0x", "*NODE") + "bad number '1.0x'"));
  CHECK(errors.size() == 1);
}

TEST_CASE("missing material", "[io][deck][errors]") {
  std::string deck = two_brick_model() + simple_step();
  deck.replace(deck.find("MATERIAL=STEEL"), 14, "MATERIAL=ALU");
  const auto errors = deck_errors(deck);
  CHECK(has_error(errors, at(deck, "*SOLID SECTION", "*SOLID SECTION") +
                              "undefined material ALU; expected *MATERIAL, NAME=ALU"));
}

TEST_CASE("material without elastic data", "[io][deck][errors]") {
  std::string deck = two_brick_model() + simple_step();
  deck.replace(deck.find("*ELASTIC\n2.1e11, 0.3\n"), 21, "");
  const auto errors = deck_errors(deck);
  CHECK(has_error(errors, at(deck, "*MATERIAL", "*MATERIAL") + "material STEEL has no elastic"));
}

TEST_CASE("undefined set", "[io][deck][errors]") {
  const std::string deck = two_brick_model() +
                           "*STEP\n*DYNAMIC, EXPLICIT\n, 1.\n*BOUNDARY\nNOPE, ENCASTRE\n"
                           "*END STEP\n";
  const auto errors = deck_errors(deck);
  CHECK(has_error(errors, at(deck, "NOPE", "*BOUNDARY") +
                              "undefined node set NOPE; expected *NSET, NSET=NOPE"));
}

TEST_CASE("element with a missing node", "[io][deck][errors]") {
  std::string deck = two_brick_model() + simple_step();
  deck.replace(deck.find("1000011, 1000012, 1000009"), 25, "1000011, 99, 1000009");
  const auto errors = deck_errors(deck);
  CHECK(has_error(errors,
                  at(deck, "5000002", "*ELEMENT") + "element 5000002 refers to undefined node 99"));
}

TEST_CASE("inverted element", "[io][deck][errors]") {
  std::string deck = two_brick_model() + simple_step();
  // Swap bottom and top faces of the first brick: negative Jacobian everywhere.
  const std::string good =
      "5000001, 1000001, 1000002, 1000003, 1000004, 1000007, 1000008, "
      "1000009, 1000010";
  const std::string bad =
      "5000001, 1000007, 1000008, 1000009, 1000010, 1000001, 1000002, "
      "1000003, 1000004";
  deck.replace(deck.find(good), good.size(), bad);
  const auto errors = deck_errors(deck);
  REQUIRE(errors.size() == 1);
  CHECK(has_error(errors,
                  at(deck, "5000001,", "*ELEMENT") +
                      "inverted element 5000001: volume -1 at corner node 1000007",
                  "positive Jacobian"));
}

TEST_CASE("unknown and missing parameters", "[io][deck][errors]") {
  std::string deck = two_brick_model() + simple_step();
  deck.replace(deck.find("*NODE, NSET=ALLN"), 16, "*NODE, NSET=ALLN, FOO=1");
  deck.replace(deck.find("*MATERIAL, NAME=STEEL"), 21, "*MATERIAL");
  const auto errors = deck_errors(deck);
  CHECK(has_error(errors, "t.inp:1: *NODE: unknown parameter FOO; accepted parameters: NSET="));
  CHECK(has_error(errors, at(deck, "*MATERIAL", "*MATERIAL") + "missing parameter NAME"));
}

TEST_CASE("two errors in one deck are both reported", "[io][deck][errors]") {
  std::string deck = two_brick_model() + simple_step();
  deck.replace(deck.find("2.1e11, 0.3"), 11, "-2.1e11, 0.5");
  const auto errors = deck_errors(deck);
  REQUIRE(errors.size() >= 2);
  CHECK(has_error(errors, at(deck, "-2.1e11", "*ELASTIC") + "Young's modulus -2.1e+11"));
  CHECK(has_error(errors, at(deck, "-2.1e11", "*ELASTIC") + "Poisson's ratio 0.5 is out of range"));
}

TEST_CASE("unsupported element type, implicit dynamics, no step", "[io][deck][errors]") {
  const auto no_step = deck_errors(two_brick_model() + "*ELEMENT, TYPE=S3R\n1, 1, 2, 3\n");
  CHECK(has_error(no_step,
                  "t.inp:23: *ELEMENT: element type S3R is not supported; nearest supported: S4R "
                  "(four-node quadrilateral shell, reduced integration); supported: C3D8R, C3D8, "
                  "S4R (S4 is run as S4R)"));
  CHECK(has_error(no_step, "t.inp: the deck has no step"));
  const auto implicit = deck_errors(two_brick_model() + "*STEP\n*DYNAMIC\n0.1, 1.\n*END STEP\n");
  CHECK(has_error(implicit,
                  "t.inp:24: *DYNAMIC: implicit dynamics is not supported; expected "
                  "*DYNAMIC, EXPLICIT"));
}

TEST_CASE("element without section and element in two sections", "[io][deck][errors]") {
  std::string deck = two_brick_model() + simple_step();
  deck.replace(deck.find("ELSET=BRICKS, MATERIAL"), 12, "ELSET=FIRST");
  deck.insert(deck.find("*MATERIAL"), "*ELSET, ELSET=FIRST\n5000001\n");
  const auto missing = deck_errors(deck);
  CHECK(has_error(missing, at(deck, "5000002,", "*ELEMENT") +
                               "element 5000002 has no section; expected a *SOLID SECTION "
                               "covering it"));
  const std::string twice =
      two_brick_model() + "*SOLID SECTION, ELSET=BRICKS, MATERIAL=STEEL\n" + simple_step();
  CHECK(has_error(deck_errors(twice),
                  "t.inp:23: *SOLID SECTION: element 5000001 already has "
                  "the section at t.inp:22"));
}

TEST_CASE("keywords in the wrong place", "[io][deck][errors]") {
  const std::string deck = two_brick_model() +
                           "*CLOAD\n1000001, 1, 1.\n"
                           "*STEP\n*DYNAMIC, EXPLICIT\n, 1.\n"
                           "*NODE\n99, 0, 0, 0\n"
                           "*END STEP\n";
  const auto errors = deck_errors(deck);
  CHECK(has_error(errors, "t.inp:23: *CLOAD: history data outside a step"));
  CHECK(has_error(errors, "t.inp:28: *NODE: model data cannot appear inside a step"));
}

TEST_CASE("output, amplitude and dof errors", "[io][deck][errors]") {
  const std::string deck = two_brick_model() +
                           "*AMPLITUDE, NAME=BACK\n0, 0, 1, 1, 0.5, 2\n"
                           "*STEP\n*DYNAMIC, EXPLICIT\n, 0.\n"
                           "*BOUNDARY, AMPLITUDE=MISSING\n1000001, 7\n1000002, 1, 1\n"
                           "*OUTPUT, FIELD, NUMBER INTERVAL=5, TIME INTERVAL=1.\n"
                           "*OUTPUT, HISTORY\n*NODE OUTPUT\nU1\n"
                           "*OUTPUT, FIELD\n*NODE OUTPUT\nU, PEEQ\n"
                           "*END STEP\n";
  const auto errors = deck_errors(deck);
  CHECK(has_error(errors, "t.inp:24: *AMPLITUDE: time 0.5 is before the previous 1"));
  CHECK(has_error(errors, "t.inp:27: *DYNAMIC: time period 0 is not positive"));
  CHECK(has_error(errors, "t.inp:29: *BOUNDARY: bad dof range 7..7"));
  CHECK(has_error(errors, "t.inp:30: *BOUNDARY: undefined amplitude MISSING"));
  CHECK(has_error(errors, "t.inp:31: *OUTPUT: both NUMBER INTERVAL and TIME INTERVAL"));
  CHECK(has_error(errors, "t.inp:33: *NODE OUTPUT: history node output needs a node set"));
  CHECK(has_error(errors,
                  "t.inp:37: *NODE OUTPUT: unknown output variable PEEQ; expected one "
                  "of U, V, A, RF"));
}

TEST_CASE("circular sets and bad set entries", "[io][deck][errors]") {
  const std::string deck = two_brick_model() +
                           "*NSET, NSET=A\nB\n"
                           "*NSET, NSET=B\nA, 77\n"
                           "*ELSET, ELSET=E, GENERATE\n5000003, 5000009\n" +
                           simple_step();
  const auto errors = deck_errors(deck);
  CHECK(has_error(errors, "t.inp:26: *NSET: node set B includes A, which includes B again"));
  CHECK(has_error(errors, "t.inp:26: *NSET: undefined node 77"));
  CHECK(has_error(errors, "t.inp:28: *ELSET: range 5000003..5000009 contains no defined element"));
}

TEST_CASE("a bad density is reported once, without follow-up errors", "[io][deck][errors]") {
  std::string deck = two_brick_model() + simple_step();
  const std::size_t density = deck.find("7800.");
  REQUIRE(density != std::string::npos);
  deck = deck.substr(0, density) + "-1" + deck.substr(density + 5);
  const auto errors = deck_errors(deck);
  REQUIRE(errors.size() == 1);
  CHECK(
      has_error(errors, "t.inp:19: *DENSITY: density -1 is not positive; expected a density > 0"));
}
