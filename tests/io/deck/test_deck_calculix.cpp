// A CalculiX-style deck: model-level *CONTACT PAIR, *SURFACE BEHAVIOR with CalculiX's extra
// values, *STEP, INC=, and the *NODE FILE / *EL FILE / *NODE PRINT / *EL PRINT /
// *CONTACT FILE / *CONTACT PRINT output keywords, each mapped or noted; MASSLESS pairs, ALPHA=,
// *CLEARANCE, and the refused *STATIC, *EQUATION, C3D20 (issue 34 item 3).

#include <catch2/catch.hpp>

#include <algorithm>

#include "deck/deck_test_support.hpp"

using namespace xpl;
using test::at;
using test::deck_errors;
using test::line_of;
using test::shell_plate_model;
using test::two_brick_model;

namespace {

const std::string CCX_DECK = two_brick_model() + shell_plate_model() +
                             "*SURFACE, NAME=SLAVE, TYPE=NODE\n"
                             "PLATE_NODES\n"
                             "*SURFACE, NAME=MASTER\n"
                             "BRICKS, S2\n"
                             "*CONTACT PAIR, INTERACTION=SI1, TYPE=NODE TO SURFACE\n"
                             "SLAVE, MASTER\n"
                             "*SURFACE INTERACTION, NAME=SI1\n"
                             "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n"
                             "1e10, 1e3\n"
                             "*FRICTION\n"
                             "0.2, 5e8\n"
                             "*STEP, NLGEOM, INC=100000\n"
                             "*DYNAMIC, EXPLICIT\n"
                             ", 1e-3\n"
                             "*BOUNDARY\n"
                             "PLATE_NODES, 1, 6\n"
                             "*NODE FILE, FREQUENCY=100\n"
                             "U, V, NT\n"
                             "*EL FILE\n"
                             "S, E\n"
                             "*NODE PRINT, NSET=ALLN, TOTALS=YES\n"
                             "RF\n"
                             "*EL PRINT, ELSET=BRICKS\n"
                             "EVOL\n"
                             "*CONTACT FILE\n"
                             "CDIS, CSTR\n"
                             "*CONTACT PRINT\n"
                             "CSTR\n"
                             "*END STEP\n";

/// `t.inp:LINE: *KEYWORD: text` for the line of `needle`.
std::string note_at(const std::string& needle, const std::string& keyword,
                    const std::string& text) {
  return "t.inp:" + std::to_string(line_of(CCX_DECK, needle)) + ": " + keyword + ": " + text;
}

}  // namespace

TEST_CASE("a CalculiX-style deck reads, with notes for what xpl does not use",
          "[io][deck][contact][calculix]") {
  const Model m = io::read_deck_text(CCX_DECK, "t.inp", io::ModelChecks::Skip);
  REQUIRE(m.surface_interactions.size() == 1);
  CHECK(m.surface_interactions[0].linear);
  CHECK(m.surface_interactions[0].linear_slope == 1e10);
  CHECK(m.surface_interactions[0].friction == 0.2);
  REQUIRE(m.contact_pairs.size() == 1);
  CHECK(m.contact_pairs[0].slave == m.find_surface("SLAVE"));
  CHECK(m.contact_pairs[0].master == m.find_surface("MASTER"));
  CHECK(m.contact_pairs[0].interaction == 0);
  REQUIRE(m.steps.size() == 1);
  CHECK_FALSE(m.steps[0].contact.has_value());

  const std::vector<OutputRequest>& outputs = m.steps[0].outputs;
  REQUIRE(outputs.size() == 3);
  CHECK(outputs[0].kind == OutputRequest::Kind::Field);
  CHECK(outputs[0].number_interval == 20);
  CHECK(outputs[0].node_variables == std::vector<std::string>{"U", "V"});
  CHECK(outputs[0].node_set == NO_INDEX);
  CHECK(outputs[1].kind == OutputRequest::Kind::Field);
  CHECK(outputs[1].element_variables == std::vector<std::string>{"S"});
  CHECK(outputs[2].kind == OutputRequest::Kind::History);
  CHECK(outputs[2].number_interval == 200);
  CHECK(outputs[2].node_variables == std::vector<std::string>{"RF1", "RF2", "RF3"});
  CHECK(outputs[2].node_set == m.find_node_set("ALLN"));

  const std::string contact_ignored =
      "ignored: contact results are requested with *CONTACT OUTPUT (CSTRESS, CSTATUS, CFORCE) "
      "and the energies ALLFD, ALLPW in *ENERGY OUTPUT";
  const std::vector<std::string> expected = {
      note_at("1e10, 1e3", "*SURFACE BEHAVIOR",
              "only the slope is used; the other values (CalculiX: sigma_inf, c0) are ignored"),
      note_at("0.2, 5e8", "*FRICTION",
              "only the friction coefficient is used; the other values (e.g. CalculiX's stick "
              "slope) are ignored"),
      note_at("*STEP", "*STEP",
              "INC=100000 (CalculiX's maximum number of increments) is not used: an explicit "
              "step runs until its time period"),
      note_at("*NODE FILE", "*NODE FILE",
              "read as *OUTPUT, FIELD, NUMBER INTERVAL=20 with *NODE OUTPUT: U, V; dropped (not "
              "available in xpl): NT; not used: FREQUENCY=100"),
      note_at("*EL FILE", "*EL FILE",
              "read as *OUTPUT, FIELD, NUMBER INTERVAL=20 with *ELEMENT OUTPUT: S; dropped (not "
              "available in xpl): E"),
      note_at("*NODE PRINT", "*NODE PRINT",
              "read as *OUTPUT, HISTORY, NUMBER INTERVAL=200 with *NODE OUTPUT, NSET=ALLN: RF; "
              "not used: TOTALS=YES"),
      note_at("*EL PRINT", "*EL PRINT", "element history output is not available in xpl; ignored"),
      note_at("*CONTACT FILE", "*CONTACT FILE", contact_ignored),
      note_at("*CONTACT PRINT", "*CONTACT PRINT", contact_ignored),
  };
  std::vector<std::string> texts;
  for (const DeckMessage& message : m.deck_messages) {
    CHECK_FALSE(message.warning);
    texts.push_back(message.text);
  }
  CHECK(texts == expected);
}

TEST_CASE("CalculiX output keywords: sets and errors", "[io][deck][contact][calculix][errors]") {
  std::string deck = two_brick_model() +
                     "*STEP\n*DYNAMIC, EXPLICIT\n, 1e-3\n"
                     "*NODE FILE, NSET=ALLN\nNT\n"
                     "*EL FILE, ELSET=NOPE\nS\n"
                     "*NODE PRINT\nU\n"
                     "*NODE PRINT, NSET=ALLN\n"
                     "*EL FILE, FREQ=3\nS\n"
                     "*END STEP\n"
                     "*NODE FILE\nU\n";
  const auto errors = deck_errors(deck);
  const std::vector<std::string> expected = {
      at(deck, "*NODE PRINT\n", "*NODE PRINT") + "missing parameter NSET; expected NSET=name",
      at(deck, "*NODE PRINT, NSET=ALLN", "*NODE PRINT") +
          "no output variables; expected a data line such as U, RF",
      at(deck, "*EL FILE, FREQ", "*EL FILE") +
          "unknown parameter FREQ; accepted parameters: ELSET=, NSET=, FREQUENCY=, FREQUENCYF=, "
          "OUTPUT=, "
          "POSITION=, GLOBAL=, TIME POINTS=, LAST ITERATIONS, CONTACT ELEMENTS, SECTION FORCES",
      at(deck, "*NODE FILE\nU", "*NODE FILE") +
          "history data outside a step; expected it between *STEP and *END STEP",
      // Resolved at the end.
      at(deck, "*EL FILE, ELSET=NOPE", "*EL FILE") +
          "undefined element set NOPE; expected *ELSET, ELSET=NOPE",
  };
  CHECK(errors == expected);

  // Only unknown variables: nothing is requested, a note says so.
  deck.erase(deck.find("*EL FILE, ELSET=NOPE"));
  deck += "*END STEP\n";
  const Model m = io::read_deck_text(deck, "t.inp");
  CHECK(m.steps[0].outputs.empty());
  REQUIRE(m.deck_messages.size() == 1);
  CHECK(m.deck_messages[0].text ==
        at(deck, "*NODE FILE", "*NODE FILE") +
            "nothing written: no variable is available in xpl; dropped (not available in xpl): NT");
}

namespace {

/// CalculiX's explicit contact deck: the bricks' top under the plate, MASSLESS, ALPHA=.
std::string massless_deck(const std::string& pair_type, const std::string& dynamic) {
  return two_brick_model() +
         "*SURFACE, NAME=TOPS\nBRICKS, S2\n"
         "*SURFACE, NAME=BOTTOMS\nBRICKS, S1\n"
         "*CONTACT PAIR, INTERACTION=SI1, TYPE=" +
         pair_type +
         "\nTOPS, BOTTOMS\n"
         "*SURFACE INTERACTION, NAME=SI1\n"
         "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=HARD\n"
         "*STEP, NLGEOM\n" +
         dynamic + "\n1.E-8, 1.E-3\n*END STEP\n";
}

}  // namespace

TEST_CASE("CalculiX's MASSLESS contact pairs and ALPHA= of an explicit step",
          "[io][deck][contact][calculix]") {
  const std::string deck = massless_deck("MASSLESS", "*DYNAMIC, ALPHA=-0.05, EXPLICIT");
  const Model m = io::read_deck_text(deck, "t.inp");
  REQUIRE(m.contact_pairs.size() == 1);
  std::vector<std::string> texts;
  for (const DeckMessage& message : m.deck_messages) texts.push_back(message.text);
  CHECK(std::count_if(texts.begin(), texts.end(), [&](const std::string& t) {
          return t.rfind(at(deck, "*CONTACT PAIR", "*CONTACT PAIR") +
                             "TYPE=MASSLESS (CalculiX's explicit contact",
                         0) == 0 &&
                 t.find(
                     "runs as xpl's node-to-face penalty contact: the slave nodes keep their "
                     "mass") != std::string::npos;
        }) == 1);
  CHECK(std::count_if(texts.begin(), texts.end(), [&](const std::string& t) {
          return t.rfind(at(deck, "*DYNAMIC", "*DYNAMIC") + "ALPHA=-0.05 ignored", 0) == 0 &&
                 t.find("the explicit central-difference method has no alpha") != std::string::npos;
        }) == 1);
  // ALPHA= on an implicit step is still the implicit step's error; a bad ALPHA one error.
  CHECK(test::has_error(deck_errors(massless_deck("MASSLESS", "*DYNAMIC, ALPHA=-0.05")),
                        at(deck, "*DYNAMIC", "*DYNAMIC"), "implicit dynamics is not supported"));
  const std::vector<std::string> bad =
      deck_errors(massless_deck("MASSLESS", "*DYNAMIC, ALPHA=x, EXPLICIT"));
  CHECK(bad == std::vector<std::string>{at(deck, "*DYNAMIC", "*DYNAMIC") +
                                        "bad ALPHA=x; expected a number (CalculiX: the alpha of "
                                        "its implicit scheme, -1/3 to 0)"});
}

TEST_CASE("CalculiX's *CLEARANCE of a contact pair", "[io][deck][contact][calculix]") {
  const std::string base = massless_deck("NODE TO SURFACE", "*DYNAMIC, EXPLICIT");
  const std::string line = "*CLEARANCE, MASTER=BOTTOMS, SLAVE=TOPS, VALUE=0.02\n";
  const std::string deck =
      base.substr(0, base.find("*STEP")) + line + base.substr(base.find("*STEP"));
  const Model m = io::read_deck_text(deck, "t.inp", io::ModelChecks::Skip);
  REQUIRE(m.contact_clearances.size() == 1);
  CHECK_FALSE(m.contact_clearances[0].adjust);
  CHECK(m.contact_clearances[0].value == 0.02);
  REQUIRE(m.steps[0].contact.has_value());
  CHECK_FALSE(m.steps[0].contact->all_exterior);
  CHECK(m.steps[0].contact->inclusions.empty());
  REQUIRE(m.steps[0].contact->clearances.size() == 1);
  const ClearanceAssignment& a = m.steps[0].contact->clearances[0];
  CHECK(a.first == m.find_surface("TOPS"));
  CHECK(a.second == m.find_surface("BOTTOMS"));
  CHECK(a.view == ClearanceAssignment::View::Slave);
  CHECK(std::any_of(m.deck_messages.begin(), m.deck_messages.end(), [&](const DeckMessage& n) {
    return n.text.rfind(at(deck, "*CLEARANCE", "*CLEARANCE") +
                            "VALUE=0.02 runs as xpl's contact clearance with ADJUST=NO",
                        0) == 0;
  }));

  SECTION("an interference, or no such pair: one error each") {
    std::string bad = deck;
    bad.replace(bad.find("VALUE=0.02"), 10, "VALUE=-0.1");
    CHECK(deck_errors(bad) ==
          std::vector<std::string>{at(deck, "*CLEARANCE", "*CLEARANCE") +
                                   "VALUE=-0.1 is an interference (a negative clearance); "
                                   "expected VALUE >= 0: xpl's clearance is a gap; an initial "
                                   "overclosure of the pair is removed in the first step without "
                                   "*CLEARANCE (SPEC C2)"});
    std::string swapped = deck;
    swapped.replace(swapped.find("MASTER=BOTTOMS, SLAVE=TOPS"), 26, "MASTER=TOPS, SLAVE=BOTTOMS");
    CHECK(deck_errors(swapped) ==
          std::vector<std::string>{at(deck, "*CLEARANCE", "*CLEARANCE") +
                                   "no *CONTACT PAIR with slave BOTTOMS and master TOPS in the "
                                   "model data or the first step; expected *CLEARANCE for a "
                                   "contact pair in effect from the start"});
  }
  SECTION("a deck without a step: its errors, not a crash (a fuzz finding)") {
    const std::vector<std::string> errors = deck_errors(deck.substr(0, deck.find("*STEP")));
    CHECK(std::any_of(errors.begin(), errors.end(), [](const std::string& e) {
      return e.find("the deck has no step") != std::string::npos;
    }));
  }
}

TEST_CASE("CalculiX's *STATIC, *EQUATION and C3D20: one error each",
          "[io][deck][calculix][errors]") {
  const std::string deck = two_brick_model() +
                           "*ELEMENT, TYPE=C3D20, ELSET=QUAD\n"
                           "9, 1000001, 1000002, 1000003, 1000004, 1000007, 1000008, 1000009, "
                           "1000010, 1000001, 1000002, 1000003, 1000004, 1000007, 1000008, "
                           "1000009, 1000010, 1000001, 1000002, 1000003, 1000004\n"
                           "*SOLID SECTION, ELSET=QUAD, MATERIAL=STEEL\n"
                           "*EQUATION\n2\n1000001, 1, 1., 1000002, 1, -1.\n"
                           "*STEP\n*STATIC\n*BOUNDARY\nALLN, 1, 3\n*END STEP\n"
                           "*STEP\n*DYNAMIC, EXPLICIT\n, 1e-3\n*END STEP\n";
  const std::vector<std::string> e = deck_errors(deck);
  CHECK(e.size() == 3);
  CHECK(test::has_error(e, at(deck, "TYPE=C3D20", "*ELEMENT"),
                        "element type C3D20 is not supported; nearest supported: C3D8R: "
                        "quadratic hexahedra are not supported"));
  CHECK(test::has_error(e, at(deck, "*EQUATION", "*EQUATION"),
                        "linear constraint equations are not supported; expected *TIE"));
  CHECK(test::has_error(e, at(deck, "*STATIC", "*STATIC"),
                        "static analysis is not supported; expected *DYNAMIC, EXPLICIT"));
}
