#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <vector>

#include "common/timer.hpp"

#include "contact/contact_clearance.hpp"
#include "contact/contact_domain.hpp"
#include "contact/contact_engine.hpp"
#include "contact_fixtures.hpp"

using namespace xpl;
using contact::ClearanceReport;
using contact::ClearanceSkip;
using contact::ClearanceView;
using contact::ContactDomain;
using contact::ContactEngine;
using contact::DomainSpec;
using contact::FaceRef;
using contact::Vec3;

namespace {

DomainSpec all_exterior() {
  DomainSpec spec;
  spec.surfaces.push_back({"ALL_EXTERIOR", true, {}});
  spec.inclusions.push_back({0, 0, false});
  return spec;
}

ContactEngine engine_for(const test::ContactMesh& mesh, const NodalVectors& x,
                         std::span<const Real> thickness = {}) {
  return ContactEngine(ContactDomain(all_exterior(), mesh.topology(), x), {}, {}, x, thickness);
}

/// Faces `face` (S1 = 0, S2 = 1; shells SNEG = 0, SPOS = 1) of elements first..last-1.
std::vector<FaceRef> faces(Index first, Index last, std::uint8_t face) {
  std::vector<FaceRef> out;
  for (Index e = first; e < last; ++e) out.push_back({e, face});
  return out;
}

/// Two 2×2×1 blocks of h = 1: A (elements 0..3, nodes 0..17) and B above it at `b_bottom`
/// (elements 4..7, nodes 18..35), B's footprint shifted by `shift` in x and y.
test::ContactMesh two_blocks(Real b_bottom, Real shift = 0.0) {
  test::ContactMesh mesh;
  test::add_hex_block(mesh, 2, 2, 1, 1.0);
  test::add_hex_block(mesh, 2, 2, 1, 1.0, Vec3(shift, shift, b_bottom));
  return mesh;
}

ClearanceView view(std::vector<FaceRef> slave, std::vector<FaceRef> master, bool adjust, Real c) {
  ClearanceView v;
  v.slave_faces = std::move(slave);
  v.master_faces = std::move(master);
  v.adjust = adjust;
  v.value = c;
  return v;
}

/// Both views of A's top (S2) and B's bottom (S1).
std::vector<ClearanceView> balanced(bool adjust, Real c, Real above, Real below) {
  std::vector<ClearanceView> views = {view(faces(0, 4, 1), faces(4, 8, 0), adjust, c),
                                      view(faces(4, 8, 0), faces(0, 4, 1), adjust, c)};
  for (ClearanceView& v : views) {
    v.search_above = above;
    v.search_below = below;
  }
  return views;
}

}  // namespace

TEST_CASE("a zero clearance brings blocks 30 % inside each other exactly into contact",
          "[contact][clearance]") {
  test::ContactMesh mesh = two_blocks(0.7);
  NodalVectors x = mesh.coordinates;
  ContactEngine engine = engine_for(mesh, x);
  const std::vector<ClearanceView> views = balanced(true, 0.0, 0.0, 0.4);
  const ClearanceReport report =
      contact::apply_clearances(engine, mesh.topology(), x, {}, {}, views, true);
  REQUIRE(report.nodes.size() == 18);
  CHECK(report.skipped.empty());
  // Both views give way half each: the faces meet at z = 0.85.
  for (Index n = 9; n < 18; ++n) CHECK(x(n, 2) == Approx(0.85).margin(1e-12));
  for (Index n = 18; n < 27; ++n) CHECK(x(n, 2) == Approx(0.85).margin(1e-12));
  for (const auto& c : report.nodes) {
    CHECK(c.offset == 0.0);
    CHECK(c.gap_before == Approx(-0.3).margin(1e-12));
    CHECK(c.distance == Approx(0.15).margin(1e-12));
  }
  // The automatic pass must leave them alone: all handled.
  Index handled = 0;
  for (char h : report.handled) handled += h;
  CHECK(handled == 18);
}

TEST_CASE("MASTER view: only the slave surface moves; SEARCH zones limit the nodes",
          "[contact][clearance]") {
  test::ContactMesh mesh = two_blocks(0.7);
  NodalVectors x = mesh.coordinates;
  ContactEngine engine = engine_for(mesh, x);
  std::vector<ClearanceView> views = {view(faces(4, 8, 0), faces(0, 4, 1), true, 0.1)};
  views[0].search_below = 0.4;
  views[0].search_above = 0.0;
  const ClearanceReport report =
      contact::apply_clearances(engine, mesh.topology(), x, {}, {}, views, true);
  CHECK(report.nodes.size() == 9);
  for (Index n = 9; n < 18; ++n) CHECK(x(n, 2) == mesh.coordinates(n, 2));
  for (Index n = 18; n < 27; ++n) CHECK(x(n, 2) == Approx(1.1).margin(1e-12));

  SECTION("a zone too shallow for the penetration leaves the nodes alone") {
    NodalVectors y = mesh.coordinates;
    ContactEngine again = engine_for(mesh, y);
    views[0].search_below = 0.2;
    const ClearanceReport none =
        contact::apply_clearances(again, mesh.topology(), y, {}, {}, views, true);
    CHECK(none.nodes.empty());
    CHECK((y - mesh.coordinates).cwiseAbs().maxCoeff() == 0.0);
  }
}

TEST_CASE("ADJUST=NO: permanent offsets make every effective gap the clearance",
          "[contact][clearance]") {
  for (const Real gap : {0.2, 0.8}) {
    test::ContactMesh mesh = two_blocks(1.0 + gap);
    NodalVectors x = mesh.coordinates;
    ContactEngine engine = engine_for(mesh, x);
    const Real margin_before = engine.broad_phase().margin();
    const std::vector<ClearanceView> views = balanced(false, 0.5, 1.0, 0.0);
    const ClearanceReport report =
        contact::apply_clearances(engine, mesh.topology(), x, {}, {}, views, true);
    CHECK((x - mesh.coordinates).cwiseAbs().maxCoeff() == 0.0);
    REQUIRE(report.nodes.size() == 18);
    const auto& slaves = engine.domain().slaves();
    for (const auto& c : report.nodes) {
      const contact::ContactConstraint& k = engine.constraints()[slaves.slot(c.node)];
      CHECK(k.offset_permanent);
      CHECK(k.offset == Approx(0.5 - gap).margin(1e-12));
      CHECK(c.gap_before + k.offset == Approx(0.5).margin(1e-12));
    }
    // A contact surface moved out towards its slave nodes needs a wider search.
    if (gap > 0.5) CHECK(engine.broad_phase().margin() >= margin_before + (gap - 0.5) - 1e-12);
    // The offsets are never ramped away: the C3 rule leaves a permanent offset alone.
    contact::ContactConstraint k = engine.constraints()[slaves.slot(20)];
    contact::normal_contact_update(k, gap, 1.0);
    CHECK(k.offset == Approx(0.5 - gap).margin(1e-12));
  }
}

TEST_CASE("perimeter nodes, missing values, rigid-free checks", "[contact][clearance]") {
  SECTION("nodes beside the master surface are skipped; nodes right above its edge are not") {
    // B shifted by 0.1 (within the search reach of A's edge): A's nodes at x = 0 or y = 0 and
    // B's at 2.1 lie beside the other surface's perimeter and are skipped (5 each); A's nodes
    // at x, y in {1, 2} and B's at {0.1, 1.1} project onto the other surface.
    test::ContactMesh mesh = two_blocks(0.9, 0.1);
    NodalVectors x = mesh.coordinates;
    ContactEngine engine = engine_for(mesh, x);
    const std::vector<ClearanceView> views = balanced(true, 0.0, 0.0, 0.2);
    const ClearanceReport report =
        contact::apply_clearances(engine, mesh.topology(), x, {}, {}, views, true);
    CHECK(report.nodes.size() == 8);
    REQUIRE(report.skipped.size() == 10);
    for (const auto& k : report.skipped) CHECK(k.why == ClearanceSkip::PerimeterEdge);
    for (const auto& c : report.nodes)
      for (int d = 0; d < 2; ++d) {
        CHECK(x(c.node, d) > 0.05);
        CHECK(x(c.node, d) < 2.05);
      }
  }
  SECTION("a distribution without values at the node or a master corner skips the node") {
    test::ContactMesh mesh = two_blocks(1.2);
    NodalVectors x = mesh.coordinates;
    ContactEngine engine = engine_for(mesh, x);
    std::vector<Real> values(static_cast<std::size_t>(mesh.node_count()),
                             std::numeric_limits<Real>::quiet_NaN());
    values[18] = 0.1;                                     // B's corner node: its own value
    for (Index n = 9; n < 18; ++n) values[n] = 0.3;       // A's top: the master nodes
    values[17] = std::numeric_limits<Real>::quiet_NaN();  // A's far corner has none
    std::vector<ClearanceView> views = {view(faces(4, 8, 0), faces(0, 4, 1), true, 0.0)};
    views[0].nodal_values = values;
    views[0].search_above = 0.5;
    views[0].search_below = 0.0;
    const ClearanceReport report =
        contact::apply_clearances(engine, mesh.topology(), x, {}, {}, views, true);
    CHECK(x(18, 2) == Approx(1.1).margin(1e-12));  // own value
    CHECK(x(19, 2) == Approx(1.3).margin(1e-12));  // interpolated 0.3
    // Node 26 (B's far corner, above A's node 17) and its neighbours 23, 25 have a master face
    // with a corner without a value.
    Index no_value = 0;
    for (const auto& k : report.skipped) no_value += k.why == ClearanceSkip::NoValue;
    CHECK(no_value >= 1);
    CHECK(x(26, 2) == mesh.coordinates(26, 2));
  }
}

TEST_CASE("double-sided shells: negative clearance is a gap to the other side",
          "[contact][clearance]") {
  test::ContactMesh mesh;
  test::add_shell_plate(mesh, 3, 3, 1.0);                       // master, SPOS +z, nodes 0..15
  test::add_shell_plate(mesh, 1, 1, 1.0, Vec3(1.0, 1.0, 0.3));  // slave, within the thickness
  std::vector<Real> thickness(static_cast<std::size_t>(mesh.node_count()), 0.4);
  NodalVectors x = mesh.coordinates;
  ContactEngine engine = engine_for(mesh, x, thickness);
  SECTION("positive: above the surface normal") {
    std::vector<ClearanceView> views = {view(faces(9, 10, 1), faces(0, 9, 1), true, 0.25)};
    views[0].search_below = 1.0;
    contact::apply_clearances(engine, mesh.topology(), x, thickness, {}, views, true);
    for (Index n = 16; n < 20; ++n) CHECK(x(n, 2) == Approx(0.25 + 0.4).margin(1e-12));
  }
  SECTION("negative: below the master, |c| from its other side") {
    std::vector<ClearanceView> views = {view(faces(9, 10, 1), faces(0, 9, 1), true, -0.25)};
    views[0].search_below = 1.0;
    contact::apply_clearances(engine, mesh.topology(), x, thickness, {}, views, true);
    for (Index n = 16; n < 20; ++n) CHECK(x(n, 2) == Approx(-0.25 - 0.4).margin(1e-12));
  }
  SECTION("ADJUST=NO on the wrong side of the mid-surface is skipped") {
    std::vector<ClearanceView> views = {view(faces(9, 10, 1), faces(0, 9, 1), false, -0.25)};
    views[0].search_below = 1.0;
    const ClearanceReport report =
        contact::apply_clearances(engine, mesh.topology(), x, thickness, {}, views, true);
    CHECK(report.nodes.empty());
    REQUIRE(report.skipped.size() == 4);
    for (const auto& k : report.skipped) CHECK(k.why == ClearanceSkip::WrongSide);
  }
}

TEST_CASE("a held node keeps its clearance violation as a permanent offset",
          "[contact][clearance]") {
  test::ContactMesh mesh = two_blocks(0.7);
  NodalVectors x = mesh.coordinates;
  std::vector<std::uint8_t> lock(static_cast<std::size_t>(mesh.node_count()), 0);
  for (Index n = 18; n < 27; ++n) lock[n] = contact::LOCK_Z;  // B's bottom fixed in z
  ContactEngine engine = engine_for(mesh, x);
  std::vector<ClearanceView> views = {view(faces(4, 8, 0), faces(0, 4, 1), true, 0.0)};
  views[0].search_below = 0.4;
  const ClearanceReport report =
      contact::apply_clearances(engine, mesh.topology(), x, {}, lock, views, true);
  REQUIRE(report.nodes.size() == 9);
  CHECK((x - mesh.coordinates).cwiseAbs().maxCoeff() == 0.0);
  for (const auto& c : report.nodes) {
    CHECK(c.reason == contact::OffsetReason::Boundary);
    CHECK(c.offset == Approx(0.3).margin(1e-12));
  }
}

TEST_CASE("interference fit: overclosures become offsets that ramp to zero, none adjusted",
          "[contact][clearance][interference]") {
  // B's bottom 0.02 inside A's top (2 % of the facet, which the automatic pass would adjust).
  test::ContactMesh mesh = two_blocks(0.98);
  NodalVectors x = mesh.coordinates;
  const NodalVectors as_read = x;
  ContactEngine engine = engine_for(mesh, x);
  std::vector<ClearanceView> views = balanced(true, 0.0, 0.0, 0.1);
  for (ClearanceView& v : views) {
    v.interference = true;
    v.ramp_time = 1.0;
  }
  const ClearanceReport report =
      contact::apply_clearances(engine, mesh.topology(), x, {}, {}, views, true);
  CHECK(report.nodes.size() == 18);                   // 9 on each side, both views
  CHECK((x - as_read).cwiseAbs().maxCoeff() == 0.0);  // nothing moves
  const auto& slaves = engine.domain().slaves();
  for (const contact::ClearedNode& c : report.nodes) {
    CHECK(c.interference == Approx(0.02).margin(1e-12));
    CHECK(c.offset == 0.0);  // no permanent base
    CHECK(c.distance == 0.0);
    const contact::ContactConstraint& k = engine.constraints()[slaves.slot(c.node)];
    CHECK(k.offset == Approx(0.02).margin(1e-12));
    CHECK(k.offset_permanent);
    CHECK(report.handled[slaves.slot(c.node)] == 1);  // the automatic pass leaves it alone
  }
  CHECK(engine.interference_ramping());

  // The ramp: d0 = 0.02 (1 − t / 1) at step time t; no force at t = 0, half the full depth's
  // force in the middle, the plain penalty (offset 0, not permanent) at the end.
  const Index n = static_cast<Index>(x.rows());
  const std::vector<Real> mass(n, 1.0), inverse_mass(n, 1.0);
  const NodalVectors velocity = NodalVectors::Zero(n, 3);
  NodalVectors force = NodalVectors::Zero(n, 3);
  PhaseTimers timers;
  const Real dt = 0.1;
  const Index probe = slaves.slot(report.nodes.front().node);
  engine.set_step_time(0.0);
  contact::ContactTotals t0 =
      engine.update(x, velocity, 0.0, dt, {}, mass, inverse_mass, force, timers);
  CHECK(t0.closed == 0);
  CHECK(t0.interference_work == 0.0);
  engine.set_step_time(0.5);
  force.setZero();
  const contact::ContactTotals half =
      engine.update(x, velocity, dt, dt, {}, mass, inverse_mass, force, timers);
  CHECK(engine.constraints()[probe].offset == Approx(0.01).margin(1e-12));
  CHECK(engine.normal_force(probe) > 0.0);
  // The ramp step from d0 = 0.02 to 0.01 with F_n = 0: ½ F_{n+1} Δd0 per spring.
  CHECK(half.interference_work > 0.0);
  CHECK(half.interference_work == Approx(0.5 * 0.01 * [&] {
          Real sum = 0.0;
          for (Index s = 0; s < slaves.size(); ++s) sum += engine.normal_force(s);
          return sum;
        }()));
  const Real f_half = engine.normal_force(probe);
  engine.set_step_time(1.0);
  force.setZero();
  engine.update(x, velocity, dt, dt, {}, mass, inverse_mass, force, timers);
  CHECK(engine.constraints()[probe].offset == 0.0);
  CHECK_FALSE(engine.constraints()[probe].offset_permanent);
  CHECK_FALSE(engine.interference_ramping());
  CHECK(engine.normal_force(probe) == Approx(2.0 * f_half));
}

TEST_CASE(
    "interference fit with a distance: nodes moved to it first, or a held node keeps "
    "the rest as a permanent offset",
    "[contact][clearance][interference]") {
  test::ContactMesh mesh = two_blocks(0.98);
  NodalVectors x = mesh.coordinates;
  std::vector<ClearanceView> views = balanced(true, 0.0, 0.0, 0.1);
  for (ClearanceView& v : views) {
    v.interference = true;
    v.interference_distance = 0.05;
    v.ramp_time = 1.0;
  }
  SECTION("free: both sides move half of 0.03, the overclosure reached is ramped") {
    ContactEngine engine = engine_for(mesh, x);
    const ClearanceReport report =
        contact::apply_clearances(engine, mesh.topology(), x, {}, {}, views, true);
    REQUIRE(report.nodes.size() == 18);
    for (const contact::ClearedNode& c : report.nodes) {
      CHECK(c.distance == Approx(0.015).margin(1e-3 * 0.05));
      CHECK(c.interference == Approx(0.05).margin(1e-3));
      CHECK(c.offset == 0.0);
    }
    // B's bottom (nodes 18..35, lowest z) now 0.05 inside A's top (nodes 0..17, highest z).
    const Real top_a = x.col(2).head(18).maxCoeff(), bottom_b = x.col(2).tail(18).minCoeff();
    CHECK(top_a - bottom_b == Approx(0.05).margin(1e-3));
  }
  SECTION("ADJUST=NO: h ramped, the rest of the overclosure (0.02 − 0.05) stays permanent") {
    for (ClearanceView& v : views) v.adjust = false;
    ContactEngine engine = engine_for(mesh, x);
    const NodalVectors before = x;
    const ClearanceReport report =
        contact::apply_clearances(engine, mesh.topology(), x, {}, {}, views, true);
    CHECK((x - before).cwiseAbs().maxCoeff() == 0.0);
    const auto& slaves = engine.domain().slaves();
    for (const contact::ClearedNode& c : report.nodes) {
      CHECK(c.interference == Approx(0.05));
      CHECK(c.offset == Approx(-0.03).margin(1e-12));
      const contact::ContactConstraint& k = engine.constraints()[slaves.slot(c.node)];
      CHECK(k.offset == Approx(0.02).margin(1e-12));  // no force at t = 0
    }
  }
}

TEST_CASE("point nodes of a node-based surface: the zone of their nearest master face",
          "[contact][clearance][node]") {
  // A 2×2×1 block (h = 1, top faces S2 of size 1) and two free nodes under its top: 0.09 below
  // (inside the default zone, a tenth of the master face's size) and 0.11 below (outside).
  test::ContactMesh mesh;
  test::add_hex_block(mesh, 2, 2, 1, 1.0);
  const Index inside = mesh.add_node(0.5, 0.5, 0.91), outside = mesh.add_node(1.5, 0.5, 0.89);
  DomainSpec spec;
  spec.surfaces.push_back({"BLOCK", false, faces(0, 4, 1)});
  contact::DomainSurface points;
  points.name = "PTS";
  points.nodes = {inside, outside};
  spec.surfaces.push_back(std::move(points));
  spec.inclusions.push_back({1, 0, true});
  for (const bool adjust : {true, false}) {
    NodalVectors x = mesh.coordinates;
    ContactEngine engine(ContactDomain(spec, mesh.topology(), x), {}, {}, x, {});
    REQUIRE(engine.domain().slave_point(engine.domain().slaves().slot(inside)));
    ClearanceView v = view({}, faces(0, 4, 1), adjust, 0.02);
    v.slave_nodes = {inside, outside};
    const std::vector<ClearanceView> views = {v};
    const ClearanceReport report =
        contact::apply_clearances(engine, mesh.topology(), x, {}, {}, views, true);
    REQUIRE(report.nodes.size() == 1);
    CHECK(report.skipped.empty());
    const contact::ClearedNode& c = report.nodes[0];
    CHECK(c.node == inside);
    CHECK(c.gap_before == Approx(-0.09).margin(1e-12));
    CHECK(x(outside, 2) == mesh.coordinates(outside, 2));  // outside the zone: left alone
    if (adjust) {
      CHECK(c.distance == Approx(0.11).margin(1e-12));
      CHECK(x(inside, 2) == Approx(1.02).margin(1e-12));
      CHECK(c.offset == 0.0);
    } else {
      CHECK(c.distance == 0.0);
      CHECK(x(inside, 2) == mesh.coordinates(inside, 2));
      CHECK(c.offset == Approx(0.11).margin(1e-12));
      CHECK(engine.constraints()[engine.domain().slaves().slot(inside)].offset_permanent);
    }
  }
}
