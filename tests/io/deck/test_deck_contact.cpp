// Contact, rigid bodies, point masses and gravity in the deck: one Abaqus deck with all of
// them read into the expected Model data, and a CalculiX-style deck.

#include <catch2/catch.hpp>

#include "deck/deck_test_support.hpp"

using namespace xpl;
using test::line_of;
using test::shell_plate_model;
using test::two_brick_model;

namespace {

/// Two bricks (elements 0, 1), a plate of two shells (11 → 2, 12 → 3), a rigid body, point
/// masses on two extra nodes, surface interactions, contact in three steps, gravity.
const std::string CONTACT_DECK =
    two_brick_model() + shell_plate_model() +
    // Model-level pair before its surfaces and interaction: resolved at the end.
    "*CONTACT PAIR, INTERACTION=SOFT, TYPE=SURFACE TO SURFACE, SMALL SLIDING\n"
    "NODES, BODY\n"
    "*NODE\n"
    "100, 5, 5, 5\n"
    "101, 0, 0, 2\n"
    "*ELEMENT, TYPE=MASS, ELSET=PM\n"
    "901, 101\n"
    "902, 100\n"
    "*ELEMENT, TYPE=MASS\n"
    "904, 100\n"
    "*ELEMENT, TYPE=ROTARYI, ELSET=RI\n"
    "903, 100\n"
    "*ELSET, ELSET=PM2\n"
    "904\n"
    "*ELSET, ELSET=MIXED\n"
    "901, 903, BRICKS\n"
    "*ELSET, ELSET=RANGE, GENERATE\n"
    "900, 910\n"
    "*NSET, NSET=PMN, ELSET=PM\n"
    "*MASS, ELSET=PM\n"
    "2.5\n"
    "*MASS, ELSET=PM2\n"
    "0.5\n"
    "*ROTARY INERTIA, ELSET=RI\n"
    "1., 2., 3., 0.1\n"
    "*ELSET, ELSET=RB\n"
    "12\n"
    "*NSET, NSET=PINS\n"
    "6\n"
    "*NSET, NSET=RN\n"
    "101\n"
    "*RIGID BODY, REF NODE=100, ELSET=RB, PIN NSET=PINS\n"
    "*RIGID BODY, REF NODE=RN, TIE NSET=PINS\n"
    "*SURFACE, NAME=BODY\n"
    "BRICKS\n"
    "*SURFACE, NAME=SKIN\n"
    "PLATE\n"
    "*SURFACE, NAME=TOPS\n"
    "PLATE, SPOS\n"
    "*SURFACE, NAME=NODES, TYPE=NODE\n"
    "PLATE_NODES\n"
    "*SURFACE INTERACTION, NAME=ROUGH\n"
    "*FRICTION\n"
    "0.3\n"
    "*Surface Interaction, name=soft\n"
    "1.0\n"
    "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=LINEAR\n"
    "1e9, 0.5, 1e-3\n"
    "*FRICTION\n"
    "0.1\n"
    "*SURFACE INTERACTION, NAME=PLAIN\n"
    "*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=HARD\n"
    "*AMPLITUDE, NAME=RAMPUP\n"
    "0, 0, 1, 1\n"
    "*STEP, NAME=IMPACT\n"
    "*DYNAMIC, EXPLICIT\n"
    ", 1e-3\n"
    "*DLOAD\n"
    ", GRAV, 9.81, 0, 0, -2\n"
    "*DLOAD, AMPLITUDE=RAMPUP\n"
    "PLATE, GRAV, 1.5, 3, 4, 0\n"
    "*CONTACT\n"
    "*CONTACT INCLUSIONS, ALL EXTERIOR\n"
    "*CONTACT INCLUSIONS\n"
    "BODY, SKIN\n"
    "SKIN\n"  // surface 2 left out: self contact
    ", BODY\n"
    "*CONTACT EXCLUSIONS\n"
    "TOPS, TOPS\n"
    "*CONTACT PROPERTY ASSIGNMENT\n"
    " , , ROUGH\n"
    "BODY, SKIN, SOFT\n"
    "*CONTACT CONTROLS ASSIGNMENT, TYPE=SCALE PENALTY\n"
    ", , 0.5\n"
    "*CONTACT PAIR, INTERACTION=PLAIN\n"
    "NODES, TOPS\n"
    "*OUTPUT, FIELD, NUMBER INTERVAL=10\n"
    "*NODE OUTPUT\n"
    "U\n"
    "*CONTACT OUTPUT, GENERAL CONTACT\n"
    "CSTRESS, CSTATUS\n"
    "*OUTPUT, HISTORY\n"
    "*ENERGY OUTPUT\n"
    "ALLKE, ALLFD, ALLPW\n"
    "*END STEP\n"
    "*STEP, NAME=SECOND\n"
    "*DYNAMIC, EXPLICIT\n"
    ", 1e-3\n"
    "*CONTACT\n"
    "*CONTACT INCLUSIONS\n"
    "BODY, BODY\n"
    "*END STEP\n"
    "*STEP, NAME=THIRD\n"
    "*DYNAMIC, EXPLICIT\n"
    ", 1e-3\n"
    "*DSLOAD, OP=NEW\n"
    "*END STEP\n"
    "*STEP, NAME=FOURTH\n"
    "*DYNAMIC, EXPLICIT\n"
    ", 1e-3\n"
    "*DLOAD, OP=NEW\n"
    "*CONTACT, OP=NEW\n"
    "*CONTACT INCLUSIONS\n"
    "SKIN, BODY\n"
    "*END STEP\n";

bool same_pair(const SurfacePair& pair, Index first, Index second) {
  return pair.first == first && pair.second == second;
}

}  // namespace

TEST_CASE("surface interactions: friction, linear and hard pressure-overclosure",
          "[io][deck][contact]") {
  const std::string& deck = CONTACT_DECK;
  const Model m = io::read_deck_text(deck, "t.inp", io::ModelChecks::Skip);
  REQUIRE(m.surface_interactions.size() == 3);
  const SurfaceInteraction& rough = m.surface_interactions[0];
  CHECK(rough.name == "ROUGH");
  CHECK(rough.friction == 0.3);
  CHECK_FALSE(rough.linear);
  const SurfaceInteraction& soft = m.surface_interactions[1];
  CHECK(soft.name == "SOFT");
  CHECK(soft.friction == 0.1);
  CHECK(soft.linear);
  CHECK(soft.linear_slope == 1e9);
  CHECK(soft.where.line == line_of(deck, "*Surface Interaction"));
  CHECK(m.surface_interactions[2].name == "PLAIN");
  CHECK_FALSE(m.surface_interactions[2].linear);

  const std::vector<std::string> notes = {
      "t.inp:" + std::to_string(line_of(deck, "*CONTACT PAIR, INTERACTION=SOFT")) +
          ": *CONTACT PAIR: xpl runs node-to-face penalty contact; not used: TYPE=SURFACE TO "
          "SURFACE, SMALL SLIDING",
      "t.inp:" + std::to_string(line_of(deck, "1e9, 0.5")) +
          ": *SURFACE BEHAVIOR: only the slope is used; the other values (CalculiX: sigma_inf, "
          "c0) are ignored",
  };
  std::vector<std::string> texts;
  for (const DeckMessage& message : m.deck_messages) texts.push_back(message.text);
  CHECK(texts == notes);
}

TEST_CASE("surfaces without a face label: both shell sides, exposed solid faces",
          "[io][deck][contact]") {
  const Model m = io::read_deck_text(CONTACT_DECK, "t.inp", io::ModelChecks::Skip);
  const Surface& body = m.surfaces[static_cast<std::size_t>(m.find_surface("BODY"))];
  // The two bricks share face S4 of the first and S6 of the second: 5 + 5 exposed faces.
  std::vector<std::pair<Index, int>> faces;
  for (const ElementFace& f : body.faces) faces.emplace_back(f.element, f.face);
  CHECK(faces ==
        std::vector<std::pair<Index, int>>{
            {0, 0}, {0, 1}, {0, 2}, {0, 4}, {0, 5}, {1, 0}, {1, 1}, {1, 2}, {1, 3}, {1, 4}});
  const Surface& skin = m.surfaces[static_cast<std::size_t>(m.find_surface("SKIN"))];
  faces.clear();
  for (const ElementFace& f : skin.faces) faces.emplace_back(f.element, f.face);
  CHECK(faces ==
        std::vector<std::pair<Index, int>>{
            {2, SHELL_FACE_NEG}, {2, SHELL_FACE_POS}, {3, SHELL_FACE_NEG}, {3, SHELL_FACE_POS}});
}

TEST_CASE("general contact per step: inclusions, exclusions, properties, penalty scale, OP=NEW",
          "[io][deck][contact]") {
  const std::string& deck = CONTACT_DECK;
  const Model m = io::read_deck_text(deck, "t.inp", io::ModelChecks::Skip);
  const Index body = m.find_surface("BODY"), skin = m.find_surface("SKIN"),
              tops = m.find_surface("TOPS"), nodes = m.find_surface("NODES");
  REQUIRE(m.steps.size() == 4);

  REQUIRE(m.steps[0].contact.has_value());
  const GeneralContact& first = *m.steps[0].contact;
  CHECK(first.where.line == line_of(deck, "*CONTACT\n"));
  CHECK(first.all_exterior);
  REQUIRE(first.inclusions.size() == 3);
  CHECK(same_pair(first.inclusions[0], body, skin));
  CHECK(same_pair(first.inclusions[1], skin, skin));  // surface 2 blank: self contact
  CHECK(same_pair(first.inclusions[2], NO_INDEX, body));
  CHECK(first.inclusions[2].where.line == line_of(deck, "SKIN\n, BODY") + 1);
  REQUIRE(first.exclusions.size() == 1);
  CHECK(same_pair(first.exclusions[0], tops, tops));
  REQUIRE(first.properties.size() == 2);
  CHECK(same_pair(first.properties[0].first, NO_INDEX, NO_INDEX));  // the global default
  CHECK(first.properties[0].second == 0);
  CHECK(same_pair(first.properties[1].first, body, skin));
  CHECK(first.properties[1].second == 1);
  CHECK(first.penalty_scale == 0.5);

  // *CONTACT in a later step adds to the earlier definition (Step::contact is complete).
  REQUIRE(m.steps[1].contact.has_value());
  const GeneralContact& second = *m.steps[1].contact;
  CHECK(second.all_exterior);
  REQUIRE(second.inclusions.size() == 4);
  CHECK(same_pair(second.inclusions[3], body, body));
  CHECK(second.properties.size() == 2);
  CHECK(second.penalty_scale == 0.5);
  CHECK(second.where.line == line_of(deck, "*CONTACT\n*CONTACT INCLUSIONS\nBODY, BODY"));

  CHECK_FALSE(m.steps[2].contact.has_value());  // carries over, nothing new
  REQUIRE(m.steps[3].contact.has_value());
  const GeneralContact& fourth = *m.steps[3].contact;  // OP=NEW: only its own options
  CHECK_FALSE(fourth.all_exterior);
  REQUIRE(fourth.inclusions.size() == 1);
  CHECK(same_pair(fourth.inclusions[0], skin, body));
  CHECK(fourth.exclusions.empty());
  CHECK(fourth.properties.empty());
  CHECK(fourth.penalty_scale == 1.0);

  // Contact pairs: model level (CalculiX style) and in a step.
  REQUIRE(m.contact_pairs.size() == 1);
  CHECK(m.contact_pairs[0].slave == nodes);
  CHECK(m.contact_pairs[0].master == body);
  CHECK(m.contact_pairs[0].interaction == 1);
  CHECK(m.contact_pairs[0].where.line == line_of(deck, "NODES, BODY"));
  REQUIRE(m.steps[0].contact_pairs.size() == 1);
  CHECK(m.steps[0].contact_pairs[0].slave == nodes);
  CHECK(m.steps[0].contact_pairs[0].master == tops);
  CHECK(m.steps[0].contact_pairs[0].interaction == 2);
  CHECK(m.steps[1].contact_pairs.empty());
}

TEST_CASE("gravity: whole model or element set, normalised direction, amplitude, OP=NEW",
          "[io][deck][contact]") {
  const std::string& deck = CONTACT_DECK;
  const Model m = io::read_deck_text(deck, "t.inp", io::ModelChecks::Skip);
  const std::vector<GravityLoad>& gravity = m.steps[0].gravity;
  REQUIRE(gravity.size() == 2);
  CHECK(gravity[0].element_set == NO_INDEX);
  CHECK(gravity[0].magnitude == 9.81);
  CHECK(gravity[0].direction[0] == 0.0);
  CHECK(gravity[0].direction[1] == 0.0);
  CHECK(gravity[0].direction[2] == -1.0);
  CHECK(gravity[0].amplitude == NO_INDEX);
  CHECK(gravity[0].where.line == line_of(deck, ", GRAV"));
  CHECK(gravity[1].element_set == m.find_element_set("PLATE"));
  CHECK(gravity[1].magnitude == 1.5);
  // 3-4-5 triangle: exact up to one rounding of the division.
  CHECK(gravity[1].direction[0] == Approx(0.6).margin(1e-15));
  CHECK(gravity[1].direction[1] == Approx(0.8).margin(1e-15));
  CHECK(gravity[1].direction[2] == 0.0);
  CHECK(gravity[1].amplitude == m.find_amplitude("RAMPUP"));
  CHECK_FALSE(m.steps[0].gravity_reset);
  // *DSLOAD, OP=NEW clears pressures only; *DLOAD, OP=NEW pressures and gravity.
  CHECK(m.steps[2].pressures_reset);
  CHECK_FALSE(m.steps[2].gravity_reset);
  CHECK(m.steps[3].pressures_reset);
  CHECK(m.steps[3].gravity_reset);
}

TEST_CASE("rigid bodies and point masses", "[io][deck][contact][rigid]") {
  const std::string& deck = CONTACT_DECK;
  const Model m = io::read_deck_text(deck, "t.inp", io::ModelChecks::Skip);
  const auto node = [&](ExternalId id) {
    for (Index n = 0; n < m.node_count(); ++n)
      if (m.node_ids[static_cast<std::size_t>(n)] == id) return n;
    return NO_INDEX;
  };
  // MASS/ROTARYI elements stay out of the element arrays (and so need no section).
  CHECK(m.element_count() == 4);
  REQUIRE(m.rigid_bodies.size() == 2);
  CHECK(m.rigid_bodies[0].reference_node == node(100));
  CHECK(m.rigid_bodies[0].element_set == m.find_element_set("RB"));
  CHECK(m.rigid_bodies[0].pin_node_set == m.find_node_set("PINS"));
  CHECK(m.rigid_bodies[0].tie_node_set == NO_INDEX);
  CHECK(m.rigid_bodies[0].where.line == line_of(deck, "*RIGID BODY, REF NODE=100"));
  CHECK(m.rigid_bodies[1].reference_node == node(101));  // a node set of one node
  CHECK(m.rigid_bodies[1].element_set == NO_INDEX);
  CHECK(m.rigid_bodies[1].tie_node_set == m.find_node_set("PINS"));

  REQUIRE(m.point_inertias.size() == 2);
  const PointInertia& on_100 = m.point_inertias[0];  // node order: 100 before 101
  CHECK(on_100.node == node(100));
  CHECK(on_100.mass == 3.0);  // MASS elements 902 (2.5) and 904 (0.5) add up
  const Real inertia[6] = {1.0, 2.0, 3.0, 0.1, 0.0, 0.0};
  for (int c = 0; c < 6; ++c) CHECK(on_100.inertia[c] == inertia[c]);
  CHECK(on_100.where.line == line_of(deck, "*MASS, ELSET=PM\n"));
  const PointInertia& on_101 = m.point_inertias[1];
  CHECK(on_101.node == node(101));
  CHECK(on_101.mass == 2.5);
  CHECK(on_101.inertia[0] == 0.0);

  // Sets that list MASS/ROTARYI elements resolve: they just hold no Model elements.
  CHECK(m.element_sets[static_cast<std::size_t>(m.find_element_set("PM"))].members.empty());
  CHECK(m.element_sets[static_cast<std::size_t>(m.find_element_set("MIXED"))].members ==
        std::vector<Index>{0, 1});
  CHECK(m.element_sets[static_cast<std::size_t>(m.find_element_set("RANGE"))].members.empty());
  CHECK(m.node_sets[static_cast<std::size_t>(m.find_node_set("PMN"))].members ==
        std::vector<Index>{node(100), node(101)});
}

TEST_CASE("contact output and contact energies", "[io][deck][contact][output]") {
  const Model m = io::read_deck_text(CONTACT_DECK, "t.inp", io::ModelChecks::Skip);
  const std::vector<OutputRequest>& outputs = m.steps[0].outputs;
  REQUIRE(outputs.size() == 2);
  CHECK(outputs[0].number_interval == 10);
  CHECK(outputs[0].node_variables == std::vector<std::string>{"U"});
  CHECK(outputs[0].contact_variables == std::vector<std::string>{"CSTRESS", "CSTATUS"});
  CHECK(outputs[1].energy);
  CHECK(outputs[1].energy_variables == std::vector<std::string>{"ALLKE", "ALLFD", "ALLPW"});
}
