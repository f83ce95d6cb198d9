// Bad contact, gravity and contact output input: every error of a deck at once, each as
// `file:LINE: *KEYWORD: problem; expected`.

#include <catch2/catch.hpp>

#include "deck/deck_test_support.hpp"

using namespace xpl;
using test::at;
using test::deck_errors;
using test::line_of;
using test::shell_plate_model;
using test::two_brick_model;

namespace {

const std::string PAIR_LINE =
    "surface 1, surface 2 (surface 1 blank: all exterior faces; surface 2 blank: self contact "
    "of surface 1)";

}  // namespace

TEST_CASE("contact errors are all reported, each at its line", "[io][deck][contact][errors]") {
  const std::string deck = two_brick_model() + shell_plate_model() +
                           "*SURFACE, NAME=TOP\nPLATE, SPOS\n"
                           "*SURFACE, NAME=PTS, TYPE=NODE\nPLATE_NODES\n"
                           "*CONTACT\n"
                           "*CONTACT INCLUSIONS, ALL EXTERIOR\n"
                           "*SURFACE INTERACTION\n"
                           "*FRICTION\n0.1\n"
                           "*SURFACE INTERACTION, NAME=A\n"
                           "*FRICTION\n-0.2\n"
                           "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=EXPONENTIAL\n"
                           "*SURFACE INTERACTION, NAME=B\n"
                           "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n-1e9\n"
                           "*SURFACE BEHAVIOR\n"
                           "*SURFACE INTERACTION, NAME=C\n"
                           "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n"
                           "*SURFACE INTERACTION, NAME=D\n"
                           "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=TIED\n"
                           "*FRICTION\n0.1\n0.2\n"
                           "*SURFACE INTERACTION, NAME=A\n"
                           "*CONTACT PAIR, INTERACTION=NOPE\nTOP, GHOST\n"
                           "*CONTACT PAIR, INTERACTION=A, TYPE=EDGE\nTOP\nTOP, PTS\n"
                           "*STEP\n*DYNAMIC, EXPLICIT\n, 1e-3\n"
                           "*CONTACT INCLUSIONS\nTOP, TOP\n"
                           "*CONTACT, OP=REPLACE\n"
                           "*CONTACT INCLUSIONS\n"
                           "*CONTACT INCLUSIONS\nTOP, GHOST\n"
                           "*CONTACT EXCLUSIONS, ALL EXTERIOR\n"
                           "*CONTACT PROPERTY ASSIGNMENT\nTOP, TOP\n, , NOPE\n"
                           "*CONTACT CONTROLS ASSIGNMENT\n"
                           "*CONTACT CONTROLS ASSIGNMENT, TYPE=SCALE PENALTY\nTOP, , 2.\n, , -1\n"
                           "*CONTACT CONTROLS ASSIGNMENT, TYPE=ENHANCEMENT\n"
                           "*CONTACT\n"
                           "*END STEP\n"
                           "*CONTACT PAIR, INTERACTION=A\nTOP, TOP\n";
  const auto errors = deck_errors(deck);
  const std::vector<std::string> expected = {
      at(deck, "*CONTACT\n", "*CONTACT") +
          "general contact outside a step; expected *CONTACT and its options between *STEP and "
          "*END STEP, as in Abaqus/Explicit (*CONTACT PAIR may be model data)",
      at(deck, "*CONTACT INCLUSIONS, ALL", "*CONTACT INCLUSIONS") +
          "general contact outside a step; expected *CONTACT and its options between *STEP and "
          "*END STEP, as in Abaqus/Explicit (*CONTACT PAIR may be model data)",
      at(deck, "*SURFACE INTERACTION\n", "*SURFACE INTERACTION") +
          "missing parameter NAME; expected NAME=name",
      at(deck, "*FRICTION\n0.1", "*FRICTION") +
          "no surface interaction to attach to; expected *FRICTION right after *SURFACE "
          "INTERACTION, NAME=...",
      at(deck, "-0.2", "*FRICTION") +
          "friction coefficient -0.2 is negative; expected a coefficient >= 0",
      at(deck, "=EXPONENTIAL", "*SURFACE BEHAVIOR") +
          "PRESSURE-OVERCLOSURE=EXPONENTIAL is not supported yet; supported: "
          "PRESSURE-OVERCLOSURE=HARD (the default), LINEAR",
      at(deck, "-1e9", "*SURFACE BEHAVIOR") +
          "pressure-overclosure slope -1e+09 is not positive; expected a slope > 0 (contact "
          "pressure per unit overclosure, Pa/m)",
      at(deck, "*SURFACE BEHAVIOR\n*", "*SURFACE BEHAVIOR") +
          "surface interaction B already has *SURFACE BEHAVIOR; expected one *SURFACE BEHAVIOR "
          "per surface interaction",
      at(deck, "=LINEAR\n*SURFACE INTERACTION, NAME=D", "*SURFACE BEHAVIOR") +
          "missing pressure-overclosure slope; expected a data line: slope (contact pressure per "
          "unit overclosure, Pa/m)",
      at(deck, "=TIED", "*SURFACE BEHAVIOR") +
          "PRESSURE-OVERCLOSURE=TIED is not supported yet; supported: PRESSURE-OVERCLOSURE=HARD "
          "(the default), LINEAR",
      at(deck, "*FRICTION\n0.1\n0.2", "*FRICTION") +
          "found 2 data lines; expected one data line with the friction coefficient (no "
          "dependence on slip rate, pressure or temperature)",
      at(deck, "*SURFACE INTERACTION, NAME=A\n*CONTACT", "*SURFACE INTERACTION") +
          "surface interaction A is defined twice at t.inp:" +
          std::to_string(line_of(deck, "NAME=A\n*FRICTION")) +
          "; expected each surface interaction name once",
      at(deck, "TYPE=EDGE", "*CONTACT PAIR") +
          "unknown TYPE=EDGE; expected TYPE=NODE TO SURFACE, SURFACE TO SURFACE or MASSLESS "
          "(CalculiX)",
      at(deck, "TOP\nTOP, PTS", "*CONTACT PAIR") +
          "missing master surface; expected slave surface, master surface",
      at(deck, "*CONTACT INCLUSIONS\nTOP, TOP", "*CONTACT INCLUSIONS") +
          "no *CONTACT in step Step-1; expected *CONTACT before *CONTACT INCLUSIONS in the same "
          "step",
      at(deck, "OP=REPLACE", "*CONTACT") +
          "bad OP=REPLACE; expected OP=MOD (the default: add to the general contact of earlier "
          "steps) or OP=NEW",
      at(deck, "*CONTACT INCLUSIONS\n*CONTACT", "*CONTACT INCLUSIONS") +
          "no surface pairs; expected ALL EXTERIOR or data lines: " + PAIR_LINE,
      at(deck, "TOP, GHOST\n*CONTACT EX", "*CONTACT INCLUSIONS") +
          "undefined surface GHOST; expected *SURFACE, NAME=GHOST",
      at(deck, "*CONTACT EXCLUSIONS, ALL", "*CONTACT EXCLUSIONS") +
          "unknown parameter ALL EXTERIOR; accepted parameters: none",
      at(deck, "*CONTACT EXCLUSIONS, ALL", "*CONTACT EXCLUSIONS") +
          "no surface pairs; expected data lines: " + PAIR_LINE,
      at(deck, "TOP, TOP\n, , NOPE", "*CONTACT PROPERTY ASSIGNMENT") +
          "missing surface interaction name; expected surface 1, surface 2, interaction name "
          "(both surfaces blank: the global default)",
      at(deck, ", , NOPE", "*CONTACT PROPERTY ASSIGNMENT") +
          "undefined surface interaction NOPE; expected *SURFACE INTERACTION, NAME=NOPE",
      at(deck, "*CONTACT CONTROLS ASSIGNMENT\n", "*CONTACT CONTROLS ASSIGNMENT") +
          "missing parameter TYPE; expected TYPE=SCALE PENALTY",
      at(deck, "TOP, , 2.", "*CONTACT CONTROLS ASSIGNMENT") +
          "penalty scaling of a surface pair is not supported yet; expected both surfaces blank "
          "(the whole general contact): , , penalty scale factor",
      at(deck, ", , -1", "*CONTACT CONTROLS ASSIGNMENT") +
          "penalty scale factor -1 is not positive; expected a factor > 0",
      at(deck, "TYPE=ENHANCEMENT", "*CONTACT CONTROLS ASSIGNMENT") +
          "TYPE=ENHANCEMENT is not supported yet; supported: TYPE=SCALE PENALTY",
      at(deck, "*CONTACT\n*END STEP", "*CONTACT") +
          "second *CONTACT in step Step-1; expected one *CONTACT per step, followed by its "
          "options",
      at(deck, "*CONTACT PAIR, INTERACTION=A\n", "*CONTACT PAIR") +
          "model data after the first step; expected all model data before the first *STEP",
      // Resolved at the end: model-level pairs.
      at(deck, "TOP, GHOST\n*CONTACT PAIR", "*CONTACT PAIR") +
          "undefined surface GHOST; expected *SURFACE, NAME=GHOST",
      at(deck, "TOP, GHOST\n*CONTACT PAIR", "*CONTACT PAIR") +
          "undefined surface interaction NOPE; expected *SURFACE INTERACTION, NAME=NOPE",
      at(deck, "TOP, PTS", "*CONTACT PAIR") +
          "master surface PTS is node-based; expected an element-based surface (*SURFACE, "
          "TYPE=ELEMENT) as the master",
  };
  CHECK(errors == expected);
}

TEST_CASE("gravity and contact output errors", "[io][deck][contact][errors]") {
  const std::string deck = two_brick_model() + shell_plate_model() +
                           "*STEP\n*DYNAMIC, EXPLICIT\n, 1e-3\n"
                           "*DLOAD\n"
                           "11, GRAV, 9.81, 0, 0, -1\n"
                           "NOPE, GRAV, 9.81, 0, 0, -1\n"
                           ", GRAV, g, 0, 0, -1\n"
                           ", GRAV, 9.81, 0, 0, -1, 7\n"
                           ", GRAV\n"
                           "PLATE, BX, 1.\n"
                           "*OUTPUT, FIELD\n"
                           "*CONTACT OUTPUT\nCSTRESS, CPRESS\n"
                           "*CONTACT OUTPUT\n"
                           "*OUTPUT, HISTORY\n"
                           "*CONTACT OUTPUT\nCFN\n"
                           "*ENERGY OUTPUT\nALLCE\n"
                           "*END STEP\n";
  const auto errors = deck_errors(deck);
  auto dload = [&](const std::string& needle) { return at(deck, needle, "*DLOAD"); };
  const std::vector<std::string> expected = {
      dload("11, GRAV") +
          "GRAV on a single element (11) is not supported; expected an element set name, or the "
          "first field blank for the whole model: element set or blank, GRAV, magnitude, dx, dy, "
          "dz",
      dload(", GRAV, g") +
          "bad number 'g' for gravity magnitude; expected a real number such as 2, -1.5, 1e3 or "
          "1.0D3",
      dload(", 7") +
          "too many values (7) on the data line; expected element set or blank, GRAV, magnitude, "
          "dx, dy, dz",
      dload(", GRAV\n") + "missing gravity magnitude; expected a number",
      dload("PLATE, BX") +
          "load type BX is not supported yet; supported: P on S4R elements (face SPOS), P1..P6 "
          "on C3D8R elements (faces S1..S6), GRAV (gravity)",
      at(deck, "CSTRESS, CPRESS", "*CONTACT OUTPUT") +
          "unknown contact output variable CPRESS; expected one of CSTRESS, CSTATUS, CFORCE",
      at(deck, "*CONTACT OUTPUT\n*OUTPUT", "*CONTACT OUTPUT") +
          "no output variables; expected a data line such as CSTRESS, CSTATUS, or "
          "VARIABLE=PRESELECT",
      at(deck, "*CONTACT OUTPUT\nCFN", "*CONTACT OUTPUT") +
          "contact history output is not supported yet; expected *CONTACT OUTPUT under *OUTPUT, "
          "FIELD (contact energies: ALLFD, ALLPW in *ENERGY OUTPUT)",
      at(deck, "ALLCE", "*ENERGY OUTPUT") +
          "unknown energy variable ALLCE; expected one of ALLKE, ALLKD, ALLSE, ALLPD, ALLAE, "
          "ALLIE, ALLVD, ALLWK, ALLFD, ALLPW, ETOTAL",
      dload("NOPE, GRAV") +
          "undefined element set NOPE; expected *ELSET, ELSET=NOPE, or the first field blank for "
          "the whole model",
  };
  CHECK(errors == expected);
}
