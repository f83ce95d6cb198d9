#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <set>

#include "contact/contact_faces.hpp"
#include "contact_fixtures.hpp"

using namespace xpl;
using contact::ContactFace;
using contact::ElementKind;
using contact::Vec3;

namespace {

std::array<Index, 4> sorted(std::array<Index, 4> a) {
  std::sort(a.begin(), a.end());
  return a;
}

}  // namespace

TEST_CASE("a 2x2x2 hex block has 24 exterior faces, all outward", "[contact][faces]") {
  test::ContactMesh mesh;
  const Real distortion = GENERATE(0.0, 0.15);
  test::add_hex_block(mesh, 2, 2, 2, 1.0, Vec3::Zero(), distortion);
  const auto faces = contact::exterior_faces(mesh.topology(), 7);
  REQUIRE(faces.size() == 24);

  std::set<std::array<Index, 4>> keys;
  for (const ContactFace& f : faces) {
    CHECK(keys.insert(sorted(f.nodes)).second);  // each face once
    CHECK_FALSE(f.shell);
    CHECK(f.surface == 7);
    const Vec3 n = test::face_normal(f, mesh.coordinates);
    // Outward: away from the owning element and away from the block centre (1, 1, 1).
    CHECK(n.dot(test::face_centroid(f, mesh.coordinates) -
                test::element_centroid(mesh, f.element)) > 0.0);
    CHECK(n.dot(test::face_centroid(f, mesh.coordinates) - Vec3(1, 1, 1)) > 0.0);
    // On the boundary of the undistorted block: every corner has a coordinate 0 or 2.
    if (distortion == 0.0) {
      int axis = -1;
      for (int d = 0; d < 3; ++d)
        if (std::abs(std::abs(n[d]) - 1.0) < 1e-12) axis = d;
      REQUIRE(axis >= 0);
      const Real side = n[axis] > 0 ? 2.0 : 0.0;
      for (Index node : f.nodes) CHECK(mesh.coordinates(node, axis) == side);
    }
  }
  // Every element of a 2x2x2 block is a corner element with 3 exterior faces.
  for (Index e = 0; e < 8; ++e)
    CHECK(std::count_if(faces.begin(), faces.end(),
                        [&](const ContactFace& f) { return f.element == e; }) == 3);
}

TEST_CASE("face numbers of one hex follow S1..S6", "[contact][faces]") {
  test::ContactMesh mesh;
  test::add_hex_block(mesh, 1, 1, 1, 1.0);
  const auto faces = contact::exterior_faces(mesh.topology());
  REQUIRE(faces.size() == 6);
  // Outward normals of S1..S6 on the unit cube (Abaqus: S1 bottom, S2 top, S3 front y = 0,
  // S4 right x = 1, S5 back y = 1, S6 left x = 0).
  const Vec3 expected[6] = {{0, 0, -1}, {0, 0, 1}, {0, -1, 0}, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0}};
  for (int f = 0; f < 6; ++f) {
    CHECK(faces[f].face == f);
    CHECK(faces[f].surface == NO_INDEX);
    CHECK((test::face_normal(faces[f], mesh.coordinates) - expected[f]).norm() < 1e-14);
  }
}

TEST_CASE("shells give two faces with opposite normals and offset surfaces",
          "[contact][faces][shell]") {
  test::ContactMesh mesh;
  test::add_shell_plate(mesh, 1, 1, 2.0, Vec3(0, 0, 1));
  const auto faces = contact::exterior_faces(mesh.topology(), 3);
  REQUIRE(faces.size() == 2);
  const ContactFace& neg = faces[0];
  const ContactFace& pos = faces[1];
  CHECK(neg.face == contact::SHELL_SNEG);
  CHECK(pos.face == contact::SHELL_SPOS);
  CHECK((neg.shell && pos.shell));
  CHECK(pos.nodes == std::array<Index, 4>{0, 1, 3, 2});  // element order (plate node numbering)
  CHECK(neg.nodes == std::array<Index, 4>{0, 2, 3, 1});  // reversed
  CHECK((test::face_normal(pos, mesh.coordinates) - Vec3(0, 0, 1)).norm() < 1e-14);
  CHECK((test::face_normal(neg, mesh.coordinates) - Vec3(0, 0, -1)).norm() < 1e-14);

  // Each side's contact surface is half the node thickness away from the mid-surface.
  const std::vector<Real> thickness = {0.1, 0.2, 0.3, 0.4};
  Vec3 c[4];
  contact::face_corners(pos, mesh.coordinates, thickness, c);
  for (int a = 0; a < 4; ++a) CHECK(c[a][2] == Approx(1.0 + 0.5 * thickness[pos.nodes[a]]));
  contact::face_corners(neg, mesh.coordinates, thickness, c);
  for (int a = 0; a < 4; ++a) CHECK(c[a][2] == Approx(1.0 - 0.5 * thickness[neg.nodes[a]]));
  // Without thickness (no shells in the model) the mid-surface is used.
  contact::face_corners(pos, mesh.coordinates, {}, c);
  CHECK(c[0][2] == 1.0);
}

TEST_CASE("a shell on a hex face leaves the hex face exterior", "[contact][faces][shell]") {
  test::ContactMesh mesh;
  test::add_hex_block(mesh, 1, 1, 1, 1.0);
  mesh.add_element(ElementKind::Shell, {4, 5, 6, 7});  // on the top face
  mesh.add_element(ElementKind::Other, {0});           // e.g. a point mass: no faces
  const auto faces = contact::exterior_faces(mesh.topology());
  CHECK(faces.size() == 8);
  CHECK(std::count_if(faces.begin(), faces.end(), [](const ContactFace& f) { return f.shell; }) ==
        2);
}

TEST_CASE("surface faces come from (element, face) references", "[contact][faces]") {
  test::ContactMesh mesh;
  test::add_hex_block(mesh, 2, 1, 1, 1.0);
  test::add_shell_plate(mesh, 1, 1, 1.0, Vec3(0, 0, 3));
  const auto all = contact::exterior_faces(mesh.topology());
  const contact::FaceRef refs[] = {{1, 3}, {0, 0}, {2, contact::SHELL_SPOS}, {2, 0}};
  const auto faces = contact::surface_faces(mesh.topology(), refs, 5);
  REQUIRE(faces.size() == 4);
  for (std::size_t i = 0; i < faces.size(); ++i) {
    CHECK(faces[i].element == refs[i].element);
    CHECK(faces[i].face == refs[i].face);
    CHECK(faces[i].surface == 5);
    // Same corner order as the face in the all-exterior list.
    const auto match = std::find_if(all.begin(), all.end(), [&](const ContactFace& f) {
      return f.element == refs[i].element && f.face == refs[i].face;
    });
    REQUIRE(match != all.end());
    CHECK(match->nodes == faces[i].nodes);
  }
  // Interior faces may be listed explicitly: S6 of element 1 is shared with element 0.
  const contact::FaceRef interior[] = {{1, 5}};
  const auto inner = contact::surface_faces(mesh.topology(), interior, 0);
  CHECK((test::face_normal(inner[0], mesh.coordinates) - Vec3(-1, 0, 0)).norm() < 1e-14);

  const contact::FaceRef bad_hex[] = {{0, 6}};
  const contact::FaceRef bad_shell[] = {{2, 2}};
  const contact::FaceRef bad_element[] = {{9, 0}};
  CHECK_THROWS_AS(contact::surface_faces(mesh.topology(), bad_hex, 0), std::invalid_argument);
  CHECK_THROWS_AS(contact::surface_faces(mesh.topology(), bad_shell, 0), std::invalid_argument);
  CHECK_THROWS_AS(contact::surface_faces(mesh.topology(), bad_element, 0), std::invalid_argument);
}

TEST_CASE("tributary areas sum to the face area", "[contact][faces][area]") {
  test::ContactMesh mesh;
  test::add_hex_block(mesh, 2, 2, 2, 1.0);
  const auto faces = contact::exterior_faces(mesh.topology());
  contact::SlaveNodes slaves(faces, mesh.node_count());
  CHECK(slaves.size() == 26);  // 27 nodes minus the centre
  CHECK(slaves.slot(13) == NO_INDEX);
  slaves.update_areas(faces, mesh.coordinates);
  Real total = 0.0;
  for (Real a : slaves.areas()) total += a;
  CHECK(total == Approx(24.0).epsilon(1e-14));
  CHECK(slaves.areas()[slaves.slot(0)] == Approx(0.75).epsilon(1e-14));  // 3 quarter faces
  CHECK(slaves.areas()[slaves.slot(1)] == Approx(1.0).epsilon(1e-14));   // 4 quarter faces

  // On a deformed configuration the sum follows the deformed faces.
  NodalVectors moved = mesh.coordinates * 1.5;
  slaves.update_areas(faces, moved);
  total = 0.0;
  for (Real a : slaves.areas()) total += a;
  CHECK(total == Approx(24.0 * 2.25).epsilon(1e-14));
}

TEST_CASE("a double-sided shell counts its area once", "[contact][faces][area][shell]") {
  test::ContactMesh mesh;
  test::add_shell_plate(mesh, 2, 2, 1.0);
  test::add_hex_block(mesh, 1, 1, 1, 0.5, Vec3(0, 0, 1), 0.1);
  const auto faces = contact::exterior_faces(mesh.topology());
  REQUIRE(faces.size() == 6 + 8);
  contact::SlaveNodes slaves(faces, mesh.node_count());
  slaves.update_areas(faces, mesh.coordinates);
  Real expected = 4.0;  // plate, once
  for (const ContactFace& f : faces) {
    if (f.shell) continue;
    Vec3 c[4];
    test::corners_of(f, mesh.coordinates, c);
    expected += contact::quad_area(c);
  }
  Real total = 0.0;
  for (Real a : slaves.areas()) total += a;
  CHECK(total == Approx(expected).epsilon(1e-14));
  CHECK(slaves.areas()[slaves.slot(4)] == Approx(1.0).epsilon(1e-14));  // plate centre node
  CHECK(slaves.areas()[slaves.slot(0)] == Approx(0.25).epsilon(1e-14));
  // A single side alone carries the full area too.
  const contact::FaceRef spos[] = {{0, contact::SHELL_SPOS}};
  const auto one = contact::surface_faces(mesh.topology(), spos, 0);
  contact::SlaveNodes one_side(one, mesh.node_count());
  one_side.update_areas(one, mesh.coordinates);
  CHECK(one_side.areas()[0] == Approx(0.25).epsilon(1e-14));
  CHECK_THROWS_AS(one_side.update_areas(faces, mesh.coordinates), std::invalid_argument);
}

TEST_CASE("areas of selected slots are bitwise those of the full pass, the rest untouched",
          "[contact][faces][area]") {
  test::ContactMesh mesh;
  test::add_hex_block(mesh, 3, 2, 2, 1.0);
  const auto faces = contact::exterior_faces(mesh.topology());
  contact::SlaveNodes full(faces, mesh.node_count());
  contact::SlaveNodes part(faces, mesh.node_count());
  // A warped configuration, so that areas and normals carry rounding.
  NodalVectors moved = mesh.coordinates;
  for (Index n = 0; n < moved.rows(); ++n)
    for (int d = 0; d < 3; ++d) moved(n, d) += 0.013 * std::sin(1.7 * n + 0.9 * d);
  full.update_areas(faces, moved);
  part.update_areas(faces, mesh.coordinates);
  const std::vector<Real> before = part.areas();
  // Every third slot, with the faces around it.
  std::vector<char> slot_needed(static_cast<std::size_t>(part.size()), 0);
  std::vector<char> face_needed(faces.size(), 0);
  for (Index s = 0; s < part.size(); s += 3) {
    slot_needed[s] = 1;
    for (Index f : part.faces_of(s)) face_needed[f] = 1;
  }
  part.update_areas(faces, moved, slot_needed, face_needed);
  for (Index s = 0; s < part.size(); ++s) {
    if (slot_needed[s]) {
      CHECK(part.areas()[s] == full.areas()[s]);
      for (int d = 0; d < 3; ++d) CHECK(part.normal(s)[d] == full.normal(s)[d]);
    } else {
      CHECK(part.areas()[s] == before[s]);
    }
  }
  CHECK(part.areas()[1] != full.areas()[1]);  // slot 1 kept the undeformed area
}
