// Node-based surfaces (`*SURFACE, TYPE=NODE`) in contact, SPEC C13: read with their per-node
// areas, accepted as slaves, refused as masters; every error of a deck at once.

#include <catch2/catch.hpp>

#include <cmath>

#include "deck/deck_test_support.hpp"

using namespace xpl;
using test::at;
using test::deck_errors;
using test::has_message;
using test::shell_plate_model;
using test::two_brick_model;

namespace {

/// The shell plate's nodes as a node-based surface with areas, a brick face, an interaction.
const std::string SURFACES =
    "*NSET, NSET=CORNERS\n1, 3\n"
    "*SURFACE, NAME=PTS, TYPE=NODE\n"
    "CORNERS, 2.5\n"
    "5\n"
    "3, 4.\n"
    "*SURFACE, NAME=TOP\nPLATE, SPOS\n"
    "*SURFACE INTERACTION, NAME=A\n";

}  // namespace

TEST_CASE("node-based surfaces keep their nodes and areas and act as slaves",
          "[io][deck][contact]") {
  const std::string deck = shell_plate_model() + SURFACES +
                           "*CONTACT PAIR, INTERACTION=A\nPTS, TOP\n"
                           "*STEP\n*DYNAMIC, EXPLICIT\n, 1e-3\n"
                           "*CONTACT\n*CONTACT INCLUSIONS\nTOP, PTS\n, PTS\n"
                           "*END STEP\n";
  const Model m = io::read_deck_text(deck, "t.inp");
  const Surface& pts = m.surfaces[static_cast<std::size_t>(m.find_surface("PTS"))];
  CHECK(pts.type == Surface::Type::Node);
  // Nodes 1, 3, 5 (indices 0, 2, 4), ascending; node 3 listed twice keeps its last area.
  CHECK(pts.nodes == std::vector<Index>{0, 2, 4});
  REQUIRE(pts.node_areas.size() == 3);
  CHECK(pts.node_areas[0] == 2.5);
  CHECK(pts.node_areas[1] == 4.0);
  CHECK(std::isnan(pts.node_areas[2]));  // no area given: the contact default
  REQUIRE(m.contact_pairs.size() == 1);
  // TOP, PTS in either order is one pair (a second line with it is refused, issue 33).
  CHECK(m.steps[0].contact->inclusions.size() == 2);
}

TEST_CASE("node-based surfaces as masters and bad node lists are errors, all reported",
          "[io][deck][contact][errors]") {
  const std::string deck = two_brick_model() + shell_plate_model() + SURFACES +
                           "*SURFACE, NAME=PTS2, TYPE=NODE\n"
                           "GHOSTSET\n"
                           "4, -1.\n"
                           "*CONTACT PAIR, INTERACTION=A\nTOP, PTS\n"
                           "*STEP\n*DYNAMIC, EXPLICIT\n, 1e-3\n"
                           "*CONTACT\n*CONTACT INCLUSIONS\nPTS, TOP\nPTS\nPTS, PTS2\n, PTS\n"
                           "*END STEP\n";
  const auto errors = deck_errors(deck);
  const std::vector<std::string> expected = {
      at(deck, "4, -1.", "*SURFACE") +
          "node area -1. is not positive; expected a positive area (m²) per node, or none",
      at(deck, "PTS\nPTS, PTS2", "*CONTACT INCLUSIONS") +
          "node-based surface PTS would act as a master (self contact); expected an "
          "element-based surface (*SURFACE, TYPE=ELEMENT) or a blank first field (all exterior "
          "faces) opposite a node-based surface, which is slave only",
      at(deck, "PTS, PTS2", "*CONTACT INCLUSIONS") +
          "node-based surface PTS2 would act as a master (both surfaces are node-based); "
          "expected an element-based surface (*SURFACE, TYPE=ELEMENT) or a blank first field "
          "(all exterior faces) opposite a node-based surface, which is slave only",
      at(deck, "GHOSTSET", "*SURFACE") +
          "undefined node set GHOSTSET; expected *NSET, NSET=GHOSTSET",
      at(deck, "TOP, PTS", "*CONTACT PAIR") +
          "master surface PTS is node-based; expected an element-based surface (*SURFACE, "
          "TYPE=ELEMENT) as the master",
  };
  for (const std::string& message : expected) {
    INFO(message);
    CHECK(has_message(errors, message));
  }
  CHECK(errors.size() == expected.size());
}
