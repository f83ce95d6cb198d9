#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "contact/contact_domain.hpp"
#include "contact/contact_engine.hpp"
#include "contact/initial_overclosure.hpp"
#include "contact/surface_corners.hpp"
#include "contact_fixtures.hpp"

using namespace xpl;
using contact::ContactDomain;
using contact::ContactEngine;
using contact::DomainSpec;
using contact::OffsetReason;
using contact::OverclosureReport;
using contact::OverclosureSettings;
using contact::Vec3;

namespace {

DomainSpec all_exterior() {
  DomainSpec spec;
  spec.surfaces.push_back({"ALL_EXTERIOR", true, {}});
  spec.inclusions.push_back({0, 0, false});
  return spec;
}

ContactEngine engine_for(const test::ContactMesh& mesh, const NodalVectors& x,
                         const DomainSpec& spec = all_exterior(),
                         std::span<const Real> thickness = {}) {
  return ContactEngine(ContactDomain(spec, mesh.topology(), x), {}, {}, x, thickness);
}

/// Largest penetration (m) of any slave node into its nearest admissible face at x.
Real deepest(ContactEngine& engine, const NodalVectors& x, std::span<const Real> thickness = {}) {
  engine.probe(x, thickness);
  Real worst = 0.0;
  for (Index s = 0; s < engine.domain().slaves().size(); ++s)
    if (engine.touch(s).face != NO_INDEX) worst = std::max(worst, -engine.touch(s).gap);
  return worst;
}

}  // namespace

TEST_CASE("non-matching blocks overlapping by 5 % end exactly on one surface",
          "[contact][overclosure]") {
  // A: 3×3×1 elements of h = 1; B: 2×2×1 elements of 1.3 (its nodes fall inside A's faces),
  // distorted by 5 % so that no face is flat, B's bottom 0.05 below A's top.
  test::ContactMesh mesh;
  test::add_hex_block(mesh, 3, 3, 1, 1.0, Vec3::Zero(), 0.0);
  test::add_hex_block(mesh, 2, 2, 1, 1.3, Vec3(0.2, 0.2, 0.95), 0.0);
  NodalVectors x = mesh.coordinates;
  // Tilt A's top face slightly so the overlap varies from node to node (3 % to 5 %).
  for (Index i = 0; i < 16; ++i) x(16 + i, 2) -= 0.02 * x(16 + i, 0) / 3.0;
  ContactEngine engine = engine_for(mesh, x);
  const NodalVectors as_read = x;
  const OverclosureReport report =
      contact::resolve_initial_overclosures(engine, mesh.topology(), x, {}, {}, {});
  CHECK(report.ignored.empty());
  CHECK(report.offsets.empty());
  CHECK(report.adjusted.size() >= 8);
  // Deepest: B's bottom nodes at x = 0.2 (A's top is 0.02·0.2/3 lower there), measured
  // along A's tilted normal. A's edge nodes at x = 0 lie beside B, not in it.
  const Real slope = 0.02 / 3.0;
  CHECK(report.max_overclosure ==
        Approx((0.05 - slope * 0.2) / std::sqrt(1.0 + slope * slope)).margin(1e-12));
  // Every slave node on or outside the other surface, to 1e-9 of the element size.
  CHECK(deepest(engine, x) < 1e-9);
  // The moves are the reported ones, and only slave nodes under the other block moved.
  NodalVectors expected = as_read;
  for (const auto& a : report.adjusted)
    expected.row(a.node) += a.distance * a.direction.transpose();
  CHECK((x - expected).cwiseAbs().maxCoeff() < 1e-15);
  for (const auto& a : report.adjusted) CHECK(a.distance < 0.06);
}

TEST_CASE("held, pinched and deep nodes: offsets and ignored nodes with their reasons",
          "[contact][overclosure]") {
  test::ContactMesh mesh;
  test::add_hex_block(mesh, 2, 2, 1, 1.0);                        // A, nodes 0..17
  test::add_hex_block(mesh, 2, 2, 1, 1.0, Vec3(0.0, 0.0, 0.95));  // B, nodes 18..35
  NodalVectors x = mesh.coordinates;

  SECTION("both contact faces fixed by boundary conditions: offsets d0, reason BC") {
    std::vector<std::uint8_t> lock(static_cast<std::size_t>(mesh.node_count()), 0);
    for (Index i = 9; i < 18; ++i) lock[i] = contact::LOCK_Z;   // A's top face
    for (Index i = 18; i < 27; ++i) lock[i] = contact::LOCK_Z;  // B's bottom face
    ContactEngine engine = engine_for(mesh, x);
    const OverclosureReport report =
        contact::resolve_initial_overclosures(engine, mesh.topology(), x, {}, lock, {});
    CHECK(report.adjusted.empty());
    REQUIRE(report.offsets.size() == 18);
    for (const auto& o : report.offsets) {
      CHECK(o.reason == OffsetReason::Boundary);
      CHECK(o.offset == Approx(0.05));
    }
    CHECK((x - mesh.coordinates).cwiseAbs().maxCoeff() == 0.0);
    // The stored offsets cancel the penetration: d − d0 = 0 for every constraint.
    for (Index s = 0; s < engine.domain().slaves().size(); ++s)
      if (engine.touch(s).face != NO_INDEX && engine.touch(s).gap < 0.0)
        CHECK(-engine.touch(s).gap - engine.constraints()[s].offset == Approx(0.0).margin(1e-12));
  }
  SECTION("a boundary condition across the move does not hold the node") {
    std::vector<std::uint8_t> lock(static_cast<std::size_t>(mesh.node_count()), 0);
    for (Index i = 9; i < 27; ++i) lock[i] = contact::LOCK_X | contact::LOCK_Y;
    ContactEngine engine = engine_for(mesh, x);
    const OverclosureReport report =
        contact::resolve_initial_overclosures(engine, mesh.topology(), x, {}, lock, {});
    CHECK(report.offsets.empty());
    CHECK(report.adjusted.size() == 18);
    CHECK(deepest(engine, x) < 1e-12);
  }
  SECTION("one face held: the other view takes the whole overlap in one pass") {
    std::vector<std::uint8_t> lock(static_cast<std::size_t>(mesh.node_count()), 0);
    for (Index i = 9; i < 18; ++i) lock[i] = contact::LOCK_X | contact::LOCK_Y | contact::LOCK_Z;
    ContactEngine engine = engine_for(mesh, x);
    const OverclosureReport report =
        contact::resolve_initial_overclosures(engine, mesh.topology(), x, {}, lock, {});
    CHECK(report.offsets.empty());
    CHECK(report.adjusted.size() == 9);
    for (const auto& a : report.adjusted) CHECK(a.distance == Approx(0.05));
    CHECK(report.passes == 1);
  }
  SECTION("deeper than 15 % of the facet: ignored, no offset") {
    for (Index i = 18; i < 36; ++i) x(i, 2) -= 0.25;  // overlap 0.30
    ContactEngine engine = engine_for(mesh, x);
    const OverclosureReport report =
        contact::resolve_initial_overclosures(engine, mesh.topology(), x, {}, {}, {});
    CHECK(report.adjusted.empty());
    CHECK(report.offsets.empty());
    REQUIRE(report.ignored.size() == 18);
    CHECK(report.ignored[0].depth == Approx(0.3));
    CHECK(report.ignored[0].limit == Approx(0.15));
  }
  SECTION("later step: offsets only, nothing moves") {
    ContactEngine engine = engine_for(mesh, x);
    OverclosureSettings settings;
    settings.adjust = false;
    settings.offset_reason = OffsetReason::LaterStep;
    const OverclosureReport report =
        contact::resolve_initial_overclosures(engine, mesh.topology(), x, {}, {}, settings);
    CHECK(report.offsets.size() == 18);
    CHECK((x - mesh.coordinates).cwiseAbs().maxCoeff() == 0.0);
    // A rebuilt engine (a domain extended in a later step) keeps them.
    ContactEngine rebuilt = engine_for(mesh, x);
    contact::carry_offsets(engine, rebuilt);
    for (Index s = 0; s < rebuilt.domain().slaves().size(); ++s)
      CHECK(rebuilt.constraints()[s].offset == engine.constraints()[s].offset);
  }
}

TEST_CASE("a shell node between two held dies is pinched", "[contact][overclosure]") {
  test::ContactMesh mesh;
  test::add_hex_block(mesh, 4, 4, 1, 1.0, Vec3(-1.0, -1.0, -1.05));  // lower die
  test::add_hex_block(mesh, 4, 4, 1, 1.0, Vec3(-1.0, -1.0, 0.05));   // upper die
  const Index first_sheet = mesh.node_count();
  test::add_shell_plate(mesh, 2, 2, 0.8, Vec3(0.1, 0.1, 0.0));
  NodalVectors x = mesh.coordinates;
  std::vector<Real> thickness(static_cast<std::size_t>(mesh.node_count()), 0.0);
  for (Index i = first_sheet; i < mesh.node_count(); ++i) thickness[i] = 0.2;
  std::vector<std::uint8_t> lock(thickness.size(), 0);
  for (Index i = 0; i < first_sheet; ++i) lock[i] = contact::LOCK_RIGID;
  DomainSpec spec = all_exterior();
  ContactEngine engine = engine_for(mesh, x, spec, thickness);
  const OverclosureReport report =
      contact::resolve_initial_overclosures(engine, mesh.topology(), x, thickness, lock, {});
  CHECK(report.adjusted.empty());
  std::size_t pinched = 0;
  for (const auto& o : report.offsets)
    if (o.node >= first_sheet) {
      CHECK(o.reason == OffsetReason::Pinched);
      CHECK(o.offset == Approx(0.05));
      ++pinched;
    }
  CHECK(pinched == 9);
}

TEST_CASE("an adjustment that would crush an element corner is refused", "[contact][overclosure]") {
  // One hex A whose corner (1, 1, 1) has a vertical edge of only 0.2 (its bottom node is
  // raised to z = 0.8), slave of a one-sided pair against block B, whose bottom face is 0.12
  // below A's top (under the 15 % limit): moving that corner down by 0.12 would leave 40 % of
  // its volume, so the element's nodes are held with reason "distortion" instead.
  test::ContactMesh mesh;
  test::add_hex_block(mesh, 1, 1, 1, 1.0);                        // A: nodes 0..7
  test::add_hex_block(mesh, 1, 1, 1, 1.0, Vec3(0.0, 0.0, 0.88));  // B: nodes 8..15
  NodalVectors x = mesh.coordinates;
  x(3, 2) = 0.8;  // node (1, 1, 0) of A
  DomainSpec spec;
  spec.surfaces.push_back({"A_TOP", false, {{0, 1}}});     // S2 of A
  spec.surfaces.push_back({"B_BOTTOM", false, {{1, 0}}});  // S1 of B
  spec.inclusions.push_back({0, 1, true});
  ContactEngine engine = engine_for(mesh, x, spec);
  const NodalVectors as_read = x;
  const OverclosureReport report =
      contact::resolve_initial_overclosures(engine, mesh.topology(), x, {}, {}, {});
  REQUIRE(report.refused_elements.size() == 1);
  CHECK(report.refused_elements[0] == 0);
  CHECK(report.adjusted.empty());
  CHECK((x - as_read).cwiseAbs().maxCoeff() == 0.0);
  REQUIRE(report.offsets.size() == 4);
  for (const auto& o : report.offsets) {
    CHECK(o.reason == OffsetReason::Distortion);
    CHECK(o.offset == Approx(0.12));
  }
}

TEST_CASE("crossed surfaces: edges of a column through a shell plate", "[contact][overclosure]") {
  test::ContactMesh mesh;
  test::add_shell_plate(mesh, 4, 4, 1.0);  // z = 0
  const Index first_column = mesh.node_count();
  test::add_hex_block(mesh, 1, 1, 2, 1.0, Vec3(1.25, 1.25, -1.5));  // z = -1.5, -0.5, 0.5
  NodalVectors x = mesh.coordinates;
  std::vector<Real> thickness(static_cast<std::size_t>(mesh.node_count()), 0.0);
  for (Index i = 0; i < first_column; ++i) thickness[i] = 0.1;
  OverclosureSettings settings;
  SECTION("on") {
    ContactEngine engine = engine_for(mesh, x, all_exterior(), thickness);
    const OverclosureReport report =
        contact::resolve_initial_overclosures(engine, mesh.topology(), x, thickness, {}, settings);
    int column_edges = 0;
    for (const auto& c : report.crossed)
      if (c.node_a >= first_column && c.node_b == c.node_a + 4) ++column_edges;  // k=1 → k=2
    CHECK(column_edges == 4);
  }
  SECTION("off") {
    settings.detect_crossed = false;
    ContactEngine engine = engine_for(mesh, x, all_exterior(), thickness);
    const OverclosureReport report =
        contact::resolve_initial_overclosures(engine, mesh.topology(), x, thickness, {}, settings);
    CHECK(report.crossed.empty());
  }
}

TEST_CASE("crossed surfaces: blocks overlapping by 4 % only graze each other's rims",
          "[contact][overclosure]") {
  // Issue 15: the adjustment moves the nodes inside the other block's footprint onto the
  // common surface, so the facet edges leaving the footprint slope and meet the other block's
  // side faces on (or, with non-matching meshes, within a fraction of a percent of the facet
  // of) their bottom rim: a graze of a corner of the master surface, not a crossing. Before
  // the rule each case below gave 4 (matching h) or 8 (non-matching) warnings.
  struct Case {
    const char* name;
    int lower_n, upper_n;
    Real upper_h, upper_origin;
  };
  const Case cases[] = {{"upper inside the lower footprint, rim mid-element", 4, 3, 1.0, 0.5},
                        {"upper overhanging the lower block", 3, 4, 1.0, -0.5},
                        {"non-matching meshes, overhanging", 3, 4, 0.7, -0.5}};
  for (const Case& c : cases) {
    DYNAMIC_SECTION(c.name) {
      test::ContactMesh mesh;
      test::add_hex_block(mesh, c.lower_n, c.lower_n, 2, 1.0, Vec3(0.0, 0.0, -2.0));  // top z=0
      test::add_hex_block(mesh, c.upper_n, c.upper_n, 1, c.upper_h,
                          Vec3(c.upper_origin, c.upper_origin, -0.04));  // 4 % of h below
      NodalVectors x = mesh.coordinates;
      ContactEngine engine = engine_for(mesh, x);
      const OverclosureReport report =
          contact::resolve_initial_overclosures(engine, mesh.topology(), x, {}, {}, {});
      CHECK(report.max_overclosure == Approx(0.04).epsilon(1e-9));
      CHECK(report.offsets.empty());
      CHECK(report.ignored.empty());
      CHECK(deepest(engine, x) <= 1e-9);  // nothing left penetrating: the adjustment worked
      CHECK(report.crossed.empty());
    }
  }
}

TEST_CASE("crossed surfaces: a column through a solid plate still warns",
          "[contact][overclosure]") {
  // A 1 × 1 × 2 hex column (z = -0.5 … 1.5, its middle nodes inside the plate, 50 % deep: far
  // beyond the 15 % limit) through a 4 × 4 × 1 hex plate (z = 0 … 1), its sides 0.25 from the
  // plate's mesh lines. Both column edges of each vertical line pass through the interior of
  // the plate's faces, and the plate's edges through the column's side faces.
  test::ContactMesh mesh;
  test::add_hex_block(mesh, 4, 4, 1, 1.0);
  const Index first_column = mesh.node_count();
  test::add_hex_block(mesh, 1, 1, 2, 1.0, Vec3(1.25, 1.25, -0.5));
  NodalVectors x = mesh.coordinates;
  ContactEngine engine = engine_for(mesh, x);
  const OverclosureReport report =
      contact::resolve_initial_overclosures(engine, mesh.topology(), x, {}, {}, {});
  int column_edges = 0;
  for (const auto& c : report.crossed)
    if (c.node_a >= first_column && c.node_b == c.node_a + 4) ++column_edges;  // vertical edges
  CHECK(column_edges == 8);  // 4 lines × (bottom face, top face)
}

TEST_CASE("corner edges of master surfaces: rims and folds, not edges inside a flat surface",
          "[contact][overclosure]") {
  test::ContactMesh mesh;
  test::add_hex_block(mesh, 2, 1, 1, 1.0);  // two hexes side by side along x
  const NodalVectors x = mesh.coordinates;
  const std::vector<contact::ContactFace> faces = contact::exterior_faces(mesh.topology());
  const std::vector<std::uint8_t> corners = contact::corner_edges(faces, x);
  REQUIRE(corners.size() == faces.size());
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const Vec3 n = test::face_normal(faces[f], x);
    int corner_count = 0;
    for (int a = 0; a < 4; ++a) corner_count += (corners[f] >> a) & 1;
    // A face normal to x is an end of the block: all four edges are 90° folds. A top,
    // bottom or side face continues across x = 1 into its neighbour's: three corner edges.
    CHECK(corner_count == (std::abs(n[0]) > 0.5 ? 4 : 3));
  }
}
