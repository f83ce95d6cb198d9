// S4R shells in the deck: elements (S4 read as S4R), *SHELL SECTION, SPOS/SNEG surfaces,
// *DLOAD/*DSLOAD pressures and rotational output variables.

#include <catch2/catch.hpp>

#include "deck/deck_test_support.hpp"

using namespace xpl;
using test::line_of;
using test::shell_plate_model;
using test::simple_step;
using test::two_brick_model;

namespace {

/// Three S4R elements in a row; 12 and 13 written as S4. One section per element.
const std::string SHELL_DECK =
    "*NODE, NSET=ALL\n"
    "1, 0, 0, 0\n"
    "2, 1, 0, 0\n"
    "3, 2, 0, 0\n"
    "4, 3, 0, 0\n"
    "5, 0, 1, 0\n"
    "6, 1, 1, 0\n"
    "7, 2, 1, 0\n"
    "8, 3, 1, 0\n"
    "*ELEMENT, TYPE=S4R, ELSET=A\n"
    "11, 1, 2, 6, 5\n"
    "*Element, type=s4, elset=B\n"
    "12, 2, 3, 7, 6\n"
    "13, 3, 4, 8, 7\n"
    "*ELSET, ELSET=B2\n"
    "12\n"
    "*ELSET, ELSET=C\n"
    "13\n"
    "*MATERIAL, NAME=ALU\n"
    "*DENSITY\n"
    "2700.\n"
    "*ELASTIC\n"
    "7e10, 0.33\n"
    "*SECTION CONTROLS, NAME=HG, HOURGLASS=VISCOUS\n"
    "*SHELL SECTION, ELSET=A, MATERIAL=ALU\n"
    "0.002\n"
    "*SHELL SECTION, ELSET=B2, MATERIAL=ALU, OFFSET=SPOS, CONTROLS=HG, SECTION "
    "INTEGRATION=SIMPSON\n"
    "1.5e-3, 3\n"
    "*Shell Section, elset=c, material=alu, offset=-0.25\n"
    "0.004, 1\n" +
    simple_step();

}  // namespace

TEST_CASE("a shell deck: S4R and S4 elements, thickness, offsets, integration points",
          "[io][deck][shell]") {
  const Model m = io::read_deck_text(SHELL_DECK, "shells.inp");
  CHECK(m.has_shells());
  REQUIRE(m.element_count() == 3);
  CHECK(m.element_types ==
        std::vector<ElementType>{ElementType::S4R, ElementType::S4R, ElementType::S4R});
  CHECK(m.element_offsets == std::vector<Index>{0, 4, 8, 12});
  CHECK(m.element_nodes == std::vector<Index>{0, 1, 5, 4, 1, 2, 6, 5, 2, 3, 7, 6});
  CHECK(m.solid_sections.empty());
  REQUIRE(m.shell_sections.size() == 3);
  CHECK(m.element_section == std::vector<Index>{0, 1, 2});

  const ShellSection& a = m.shell_sections[0];
  CHECK(a.thickness == 0.002);
  CHECK(a.integration_points == 5);  // the Abaqus default
  CHECK(a.offset == 0.0);
  CHECK(a.material == m.find_material("ALU"));
  CHECK(a.controls == NO_INDEX);
  CHECK(a.element_set == m.find_element_set("A"));
  CHECK(a.where.line == line_of(SHELL_DECK, "*SHELL SECTION, ELSET=A"));
  const ShellSection& b = m.shell_sections[1];
  CHECK(b.thickness == 1.5e-3);
  CHECK(b.integration_points == 3);
  CHECK(b.offset == 0.5);
  CHECK(b.controls == 0);
  const ShellSection& c = m.shell_sections[2];
  CHECK(c.thickness == 0.004);
  CHECK(c.integration_points == 1);
  CHECK(c.offset == -0.25);

  // One note per *ELEMENT keyword written with S4, not one per element.
  REQUIRE(m.deck_messages.size() == 1);
  CHECK_FALSE(m.deck_messages[0].warning);
  CHECK(m.deck_messages[0].text ==
        "shells.inp:" + std::to_string(line_of(SHELL_DECK, "*Element, type=s4")) +
            ": *ELEMENT: S4 elements are run as S4R (reduced integration with hourglass control)");
}

TEST_CASE("OFFSET words and numbers", "[io][deck][shell]") {
  const std::pair<std::string, Real> cases[] = {{"SNEG", -0.5}, {"midsurface", 0.0}, {"SPOS", 0.5},
                                                {"0.5", 0.5},   {"-.5", -0.5},       {"0", 0.0}};
  for (const auto& [word, offset] : cases) {
    std::string deck = shell_plate_model() + simple_step();
    const std::string section = "*SHELL SECTION, ELSET=PLATE, MATERIAL=ALU";
    deck.replace(deck.find(section), section.size(), section + ", OFFSET=" + word);
    const Model m = io::read_deck_text(deck, "offset.inp");
    INFO("OFFSET=" << word);
    CHECK(m.shell_sections[0].offset == offset);
    CHECK(m.deck_messages.empty());
  }
}

TEST_CASE("solids and shells in one model keep separate section lists", "[io][deck][shell]") {
  const Model m =
      io::read_deck_text(two_brick_model() + shell_plate_model() + simple_step(), "mixed.inp");
  REQUIRE(m.element_count() == 4);
  CHECK(m.element_types == std::vector<ElementType>{ElementType::C3D8R, ElementType::C3D8R,
                                                    ElementType::S4R, ElementType::S4R});
  CHECK(m.element_offsets == std::vector<Index>{0, 8, 16, 20, 24});
  // Element i's section indexes solid_sections for the bricks, shell_sections for the shells.
  CHECK(m.element_section == std::vector<Index>{0, 0, 0, 0});
  REQUIRE(m.solid_sections.size() == 1);
  REQUIRE(m.shell_sections.size() == 1);
  CHECK(m.solid_sections[0].material == m.find_material("STEEL"));
  CHECK(m.shell_sections[0].material == m.find_material("ALU"));
  CHECK(m.has_shells());
  // Plate node 5 (deck id 5) is row 16 of the nodes: after the 12 brick nodes.
  CHECK(m.nodes_of(2)[2] == 16);
}

TEST_CASE("a model of bricks only has no shells", "[io][deck][shell]") {
  CHECK_FALSE(io::read_deck_text(two_brick_model() + simple_step(), "b.inp").has_shells());
}

TEST_CASE("SPOS and SNEG surfaces on shells, S1..S6 on bricks", "[io][deck][shell]") {
  const std::string deck = two_brick_model() + shell_plate_model() +
                           "*SURFACE, NAME=TOP\n"
                           "PLATE, SPOS\n"
                           "*SURFACE, NAME=UNDER\n"
                           "12, sneg\n"
                           "*SURFACE, NAME=BOTH\n"
                           "11, SNEG\n"
                           "BRICKS, S2\n" +
                           simple_step();
  const Model m = io::read_deck_text(deck, "surf.inp");
  const Surface& top = m.surfaces[m.find_surface("TOP")];
  REQUIRE(top.faces.size() == 2);
  CHECK(top.faces[0].element == 2);
  CHECK(top.faces[0].face == SHELL_FACE_POS);
  CHECK(top.faces[1].element == 3);
  CHECK(top.faces[1].face == SHELL_FACE_POS);
  const Surface& under = m.surfaces[m.find_surface("UNDER")];
  REQUIRE(under.faces.size() == 1);
  CHECK(under.faces[0].element == 3);
  CHECK(under.faces[0].face == SHELL_FACE_NEG);
  const Surface& both = m.surfaces[m.find_surface("BOTH")];
  REQUIRE(both.faces.size() == 3);
  CHECK(both.faces[0].face == SHELL_FACE_NEG);
  CHECK(both.faces[1].element == 0);
  CHECK(both.faces[1].face == 1);  // S2
  CHECK(both.faces[2].element == 1);
}

TEST_CASE("pressures from *DLOAD and *DSLOAD with amplitude, OP=MOD and OP=NEW",
          "[io][deck][shell]") {
  const std::string deck = two_brick_model() + shell_plate_model() +
                           "*SURFACE, NAME=TOP\nPLATE, SPOS\n"
                           "*SURFACE, NAME=BACK\n12, SNEG\n"
                           "*SURFACE, NAME=BRICK_END\n5000002, S4\n"
                           "*AMPLITUDE, NAME=RISE\n0, 0, 1e-3, 1\n"
                           "*STEP, NAME=LOAD\n*DYNAMIC, EXPLICIT\n, 1e-3\n"
                           "*DLOAD, AMPLITUDE=RISE\n"
                           "PLATE, P, 1e5\n"
                           "5000001, p2, -2.5e4\n"
                           "*DSLOAD\n"
                           "BACK, P, 3e3\n"
                           "brick_end, p, 7.\n"
                           "*END STEP\n"
                           "*STEP, NAME=SWAP\n*DYNAMIC, EXPLICIT\n, 1e-3\n"
                           "*DSLOAD, OP=NEW, AMPLITUDE=RISE\n"
                           "TOP, P, 2e5\n"
                           "*DLOAD, OP=MOD\n"
                           "11, P, 1\n"
                           "*END STEP\n"
                           "*STEP, NAME=CLEAR\n*DYNAMIC, EXPLICIT\n, 1e-3\n"
                           "*DLOAD, OP=NEW\n"
                           "*END STEP\n";
  const Model m = io::read_deck_text(deck, "p.inp");
  const Index rise = m.find_amplitude("RISE");
  REQUIRE(m.steps.size() == 3);

  const Step& load = m.steps[0];
  CHECK_FALSE(load.pressures_reset);
  REQUIRE(load.pressures.size() == 5);
  // Deck order; sets expanded in element order. Shell P acts on face SPOS.
  CHECK(load.pressures[0].face.element == 2);
  CHECK(load.pressures[0].face.face == SHELL_FACE_POS);
  CHECK(load.pressures[0].value == 1e5);
  CHECK(load.pressures[0].amplitude == rise);
  CHECK(load.pressures[0].where.line == line_of(deck, "PLATE, P, 1e5"));
  CHECK(load.pressures[1].face.element == 3);
  CHECK(load.pressures[1].face.face == SHELL_FACE_POS);
  CHECK(load.pressures[2].face.element == 0);
  CHECK(load.pressures[2].face.face == 1);  // P2 -> face S2
  CHECK(load.pressures[2].value == -2.5e4);
  CHECK(load.pressures[2].amplitude == rise);
  CHECK(load.pressures[3].face.element == 3);
  CHECK(load.pressures[3].face.face == SHELL_FACE_NEG);
  CHECK(load.pressures[3].value == 3e3);
  CHECK(load.pressures[3].amplitude == NO_INDEX);
  CHECK(load.pressures[4].face.element == 1);
  CHECK(load.pressures[4].face.face == 3);  // S4
  CHECK(load.pressures[4].value == 7.0);

  const Step& swap = m.steps[1];
  CHECK(swap.pressures_reset);
  REQUIRE(swap.pressures.size() == 3);
  CHECK(swap.pressures[0].face.element == 2);
  CHECK(swap.pressures[0].value == 2e5);
  CHECK(swap.pressures[0].amplitude == rise);
  CHECK(swap.pressures[1].face.element == 3);
  CHECK(swap.pressures[2].face.element == 2);
  CHECK(swap.pressures[2].value == 1.0);
  CHECK(swap.pressures[2].amplitude == NO_INDEX);

  const Step& clear = m.steps[2];
  CHECK(clear.pressures_reset);
  CHECK(clear.pressures.empty());
}

TEST_CASE("rotational output variables and shell thickness", "[io][deck][shell]") {
  const std::string deck = shell_plate_model() +
                           "*BOUNDARY\nPLATE_NODES, 4, 6\n1, ENCASTRE\n"
                           "*STEP\n*DYNAMIC, EXPLICIT\n, 1.\n"
                           "*OUTPUT, FIELD\n"
                           "*NODE OUTPUT\n"
                           "U, UR, VR, RM\n"
                           "*ELEMENT OUTPUT\n"
                           "S, STH\n"
                           "*OUTPUT, HISTORY\n"
                           "*NODE OUTPUT, NSET=PLATE_NODES\n"
                           "UR, RM3, vr1\n"
                           "*END STEP\n";
  const Model m = io::read_deck_text(deck, "rot.inp");
  const std::vector<OutputRequest>& out = m.steps[0].outputs;
  REQUIRE(out.size() == 2);
  CHECK(out[0].node_variables == std::vector<std::string>{"U", "UR", "VR", "RM"});
  CHECK(out[0].element_variables == std::vector<std::string>{"S", "STH"});
  CHECK(out[1].node_variables == std::vector<std::string>{"UR1", "UR2", "UR3", "RM3", "VR1"});
  const std::vector<BoundaryCondition>& bcs = m.steps[0].boundaries;
  REQUIRE(bcs.size() == 7);
  CHECK(bcs[0].first_dof == 4);
  CHECK(bcs[0].last_dof == 6);
  CHECK(bcs[6].first_dof == 1);
  CHECK(bcs[6].last_dof == 6);
}

TEST_CASE("ROTARY INERTIA=ISOTROPIC (default) and EXACT", "[io][deck][shell]") {
  const std::pair<std::string, bool> cases[] = {
      {"", false}, {", ROTARY INERTIA=ISOTROPIC", false}, {", rotary inertia=exact", true}};
  for (const auto& [extra, exact] : cases) {
    std::string deck = shell_plate_model() + simple_step();
    const std::string section = "*SHELL SECTION, ELSET=PLATE, MATERIAL=ALU";
    deck.replace(deck.find(section), section.size(), section + extra);
    const Model m = io::read_deck_text(deck, "rotary.inp");
    INFO("parameters: " << extra);
    CHECK(m.shell_sections[0].rotary_exact == exact);
    CHECK(m.deck_messages.empty());
  }
}
