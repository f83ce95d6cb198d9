// Decks as mesh generators write them (SPEC I5, issue 34 item 2): section-less CPS4/CPS3/T3D2
// blocks read as geometry (node sets, surfaces by matching faces), CPS4 under a *SHELL SECTION
// run as S4R, foreign element names refused once with the nearest supported type, integral
// floats as ids.

#include <catch2/catch.hpp>

#include <algorithm>

#include "deck/deck_test_support.hpp"

using namespace xpl;
using test::at;
using test::deck_errors;
using test::has_error;

namespace {

/// Two unit hexes along x (nodes 1..12, elements 21, 22), as gmsh writes them: a CPS4 block per
/// physical surface (the x = 0 end face, element 1; the top faces, elements 2 and 3), a T3D2
/// edge and an *ELSET per physical group.
const std::string MESH =
    "*NODE\n"
    "1, 0, 0, 0\n"
    "2, 1, 0, 0\n"
    "3, 1, 1, 0\n"
    "4, 0, 1, 0\n"
    "5, 2, 0, 0\n"
    "6, 2, 1, 0\n"
    "7, 0, 0, 1\n"
    "8, 1, 0, 1\n"
    "9, 1, 1, 1\n"
    "10, 0, 1, 1\n"
    "11, 2, 0, 1\n"
    "12, 2, 1, 1\n"
    "*ELEMENT, type=T3D2, ELSET=Line1\n"
    "30, 1, 4\n"
    "*ELEMENT, type=CPS4, ELSET=Surface1\n"
    "1, 1, 4, 10, 7\n"
    "*ELEMENT, type=CPS4, ELSET=Surface2\n"
    "2, 7, 8, 9, 10\n"
    "3, 8, 11, 12, 9\n"
    "*ELEMENT, type=C3D8, ELSET=Volume1\n"
    "21, 1, 2, 3, 4, 7, 8, 9, 10\n"
    "22, 2, 5, 6, 3, 8, 11, 12, 9\n"
    "*ELSET,ELSET=edge\n"
    "30, \n"
    "*ELSET,ELSET=end\n"
    "1, \n"
    "*ELSET,ELSET=top\n"
    "2, 3, \n"
    "*ELSET,ELSET=body\n"
    "21, 22, \n";

const std::string PHYSICS =
    "*MATERIAL, NAME=STEEL\n"
    "*DENSITY\n"
    "7800.\n"
    "*ELASTIC\n"
    "2.1e11, 0.3\n"
    "*SOLID SECTION, ELSET=body, MATERIAL=STEEL\n"
    "*SURFACE, NAME=TOP_FACE\n"
    "top\n"
    "*STEP\n"
    "*DYNAMIC, EXPLICIT\n"
    ", 1e-5\n"
    "*BOUNDARY\n"
    "end, ENCASTRE\n"
    "*DSLOAD\n"
    "TOP_FACE, P, 1e6\n"
    "*END STEP\n";

const NamedSet& set_named(const std::vector<NamedSet>& sets, const std::string& name) {
  const auto it =
      std::find_if(sets.begin(), sets.end(), [&](const NamedSet& s) { return s.name == name; });
  REQUIRE(it != sets.end());
  return *it;
}

bool has_note(const Model& m, const std::string& text) {
  return std::any_of(m.deck_messages.begin(), m.deck_messages.end(),
                     [&](const DeckMessage& n) { return n.text.find(text) != std::string::npos; });
}

}  // namespace

TEST_CASE("gmsh's section-less faces and edges are geometry", "[io][deck][mesh_export]") {
  const std::string deck = MESH + PHYSICS;
  const Model m = io::read_deck_text(deck, "t.inp");
  REQUIRE(m.element_count() == 2);  // the hexes only
  CHECK(m.element_ids == std::vector<ExternalId>{21, 22});
  // Element sets of geometry only are node sets of their nodes.
  CHECK(set_named(m.node_sets, "END").members == std::vector<Index>{0, 3, 6, 9});
  CHECK(set_named(m.node_sets, "TOP").members.size() == 6);
  CHECK(set_named(m.node_sets, "EDGE").members == std::vector<Index>{0, 3});
  CHECK(set_named(m.node_sets, "SURFACE1").members.size() == 4);
  CHECK(set_named(m.element_sets, "TOP").members.empty());
  // The BC on the end face: 4 nodes.
  CHECK(m.steps[0].boundaries.size() == 4);
  // TOP_FACE: the faces S2 of both hexes (the CPS4 faces lie on them).
  const Surface& top = m.surfaces[static_cast<std::size_t>(m.find_surface("TOP_FACE"))];
  REQUIRE(top.faces.size() == 2);
  CHECK(top.faces[0].element == 0);
  CHECK(top.faces[0].face == 1);
  CHECK(top.faces[1].element == 1);
  CHECK(top.faces[1].face == 1);
  CHECK(m.steps[0].pressures.size() == 2);
  CHECK(has_note(m, "t.inp:" + std::to_string(test::line_of(deck, "type=CPS4, ELSET=Surface2")) +
                        ": *ELEMENT: 2 CPS4 elements (ELSET=SURFACE2) carry no section: read as "
                        "geometry"));
  CHECK(has_note(m,
                 "node sets made from element sets of geometry (nodes): LINE1 (2), "
                 "SURFACE1 (4), SURFACE2 (6), EDGE (2), END (4), TOP (6)"));
}

TEST_CASE("CPS4 under a *SHELL SECTION run as S4R", "[io][deck][mesh_export]") {
  const std::string deck =
      "*NODE\n"
      "1, 0, 0, 0\n"
      "2, 1, 0, 0\n"
      "3, 2, 0, 0\n"
      "4, 0, 1, 0\n"
      "5, 1, 1, 0\n"
      "6, 2, 1, 0\n"
      "*ELEMENT, type=T3D2, ELSET=Line4\n"
      "1, 4, 1\n"
      "*ELEMENT, type=CPS4, ELSET=Surface1\n"
      "2, 1, 2, 5, 4\n"
      "3, 2, 3, 6, 5\n"
      "*ELSET,ELSET=clamped\n"
      "1, \n"
      "*ELSET,ELSET=plate\n"
      "2, 3, \n"
      "*MATERIAL, NAME=ALU\n*DENSITY\n2700.\n*ELASTIC\n7e10, 0.33\n"
      "*SHELL SECTION, ELSET=plate, MATERIAL=ALU\n"
      "0.002\n"
      "*SURFACE, NAME=SKIN\n"
      "Surface1\n" +
      test::simple_step();
  const Model m = io::read_deck_text(deck, "t.inp");
  REQUIRE(m.element_count() == 2);
  CHECK(m.element_types == std::vector<ElementType>{ElementType::S4R, ElementType::S4R});
  CHECK(m.element_ids == std::vector<ExternalId>{2, 3});
  CHECK(m.element_section == std::vector<Index>{0, 0});
  CHECK(set_named(m.element_sets, "PLATE").members == std::vector<Index>{0, 1});
  CHECK(set_named(m.element_sets, "SURFACE1").members == std::vector<Index>{0, 1});
  CHECK(set_named(m.node_sets, "CLAMPED").members == std::vector<Index>{0, 3});
  // A surface of elements that now run: both sides of each shell.
  CHECK(m.surfaces[0].faces.size() == 4);
  CHECK(has_note(m,
                 ": *ELEMENT: 2 CPS4 elements (ELSET=SURFACE1) are under a *SHELL SECTION: "
                 "run as S4R shells"));
}

TEST_CASE("geometry a section or a surface cannot take", "[io][deck][mesh_export][errors]") {
  SECTION("CPS3 under a shell section, CPS4 under a solid section") {
    const std::string deck =
        "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 1, 1, 0\n4, 0, 1, 0\n"
        "*ELEMENT, type=CPS3, ELSET=Tri\n"
        "1, 1, 2, 3\n"
        "*ELEMENT, type=CPS4, ELSET=Quad\n"
        "2, 1, 2, 3, 4\n"
        "*MATERIAL, NAME=M\n*DENSITY\n1.\n*ELASTIC\n1e6, 0.3\n"
        "*SHELL SECTION, ELSET=Tri, MATERIAL=M\n0.1\n"
        "*SOLID SECTION, ELSET=Quad, MATERIAL=M\n" +
        test::simple_step();
    const std::vector<std::string> e = deck_errors(deck);
    CHECK(has_error(
        e, at(deck, "*SHELL SECTION", "*SHELL SECTION"),
        "CPS3 elements of the block at t.inp:" + std::to_string(test::line_of(deck, "type=CPS3")) +
            " in ELSET=TRI; expected quadrilaterals"));
    CHECK(has_error(e, at(deck, "*SOLID SECTION", "*SOLID SECTION"),
                    "expected a *SHELL SECTION (CPS4 then run as S4R) or no section"));
  }
  SECTION("edges and face labels in a surface, a face off the mesh") {
    const std::string deck = MESH +
                             "*ELEMENT, type=CPS4, ELSET=Loose\n"
                             "40, 1, 2, 5, 4\n"
                             "*SURFACE, NAME=A\nedge\n"
                             "*SURFACE, NAME=B\ntop, S2\n"
                             "*SURFACE, NAME=C\nLoose\n" +
                             PHYSICS;
    const std::vector<std::string> e = deck_errors(deck);
    CHECK(has_error(e, at(deck, "edge\n*SURFACE, NAME=B", "*SURFACE"), "is an edge"));
    CHECK(has_error(e, at(deck, "top, S2", "*SURFACE"), "face label S2 on geometry elements"));
    CHECK(has_error(e, at(deck, "Loose\n*MATERIAL", "*SURFACE"),
                    "1 geometry faces (first: element 40) lie on no solid or shell face"));
    CHECK(e.size() == 3);
  }
}

TEST_CASE("element names Abaqus/Explicit does not have: one error per type",
          "[io][deck][mesh_export][errors]") {
  const std::string deck =
      "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 1, 1, 0\n4, 0, 1, 0\n"
      "5, 0, 0, 1\n6, 1, 0, 1\n7, 1, 1, 1\n8, 0, 1, 1\n"
      "*ELEMENT, TYPE=CAX4P\n"
      "1, 1, 2, 3, 4\n"
      "*ELEMENT, TYPE=CAX4P\n"
      "2, 5, 6, 7, 8\n"
      "*ELEMENT, TYPE=C3D8RH\n"
      "3, 1, 2, 3, 4, 5, 6, 7, 8\n"
      "*ELSET, ELSET=all\n"
      "1, 2, 3\n"
      "*MATERIAL, NAME=M\n*DENSITY\n1.\n*ELASTIC\n1e6, 0.3\n"
      "*SOLID SECTION, ELSET=all, MATERIAL=M\n" +
      test::simple_step();
  const std::vector<std::string> e = deck_errors(deck);
  CHECK(e.size() == 2);
  CHECK(has_error(e, at(deck, "TYPE=CAX4P\n1,", "*ELEMENT"),
                  "element type CAX4P is not supported; nearest supported: S4R"));
  CHECK(has_error(e, at(deck, "TYPE=C3D8RH", "*ELEMENT"),
                  "element type C3D8RH is not supported; nearest supported: C3D8R (or C3D8); "
                  "C3D8RH is a hybrid element"));
}

TEST_CASE("ids written as integral floats", "[io][deck][mesh_export]") {
  std::string deck = test::two_brick_model() + test::simple_step();
  deck.replace(deck.find("1000001, 0, 0, 0"), 16, "1000001.0, 0, 0, 0");
  deck.replace(deck.find("5000002, 1000002"), 16, "5000002., 1000002.000");
  const Model m = io::read_deck_text(deck, "t.inp");
  CHECK(m.node_ids[0] == 1000001);
  CHECK(m.element_ids[1] == 5000002);
  CHECK(m.nodes_of(1)[0] == 1);
}
