// A CalculiX-style deck: model-level *CONTACT PAIR, *SURFACE BEHAVIOR with CalculiX's extra
// values, *STEP, INC=, and the *NODE FILE / *EL FILE / *NODE PRINT / *EL PRINT /
// *CONTACT FILE / *CONTACT PRINT output keywords, each mapped or noted.

#include <catch2/catch.hpp>

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
