// A complete small deck read into a Model: every field checked.

#include <catch2/catch.hpp>

#include "deck/deck_test_support.hpp"

using namespace xpl;

namespace {

const std::string COMPLETE_DECK =
    "*HEADING\n"
    "Two bricks, one impact\n"
    "** a comment line\n"
    "*NODE, NSET=ALLN\n"
    "1000001, 0, 0, 0\n"
    "1000002, 1, 0, 0\n"
    "1000003, 1, 1, 0\n"
    "1000004, 0, 1, 0\n"
    "1000005, 2, 0, 0\n"
    "1000006, 2, 1\n"  // missing z = 0
    "1000007, 0, 0, 1\n"
    "1000008, 1., 0, 1\n"
    "1000009, 1, 1, 1.0D0\n"
    "1000010, 0, 1, 1\n"
    "1000011, 2, 0, 1e0\n"
    "1000012, 2, 1, 1\n"
    "*ELEMENT, TYPE=C3D8R, ELSET=BRICKS\n"
    "5000001, 1000001, 1000002, 1000003, 1000004,\n"
    "         1000007, 1000008, 1000009, 1000010\n"
    "5000002, 1000002, 1000005, 1000006, 1000003, 1000008, 1000011, 1000012, 1000009\n"
    "*NSET, NSET=LEFT\n"
    "1000001, 1000004, 1000007, 1000010\n"
    "*NSET, NSET=RIGHT, GENERATE\n"
    "1000005, 1000006, 1\n"
    "1000011, 1000012\n"
    "*ELSET, ELSET=FIRST\n"
    "5000001\n"
    "*SURFACE, NAME=TOP\n"
    "BRICKS, S2\n"
    "*MATERIAL, NAME=Steel\n"
    "*DENSITY\n"
    "7.8e3\n"
    "*ELASTIC, TYPE=ISOTROPIC\n"
    "2.1D11, 0.3\n"
    "*SECTION CONTROLS, NAME=HG, HOURGLASS=VISCOUS\n"
    "0.5, 1.0\n"
    "*SOLID SECTION, ELSET=BRICKS, MATERIAL=STEEL, CONTROLS=HG\n"
    ",\n"
    "*AMPLITUDE, NAME=RAMP1\n"
    "0., 0., 1.e-3, 1.\n"
    "*INITIAL CONDITIONS, TYPE=VELOCITY\n"
    "RIGHT, 1, -10.\n"
    "*BOUNDARY\n"
    "LEFT, ENCASTRE\n"
    "*STEP, NAME=Impact, NLGEOM=YES\n"
    "*DYNAMIC, EXPLICIT, SCALE FACTOR=0.8\n"
    ", 1.0e-3\n"
    "*BULK VISCOSITY\n"
    "0.1, 1.5\n"
    "*BOUNDARY, TYPE=VELOCITY, AMPLITUDE=RAMP1\n"
    "1000005, 1, 1, 2.5\n"
    "*CLOAD\n"
    "1000006, 2, 100.\n"
    "*OUTPUT, FIELD, NUMBER INTERVAL=10\n"
    "*NODE OUTPUT\n"
    "U, V\n"
    "*ELEMENT OUTPUT, ELSET=FIRST\n"
    "S, EVOL\n"
    "*OUTPUT, HISTORY, TIME INTERVAL=1e-5\n"
    "*NODE OUTPUT, NSET=RIGHT\n"
    "U1, RF\n"
    "*ENERGY OUTPUT\n"
    "ALLKE, ALLIE\n"
    "*END STEP\n";

}  // namespace

TEST_CASE("a complete small deck fills every Model field", "[io][deck]") {
  const Model m = io::read_deck_text(COMPLETE_DECK, "decks/impact.inp");
  CHECK(m.job_name == "impact");
  CHECK(m.heading == "Two bricks, one impact");

  // Nodes: deck order, sparse ids mapped to 0..11.
  REQUIRE(m.node_count() == 12);
  CHECK(m.node_ids.front() == 1000001);
  CHECK(m.node_ids.back() == 1000012);
  REQUIRE(m.coordinates.rows() == 12);
  CHECK(m.coordinates(1, 0) == 1.0);
  CHECK(m.coordinates(5, 2) == 0.0);  // missing coordinate
  CHECK(m.coordinates(8, 2) == 1.0);  // Fortran exponent

  // Elements: CSR connectivity in internal node indices.
  REQUIRE(m.element_count() == 2);
  CHECK(m.element_ids == std::vector<ExternalId>{5000001, 5000002});
  CHECK(m.element_types == std::vector<ElementType>{ElementType::C3D8R, ElementType::C3D8R});
  CHECK(m.element_offsets == std::vector<Index>{0, 8, 16});
  CHECK(m.element_nodes == std::vector<Index>{0, 1, 2, 3, 6, 7, 8, 9, 1, 4, 5, 2, 7, 10, 11, 8});
  REQUIRE(m.element_line.size() == 2);
  CHECK(m.element_where(0).file == "decks/impact.inp");
  CHECK(m.element_where(0).line == 18);
  CHECK(m.element_where(1).line == 20);
  CHECK(m.element_section == std::vector<Index>{0, 0});

  // Materials, controls, section.
  REQUIRE(m.materials.size() == 1);
  CHECK(m.materials[0].name == "STEEL");
  CHECK(m.materials[0].density == 7800.0);
  CHECK(m.materials[0].young == 2.1e11);
  CHECK(m.materials[0].poisson == 0.3);
  CHECK(m.materials[0].where.line == 30);
  REQUIRE(m.section_controls.size() == 1);
  CHECK(m.section_controls[0].hourglass == HourglassType::Viscous);
  CHECK(m.section_controls[0].stiffness_scale == 0.5);
  CHECK(m.section_controls[0].viscous_scale == 0.5);
  REQUIRE(m.solid_sections.size() == 1);
  CHECK(m.solid_sections[0].material == 0);
  CHECK(m.solid_sections[0].controls == 0);
  CHECK(m.solid_sections[0].element_set == m.find_element_set("bricks"));

  // Sets (internal indices, sorted) and the surface.
  REQUIRE(m.find_node_set("ALLN") != NO_INDEX);
  CHECK(m.node_sets[m.find_node_set("ALLN")].members.size() == 12);
  CHECK(m.node_sets[m.find_node_set("left")].members == std::vector<Index>{0, 3, 6, 9});
  CHECK(m.node_sets[m.find_node_set("RIGHT")].members == std::vector<Index>{4, 5, 10, 11});
  CHECK(m.element_sets[m.find_element_set("FIRST")].members == std::vector<Index>{0});
  REQUIRE(m.surfaces.size() == 1);
  CHECK(m.surfaces[0].type == Surface::Type::Element);
  REQUIRE(m.surfaces[0].faces.size() == 2);
  CHECK(m.surfaces[0].faces[1].element == 1);
  CHECK(m.surfaces[0].faces[1].face == 1);

  // Amplitude and initial velocity.
  REQUIRE(m.amplitudes.size() == 1);
  CHECK(m.amplitudes[0].time == std::vector<Real>{0.0, 1e-3});
  CHECK(m.amplitudes[0].value == std::vector<Real>{0.0, 1.0});
  CHECK_FALSE(m.amplitudes[0].total_time);
  REQUIRE(m.initial_velocity.rows() == 12);
  CHECK(m.initial_velocity(4, 0) == -10.0);
  CHECK(m.initial_velocity(11, 0) == -10.0);
  CHECK(m.initial_velocity(0, 0) == 0.0);
  CHECK(m.initial_velocity(4, 1) == 0.0);

  // The step.
  REQUIRE(m.steps.size() == 1);
  const Step& s = m.steps[0];
  CHECK(s.name == "Impact");
  CHECK(s.time_period == 1e-3);
  CHECK_FALSE(s.increment.fixed.has_value());
  CHECK(s.increment.scale_factor == 0.8);
  CHECK(s.bulk_linear == 0.1);
  CHECK(s.bulk_quadratic == 1.5);
  CHECK_FALSE(s.ramp_amplitude);
  // Model-level ENCASTRE on 4 nodes first, then the velocity condition.
  REQUIRE(s.boundaries.size() == 5);
  CHECK(s.boundaries[0].node == 0);
  CHECK(s.boundaries[0].first_dof == 1);
  CHECK(s.boundaries[0].last_dof == 6);
  CHECK(s.boundaries[0].type == BoundaryType::Displacement);
  CHECK(s.boundaries[4].node == 4);
  CHECK(s.boundaries[4].type == BoundaryType::Velocity);
  CHECK(s.boundaries[4].value == 2.5);
  CHECK(s.boundaries[4].amplitude == 0);
  CHECK(s.boundaries[4].where.line == 51);
  REQUIRE(s.loads.size() == 1);
  CHECK(s.loads[0].node == 5);
  CHECK(s.loads[0].dof == 2);
  CHECK(s.loads[0].value == 100.0);
  CHECK(s.loads[0].amplitude == NO_INDEX);

  REQUIRE(s.outputs.size() == 2);
  const OutputRequest& field = s.outputs[0];
  CHECK(field.kind == OutputRequest::Kind::Field);
  CHECK(field.number_interval == 10);
  CHECK(field.node_variables == std::vector<std::string>{"U", "V"});
  CHECK(field.node_set == NO_INDEX);
  CHECK(field.element_variables == std::vector<std::string>{"S", "EVOL"});
  CHECK(field.element_set == m.find_element_set("FIRST"));
  const OutputRequest& history = s.outputs[1];
  CHECK(history.kind == OutputRequest::Kind::History);
  CHECK(history.time_interval == 1e-5);
  CHECK(history.number_interval == 0);
  CHECK(history.node_variables == std::vector<std::string>{"U1", "RF1", "RF2", "RF3"});
  CHECK(history.node_set == m.find_node_set("RIGHT"));
  CHECK(history.energy);
  CHECK(history.energy_variables == std::vector<std::string>{"ALLKE", "ALLIE"});
}

TEST_CASE("sparse ids up to 1e12 map to contiguous indices", "[io][deck]") {
  std::string deck = test::two_brick_model() + test::simple_step();
  const std::string from = "1000012, 2, 1, 1";
  deck.replace(deck.find(from), from.size(), "999999999999, 2, 1, 1");
  const std::string in_element = "1000011, 1000012";
  deck.replace(deck.find(in_element), in_element.size(), "1000011, 999999999999");
  const Model m = io::read_deck_text(deck, "big.inp");
  CHECK(m.node_ids.back() == 999999999999);
  CHECK(m.element_nodes[14] == 11);
}
