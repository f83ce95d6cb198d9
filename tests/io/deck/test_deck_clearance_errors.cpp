// Bad contact clearance input (SPEC C7–C10): every error of a deck at once, each as
// `file:LINE: *KEYWORD: problem; expected`.

#include <catch2/catch.hpp>

#include "deck/deck_test_support.hpp"

using namespace xpl;
using test::at;
using test::deck_errors;
using test::shell_plate_model;
using test::two_brick_model;

namespace {

/// Bricks, the plate with a fin (element 13 standing on the edge of nodes 2 and 5), a rigid
/// body on element 12, and surfaces that a clearance can and cannot use.
const std::string MODEL = two_brick_model() + shell_plate_model() +
                          "*NODE\n7, 1, 0, 1\n8, 1, 1, 1\n100, 5, 5, 5\n"
                          "*ELEMENT, TYPE=S4R, ELSET=FIN\n13, 2, 5, 8, 7\n"
                          "*SHELL SECTION, ELSET=FIN, MATERIAL=ALU\n0.002\n"
                          "*ELSET, ELSET=RIGIDS\n12\n"
                          "*RIGID BODY, REF NODE=100, ELSET=RIGIDS\n"
                          "*SURFACE, NAME=BODY\nBRICKS\n"
                          "*SURFACE, NAME=TOPS\nPLATE, SPOS\n"
                          "*SURFACE, NAME=SKIN\nPLATE\n"
                          "*SURFACE, NAME=TEE\nPLATE, SPOS\nFIN, SPOS\n"
                          "*SURFACE, NAME=FLIP\n11, SPOS\n12, SNEG\n"
                          "*SURFACE, NAME=R12\n12, SPOS\n"
                          "*SURFACE, NAME=PTS, TYPE=NODE\nPLATE_NODES\n"
                          "*CONTACT CLEARANCE, NAME=ZERO\n"
                          "*CONTACT CLEARANCE, NAME=OFF, ADJUST=NO\n";

const std::string STEP = "*DYNAMIC, EXPLICIT\n, 1e-3\n";
const std::string ASSIGNMENT_LINE = "surface 1, surface 2, clearance name[, MASTER|SLAVE]";
const std::string NON_NEGATIVE =
    "; expected a clearance >= 0 where the slave nodes or the master faces are on solids (a "
    "negative clearance is a gap below the normal of a shell surface)";

}  // namespace

TEST_CASE("contact clearance and distribution errors", "[io][deck][clearance][errors]") {
  const std::string deck =
      MODEL +
      "*CONTACT CLEARANCE, NAME=BAD, ADJUST=MAYBE, CLEARANCE=1e-3x, SEARCH ABOVE=-1\n"
      "SEARCH BELOW=b\n"
      "*CONTACT CLEARANCE, NAME=ZERO, CLEARANCE=NOPE\n"
      "*CONTACT CLEARANCE, ADJUST=NO\n"
      "0.5\n"
      "SEARCH ABOVE=1, NAME=X\n"
      "*CONTACT CLEARANCE, NAME=TWICE, SEARCH ABOVE=1\n"
      "SEARCH ABOVE=2\n"
      "*CONTACT CLEARANCE, NAME=GHOSTLY, CLEARANCE=GHOST\n"
      "*DISTRIBUTION, NAME=E, LOCATION=ELEMENT\n, 1\n"
      "*DISTRIBUTION, NAME=F\n, 1\n"
      "*DISTRIBUTION, NAME=G, LOCATION=NODE, TABLE=NOTAB\n"
      ", 1\n"
      "2, 1, 2\n"
      "3\n"
      ", 4\n"
      "NOSET, 5\n"
      "*DISTRIBUTION, NAME=G, LOCATION=NODE\n, 1\n"
      "*DISTRIBUTION TABLE, NAME=T2\nLENGTH, LENGTH\n"
      "*DISTRIBUTION TABLE, NAME=T3\nVECTOR\n"
      "*STEP\n" +
      STEP + "*END STEP\n" + "*CONTACT CLEARANCE, NAME=LATE\n";
  const auto errors = deck_errors(deck);
  auto clearance = [&](const std::string& needle) {
    return at(deck, needle, "*CONTACT CLEARANCE");
  };
  auto distribution = [&](const std::string& needle) { return at(deck, needle, "*DISTRIBUTION"); };
  const std::string only_nodal =
      "; expected LOCATION=NODE (only nodal distributions are read: a clearance per node)";
  const std::string one_type =
      "; expected one column type, LENGTH or SCALAR (a nodal distribution holds one value per "
      "node)";
  const std::vector<std::string> expected = {
      clearance("NAME=BAD") +
          "bad ADJUST=MAYBE; expected ADJUST=YES (move the slave nodes, strain free, in the first "
          "step; the default) or ADJUST=NO (permanent contact offsets)",
      clearance("NAME=BAD") +
          "bad number '1e-3x' for CLEARANCE; expected a real number such as 0.5 or 1e-3, or the "
          "name of a *DISTRIBUTION",
      clearance("NAME=BAD") + "SEARCH ABOVE=-1 is negative; expected a search distance >= 0",
      clearance("SEARCH BELOW=b") +
          "bad number 'b' for SEARCH BELOW; expected a search distance >= 0 such as 0.2",
      clearance("NAME=ZERO, CLEARANCE=NOPE") + "contact clearance ZERO is defined twice at t.inp:" +
          std::to_string(test::line_of(deck, "NAME=ZERO\n")) +
          "; expected each contact clearance name once",
      clearance("*CONTACT CLEARANCE, ADJUST=NO") + "missing parameter NAME; expected NAME=name",
      clearance("0.5\n") +
          "unexpected data line; expected no data lines, or a line of more parameters such as "
          "SEARCH ABOVE=0.0 (ADJUST=, CLEARANCE=, SEARCH ABOVE=, SEARCH BELOW=)",
      clearance("NAME=X") +
          "unknown parameter NAME; accepted parameters: ADJUST=, CLEARANCE=, SEARCH ABOVE=, "
          "SEARCH BELOW=",
      clearance("SEARCH ABOVE=2") + "parameter SEARCH ABOVE given twice; expected it at most once",
      distribution("LOCATION=ELEMENT") + "LOCATION=ELEMENT is not supported" + only_nodal,
      distribution("*DISTRIBUTION, NAME=F\n") + "missing parameter LOCATION" + only_nodal,
      distribution("2, 1, 2") +
          "too many values (3) on the data line; expected node or node set, value (a blank node "
          "field on the first line: the default of every node not listed)",
      distribution("3\n, 4") + "missing distribution value; expected a number",
      distribution(", 4\nNOSET") +
          "blank node field; expected a node id or node set (only the first data line may leave "
          "it blank: the default value)",
      distribution("*DISTRIBUTION, NAME=G, LOCATION=NODE\n") +
          "distribution G is defined twice at t.inp:" +
          std::to_string(test::line_of(deck, "NAME=G, LOCATION=NODE, TABLE")) +
          "; expected each distribution name once",
      at(deck, "LENGTH, LENGTH", "*DISTRIBUTION TABLE") + "2 column types (LENGTH, LENGTH)" +
          one_type,
      at(deck, "VECTOR", "*DISTRIBUTION TABLE") + "unsupported column type VECTOR" + one_type,
      clearance("NAME=LATE") +
          "model data after the first step; expected all model data before the first *STEP",
      // Resolved at the end.
      distribution("TABLE=NOTAB") +
          "undefined distribution table NOTAB; expected *DISTRIBUTION TABLE, NAME=NOTAB or no "
          "TABLE=",
      distribution("NOSET, 5") + "undefined node set NOSET; expected *NSET, NSET=NOSET",
      clearance("CLEARANCE=GHOST") +
          "undefined distribution GHOST; expected *DISTRIBUTION, NAME=GHOST, LOCATION=NODE, or a "
          "number",
  };
  CHECK(errors == expected);
}

TEST_CASE("clearance assignment errors: names, surfaces, signs, rigid slaves",
          "[io][deck][clearance][errors]") {
  const std::string deck = MODEL +
                           "*CONTACT CLEARANCE, NAME=NEG, ADJUST=NO, CLEARANCE=-1e-3\n"
                           "*CONTACT CLEARANCE, NAME=NEGD, CLEARANCE=D\n"
                           "*DISTRIBUTION, NAME=D, LOCATION=NODE\n"
                           "1, -0.002\n"
                           "*STEP, NAME=FIRST\n" +
                           STEP +
                           "*CONTACT CLEARANCE ASSIGNMENT\nBODY, TOPS, ZERO\n"
                           "*CONTACT\n*CONTACT INCLUSIONS, ALL EXTERIOR\n"
                           "*CONTACT CLEARANCE ASSIGNMENT, TYPE=X\n"
                           "BODY, TOPS, NEG\n"
                           "TOPS, BODY, NEGD, MASTER\n"
                           "BODY, TOPS, NOBODY\n"
                           "BODY, GHOST, ZERO\n"
                           "BODY, PTS, ZERO, SLAVE\n"
                           "TOPS, tops, ZERO\n"
                           "BODY, TOPS, ZERO, BOTH\n"
                           "BODY, , ZERO\n"
                           "SKIN, BODY, ZERO\n"
                           "TEE, BODY, ZERO\n"
                           "FLIP, BODY, ZERO\n"
                           "BODY, R12, ZERO, MASTER\n"
                           "BODY, TOPS, ZERO, SLAVE, 1\n"
                           "SKIN, TOPS, ZERO\n"  // SKIN reported once
                           "*CONTACT CLEARANCE ASSIGNMENT\n"
                           "*END STEP\n";
  const auto errors = deck_errors(deck);
  auto assignment = [&](const std::string& needle) {
    return at(deck, needle, "*CONTACT CLEARANCE ASSIGNMENT");
  };
  const std::vector<std::string> expected = {
      assignment("*CONTACT CLEARANCE ASSIGNMENT\nBODY") +
          "no *CONTACT in step FIRST; expected *CONTACT before *CONTACT CLEARANCE ASSIGNMENT in "
          "the same step",
      assignment("TYPE=X") + "unknown parameter TYPE; accepted parameters: none",
      assignment("BODY, GHOST") + "undefined surface GHOST; expected *SURFACE, NAME=GHOST",
      assignment("BODY, PTS, ZERO, SLAVE") +
          "surface PTS is node-based and would act as a master (SLAVE); expected a node-based "
          "surface (*SURFACE, TYPE=NODE) as the slave of an element-based surface: no view (the "
          "one view that exists), MASTER with the node-based surface second or SLAVE with it "
          "first (a node-based surface has no faces to be a master)",
      assignment("TOPS, tops") +
          "self contact of surface TOPS; expected two different surfaces (clearances do not "
          "apply to self contact)",
      assignment("ZERO, BOTH") +
          "bad view 'BOTH'; expected MASTER (surface 1 is the master: only the nodes of surface "
          "2 move), SLAVE (surface 1 is the slave) or nothing (both views)",
      assignment("BODY, , ZERO") + "missing surface 2; expected " + ASSIGNMENT_LINE,
      assignment("SLAVE, 1") + "too many values (5) on the data line; expected " + ASSIGNMENT_LINE,
      assignment("*CONTACT CLEARANCE ASSIGNMENT\n*END") +
          "no assignments; expected data lines: " + ASSIGNMENT_LINE,
      // Resolved at the end.
      assignment("BODY, TOPS, NEG\n") +
          "clearance NEG is negative (-0.001) between surfaces BODY (slave) and TOPS (master), "
          "and BODY is on C3D8R solid elements" +
          NON_NEGATIVE,
      // No default value: the brick nodes take theirs from the master face, node 1 among them.
      assignment("NEGD, MASTER") +
          "clearance NEGD is negative (-0.002 at node 1 in distribution D) between surfaces BODY "
          "(slave) and TOPS (master), and BODY is on C3D8R solid elements" +
          NON_NEGATIVE,
      assignment("NOBODY") +
          "undefined contact clearance NOBODY; expected *CONTACT CLEARANCE, NAME=NOBODY",
      assignment("SKIN, BODY") +
          "surface SKIN is not single sided: it holds both SPOS and SNEG of S4R element 11; "
          "expected one side of each shell (SPOS or SNEG; a surface line without a face label "
          "takes both sides)",
      assignment("TEE, BODY") +
          "surface TEE has the edge of nodes 2 and 5 on 3 of its faces; expected each edge on at "
          "most two faces of a surface with a clearance",
      assignment("FLIP, BODY") +
          "surface FLIP has discontinuous normals: elements 11 and 12 run through the edge of "
          "nodes 2 and 5 in the same direction; expected neighbouring faces with their normals "
          "on the same side (swap SPOS and SNEG of one of them)",
      assignment("BODY, R12") +
          "slave surface R12 lies wholly on rigid bodies: the assignment has no slave nodes; "
          "expected a deformable slave surface (elements outside *RIGID BODY, ELSET=): MASTER "
          "makes surface 2 the slave, SLAVE surface 1",
  };
  CHECK(errors == expected);
}

TEST_CASE("clearance assignment errors: steps whose contact domain is not new",
          "[io][deck][clearance][errors]") {
  // FIRST has contact, SECOND carries it over, THIRD drops it (OP=NEW without inclusions),
  // FOURTH builds a new domain: ADJUST=NO is fine there, ADJUST=YES is not.
  const std::string deck = MODEL + "*STEP, NAME=FIRST\n" + STEP +
                           "*CONTACT\n*CONTACT INCLUSIONS, ALL EXTERIOR\n"
                           "*CONTACT CLEARANCE ASSIGNMENT\nBODY, TOPS, ZERO\n*END STEP\n"
                           "*STEP, NAME=SECOND\n" +
                           STEP +
                           "*CONTACT\n*CONTACT CLEARANCE ASSIGNMENT\nTOPS, BODY, OFF\n*END STEP\n"
                           "*STEP, NAME=THIRD\n" +
                           STEP +
                           "*CONTACT, OP=NEW\n*CONTACT CLEARANCE ASSIGNMENT\nBODY, TOPS, OFF, "
                           "SLAVE\n*END STEP\n"
                           "*STEP, NAME=FOURTH\n" +
                           STEP +
                           "*CONTACT\n*CONTACT INCLUSIONS\nBODY, TOPS\n"
                           "*CONTACT CLEARANCE ASSIGNMENT\nTOPS, BODY, ZERO, MASTER\n"
                           "BODY, TOPS, OFF\n*END STEP\n";
  auto assignment = [&](const std::string& needle) {
    return at(deck, needle, "*CONTACT CLEARANCE ASSIGNMENT");
  };
  const std::vector<std::string> expected = {
      assignment("TOPS, BODY, OFF\n") +
          "clearances apply only when a step's contact domain is built new; the contact in "
          "effect in step FIRST carries over into step SECOND; expected the assignment in the "
          "first step, or in a step that follows one without contact (then with ADJUST=NO)",
      assignment("OFF, SLAVE") +
          "step THIRD has no general contact domain to assign clearances to; expected *CONTACT "
          "INCLUSIONS in the step of the *CONTACT (or an earlier one)",
      assignment("ZERO, MASTER") +
          "clearance ZERO moves nodes (ADJUST=YES, also the default), which only the first step "
          "can do, and step FOURTH is not the first; expected ADJUST=NO (contact offsets) on "
          "*CONTACT CLEARANCE, NAME=ZERO for a step after the first",
  };
  CHECK(deck_errors(deck) == expected);

  // A model-level *CONTACT PAIR is in effect from the first step on: no later step is new.
  const std::string paired = MODEL +
                             "*SURFACE INTERACTION, NAME=PLAIN\n"
                             "*CONTACT PAIR, INTERACTION=PLAIN\nTOPS, BODY\n"
                             "*STEP, NAME=FIRST\n" +
                             STEP + "*END STEP\n*STEP, NAME=SECOND\n" + STEP +
                             "*CONTACT\n*CONTACT INCLUSIONS, ALL EXTERIOR\n"
                             "*CONTACT CLEARANCE ASSIGNMENT\nBODY, TOPS, OFF\n*END STEP\n";
  CHECK(deck_errors(paired) ==
        std::vector<std::string>{
            at(paired, "BODY, TOPS, OFF", "*CONTACT CLEARANCE ASSIGNMENT") +
            "clearances apply only when a step's contact domain is built new; the contact in "
            "effect in step FIRST carries over into step SECOND; expected the assignment in the "
            "first step, or in a step that follows one without contact (then with ADJUST=NO)"});
}
