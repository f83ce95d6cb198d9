// Deck syntax and keyword features: continuation, comments, case, *INCLUDE, sets, surfaces,
// amplitudes, boundary conditions, output requests, several steps.

#include <catch2/catch.hpp>

#include "deck/deck_test_support.hpp"

using namespace xpl;
using test::simple_step;
using test::two_brick_model;

TEST_CASE("comments, blank lines, case and continued keyword lines", "[io][deck]") {
  const std::string deck =
      "** leading comment\n"
      "\n"
      "*node,\n"
      "  nset=\"Corner Nodes\"\n"
      "1000001, 0, 0, 0\n"
      "   \n"
      "** between data lines\n" +
      // The remaining nodes, elements, ... of the two bricks continue the *node block.
      two_brick_model().substr(two_brick_model().find("1000002")) +
      "*Step, Name=S1\n*Dynamic, Explicit\n, 2.5e-3\n*end step\n";
  const Model m = io::read_deck_text(deck, "case.inp");
  CHECK(m.node_count() == 12);
  CHECK(m.node_ids[1] == 1000002);
  const Index set = m.find_node_set("corner nodes");
  REQUIRE(set != NO_INDEX);
  CHECK(m.node_sets[set].name == "CORNER NODES");
  CHECK(m.node_sets[set].members.size() == 12);
  CHECK(m.element_where(0).line == 20);
  REQUIRE(m.steps.size() == 1);
  CHECK(m.steps[0].name == "S1");
  CHECK(m.steps[0].time_period == 2.5e-3);
}

TEST_CASE("trailing commas as CalculiX decks write them, and keywords written without blanks",
          "[io][deck][calculix]") {
  // CalculiX (and Abaqus/CAE's exports) end complete element lines and keyword lines with a
  // comma: an element line stops continuing once it holds all its nodes, and a keyword line
  // is continued only by parameters (a line starting with a number is its data). CalculiX
  // ignores the blanks of keyword names: *ENDSTEP is *END STEP.
  std::string bricks = two_brick_model();
  const std::string first =
      "5000001, 1000001, 1000002, 1000003, 1000004, 1000007, 1000008, "
      "1000009, 1000010\n";
  bricks.replace(bricks.find(first), first.size(),
                 "5000001, 1000001, 1000002, 1000003, 1000004, 1000007, 1000008, 1000009, "
                 "1000010,\n");
  const std::string deck = bricks +
                           "*NSET, NSET=SPLIT,\n"
                           "1000001, 1000002,\n"
                           "1000003\n"
                           "*ELEMENT, TYPE=C3D8R, ELSET=BRICKS\n"
                           "5000003, 1000001, 1000002, 1000003,\n"
                           "1000004, 1000007, 1000008, 1000009, 1000010,\n"
                           "5000004, 1000002, 1000005, 1000006, 1000003, 1000008, 1000011, "
                           "1000012, 1000009\n"
                           "*STEP\n*DYNAMIC, EXPLICIT\n, 1e-3\n*ENDSTEP\n";
  const Model m = io::read_deck_text(deck, "commas.inp");
  CHECK(m.element_count() == 4);
  CHECK(m.element_ids == std::vector<ExternalId>{5000001, 5000002, 5000003, 5000004});
  CHECK(m.element_where(3).line == test::line_of(deck, "5000004,"));
  const Index split = m.find_node_set("SPLIT");
  REQUIRE(split != NO_INDEX);
  CHECK(m.node_sets[split].members == std::vector<Index>{0, 1, 2});
  CHECK(m.steps.size() == 1);
  // A keyword line is still continued by a parameter line.
  const Model c = io::read_deck_text(
      two_brick_model() + "*NSET,\nNSET=CONT\n1000004\n" + test::simple_step(), "continued.inp");
  REQUIRE(c.find_node_set("CONT") != NO_INDEX);
  CHECK(c.node_sets[c.find_node_set("CONT")].members == std::vector<Index>{3});
}

TEST_CASE("*INCLUDE reads files relative to the including file", "[io][deck]") {
  const Model m = io::read_deck(std::string(XPL_TEST_DATA_DIR) + "/decks/include_main.inp");
  CHECK(m.job_name == "include_main");
  CHECK(m.heading == "included mesh");
  CHECK(m.node_count() == 12);
  REQUIRE(m.element_count() == 2);
  CHECK(m.element_where(1).file.find("include_elements.inp") != std::string::npos);
  CHECK(m.element_where(1).line == 3);
  CHECK(m.element_section == std::vector<Index>{0, 0});
}

TEST_CASE("errors inside an included file name that file and its line", "[io][deck]") {
  const std::string dir = std::string(XPL_TEST_DATA_DIR) + "/decks/";
  try {
    io::read_deck(dir + "include_bad_main.inp");
    FAIL("expected an InputError");
  } catch (const InputError& e) {
    CHECK(test::has_error(e.messages(), dir + "include_bad_part.inp:3: *NODE: bad number 'abc'"));
  }
}

TEST_CASE("GENERATE, set of sets, NSET from ELSET and repeated definitions", "[io][deck]") {
  const std::string deck = two_brick_model() +
                           "*NSET, NSET=BOTTOM, GENERATE\n"
                           "1000001, 1000006\n"
                           "*NSET, NSET=TOPLEFT\n"
                           "1000007, 1000010\n"
                           "*NSET, NSET=MIXED\n"
                           "BOTTOM, TopLeft, 1000008\n"
                           "*NSET, NSET=MIXED\n"
                           "1000009\n"
                           "*ELSET, ELSET=SECOND, GENERATE\n"
                           "5000002, 5000002, 1\n"
                           "*NSET, NSET=OF_SECOND, ELSET=SECOND\n"
                           "*ELSET, ELSET=BOTH\n"
                           "SECOND, 5000001\n" +
                           simple_step();
  const Model m = io::read_deck_text(deck, "sets.inp");
  CHECK(m.node_sets[m.find_node_set("BOTTOM")].members == std::vector<Index>{0, 1, 2, 3, 4, 5});
  CHECK(m.node_sets[m.find_node_set("MIXED")].members ==
        std::vector<Index>{0, 1, 2, 3, 4, 5, 6, 7, 8, 9});
  CHECK(m.node_sets[m.find_node_set("OF_SECOND")].members ==
        std::vector<Index>{1, 2, 4, 5, 7, 8, 10, 11});
  CHECK(m.element_sets[m.find_element_set("SECOND")].members == std::vector<Index>{1});
  CHECK(m.element_sets[m.find_element_set("BOTH")].members == std::vector<Index>{0, 1});
}

TEST_CASE("element and node surfaces", "[io][deck]") {
  const std::string deck = two_brick_model() +
                           "*SURFACE, NAME=BOTTOM\n"
                           "5000001, S1\n"
                           "5000002, s1\n"
                           "*NSET, NSET=TIPS\n"
                           "1000011, 1000012\n"
                           "*SURFACE, NAME=TIPNODES, TYPE=NODE\n"
                           "TIPS, 1.0\n"
                           "1000005\n" +
                           simple_step();
  const Model m = io::read_deck_text(deck, "surf.inp");
  const Surface& bottom = m.surfaces[m.find_surface("bottom")];
  REQUIRE(bottom.faces.size() == 2);
  CHECK(bottom.faces[0].element == 0);
  CHECK(bottom.faces[0].face == 0);
  CHECK(bottom.faces[1].element == 1);
  const Surface& tips = m.surfaces[m.find_surface("TIPNODES")];
  CHECK(tips.type == Surface::Type::Node);
  CHECK(tips.nodes == std::vector<Index>{4, 10, 11});
}

TEST_CASE("amplitudes: several pairs per line and continued lines", "[io][deck]") {
  const std::string deck = two_brick_model() +
                           "*AMPLITUDE, NAME=A1, DEFINITION=TABULAR, TIME=TOTAL TIME\n"
                           "0, 0, 1, 2,\n"
                           "2, 2\n"
                           "3, 0.5, 3, 0.25\n" +
                           simple_step();
  const Model m = io::read_deck_text(deck, "amp.inp");
  const Amplitude& a = m.amplitudes[m.find_amplitude("a1")];
  CHECK(a.total_time);
  CHECK(a.time == std::vector<Real>{0, 1, 2, 3, 3});
  CHECK(a.value == std::vector<Real>{0, 2, 2, 0.5, 0.25});
}

TEST_CASE("boundary conditions: symmetry words, ranges, velocity, amplitude, OP=NEW",
          "[io][deck]") {
  const std::string deck = two_brick_model() +
                           "*AMPLITUDE, NAME=UP\n0, 0, 1, 1\n"
                           "*STEP, AMPLITUDE=RAMP\n*DYNAMIC, EXPLICIT\n, 1.\n"
                           "*BOUNDARY\n"
                           "1000001, XSYMM\n"
                           "1000002, YSYMM\n"
                           "1000003, 1, 3\n"
                           "1000004, 2, , 0.5\n"
                           "*BOUNDARY, TYPE=VELOCITY, AMPLITUDE=UP\n"
                           "1000005, 3, 3, -1.5\n"
                           "*END STEP\n"
                           "*STEP\n*DYNAMIC, EXPLICIT, DIRECT USER CONTROL\n1e-6, 2.\n"
                           "*BOUNDARY, OP=NEW\n"
                           "1000006, PINNED\n"
                           "*CLOAD, OP=NEW\n"
                           "1000006, 3, -5.\n"
                           "*END STEP\n";
  const Model m = io::read_deck_text(deck, "bc.inp");
  REQUIRE(m.steps.size() == 2);
  const Step& first = m.steps[0];
  CHECK(first.ramp_amplitude);
  CHECK_FALSE(first.boundaries_reset);
  REQUIRE(first.boundaries.size() == 8);
  // XSYMM = dofs 1, 5, 6 as two contiguous ranges.
  CHECK(first.boundaries[0].first_dof == 1);
  CHECK(first.boundaries[0].last_dof == 1);
  CHECK(first.boundaries[1].first_dof == 5);
  CHECK(first.boundaries[1].last_dof == 6);
  // YSYMM = 2, 4, 6.
  CHECK(first.boundaries[2].first_dof == 2);
  CHECK(first.boundaries[3].first_dof == 4);
  CHECK(first.boundaries[4].last_dof == 6);
  CHECK(first.boundaries[5].node == 2);
  CHECK(first.boundaries[5].last_dof == 3);
  CHECK(first.boundaries[6].first_dof == 2);
  CHECK(first.boundaries[6].last_dof == 2);
  CHECK(first.boundaries[6].value == 0.5);
  CHECK(first.boundaries[7].type == BoundaryType::Velocity);
  CHECK(first.boundaries[7].value == -1.5);
  CHECK(first.boundaries[7].amplitude == m.find_amplitude("UP"));
  const Step& second = m.steps[1];
  CHECK(second.name == "Step-2");
  REQUIRE(second.increment.fixed.has_value());
  CHECK(*second.increment.fixed == 1e-6);
  CHECK(second.boundaries_reset);
  REQUIRE(second.boundaries.size() == 1);
  CHECK(second.boundaries[0].first_dof == 1);
  CHECK(second.boundaries[0].last_dof == 3);
  CHECK(second.loads_reset);
  REQUIRE(second.loads.size() == 1);
  CHECK(second.loads[0].value == -5.0);
}

TEST_CASE("output requests: PRESELECT, defaults, several *NODE OUTPUT", "[io][deck]") {
  const std::string deck = two_brick_model() +
                           "*STEP\n*DYNAMIC, EXPLICIT\n, 1.\n"
                           "*OUTPUT, FIELD, VARIABLE=PRESELECT\n"
                           "*OUTPUT, HISTORY, VARIABLE=PRESELECT, NUMBER INTERVAL=50\n"
                           "*NODE OUTPUT, NSET=ALLN\n"
                           "V\n"
                           "*NODE OUTPUT, NSET=ALLN\n"
                           "A2\n"
                           "*OUTPUT, HISTORY\n"
                           "*ENERGY OUTPUT\n"
                           "*END STEP\n";
  const Model m = io::read_deck_text(deck, "out.inp");
  const std::vector<OutputRequest>& out = m.steps[0].outputs;
  REQUIRE(out.size() == 4);
  CHECK(out[0].number_interval == 20);
  CHECK(out[0].node_variables == std::vector<std::string>{"U", "V", "A", "RF"});
  // PEEQ is written on plastic models only (OutputModels::Plastic).
  CHECK(out[0].element_variables == std::vector<std::string>{"S", "PEEQ"});
  CHECK(out[1].number_interval == 50);
  CHECK(out[1].energy);
  CHECK(out[1].energy_variables.empty());
  CHECK(out[1].node_variables == std::vector<std::string>{"V1", "V2", "V3"});
  CHECK(out[1].node_set == m.find_node_set("ALLN"));
  CHECK(out[2].node_variables == std::vector<std::string>{"A2"});
  CHECK(out[2].number_interval == 50);
  CHECK_FALSE(out[2].energy);
  CHECK(out[3].number_interval == 200);
  CHECK(out[3].energy);
}

TEST_CASE("an element may come before its nodes", "[io][deck]") {
  const std::string model = two_brick_model();
  const std::size_t elements = model.find("*ELEMENT");
  const std::size_t material = model.find("*MATERIAL");
  const std::string deck = model.substr(elements, material - elements) + model.substr(0, elements) +
                           model.substr(material) + simple_step();
  const Model m = io::read_deck_text(deck, "order.inp");
  CHECK(m.element_nodes[15] == 8);
  CHECK(m.element_where(0).line == 2);
}

TEST_CASE("a GENERATE range up to 1e12 costs no more than the defined ids", "[io][deck]") {
  const std::string deck = two_brick_model() +
                           "*NSET, NSET=HUGE, GENERATE\n"
                           "1, 1000000000000, 1\n"
                           "*NSET, NSET=ODD, GENERATE\n"
                           "1000001, 1000012, 2\n" +
                           simple_step();
  const Model m = io::read_deck_text(deck, "huge.inp");
  CHECK(m.node_sets[m.find_node_set("HUGE")].members.size() == 12);
  CHECK(m.node_sets[m.find_node_set("ODD")].members == std::vector<Index>{0, 2, 4, 6, 8, 10});
}
