// Bad shell input: *SHELL SECTION values, sections of the wrong kind, degenerate S4R
// elements, faces and load types that do not fit the element. Exact messages.

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

const std::string SECTION_LINE = "*SHELL SECTION, ELSET=PLATE, MATERIAL=ALU";

/// The plate deck with the section's keyword line and data line replaced.
std::string plate_with_section(const std::string& keyword_line, const std::string& data) {
  std::string deck = shell_plate_model() + simple_step();
  const std::string old = SECTION_LINE + "\n0.002\n";
  deck.replace(deck.find(old), old.size(), keyword_line + "\n" + data);
  return deck;
}

const std::string POINTS_EXPECTED =
    "expected an odd number of points from 1 to 99 (Simpson's rule through the thickness), "
    "e.g. 5";

}  // namespace

TEST_CASE("the plate deck reads without errors", "[io][deck][shell][errors]") {
  CHECK(deck_errors(shell_plate_model() + simple_step()).empty());
  CHECK(deck_errors(two_brick_model() + shell_plate_model() + simple_step()).empty());
}

TEST_CASE("bad shell thickness and integration points: one error each",
          "[io][deck][shell][errors]") {
  const std::string p = "t.inp:17: *SHELL SECTION: ";
  const std::pair<std::string, std::string> cases[] = {
      {"-1\n", p + "shell thickness -1 is not positive; expected a thickness > 0"},
      {"0\n", p + "shell thickness 0 is not positive; expected a thickness > 0"},
      {"abc\n", p + "bad number 'abc' for shell thickness; expected a real number such as 2, "
                    "-1.5, 1e3 or 1.0D3"},
      {", 5\n", p + "missing shell thickness; expected a data line: thickness[, number of "
                    "integration points]"},
      {"",
       "t.inp:16: *SHELL SECTION: missing shell thickness; expected a data line: "
       "thickness[, number of integration points]"},
      {"0.002, 0\n", p + "number of integration points 0 is less than 1; " + POINTS_EXPECTED},
      {"0.002, 4\n", p + "number of integration points 4 is even; " + POINTS_EXPECTED},
      {"0.002, 2.5\n", p + "bad number of integration points '2.5'; " + POINTS_EXPECTED},
      {"0.002, 101\n", p + "number of integration points 101 is too large; " + POINTS_EXPECTED},
      {"0.002, 5, 3\n", p + "too many values (3) on the data line; expected thickness[, number "
                            "of integration points]"},
      {"0.002\n0.003\n",
       "t.inp:18: *SHELL SECTION: unexpected second data line; expected one "
       "data line: thickness[, number of integration points] (composite "
       "layups are not supported)"},
  };
  for (const auto& [data, message] : cases) {
    const auto errors = deck_errors(plate_with_section(SECTION_LINE, data));
    INFO("data line: " << data);
    REQUIRE(errors.size() == 1);
    CHECK(errors[0] == message);
  }
}

TEST_CASE("bad *SHELL SECTION parameters", "[io][deck][shell][errors]") {
  const std::string p = "t.inp:16: *SHELL SECTION: ";
  const std::pair<std::string, std::string> cases[] = {
      {", SECTION INTEGRATION=GAUSS",
       p + "SECTION INTEGRATION=GAUSS is not supported yet; supported: SECTION "
           "INTEGRATION=SIMPSON (the default)"},
      {", SECTION INTEGRATION=TRAPEZ",
       p + "unknown SECTION INTEGRATION=TRAPEZ; expected SECTION INTEGRATION=SIMPSON"},
      {", OFFSET=TOP",
       p + "unknown OFFSET=TOP; expected OFFSET=SPOS, SNEG, MIDSURFACE or a fraction of the "
           "thickness between -0.5 and 0.5"},
      {", OFFSET=0.7",
       p + "OFFSET=0.7 is outside [-0.5, 0.5]; expected a fraction of the thickness between "
           "-0.5 (SNEG) and 0.5 (SPOS)"},
      {", OFFSET=-1e0",
       p + "OFFSET=-1 is outside [-0.5, 0.5]; expected a fraction of the thickness between "
           "-0.5 (SNEG) and 0.5 (SPOS)"},
      {", CONTROLS=HG", p + "undefined section controls HG; expected *SECTION CONTROLS, NAME=HG"},
      {", ROTARY INERTIA=FULL",
       p + "unknown ROTARY INERTIA=FULL; expected ROTARY INERTIA=ISOTROPIC (the default, scaled "
           "to keep the membrane increment) or EXACT (t^2/12, with a smaller increment on thin "
           "elements)"},
      {", ORIENTATION=O1",
       p + "unknown parameter ORIENTATION; accepted parameters: ELSET=, MATERIAL=, OFFSET=, "
           "CONTROLS=, SECTION INTEGRATION=, ROTARY INERTIA="},
  };
  for (const auto& [extra, message] : cases) {
    const auto errors = deck_errors(plate_with_section(SECTION_LINE + extra, "0.002\n"));
    INFO("parameters: " << extra);
    REQUIRE(errors.size() == 1);
    CHECK(errors[0] == message);
  }
}

TEST_CASE("undefined element set and material of a shell section", "[io][deck][shell][errors]") {
  const auto errors =
      deck_errors(plate_with_section("*SHELL SECTION, ELSET=NOPE, MATERIAL=STEEL", "0.002\n"));
  REQUIRE(errors.size() == 4);
  CHECK(has_message(errors,
                    "t.inp:16: *SHELL SECTION: undefined material STEEL; expected *MATERIAL, "
                    "NAME=STEEL"));
  CHECK(has_message(errors,
                    "t.inp:16: *SHELL SECTION: undefined element set NOPE; expected *ELSET, "
                    "ELSET=NOPE or *ELEMENT, ELSET="));
  CHECK(has_message(errors,
                    "t.inp:9: *ELEMENT: element 11 has no section; expected a *SHELL SECTION "
                    "covering it"));
  CHECK(has_message(errors,
                    "t.inp:10: *ELEMENT: element 12 has no section; expected a *SHELL SECTION "
                    "covering it"));
}

TEST_CASE("a section of the wrong kind names the element", "[io][deck][shell][errors]") {
  std::string deck = two_brick_model() + shell_plate_model() + simple_step();
  deck.replace(deck.find("*SOLID SECTION, ELSET=BRICKS"), 28, "*SOLID SECTION, ELSET=PLATE");
  deck.replace(deck.find("*SHELL SECTION, ELSET=PLATE"), 27, "*SHELL SECTION, ELSET=BRICKS");
  const auto errors = deck_errors(deck);
  const std::string solid = at(deck, "*SOLID SECTION", "*SOLID SECTION");
  const std::string shell = at(deck, "*SHELL SECTION", "*SHELL SECTION");
  REQUIRE(errors.size() == 4);
  CHECK(has_message(errors, solid +
                                "element 11 is an S4R shell element; expected a *SHELL "
                                "SECTION for it (*SOLID SECTION is for C3D8R and C3D8 elements)"));
  CHECK(has_message(errors, solid +
                                "element 12 is an S4R shell element; expected a *SHELL "
                                "SECTION for it (*SOLID SECTION is for C3D8R and C3D8 elements)"));
  CHECK(has_message(errors, shell + "element 5000001 is a C3D8R solid element; expected a *SOLID "
                                    "SECTION for it (*SHELL SECTION is for S4R elements)"));
  CHECK(has_message(errors, shell + "element 5000002 is a C3D8R solid element; expected a *SOLID "
                                    "SECTION for it (*SHELL SECTION is for S4R elements)"));
}

TEST_CASE("two shell sections on one element", "[io][deck][shell][errors]") {
  const std::string deck =
      shell_plate_model() + "*SHELL SECTION, ELSET=PLATE, MATERIAL=ALU\n0.001\n" + simple_step();
  const auto errors = deck_errors(deck);
  REQUIRE(errors.size() == 2);
  CHECK(errors[0] ==
        "t.inp:18: *SHELL SECTION: element 11 already has the section at t.inp:16; expected "
        "each element in exactly one *SHELL SECTION");
}

TEST_CASE("*SHELL GENERAL SECTION is refused once, without follow-up errors",
          "[io][deck][shell][errors]") {
  const auto errors = deck_errors(
      plate_with_section("*SHELL GENERAL SECTION, ELSET=PLATE, MATERIAL=ALU", "0.002\n"));
  REQUIRE(errors.size() == 1);
  CHECK(errors[0] ==
        "t.inp:16: *SHELL GENERAL SECTION: general shell sections (section stiffness given "
        "directly) are not supported; expected *SHELL SECTION, ELSET=, MATERIAL= with the "
        "thickness on the data line");
}

TEST_CASE("S4R element with a wrong node count", "[io][deck][shell][errors]") {
  std::string deck = shell_plate_model() + simple_step();
  deck.replace(deck.find("11, 1, 2, 5, 4"), 14, "11, 1, 2, 5");
  const auto errors = deck_errors(deck);
  REQUIRE(errors.size() == 1);
  CHECK(errors[0] ==
        "t.inp:9: *ELEMENT: element 11 has 3 node ids; expected 4 node ids for S4R (end a line "
        "with a comma to continue it)");
}

TEST_CASE("degenerate and crossed S4R elements", "[io][deck][shell][errors]") {
  const std::string distinct =
      "expected 4 distinct corner nodes (triangles and collapsed quadrilaterals are not "
      "supported)";
  SECTION("a repeated node") {
    std::string deck = shell_plate_model() + simple_step();
    deck.replace(deck.find("11, 1, 2, 5, 4"), 14, "11, 1, 2, 2, 4");
    const auto errors = deck_errors(deck);
    REQUIRE(errors.size() == 1);
    CHECK(errors[0] ==
          "t.inp:9: *ELEMENT: degenerate element 11: node 2 appears twice; " + distinct);
  }
  SECTION("two nodes at the same place") {
    std::string deck = shell_plate_model() + simple_step();
    deck.replace(deck.find("4, 0, 1, 0"), 10, "4, 1, 1, 0");
    const auto errors = deck_errors(deck);
    REQUIRE(errors.size() == 1);
    CHECK(errors[0] ==
          "t.inp:9: *ELEMENT: degenerate element 11: nodes 5 and 4 are at the same place; " +
              distinct);
  }
  SECTION("zero area, crossed; a concave element is accepted") {
    const std::string deck = shell_plate_model() +
                             "*NODE\n"
                             "21, 0, 0, 5\n22, 1, 0, 5\n23, 2, 0, 5\n24, 3, 0, 5\n"
                             "41, 0, 0, 7\n42, 2, 0, 7\n43, 0, 1, 7\n44, 1, 1, 7\n"
                             "61, 0, 0, 9\n62, 2, 0, 9\n63, 0.5, 0.5, 9\n64, 0, 2, 9\n"
                             "*ELEMENT, TYPE=S4R, ELSET=PLATE\n"
                             "31, 21, 22, 23, 24\n"
                             "51, 41, 42, 43, 44\n"
                             "71, 61, 62, 63, 64\n" +
                             simple_step();
    const auto errors = deck_errors(deck);
    REQUIRE(errors.size() == 2);
    CHECK(errors[0] == at(deck, "31, 21", "*ELEMENT") +
                           "degenerate element 31: area 0 with edges up to 3; expected 4 corner "
                           "nodes in order around a quadrilateral of non-zero area");
    CHECK(errors[1] == at(deck, "51, 41", "*ELEMENT") +
                           "crossed element 51: seen along its normal, edges 1-2 and 3-4 or 2-3 "
                           "and 4-1 cross; expected 4 corner nodes in order around the "
                           "quadrilateral");
  }
}

TEST_CASE("faces that do not fit the element type", "[io][deck][shell][errors]") {
  const std::string deck = two_brick_model() + shell_plate_model() +
                           "*SURFACE, NAME=BAD1\nPLATE, S1\n"
                           "*SURFACE, NAME=BAD2\nBRICKS, SPOS\n"
                           "*SURFACE, NAME=BAD3\n11, SIDE\n"
                           "*SURFACE, NAME=BAD4\n12, S3\n" +
                           simple_step();
  const auto errors = deck_errors(deck);
  REQUIRE(errors.size() == 4);
  CHECK(has_message(errors, at(deck, "PLATE, S1", "*SURFACE") +
                                "face S1 does not fit S4R element 11 of set PLATE; expected SPOS "
                                "or SNEG on S4R shell elements"));
  CHECK(has_message(errors, at(deck, "BRICKS, SPOS", "*SURFACE") +
                                "face SPOS does not fit C3D8R element 5000001 of set BRICKS; "
                                "expected S1..S6 on C3D8R solid elements"));
  CHECK(has_message(errors, at(deck, "11, SIDE", "*SURFACE") +
                                "bad face label SIDE; expected S1, S2, S3, S4, S5 or S6 on C3D8R "
                                "elements, SPOS or SNEG on S4R elements, or none (all exposed "
                                "faces, both sides of shells)"));
  CHECK(has_message(errors, at(deck, "12, S3", "*SURFACE") +
                                "face S3 does not fit S4R element 12; expected SPOS or SNEG on "
                                "S4R shell elements"));
}

TEST_CASE("*SECTION CONTROLS, PLASTIC HOURGLASS: TANGENT (the default) or ELASTIC",
          "[io][deck][shell][errors]") {
  auto with_controls = [](const std::string& parameters) {
    return plate_with_section(
        "*SECTION CONTROLS, NAME=HG" + parameters + "\n" + SECTION_LINE + ", CONTROLS=HG",
        "0.002\n");
  };
  const std::pair<std::string, bool> reads[] = {
      {"", false}, {", PLASTIC HOURGLASS=TANGENT", false}, {", PLASTIC HOURGLASS=ELASTIC", true}};
  for (const auto& [parameters, elastic] : reads) {
    INFO("parameters: " << parameters);
    const Model m = io::read_deck_text(with_controls(parameters), "t.inp");
    REQUIRE(m.section_controls.size() == 1);
    CHECK(m.section_controls[0].plastic_hourglass_elastic == elastic);
  }
  const auto errors = deck_errors(with_controls(", PLASTIC HOURGLASS=SOFT"));
  INFO(errors.size() << " errors; first: " << (errors.empty() ? "" : errors[0])
                     << "; second: " << (errors.size() > 1 ? errors[1] : ""));
  REQUIRE(errors.size() == 1);
  CHECK(errors[0] ==
        "t.inp:16: *SECTION CONTROLS: plastic hourglass control SOFT is not supported; expected "
        "PLASTIC HOURGLASS=TANGENT or ELASTIC");
}
