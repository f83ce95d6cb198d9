// *CONTACT INITIALIZATION DATA / ASSIGNMENT (SPEC C14, C15): today's spelling of the contact
// clearances, read into the same definitions, with the interference fit; and its bad input,
// every error of a deck at once as `file:LINE: *KEYWORD: problem; expected`.

#include <catch2/catch.hpp>

#include "deck/deck_test_support.hpp"

using namespace xpl;
using test::at;
using test::deck_errors;
using test::line_of;
using test::shell_plate_model;
using test::two_brick_model;

namespace {

const std::string SURFACES = two_brick_model() + shell_plate_model() +
                             "*SURFACE, NAME=BODY\nBRICKS\n"
                             "*SURFACE, NAME=TOPS\nPLATE, SPOS\n"
                             "*SURFACE, NAME=PTS, TYPE=NODE\nPLATE_NODES\n"
                             "*SURFACE, NAME=PTS2, TYPE=NODE\nPLATE_NODES\n";

const std::string STEP = "*DYNAMIC, EXPLICIT\n, 1e-3\n";

}  // namespace

TEST_CASE("contact initialization data: clearance, interference fit, zones, views",
          "[io][deck][clearance][initialization]") {
  const std::string deck =
      SURFACES +
      "*CONTACT INITIALIZATION DATA, NAME=I1, ADJUST=YES, SEARCH BELOW=0.2\n"
      "SEARCH ABOVE=0.0\n"
      "*CONTACT INITIALIZATION DATA, NAME=I2, INITIAL CLEARANCE=1e-3, ADJUST=NO\n"
      "*CONTACT INITIALIZATION DATA, NAME=FIT, INTERFERENCE FIT, STEP FRACTION=0.5, "
      "MINIMUM DISTANCE=NO\n"
      "*CONTACT INITIALIZATION DATA, NAME=FITH, INTERFERENCE FIT=2e-5, SEARCH BELOW=1e-4\n"
      "*CONTACT CLEARANCE, NAME=I1, CLEARANCE=5e-4\n"  // the other spelling's names are apart
      "*STEP, NAME=FIRST\n" +
      STEP +
      "*CONTACT\n*CONTACT INCLUSIONS, ALL EXTERIOR\n"
      "*CONTACT INITIALIZATION ASSIGNMENT\n"
      "BODY, TOPS, I1, SECOND SURFACE SFC\n"
      "TOPS, BODY, I2, FIRST SURFACE SFC\n"
      "BODY, TOPS, FIT\n"
      // A node-based surface as the slave of an element-based one (SPEC C13): the one view
      // that exists, named or not.
      "PTS, BODY, I2\n"
      "TOPS, PTS, I1, SECOND SURFACE SFC\n"
      "PTS, BODY, FIT\n"
      "*CONTACT CLEARANCE ASSIGNMENT\n"
      "BODY, TOPS, I1, MASTER\n"
      "BODY, PTS, I1\n"
      "PTS, TOPS, I1, SLAVE\n"
      "*END STEP\n";
  const Model m = io::read_deck_text(deck, "t.inp");
  REQUIRE(m.contact_clearances.size() == 5);
  const ContactClearance& i1 = m.contact_clearances[0];
  CHECK(i1.name == "I1");
  CHECK(i1.initialization);
  CHECK(i1.adjust);
  CHECK(i1.value == 0.0);  // no INITIAL CLEARANCE: overclosures adjusted to touching
  CHECK(i1.search_below == 0.2);
  CHECK(i1.search_above == 0.0);  // the manual's continuation line
  CHECK_FALSE(i1.interference);
  const ContactClearance& i2 = m.contact_clearances[1];
  CHECK(i2.value == 1e-3);
  CHECK_FALSE(i2.adjust);
  const ContactClearance& fit = m.contact_clearances[2];
  CHECK(fit.interference);
  CHECK_FALSE(fit.interference_distance.has_value());
  CHECK(fit.step_fraction == 0.5);
  CHECK_FALSE(fit.adjust);  // nothing to move without a distance
  const ContactClearance& fith = m.contact_clearances[3];
  CHECK(fith.interference);
  CHECK(fith.interference_distance == 2e-5);
  CHECK(fith.step_fraction == 1.0);  // the default: the whole first step
  CHECK(fith.adjust);                // moved to the distance first
  CHECK(fith.search_below == 1e-4);
  const ContactClearance& old = m.contact_clearances[4];
  CHECK(old.name == "I1");
  CHECK_FALSE(old.initialization);
  CHECK(old.value == 5e-4);

  REQUIRE(m.steps[0].contact);
  const std::vector<ClearanceAssignment>& a = m.steps[0].contact->clearances;
  REQUIRE(a.size() == 9);
  CHECK(a[0].clearance == 0);
  CHECK(a[0].view == ClearanceAssignment::View::Master);  // SECOND SURFACE SFC
  CHECK(a[1].clearance == 1);
  CHECK(a[1].view == ClearanceAssignment::View::Slave);  // FIRST SURFACE SFC
  CHECK(a[2].clearance == 2);
  CHECK(a[2].view == ClearanceAssignment::View::Both);
  const auto pts = static_cast<Index>(m.surfaces.size() - 2);
  CHECK(m.surfaces[pts].name == "PTS");
  CHECK((a[3].first == pts && a[3].clearance == 1 && a[3].view == ClearanceAssignment::View::Both));
  CHECK((a[4].second == pts && a[4].view == ClearanceAssignment::View::Master));
  CHECK((a[5].first == pts && a[5].clearance == 2));  // an interference fit: no view word
  CHECK(a[6].clearance == 4);  // *CONTACT CLEARANCE ASSIGNMENT finds *CONTACT CLEARANCE's I1
  CHECK(a[6].view == ClearanceAssignment::View::Master);
  CHECK((a[7].second == pts && a[7].view == ClearanceAssignment::View::Both));
  CHECK((a[8].first == pts && a[8].view == ClearanceAssignment::View::Slave));

  // MINIMUM DISTANCE is accepted with a note of what xpl does with it.
  const auto note =
      std::find_if(m.deck_messages.begin(), m.deck_messages.end(), [](const auto& msg) {
        return msg.text.find(
                   "MINIMUM DISTANCE=NO accepted without "
                   "effect") != std::string::npos;
      });
  REQUIRE(note != m.deck_messages.end());
  CHECK(note->text.rfind("t.inp:" + std::to_string(line_of(deck, "NAME=FIT,")), 0) == 0);
}

TEST_CASE("contact initialization errors, all together", "[io][deck][clearance][initialization]") {
  const std::string deck =
      SURFACES +
      "*CONTACT INITIALIZATION DATA, NAME=NEG, INTERFERENCE FIT=-1e-5\n"
      "*CONTACT INITIALIZATION DATA, NAME=F0, INTERFERENCE FIT, STEP FRACTION=0\n"
      "*CONTACT INITIALIZATION DATA, NAME=F2, INTERFERENCE FIT, STEP FRACTION=1.5\n"
      "*CONTACT INITIALIZATION DATA, NAME=SF, STEP FRACTION=0.5\n"
      "*CONTACT INITIALIZATION DATA, NAME=BOTH, INITIAL CLEARANCE=1e-3, INTERFERENCE FIT\n"
      "*CONTACT INITIALIZATION DATA, NAME=TOL, OVERCLOSURE TOLERANCE=1e-3\n"
      "*CONTACT INITIALIZATION DATA, NAME=MD, MINIMUM DISTANCE=MAYBE\n"
      "*CONTACT INITIALIZATION DATA, NAME=FIT, INTERFERENCE FIT\n"
      "*CONTACT INITIALIZATION DATA, NAME=ZERO\n"
      "*CONTACT INITIALIZATION DATA, NAME=ZERO\n"
      "*CONTACT CLEARANCE, NAME=OLD\n"
      "*STEP, NAME=FIRST\n" +
      STEP +
      "*CONTACT\n*CONTACT INCLUSIONS, ALL EXTERIOR\n"
      "*CONTACT INITIALIZATION ASSIGNMENT\n"
      "BODY, TOPS, NOSUCH\n"
      "BODY, TOPS, OLD\n"
      "PTS, TOPS, ZERO, MASTER\n"
      "TOPS, PTS, ZERO, SLAVE\n"
      "TOPS, PTS, ZERO, FIRST SURFACE SFC\n"
      "PTS, TOPS, ZERO, SECOND SURFACE SFC\n"
      "PTS, PTS2, ZERO\n"
      "BODY, TOPS, FIT, MASTER\n"
      "BODY, TOPS, ZERO, SIDEWAYS\n"
      "*END STEP\n"
      "*STEP, NAME=SECOND\n" +
      STEP +
      "*END STEP\n"
      "*STEP, NAME=THIRD\n" +
      STEP +
      "*CONTACT\n*CONTACT INCLUSIONS, ALL EXTERIOR\n"
      "*CONTACT INITIALIZATION ASSIGNMENT\n"
      "BODY, TOPS, FIT\n"
      "*END STEP\n";
  const auto errors = deck_errors(deck);
  auto data = [&](const std::string& needle) {
    return at(deck, needle, "*CONTACT INITIALIZATION DATA");
  };
  auto assignment = [&](const std::string& needle) {
    return at(deck, needle, "*CONTACT INITIALIZATION ASSIGNMENT");
  };
  const std::string outside =
      " is outside (0, 1]; expected a fraction of the step time 0 < f <= 1 (default 1: the "
      "whole first step)";
  // A view word that turns a node-based surface into the master (SPEC C13).
  const std::string node_expected =
      "expected a node-based surface (*SURFACE, TYPE=NODE) as the slave of an element-based "
      "surface: no view (the one view that exists), MASTER with the node-based surface second or "
      "SLAVE with it first (a node-based surface has no faces to be a master)";
  const auto as_master = [&](const std::string& view) {
    return " is node-based and would act as a master (" + view + "); " + node_expected;
  };
  const std::vector<std::string> expected = {
      data("NAME=NEG") +
          "INTERFERENCE FIT=-1e-5 is negative; expected an interference distance h > 0 (an "
          "overclosure), or INTERFERENCE FIT alone to take the overclosures as read",
      data("NAME=F0") + "STEP FRACTION=0" + outside,
      data("NAME=F2") + "STEP FRACTION=1.5" + outside,
      data("NAME=SF") +
          "STEP FRACTION without INTERFERENCE FIT; expected STEP FRACTION only with INTERFERENCE "
          "FIT (the fraction of the first step over which the interference is resolved)",
      data("NAME=BOTH") +
          "INITIAL CLEARANCE and INTERFERENCE FIT are both given; expected one of them (they are "
          "mutually exclusive): INITIAL CLEARANCE=c for a gap, INTERFERENCE FIT[=h] to resolve "
          "overclosures over the first step",
      data("NAME=TOL") +
          "unknown parameter OVERCLOSURE TOLERANCE; accepted parameters: NAME=, INITIAL "
          "CLEARANCE=, INTERFERENCE FIT=, ADJUST=, SEARCH ABOVE=, SEARCH BELOW=, MINIMUM "
          "DISTANCE=, STEP FRACTION=",
      data("NAME=MD") + "bad MINIMUM DISTANCE=MAYBE; expected MINIMUM DISTANCE=YES or NO",
      data("NAME=ZERO\n*CONTACT CLEARANCE") +
          "contact initialization ZERO is defined twice at t.inp:" +
          std::to_string(line_of(deck, "NAME=ZERO\n")) +
          "; expected each contact initialization name once",
      assignment("PTS, TOPS, ZERO, MASTER") + "surface PTS" + as_master("MASTER"),
      assignment("TOPS, PTS, ZERO, SLAVE") + "surface PTS" + as_master("SLAVE"),
      assignment("TOPS, PTS, ZERO, FIRST") + "surface PTS" + as_master("FIRST SURFACE SFC"),
      assignment("PTS, TOPS, ZERO, SECOND") + "surface PTS" + as_master("SECOND SURFACE SFC"),
      assignment("PTS, PTS2") +
          "surfaces PTS and PTS2 are both node-based: neither can be a "
          "master; " +
          node_expected,
      assignment("SIDEWAYS") +
          "bad view 'SIDEWAYS'; expected MASTER (surface 1 is the master: only the nodes of "
          "surface 2 move), SLAVE (surface 1 is the slave), SECOND SURFACE SFC (as MASTER), "
          "FIRST SURFACE SFC (as SLAVE) or nothing (both views)",
      // Resolved at the end.
      assignment("NOSUCH") +
          "undefined contact initialization NOSUCH; expected *CONTACT INITIALIZATION DATA, "
          "NAME=NOSUCH",
      // A *CONTACT CLEARANCE name is not an initialization.
      assignment("BODY, TOPS, OLD") +
          "undefined contact initialization OLD; expected *CONTACT INITIALIZATION DATA, NAME=OLD",
      assignment("FIT, MASTER") +
          "a view (MASTER, SLAVE, FIRST or SECOND SURFACE SFC) with interference fit FIT; "
          "expected no fourth field: an interference fit acts on both master-slave views of the "
          "pair (the view directs the adjustments of INITIAL CLEARANCE with ADJUST=YES only)",
      at(deck, "BODY, TOPS, FIT\n*END STEP\n", "*CONTACT INITIALIZATION ASSIGNMENT") +
          "interference fit FIT is assigned in step THIRD, which is not the first; expected an "
          "interference fit in the first step of the analysis (it is resolved over a fraction of "
          "that step, SPEC C15)",
  };
  CHECK(errors == expected);
}
