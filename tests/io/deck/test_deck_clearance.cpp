// Contact clearances in the deck (SPEC C7–C10): *CONTACT CLEARANCE with its parameters, also
// given on a data line as the manual writes it, *CONTACT CLEARANCE ASSIGNMENT views and steps,
// and nodal *DISTRIBUTION values with a default line.

#include <cmath>

#include <catch2/catch.hpp>

#include "deck/deck_test_support.hpp"

using namespace xpl;
using test::line_of;
using test::shell_plate_model;
using test::two_brick_model;

namespace {

/// Bricks (elements 0, 1) and a plate of two shells 11, 12 (elements 2, 3; nodes 1..6) with
/// single-sided surfaces, a nodal distribution and clearances in every form.
const std::string SURFACES =
    "*SURFACE, NAME=BODY\n"
    "BRICKS\n"
    "*SURFACE, NAME=TOPS\n"
    "PLATE, SPOS\n"
    "*SURFACE, NAME=LEFT\n"
    "11, SNEG\n"
    "*SURFACE, NAME=RIGHT\n"
    "12, SNEG\n"
    "*NSET, NSET=EDGE\n"
    "3, 6\n"
    "*DISTRIBUTION TABLE, NAME=GAPS\n"
    "LENGTH\n"
    "*Distribution, name=Gap, location=node, table=gaps\n"
    ", 0.001\n"
    "EDGE, 0.004\n"
    "1, -0.002\n"
    "*DISTRIBUTION, NAME=SPARSE, LOCATION=NODE\n"
    "2, 0.5\n";

const std::string CLEARANCE_DECK =
    two_brick_model() + shell_plate_model() + SURFACES +
    // The manual's first example: SEARCH ABOVE on a data line after a line without a comma.
    "*CONTACT CLEARANCE, NAME=c1, ADJUST=YES, SEARCH BELOW=0.2\n"
    "SEARCH ABOVE=0.0\n"
    // Its second example: the keyword line continues after a trailing comma.
    "*CONTACT CLEARANCE, NAME=C2, ADJUST=NO, SEARCH BELOW=1.5,\n"
    "SEARCH ABOVE=0.0, CLEARANCE=gap\n"
    "*CONTACT CLEARANCE, NAME=C3, CLEARANCE=-1e-3\n"
    "*STEP, NAME=FIRST\n"
    "*DYNAMIC, EXPLICIT\n"
    ", 1e-3\n"
    "*CONTACT\n"
    "*CONTACT CLEARANCE ASSIGNMENT\n"
    "BODY, TOPS, c1\n"
    "tops, body, C2, master\n"
    "LEFT, RIGHT, C3, SLAVE\n"
    "TOPS, BODY, C4\n"
    "*CONTACT INCLUSIONS, ALL EXTERIOR\n"
    // Defined after the assignment that uses it, inside the step: names resolve at the end.
    "*CONTACT CLEARANCE, NAME=C4, clearance=2.5D-3\n"
    "*END STEP\n"
    "*STEP, NAME=SECOND\n"
    "*DYNAMIC, EXPLICIT\n"
    ", 1e-3\n"
    "*CONTACT\n"
    "*END STEP\n";

}  // namespace

TEST_CASE("contact clearances: name, adjust, value or distribution, search zones",
          "[io][deck][clearance]") {
  const std::string& deck = CLEARANCE_DECK;
  const Model m = io::read_deck_text(deck, "t.inp");
  REQUIRE(m.contact_clearances.size() == 4);
  const ContactClearance& c1 = m.contact_clearances[0];
  CHECK(c1.name == "C1");
  CHECK(c1.adjust);
  CHECK(c1.value == 0.0);
  CHECK(c1.distribution == NO_INDEX);
  CHECK(c1.search_below == 0.2);
  CHECK(c1.search_above == 0.0);  // from the data line
  CHECK(c1.where.line == line_of(deck, "NAME=c1"));

  const ContactClearance& c2 = m.contact_clearances[1];
  CHECK(c2.name == "C2");
  CHECK_FALSE(c2.adjust);
  CHECK(c2.distribution == 0);  // GAP
  CHECK(c2.search_below == 1.5);
  CHECK(c2.search_above == 0.0);  // from the continuation line

  const ContactClearance& c3 = m.contact_clearances[2];
  CHECK(c3.value == -1e-3);
  CHECK(c3.adjust);  // the default
  CHECK_FALSE(c3.search_above.has_value());
  CHECK_FALSE(c3.search_below.has_value());

  const ContactClearance& c4 = m.contact_clearances[3];
  CHECK(c4.name == "C4");
  CHECK(c4.value == 2.5e-3);
  CHECK(c4.where.line == line_of(deck, "NAME=C4"));
}

TEST_CASE("clearance assignments: surfaces, clearance and view, in their step only",
          "[io][deck][clearance]") {
  const std::string& deck = CLEARANCE_DECK;
  const Model m = io::read_deck_text(deck, "t.inp");
  const Index body = m.find_surface("BODY"), tops = m.find_surface("TOPS"),
              left = m.find_surface("LEFT"), right = m.find_surface("RIGHT");
  REQUIRE(m.steps.size() == 2);
  REQUIRE(m.steps[0].contact.has_value());
  const std::vector<ClearanceAssignment>& a = m.steps[0].contact->clearances;
  REQUIRE(a.size() == 4);
  using View = ClearanceAssignment::View;
  CHECK((a[0].first == body && a[0].second == tops && a[0].clearance == 0));
  CHECK(a[0].view == View::Both);
  CHECK(a[0].where.line == line_of(deck, "BODY, TOPS, c1"));
  CHECK((a[1].first == tops && a[1].second == body && a[1].clearance == 1));
  CHECK(a[1].view == View::Master);
  CHECK((a[2].first == left && a[2].second == right && a[2].clearance == 2));
  CHECK(a[2].view == View::Slave);
  CHECK((a[3].first == tops && a[3].second == body && a[3].clearance == 3));
  // The second step's *CONTACT starts from the first one's definition, without its clearances.
  REQUIRE(m.steps[1].contact.has_value());
  CHECK(m.steps[1].contact->all_exterior);
  CHECK(m.steps[1].contact->clearances.empty());
}

TEST_CASE("nodal distributions: default line, node sets, nodes without a value",
          "[io][deck][clearance]") {
  const Model m = io::read_deck_text(CLEARANCE_DECK, "t.inp");
  REQUIRE(m.distributions.size() == 2);
  const NodalDistribution& gap = m.distributions[0];
  CHECK(gap.name == "GAP");
  REQUIRE(gap.values.size() == static_cast<std::size_t>(m.node_count()));
  // Deck order: the 12 brick nodes (ids 1000001..12), then the plate nodes 1..6.
  for (Index n = 0; n < m.node_count(); ++n) {
    const ExternalId id = m.node_ids[static_cast<std::size_t>(n)];
    const Real expected = id == 1 ? -0.002 : (id == 3 || id == 6) ? 0.004 : 0.001;
    CHECK(gap.values[static_cast<std::size_t>(n)] == expected);
  }
  const NodalDistribution& sparse = m.distributions[1];
  for (Index n = 0; n < m.node_count(); ++n) {
    const Real value = sparse.values[static_cast<std::size_t>(n)];
    if (m.node_ids[static_cast<std::size_t>(n)] == 2)
      CHECK(value == 0.5);
    else
      CHECK(std::isnan(value));
  }
}

TEST_CASE("ADJUST=NO clearances in a later step whose contact domain is new",
          "[io][deck][clearance]") {
  // Contact in FIRST, none in SECOND (OP=NEW without inclusions), new contact in THIRD.
  const std::string deck = two_brick_model() + shell_plate_model() + SURFACES +
                           "*CONTACT CLEARANCE, NAME=OFFSET, ADJUST=NO, CLEARANCE=1e-3\n"
                           "*STEP, NAME=FIRST\n*DYNAMIC, EXPLICIT\n, 1e-3\n"
                           "*CONTACT\n*CONTACT INCLUSIONS, ALL EXTERIOR\n*END STEP\n"
                           "*STEP, NAME=SECOND\n*DYNAMIC, EXPLICIT\n, 1e-3\n"
                           "*CONTACT, OP=NEW\n*END STEP\n"
                           "*STEP, NAME=THIRD\n*DYNAMIC, EXPLICIT\n, 1e-3\n"
                           "*CONTACT\n*CONTACT INCLUSIONS\nBODY, TOPS\n"
                           "*CONTACT CLEARANCE ASSIGNMENT\nBODY, TOPS, OFFSET\n*END STEP\n";
  const Model m = io::read_deck_text(deck, "t.inp");
  REQUIRE(m.steps.size() == 3);
  REQUIRE(m.steps[2].contact.has_value());
  REQUIRE(m.steps[2].contact->clearances.size() == 1);
  CHECK(m.steps[2].contact->clearances[0].clearance == 0);
  CHECK_FALSE(m.contact_clearances[0].adjust);
}
