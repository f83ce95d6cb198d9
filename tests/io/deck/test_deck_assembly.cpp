// Parts, assemblies and instances as Abaqus/CAE writes them (SPEC I5, issue 34 item 1): ids per
// instance, placement (translation, then rotation), sets and surfaces at the part, instance and
// assembly levels with Abaqus' scoping, and one error per cause for what is wrong.

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>

#include "deck/deck_test_support.hpp"

using namespace xpl;
using test::at;
using test::deck_errors;
using test::has_error;

namespace {

/// A part of one unit brick (nodes 1..8, element 1) with part-level sets, a surface and the
/// section; a material in the part (read once).
const std::string PART =
    "*PART, NAME=Brick\n"
    "*NODE\n"
    "1, 0, 0, 0\n"
    "2, 1, 0, 0\n"
    "3, 1, 1, 0\n"
    "4, 0, 1, 0\n"
    "5, 0, 0, 1\n"
    "6, 1, 0, 1\n"
    "7, 1, 1, 1\n"
    "8, 0, 1, 1\n"
    "*ELEMENT, TYPE=C3D8R\n"
    "1, 1, 2, 3, 4, 5, 6, 7, 8\n"
    "*NSET, NSET=Bottom, GENERATE\n"
    "1, 4, 1\n"
    "*ELSET, ELSET=All, INTERNAL\n"
    "1,\n"
    "*SURFACE, TYPE=ELEMENT, NAME=Top, INTERNAL\n"
    "All, S2\n"
    "*SOLID SECTION, ELSET=All, MATERIAL=Steel\n"
    ",\n"
    "*MATERIAL, NAME=Steel\n"
    "*DENSITY\n"
    "7800.\n"
    "*ELASTIC\n"
    "2e11, 0.3\n"
    "*END PART\n";

/// Two instances: B1 in place, B2 translated by (0, 0, 2), then rotated by 90 degrees about
/// the z axis through (0.5, 0.5, 0); an instance-level set, assembly-level sets (INSTANCE=,
/// GENERATE, INTERNAL) and a surface; a reference point at the assembly level.
const std::string ASSEMBLY =
    "*ASSEMBLY, NAME=Assembly\n"
    "*INSTANCE, NAME=B1, PART=Brick\n"
    "*END INSTANCE\n"
    "*INSTANCE, NAME=B2, PART=Brick\n"
    "0., 0., 2.\n"
    "0.5, 0.5, 0., 0.5, 0.5, 1., 90.\n"
    "*NSET, NSET=Corner\n"
    "7,\n"
    "*END INSTANCE\n"
    "*NODE\n"
    "1, 5., 5., 5.\n"
    "*NSET, NSET=RP\n"
    "1,\n"
    "*NSET, NSET=Upper, INSTANCE=B2, GENERATE\n"
    "5, 8, 1\n"
    "*ELSET, ELSET=_Under_S1, INTERNAL, INSTANCE=B2\n"
    "1,\n"
    "*SURFACE, TYPE=ELEMENT, NAME=Under\n"
    "_Under_S1, S1\n"
    "*NSET, NSET=Both\n"
    "B1.Bottom, B2.3\n"
    "*END ASSEMBLY\n";

const std::string STEP =
    "*STEP\n"
    "*DYNAMIC, EXPLICIT\n"
    ", 1e-3\n"
    "*BOUNDARY\n"
    "B1.Bottom, ENCASTRE\n"
    "B2.1, 1, 3\n"
    "*RESTART, WRITE, FREQUENCY=0\n"
    "*END STEP\n";

const std::string DECK = PART + ASSEMBLY + STEP;

Index set_of(const std::vector<NamedSet>& sets, const std::string& name) {
  for (std::size_t s = 0; s < sets.size(); ++s)
    if (sets[s].name == name) return static_cast<Index>(s);
  return NO_INDEX;
}

/// Model ids of a set's members.
std::vector<ExternalId> ids_of(const Model& m, const std::string& name, bool nodes = true) {
  const std::vector<NamedSet>& sets = nodes ? m.node_sets : m.element_sets;
  const Index s = set_of(sets, name);
  REQUIRE(s != NO_INDEX);
  std::vector<ExternalId> ids;
  for (Index i : sets[static_cast<std::size_t>(s)].members)
    ids.push_back((nodes ? m.node_ids : m.element_ids)[static_cast<std::size_t>(i)]);
  std::sort(ids.begin(), ids.end());
  return ids;
}

Index node_of(const Model& m, ExternalId id) {
  const auto it = std::find(m.node_ids.begin(), m.node_ids.end(), id);
  REQUIRE(it != m.node_ids.end());
  return static_cast<Index>(it - m.node_ids.begin());
}

}  // namespace

TEST_CASE("two instances of a part: ids, local ids and placement", "[io][deck][assembly]") {
  const Model m = io::read_deck_text(DECK, "t.inp");
  REQUIRE(m.node_count() == 17);  // 2 × 8 and the reference point
  REQUIRE(m.element_count() == 2);
  REQUIRE(m.instances.size() == 2);
  CHECK(m.instances[0].name == "B1");
  CHECK(m.instances[1].name == "B2");
  CHECK(m.instances[1].part == "BRICK");
  CHECK(m.instances[0].nodes == 8);
  CHECK(m.instances[1].elements == 1);
  // Ids below 10: instance k has 10·k + local id, the assembly level comes last.
  CHECK(m.instances[1].node_offset == 10);
  CHECK(m.assembly_node_offset == 20);
  CHECK(m.node_ids ==
        std::vector<ExternalId>{1, 2, 3, 4, 5, 6, 7, 8, 11, 12, 13, 14, 15, 16, 17, 18, 21});
  CHECK(m.element_ids == std::vector<ExternalId>{1, 11});
  CHECK(m.node_local_ids[9] == 2);
  CHECK(m.node_instance[9] == 1);
  CHECK(m.node_instance[16] == -1);
  CHECK(m.element_local_ids == std::vector<ExternalId>{1, 1});
  CHECK(m.element_instance == std::vector<std::int32_t>{0, 1});

  // B2's node 2 (1, 0, 0): translated to (1, 0, 2), rotated by 90° about the z axis through
  // (0.5, 0.5): (1, 1, 2). Node 5 (0, 0, 1) -> (0, 0, 3) -> (1, 0, 3).
  const Index n2 = node_of(m, 12), n5 = node_of(m, 15);
  CHECK(m.coordinates(n2, 0) == Approx(1.0).margin(1e-15));  // 1e-15: cos 90° ≠ 0 in doubles
  CHECK(m.coordinates(n2, 1) == Approx(1.0).margin(1e-15));
  CHECK(m.coordinates(n2, 2) == 2.0);
  CHECK(m.coordinates(n5, 0) == Approx(1.0).margin(1e-15));
  CHECK(m.coordinates(n5, 1) == Approx(0.0).margin(1e-15));
  CHECK(m.coordinates(n5, 2) == 3.0);
  // B1 stays where the part is: bitwise.
  const Index n7 = node_of(m, 7);
  CHECK(
      (m.coordinates(n7, 0) == 1.0 && m.coordinates(n7, 1) == 1.0 && m.coordinates(n7, 2) == 1.0));

  // Each instance has its section (the part's, read per instance) and the one material.
  REQUIRE(m.materials.size() == 1);
  REQUIRE(m.solid_sections.size() == 2);
  CHECK(m.element_section == std::vector<Index>{0, 1});
}

TEST_CASE("sets and surfaces at the part, instance and assembly levels", "[io][deck][assembly]") {
  const Model m = io::read_deck_text(DECK, "t.inp");
  // Part level, qualified by the instance; GENERATE.
  CHECK(ids_of(m, "B1.BOTTOM") == std::vector<ExternalId>{1, 2, 3, 4});
  CHECK(ids_of(m, "B2.BOTTOM") == std::vector<ExternalId>{11, 12, 13, 14});
  CHECK(ids_of(m, "B2.ALL", false) == std::vector<ExternalId>{11});
  // Instance level.
  CHECK(ids_of(m, "B2.CORNER") == std::vector<ExternalId>{17});
  // Assembly level: its own node 1, INSTANCE= with GENERATE, qualified names and ids.
  CHECK(ids_of(m, "RP") == std::vector<ExternalId>{21});
  CHECK(ids_of(m, "UPPER") == std::vector<ExternalId>{15, 16, 17, 18});
  CHECK(ids_of(m, "_UNDER_S1", false) == std::vector<ExternalId>{11});
  CHECK(ids_of(m, "BOTH") == std::vector<ExternalId>{1, 2, 3, 4, 13});
  // Surfaces: the part's per instance, and the assembly's.
  const Index top = m.find_surface("B1.TOP"), under = m.find_surface("UNDER");
  REQUIRE(top != NO_INDEX);
  REQUIRE(m.find_surface("B2.TOP") != NO_INDEX);
  REQUIRE(under != NO_INDEX);
  CHECK(m.surfaces[static_cast<std::size_t>(top)].faces.size() == 1);
  CHECK(m.surfaces[static_cast<std::size_t>(top)].faces[0].element == 0);
  CHECK(m.surfaces[static_cast<std::size_t>(under)].faces[0].element == 1);
  CHECK(m.surfaces[static_cast<std::size_t>(under)].faces[0].face == 0);
  // *BOUNDARY on a qualified set and a qualified node id.
  const std::vector<BoundaryCondition>& bcs = m.steps[0].boundaries;
  REQUIRE(bcs.size() == 5);
  CHECK(m.node_ids[static_cast<std::size_t>(bcs[4].node)] == 11);
}

TEST_CASE("the .msg notes list the instances and *RESTART", "[io][deck][assembly]") {
  const Model m = io::read_deck_text(DECK, "t.inp");
  const auto has_note = [&](const std::string& prefix, const std::string& text) {
    return std::any_of(m.deck_messages.begin(), m.deck_messages.end(), [&](const DeckMessage& n) {
      return n.text.rfind(prefix, 0) == 0 && n.text.find(text) != std::string::npos;
    });
  };
  CHECK(has_note(at(DECK, "*INSTANCE, NAME=B2", "*INSTANCE"),
                 "instance B2 of part BRICK: 8 nodes, 1 element, translated by (0, 0, 2), then "
                 "rotated by 90 degrees about the axis (0.5, 0.5, 0) -> (0.5, 0.5, 1); in the "
                 "results its ids are 10 + the part's ids"));
  CHECK(has_note(at(DECK, "*INSTANCE, NAME=B1", "*INSTANCE"), "instance B1 of part BRICK"));
  CHECK(has_note(at(DECK, "*ASSEMBLY", "*ASSEMBLY"), "1 node and 0 elements at the assembly"));
  CHECK(has_note(at(DECK, "*RESTART", "*RESTART"), "--import"));
}

TEST_CASE("a flat deck has no instances", "[io][deck][assembly]") {
  const Model m = io::read_deck_text(test::two_brick_model() + test::simple_step(), "t.inp");
  CHECK(m.instances.empty());
  CHECK(m.node_local_ids.empty());
  CHECK(m.node_instance.empty());
  CHECK(m.element_ids == std::vector<ExternalId>{5000001, 5000002});
}

TEST_CASE("assembly errors: one per cause, at its line", "[io][deck][assembly][errors]") {
  SECTION("INSTANCE= and qualified names together") {
    const std::string deck = PART +
                             "*ASSEMBLY, NAME=A\n"
                             "*INSTANCE, NAME=B1, PART=Brick\n"
                             "*END INSTANCE\n"
                             "*NSET, NSET=X, INSTANCE=B1\n"
                             "B1.Bottom\n"
                             "*END ASSEMBLY\n" +
                             test::simple_step();
    const std::vector<std::string> e = deck_errors(deck);
    CHECK(e.size() == 1);
    CHECK(has_error(e, at(deck, "B1.Bottom\n", "*NSET"),
                    "instance-qualified name B1.BOTTOM in a set with INSTANCE="));
  }
  SECTION("undefined part, undefined instance, bad rotation axis") {
    const std::string deck = PART +
                             "*ASSEMBLY, NAME=A\n"
                             "*INSTANCE, NAME=B1, PART=Plate\n"
                             "*END INSTANCE\n"
                             "*INSTANCE, NAME=B2, PART=Brick\n"
                             "0, 0, 0\n"
                             "1, 1, 1, 1, 1, 1, 30\n"
                             "*END INSTANCE\n"
                             "*NSET, NSET=X, INSTANCE=B9\n"
                             "1,\n"
                             "*END ASSEMBLY\n" +
                             test::simple_step();
    const std::vector<std::string> e = deck_errors(deck);
    CHECK(has_error(e, at(deck, "PART=Plate", "*INSTANCE"), "undefined part PLATE"));
    CHECK(has_error(e, at(deck, "1, 1, 1, 1, 1, 1, 30", "*INSTANCE"),
                    "points a and b of the rotation axis coincide"));
    CHECK(has_error(e, at(deck, "INSTANCE=B9", "*NSET"), "undefined instance B9"));
    CHECK(e.size() == 3);
  }
  SECTION("history data in a part, structures left open") {
    const std::string deck =
        "*PART, NAME=P\n"
        "*NODE\n"
        "1, 0, 0, 0\n"
        "*BOUNDARY\n"
        "1, 1, 3\n"
        "*ASSEMBLY, NAME=A\n"
        "*INSTANCE, NAME=I, PART=P\n"
        "*MATERIAL, NAME=M\n" +
        test::simple_step();
    const std::vector<std::string> e = deck_errors(deck);
    CHECK(has_error(e, at(deck, "*BOUNDARY", "*BOUNDARY"), "*BOUNDARY inside part P"));
    CHECK(has_error(e, at(deck, "*ASSEMBLY", "*ASSEMBLY"), "part P is not closed"));
    CHECK(has_error(e, at(deck, "*MATERIAL", "*MATERIAL"), "instance I is not closed"));
    CHECK(has_error(e, at(deck, "*STEP", "*STEP"), "the *ASSEMBLY is not closed"));
  }
  SECTION("an error in a part instanced twice is reported once") {
    std::string part = PART;
    part.replace(part.find("8, 0, 1, 1\n"), 10, "8, 0, 1, x\n");
    const std::string deck = part + ASSEMBLY + STEP;
    const std::vector<std::string> e = deck_errors(deck);
    CHECK(e.size() == 1);
    CHECK(has_error(e, at(deck, "8, 0, 1, x", "*NODE"), "bad number 'x' for coordinate z"));
  }
  SECTION("an undefined qualified node names its instance") {
    const std::string deck = PART + ASSEMBLY +
                             "*STEP\n*DYNAMIC, EXPLICIT\n, 1e-3\n*BOUNDARY\nB2.99, 1, 3\n"
                             "*END STEP\n";
    const std::vector<std::string> e = deck_errors(deck);
    CHECK(e.size() == 1);
    CHECK(has_error(e, at(deck, "B2.99", "*BOUNDARY"), "undefined node 99 of instance B2"));
  }
}
