// The whole-model checks the deck reader runs after building a Model (model_checks.hpp),
// on models built in code.

#include <catch2/catch.hpp>

#include "../../solver/solver_fixtures.hpp"
#include "io/deck/model_checks.hpp"

using namespace xpl;
using namespace xpl::test;
using io::unsupported_features;

TEST_CASE("features read but not run yet are refused with their deck line", "[io][deck]") {
  BoxSpec spec;
  spec.nx = spec.ny = spec.nz = 1;
  Model m = make_box(spec);
  CHECK(unsupported_features(m).empty());
  // Rigid bodies, general contact and node-based contact surfaces (SPEC C13) run; rotary
  // inertia away from a rigid body's reference node does not yet.
  m.rigid_bodies.push_back({0, 0, NO_INDEX, NO_INDEX, {"box.inp", 12}});
  GeneralContact contact;
  contact.all_exterior = true;
  contact.where = {"box.inp", 30};
  m.steps[0].contact = contact;
  CHECK(unsupported_features(m).empty());
  Surface nodes;
  nodes.name = "TIPS";
  nodes.type = Surface::Type::Node;
  nodes.nodes = {1};
  m.surfaces.push_back(nodes);
  m.steps[0].contact->inclusions.push_back({0, NO_INDEX, {"box.inp", 31}});
  PointInertia inertia;
  inertia.node = 3;
  inertia.inertia[0] = 1.0;
  inertia.where = {"box.inp", 20};
  m.point_inertias.push_back(inertia);
  const auto refused = unsupported_features(m);
  REQUIRE(refused.size() == 1);
  CHECK(refused[0].rfind("box.inp:20: *ROTARY INERTIA: rotary inertia on a node", 0) == 0);
}

TEST_CASE("a node shared by two rigid bodies is refused with the deck line", "[io][deck]") {
  BoxSpec spec;
  spec.nx = spec.ny = spec.nz = 1;
  Model m = make_box(spec);
  m.rigid_bodies.push_back({0, 0, NO_INDEX, NO_INDEX, {"box.inp", 12}});
  CHECK(unsupported_features(m).empty());
  m.rigid_bodies.push_back({1, 0, NO_INDEX, NO_INDEX, {"box.inp", 13}});
  const auto refused = unsupported_features(m);
  REQUIRE(refused.size() == 8);  // the 8 nodes of the one element
  CHECK(refused[0].rfind("box.inp:13: *RIGID BODY: node ", 0) == 0);
  CHECK(refused[0].find("also belongs to an earlier rigid body") != std::string::npos);
}
