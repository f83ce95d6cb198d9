// The *DYNAMIC, EXPLICIT data line as Abaqus and CalculiX write it (initial increment noted and
// ignored, minimum increment warned about, maximum increment kept, ELEMENT BY ELEMENT accepted),
// C3D8 elements (and C3D8I refused), and *FIXED MASS SCALING, with their deck errors.

#include <catch2/catch.hpp>

#include "deck/deck_test_support.hpp"

using namespace xpl;
using test::at;
using test::deck_errors;
using test::has_error;
using test::two_brick_model;

namespace {

Model read(const std::string& deck) {
  return io::read_deck_text(deck, "t.inp", io::ModelChecks::Skip);
}

std::string step_with(const std::string& dynamic) {
  return "*STEP\n" + dynamic + "*END STEP\n";
}

bool has_text(const Model& m, const std::string& text, bool warning) {
  for (const DeckMessage& d : m.deck_messages)
    if (d.text == text && d.warning == warning) return true;
  return false;
}

}  // namespace

TEST_CASE("*DYNAMIC, EXPLICIT: CalculiX's initial, minimum, maximum and CFD increments",
          "[io][deck][dynamic][calculix]") {
  const std::string deck =
      two_brick_model() + step_with("*DYNAMIC,EXPLICIT\n1.E-8,5.E-6,5.E-7,2.5E-8,1e-2\n");
  const Model m = read(deck);
  REQUIRE(m.steps.size() == 1);
  const Step& s = m.steps[0];
  CHECK(s.time_period == 5e-6);
  CHECK_FALSE(s.increment.fixed.has_value());
  REQUIRE(s.increment.max.has_value());
  CHECK(*s.increment.max == 2.5e-8);
  const std::string where = at(deck, "1.E-8", "*DYNAMIC");
  CHECK(has_text(m,
                 where + "initial time increment 1e-08 ignored: without DIRECT USER CONTROL "
                         "every increment is the stable one (as CalculiX's explicit solver does)",
                 false));
  CHECK(has_text(m,
                 where + "minimum time increment 5e-07 (CalculiX's third value) ignored: xpl "
                         "never cuts an explicit increment back and does no selective mass "
                         "scaling to reach it (*FIXED MASS SCALING, DT= scales the mass to a "
                         "target increment)",
                 true));
  CHECK(has_text(m, where + "initial CFD time increment 0.01 ignored (xpl has no fluid)", false));
}

TEST_CASE("*DYNAMIC, EXPLICIT: Abaqus' maximum increment, ELEMENT BY ELEMENT, EXPLICIT=3",
          "[io][deck][dynamic]") {
  const std::string deck =
      two_brick_model() + step_with("*DYNAMIC, EXPLICIT, ELEMENT BY ELEMENT\n, 1e-3, , 2e-6\n") +
      step_with("*DYNAMIC, EXPLICIT=3\n, 1e-3\n") +
      step_with("*DYNAMIC, EXPLICIT, DIRECT USER CONTROL\n1e-7, 1e-3, , 2e-6\n");
  const Model m = read(deck);
  REQUIRE(m.steps.size() == 3);
  REQUIRE(m.steps[0].increment.max.has_value());
  CHECK(*m.steps[0].increment.max == 2e-6);
  CHECK_FALSE(m.steps[1].increment.max.has_value());
  CHECK_FALSE(m.steps[1].increment.fixed.has_value());
  CHECK(*m.steps[2].increment.fixed == 1e-7);
  CHECK_FALSE(m.steps[2].increment.max.has_value());
  CHECK(has_text(m,
                 at(deck, "*DYNAMIC, EXPLICIT, ELEMENT", "*DYNAMIC") +
                     "ELEMENT BY ELEMENT: the stable increment is xpl's element-by-element "
                     "estimate, which a global estimate only ever shortens (meshes with few "
                     "neighbours)",
                 false));
  CHECK(has_text(m,
                 at(deck, "1e-7, 1e-3", "*DYNAMIC") +
                     "maximum time increment 2e-06 not used: DIRECT USER CONTROL fixes the "
                     "increment",
                 false));
}

TEST_CASE("*DYNAMIC, EXPLICIT: wrong values are errors at their line", "[io][deck][dynamic]") {
  const std::string deck = two_brick_model() + step_with("*DYNAMIC, EXPLICIT\n-1e-8, 1e-3, , 0\n") +
                           step_with("*DYNAMIC, EXPLICIT\n, 1e-3, x\n") +
                           step_with("*DYNAMIC, EXPLICIT=1\n, 1e-3\n") +
                           step_with("*DYNAMIC, EXPLICIT, DIRECT USER CONTROL\n, 1e-3\n") +
                           step_with("*DYNAMIC, EXPLICIT\n, 1e-3, , , , 7\n");
  const auto errors = deck_errors(deck);
  CHECK(has_error(errors, at(deck, "-1e-8", "*DYNAMIC") + "time increment -1e-08 is not positive",
                  "expected a time increment > 0 or blank"));
  CHECK(has_error(errors, at(deck, "-1e-8", "*DYNAMIC") + "maximum time increment 0 is not "
                                                          "positive"));
  CHECK(has_error(errors,
                  at(deck, "1e-3, x", "*DYNAMIC") + "bad number 'x' for minimum time increment"));
  CHECK(has_error(errors, at(deck, "EXPLICIT=1", "*DYNAMIC") +
                              "EXPLICIT=1 (CalculiX: implicit structural computation) is not "
                              "supported"));
  CHECK(has_error(
      errors, "t.inp:" + std::to_string(test::line_of(deck, "DIRECT USER CONTROL\n, 1e-3") + 1) +
                  ": *DYNAMIC: DIRECT USER CONTROL without a time increment"));
  CHECK(has_error(errors, at(deck, "1e-3, , , , 7", "*DYNAMIC")));
  CHECK(errors.size() == 6);
}

TEST_CASE("C3D8 is read; C3D8I is refused with a clear message", "[io][deck][c3d8]") {
  std::string deck = two_brick_model() + test::simple_step();
  deck.replace(deck.find("TYPE=C3D8R"), 10, "TYPE=C3D8");
  const Model m = read(deck);
  REQUIRE(m.element_count() == 2);
  CHECK(m.element_types[0] == ElementType::C3D8);
  CHECK(is_hex(m.element_types[1]));
  std::string bad = two_brick_model() + test::simple_step();
  bad.replace(bad.find("TYPE=C3D8R"), 10, "TYPE=C3D8I");
  CHECK(has_error(deck_errors(bad),
                  at(bad, "*ELEMENT", "*ELEMENT") +
                      "element type C3D8I (incompatible modes) is not supported; expected C3D8"));
}

TEST_CASE("*FIXED MASS SCALING: FACTOR, DT, TYPE, ELSET", "[io][deck][mass-scaling]") {
  const std::string deck = two_brick_model() +
                           "*STEP\n*DYNAMIC, EXPLICIT\n, 1e-3\n"
                           "*FIXED MASS SCALING, FACTOR=4\n"
                           "*FIXED MASS SCALING, DT=1e-6, TYPE=UNIFORM, ELSET=BRICKS\n"
                           "*FIXED MASS SCALING, DT=2e-6\n"
                           "*END STEP\n";
  const Model m = read(deck);
  const std::vector<FixedMassScaling>& s = m.steps[0].mass_scaling;
  REQUIRE(s.size() == 3);
  CHECK(s[0].factor == 4.0);
  CHECK_FALSE(s[0].dt.has_value());
  CHECK(s[0].element_set == NO_INDEX);
  CHECK(s[1].factor == 1.0);
  CHECK(*s[1].dt == 1e-6);
  CHECK(s[1].type == FixedMassScaling::Type::Uniform);
  CHECK(s[1].element_set == m.find_element_set("BRICKS"));
  CHECK(s[2].type == FixedMassScaling::Type::BelowMin);
}

TEST_CASE("*FIXED MASS SCALING: errors", "[io][deck][mass-scaling][errors]") {
  const std::string deck = two_brick_model() +
                           "*STEP\n*DYNAMIC, EXPLICIT\n, 1e-3\n"
                           "*FIXED MASS SCALING, FACTOR=-2\n"
                           "*FIXED MASS SCALING, TYPE=UNIFORM\n"
                           "*FIXED MASS SCALING, DT=1e-6, TYPE=ABOVE\n"
                           "*FIXED MASS SCALING, ELSET=NOPE, FACTOR=2\n"
                           "*FIXED MASS SCALING\n"
                           "*END STEP\n"
                           "*STEP\n*DYNAMIC, EXPLICIT\n, 1e-3\n"
                           "*FIXED MASS SCALING, FACTOR=2\n"
                           "*END STEP\n";
  const auto errors = deck_errors(deck);
  const std::string k = "*FIXED MASS SCALING";
  CHECK(has_error(errors, at(deck, "FACTOR=-2", k) + "bad FACTOR=-2; expected a number > 0"));
  CHECK(has_error(errors, at(deck, "TYPE=UNIFORM\n", k) + "TYPE=UNIFORM without DT="));
  CHECK(has_error(errors, at(deck, "TYPE=ABOVE", k) + "bad TYPE=ABOVE"));
  CHECK(has_error(errors, at(deck, "ELSET=NOPE", k) + "undefined element set NOPE"));
  CHECK(has_error(errors, at(deck, "SCALING\n*END", k) + "no scaling given"));
  CHECK(has_error(errors, at(deck, "FACTOR=2\n*END", k) + "fixed mass scaling in step 2",
                  "first step only"));
  for (const std::string& e : errors) UNSCOPED_INFO(e);
  CHECK(errors.size() == 6);
}
