// General contact definitions read as written (issue 33, item 3): a trailing comma does not
// join two contact data lines, and a surface pair given twice is refused in one step and
// merged (with a note) when a later step's *CONTACT, OP=MOD repeats it.

#include <catch2/catch.hpp>

#include "deck/deck_test_support.hpp"

using namespace xpl;
using test::at;
using test::deck_errors;
using test::line_of;
using test::shell_plate_model;
using test::two_brick_model;

namespace {

/// Bricks (surface BODY) and a plate (surface SKIN), then `steps`.
std::string contact_deck(const std::string& steps) {
  return two_brick_model() + shell_plate_model() +
         "*SURFACE, NAME=BODY\nBRICKS\n*SURFACE, NAME=SKIN\nPLATE\n" + steps;
}

bool same_pair(const SurfacePair& pair, Index first, Index second) {
  return pair.first == first && pair.second == second;
}

}  // namespace

TEST_CASE("a trailing comma does not join contact data lines", "[io][deck][contact]") {
  // Two self-contact lines, each ending with a comma: before, the comma continued the line
  // and the block excluded the pair BODY, SKIN instead (the plate then passed through the
  // bricks without a word).
  const std::string deck = contact_deck(
      "*STEP, NAME=S1\n*DYNAMIC, EXPLICIT\n, 1e-3\n"
      "*CONTACT\n"
      "*CONTACT INCLUSIONS\n"
      "BODY, SKIN,\n"
      "SKIN,\n"
      "BODY,\n"
      "*CONTACT EXCLUSIONS\n"
      "BODY,\n"
      "SKIN,\n"
      "*END STEP\n");
  const Model m = io::read_deck_text(deck, "t.inp", io::ModelChecks::Skip);
  const Index body = m.find_surface("BODY"), skin = m.find_surface("SKIN");
  REQUIRE(m.steps.size() == 1);
  REQUIRE(m.steps[0].contact.has_value());
  const GeneralContact& contact = *m.steps[0].contact;
  REQUIRE(contact.inclusions.size() == 3);
  CHECK(same_pair(contact.inclusions[0], body, skin));
  CHECK(same_pair(contact.inclusions[1], skin, skin));
  CHECK(same_pair(contact.inclusions[2], body, body));
  REQUIRE(contact.exclusions.size() == 2);
  CHECK(same_pair(contact.exclusions[0], body, body));
  CHECK(contact.exclusions[0].where.line == line_of(deck, "*CONTACT EXCLUSIONS") + 1);
  CHECK(same_pair(contact.exclusions[1], skin, skin));
  CHECK(contact.exclusions[1].where.line == line_of(deck, "*CONTACT EXCLUSIONS") + 2);
}

TEST_CASE("element lines still continue after a trailing comma", "[io][deck]") {
  // *ELEMENT is where Abaqus defines data continuation lines: the nodes go on.
  std::string deck = two_brick_model();
  const std::string line =
      "5000001, 1000001, 1000002, 1000003, 1000004, 1000007, 1000008, 1000009, 1000010\n";
  deck.replace(deck.find(line), line.size(),
               "5000001, 1000001, 1000002, 1000003,\n1000004, 1000007,\n1000008, 1000009, "
               "1000010\n");
  const Model m = io::read_deck_text(deck + test::simple_step(), "t.inp");
  REQUIRE(m.element_count() == 2);
  CHECK(m.node_ids[static_cast<std::size_t>(m.nodes_of(0)[7])] == 1000010);
  CHECK(m.element_where(0).line == line_of(deck, "5000001,"));
}

TEST_CASE("a contact pair given twice in one step is refused at its line",
          "[io][deck][contact][errors]") {
  const std::string deck = contact_deck(
      "*STEP, NAME=S1\n*DYNAMIC, EXPLICIT\n, 1e-3\n"
      "*CONTACT\n"
      "*CONTACT INCLUSIONS\n"
      "BODY, SKIN\n"
      "SKIN\n"
      "*CONTACT INCLUSIONS\n"
      "SKIN , BODY\n"  // the same pair, the other way round, in a second block
      "SKIN, SKIN\n"   // self contact of SKIN again, written out
      "*CONTACT EXCLUSIONS\n"
      "BODY\n"
      "BODY, BODY\n"
      "*END STEP\n");
  const std::vector<std::string> errors = deck_errors(deck);
  const std::string first_pair = std::to_string(line_of(deck, "BODY, SKIN\n"));
  const std::string first_self = std::to_string(line_of(deck, "SKIN\n*CONTACT INCLUSIONS"));
  const std::string first_exclusion = std::to_string(line_of(deck, "BODY\nBODY, BODY"));
  const std::vector<std::string> expected = {
      at(deck, "SKIN , BODY", "*CONTACT INCLUSIONS") +
          "the pair SKIN, BODY is given twice in step S1 (first at t.inp:" + first_pair +
          "); expected each surface pair once per step",
      at(deck, "SKIN, SKIN", "*CONTACT INCLUSIONS") +
          "the pair SKIN (self contact) is given twice in step S1 (first at t.inp:" + first_self +
          "); expected each surface pair once per step",
      at(deck, "BODY, BODY", "*CONTACT EXCLUSIONS") +
          "the pair BODY (self contact) is given twice in step S1 (first at t.inp:" +
          first_exclusion + "); expected each surface pair once per step",
  };
  CHECK(errors == expected);
}

TEST_CASE("a later step's OP=MOD repeating a pair merges it with a note", "[io][deck][contact]") {
  // Before, the pair was kept twice and the run stopped with exit 4 when the second copy's
  // history dataset was created ("name already exists").
  const std::string deck = contact_deck(
      "*STEP, NAME=S1\n*DYNAMIC, EXPLICIT\n, 1e-3\n"
      "*CONTACT\n*CONTACT INCLUSIONS\nBODY, SKIN\n*END STEP\n"
      "*STEP, NAME=S2\n*DYNAMIC, EXPLICIT\n, 1e-3\n"
      "*CONTACT\n*CONTACT INCLUSIONS\nSKIN, BODY\nSKIN\n*END STEP\n"
      "*STEP, NAME=S3\n*DYNAMIC, EXPLICIT\n, 1e-3\n"
      "*CONTACT, OP=MOD\n*CONTACT INCLUSIONS\nBODY, SKIN\n*END STEP\n");
  const Model m = io::read_deck_text(deck, "t.inp", io::ModelChecks::Skip);
  const Index body = m.find_surface("BODY"), skin = m.find_surface("SKIN");
  REQUIRE(m.steps.size() == 3);
  for (std::size_t s = 0; s < 3; ++s) {
    INFO("step " << s + 1);
    REQUIRE(m.steps[s].contact.has_value());
    const std::vector<SurfacePair>& pairs = m.steps[s].contact->inclusions;
    REQUIRE(pairs.size() == (s == 0 ? 1U : 2U));
    CHECK(same_pair(pairs[0], body, skin));
    if (s > 0) CHECK(same_pair(pairs[1], skin, skin));
  }
  const int second = test::line_of(deck, "SKIN, BODY\n");
  const int third = line_of(deck, "*CONTACT, OP=MOD") + 2;
  std::vector<std::string> texts;
  for (const DeckMessage& message : m.deck_messages) texts.push_back(message.text);
  const std::vector<std::string> notes = {
      "t.inp:" + std::to_string(second) +
          ": *CONTACT INCLUSIONS: the pair SKIN, BODY is in effect since t.inp:" +
          std::to_string(line_of(deck, "BODY, SKIN\n")) + "; given again, it changes nothing",
      "t.inp:" + std::to_string(third) +
          ": *CONTACT INCLUSIONS: the pair BODY, SKIN is in effect since t.inp:" +
          std::to_string(second) + "; given again, it changes nothing",
  };
  CHECK(texts == notes);
}
