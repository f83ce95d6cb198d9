// Point nodes: the nodes of node-based surfaces that lie on no face of the contact domain
// (SPEC C13). They are slave nodes with a fixed area and no normal of their own.

#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <vector>

#include "contact/contact_domain.hpp"
#include "contact/contact_engine.hpp"
#include "contact/contact_options.hpp"
#include "contact_fixtures.hpp"

using namespace xpl;
using contact::ContactDomain;
using contact::DomainSpec;
using contact::Vec3;

namespace {

/// A 2×2×1 block (h = 1) plus one free node at `point` (index 18), unit masses.
test::ContactMesh block_and_point(const Vec3& point) {
  test::ContactMesh mesh;
  test::add_hex_block(mesh, 2, 2, 1, 1.0);
  const Index n = mesh.node_count();
  mesh.coordinates.conservativeResize(n + 1, 3);
  for (int d = 0; d < 3; ++d) mesh.coordinates(n, d) = point[d];
  return mesh;
}

/// Face `face` (hex S1..S6 = 0..5) of every element as surface 0, the nodes `nodes` with
/// areas `areas` as the node-based surface 1, one-sided 1 → 0 (as the solver builds it).
DomainSpec point_spec(const test::ContactMesh& mesh, std::uint8_t face, std::vector<Index> nodes,
                      std::vector<Real> areas) {
  DomainSpec spec;
  spec.surfaces.push_back({"BLOCK", false, {}});
  for (Index e = 0; e < static_cast<Index>(mesh.kinds.size()); ++e)
    spec.surfaces[0].faces.push_back({e, face});
  contact::DomainSurface points;
  points.name = "PTS";
  points.nodes = std::move(nodes);
  points.node_areas = std::move(areas);
  spec.surfaces.push_back(std::move(points));
  spec.inclusions.push_back({1, 0, true});
  return spec;
}

/// Contact force on node `node` (N) of one engine update with Δt = 1e-3 s.
Vec3 contact_force(const test::ContactMesh& mesh, const DomainSpec& spec, Index node) {
  const NodalVectors& x = mesh.coordinates;
  const Index n = mesh.node_count();
  contact::ContactEngine engine(ContactDomain(spec, mesh.topology(), x), {}, {}, x, {});
  const std::vector<Real> mass(n, 1.0), inverse_mass(n, 1.0);
  NodalVectors force = NodalVectors::Zero(n, 3);
  PhaseTimers timers;
  engine.update(x, NodalVectors::Zero(n, 3), 0.0, 1e-3, {}, mass, inverse_mass, force, timers);
  return -Vec3(force(node, 0), force(node, 1), force(node, 2));  // force_internal: minus
}

}  // namespace

TEST_CASE("point nodes are slave nodes with their own area and no normal", "[contact][domain]") {
  const test::ContactMesh mesh = block_and_point(Vec3(0.5, 0.5, 1.5));
  const Index point = 18;
  const Index top_centre = 4 + 9;  // node (1, 1, 1): on the top faces
  const Real nan = std::numeric_limits<Real>::quiet_NaN();
  ContactDomain domain(point_spec(mesh, 1, {top_centre, point}, {3.0, nan}), mesh.topology(),
                       mesh.coordinates);
  domain.slaves().update_areas(domain.faces(), mesh.coordinates);
  const Index s = domain.slaves().slot(point);
  const Index t = domain.slaves().slot(top_centre);
  REQUIRE(s != NO_INDEX);
  CHECK(domain.point_count() == 1);
  CHECK(domain.slave_point(s));
  CHECK_FALSE(domain.slave_double_sided(s));
  CHECK(domain.slaves().faces_of(s).empty());
  CHECK(domain.slaves().normal(s).norm() == 0.0);
  // No area given: the default; a node on faces keeps its faces' area (4 × ¼ of 1 m²).
  CHECK(domain.slaves().areas()[s] == contact::POINT_NODE_DEFAULT_AREA);
  CHECK_FALSE(domain.slave_point(t));
  CHECK(domain.slaves().areas()[t] == Approx(1.0).epsilon(1e-14));
  // One-sided: the point node on a block face with weight 1; the block's nodes have no view
  // on anything (the node-based surface has no faces).
  Index pair = NO_INDEX;
  CHECK(domain.weight(s, 0, pair) == 1.0);
  CHECK(pair == 0);

  // A rigid point node on a rigid body's face: two rigid bodies never touch.
  DomainSpec rigid = point_spec(mesh, 1, {point}, {});
  rigid.element_body.assign(mesh.kinds.size(), 0);
  const ContactDomain deformable_point(rigid, mesh.topology(), mesh.coordinates);
  CHECK(deformable_point.weight(deformable_point.slaves().slot(point), 0, pair) == 1.0);
  rigid.rigid_node.assign(static_cast<std::size_t>(mesh.node_count()), 0);
  rigid.rigid_node[point] = 1;
  const ContactDomain rigid_point(rigid, mesh.topology(), mesh.coordinates);
  CHECK(rigid_point.slave_rigid(rigid_point.slaves().slot(point)));
  CHECK(rigid_point.weight(rigid_point.slaves().slot(point), 0, pair) == 0.0);

  const ContactDomain with_area(point_spec(mesh, 1, {point}, {2.5}), mesh.topology(),
                                mesh.coordinates);
  CHECK(with_area.slaves().areas()[with_area.slaves().slot(point)] == 2.5);
}

TEST_CASE("a point node is pushed out of a face of either orientation by k·d",
          "[contact][engine]") {
  const Real depth = 0.01;
  // k = α m_eff/Δt² with m_eff = ½ (unit slave mass, master mass Σ N_I m_I = 1 in a face
  // interior).
  const Real k = contact::DEFAULT_PENALTY_FACTOR * 0.5 / (1e-3 * 1e-3);
  SECTION("under the top faces (normal +z): pushed up") {
    const test::ContactMesh mesh = block_and_point(Vec3(0.5, 0.5, 1.0 - depth));
    const Vec3 f = contact_force(mesh, point_spec(mesh, 1, {18}, {}), 18);
    CHECK(f[2] == Approx(k * depth).epsilon(1e-9));
    CHECK(std::abs(f[0]) + std::abs(f[1]) < 1e-9 * k * depth);
  }
  SECTION("above the bottom faces (normal −z): pushed down") {
    const test::ContactMesh mesh = block_and_point(Vec3(0.5, 0.5, depth));
    const Vec3 f = contact_force(mesh, point_spec(mesh, 0, {18}, {}), 18);
    CHECK(f[2] == Approx(-k * depth).epsilon(1e-9));
  }
}
