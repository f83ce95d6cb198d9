#include <catch2/catch.hpp>

#include <omp.h>

#include <cmath>
#include <limits>
#include <vector>

#include "contact/contact_domain.hpp"
#include "contact/contact_engine.hpp"
#include "contact_fixtures.hpp"

using namespace xpl;
using contact::ContactDomain;
using contact::DomainSpec;
using contact::Vec3;

namespace {

/// Block A (2×2×1, h = 1) under block B (2×2×1), B's bottom at z = 1 + gap.
struct TwoBlocks {
  test::ContactMesh mesh;
  Index a_elements = 0;
  explicit TwoBlocks(Real gap) {
    test::add_hex_block(mesh, 2, 2, 1, 1.0);
    a_elements = static_cast<Index>(mesh.kinds.size());
    test::add_hex_block(mesh, 2, 2, 1, 1.0, Vec3(0.0, 0.0, 1.0 + gap));
  }
  Index top_centre_of_a() const { return 4 + 9; }  // node (1, 1, 1) of block A
};

DomainSpec all_exterior() {
  DomainSpec spec;
  spec.surfaces.push_back({"ALL_EXTERIOR", true, {}});
  spec.inclusions.push_back({0, 0, false});
  return spec;
}

/// Index of the face of `domain` whose corners are all nodes of elements >= first_element and
/// whose normal points along `direction`.
Index face_of(const ContactDomain& domain, const NodalVectors& x, Index first_element,
              const Vec3& direction) {
  for (Index f = 0; f < static_cast<Index>(domain.faces().size()); ++f) {
    const auto& face = domain.faces()[f];
    if (face.element < first_element) continue;
    if (test::face_normal(face, x).dot(direction) > 0.99) return f;
  }
  return NO_INDEX;
}

}  // namespace

TEST_CASE("the pair rule weighs balanced, one-sided, excluded and rigid pairs",
          "[contact][domain]") {
  TwoBlocks blocks(0.0);
  const auto topology = blocks.mesh.topology();
  const NodalVectors& x = blocks.mesh.coordinates;
  const Index node = blocks.top_centre_of_a();

  SECTION("ALL EXTERIOR: both views, weight 1/2 each") {
    const ContactDomain domain(all_exterior(), topology, x);
    const Index s = domain.slaves().slot(node);
    const Index bottom_of_b = face_of(domain, x, blocks.a_elements, Vec3(0, 0, -1));
    REQUIRE(bottom_of_b != NO_INDEX);
    Index pair = NO_INDEX;
    CHECK(domain.weight(s, bottom_of_b, pair) == 0.5);
    CHECK(pair == 0);
  }
  SECTION("a rigid master takes the whole force, and so do its nodes on a deformable face") {
    DomainSpec spec = all_exterior();
    spec.element_body.assign(blocks.mesh.kinds.size(), NO_INDEX);
    for (Index e = blocks.a_elements; e < static_cast<Index>(spec.element_body.size()); ++e)
      spec.element_body[e] = 0;
    const ContactDomain domain(spec, topology, x);
    const Index bottom_of_b = face_of(domain, x, blocks.a_elements, Vec3(0, 0, -1));
    const Index top_of_a = face_of(domain, x, 0, Vec3(0, 0, 1));
    Index pair = NO_INDEX;
    CHECK(domain.weight(domain.slaves().slot(node), bottom_of_b, pair) == 1.0);
    const Index b_node = 18 + 4;  // node (1, 1, 0) of block B
    CHECK(domain.slave_rigid(domain.slaves().slot(b_node)));
    CHECK(domain.weight(domain.slaves().slot(b_node), top_of_a, pair) == 1.0);
    // Rigid against rigid: none (here a face of its own body).
    CHECK(domain.weight(domain.slaves().slot(b_node), bottom_of_b, pair) == 0.0);
  }
  SECTION("a one-sided pair has one view; an exclusion removes a pair") {
    DomainSpec spec;
    spec.surfaces.push_back({"A", false, {}});
    spec.surfaces.push_back({"B", false, {}});
    for (Index e = 0; e < blocks.a_elements; ++e) spec.surfaces[0].faces.push_back({e, 1});
    for (Index e = blocks.a_elements; e < static_cast<Index>(blocks.mesh.kinds.size()); ++e)
      spec.surfaces[1].faces.push_back({e, 0});
    spec.inclusions.push_back({0, 1, true});
    const ContactDomain one_sided(spec, topology, x);
    const Index face_b = face_of(one_sided, x, blocks.a_elements, Vec3(0, 0, -1));
    const Index face_a = face_of(one_sided, x, 0, Vec3(0, 0, 1));
    Index pair = NO_INDEX;
    CHECK(one_sided.weight(one_sided.slaves().slot(node), face_b, pair) == 1.0);
    CHECK(one_sided.weight(one_sided.slaves().slot(18 + 4), face_a, pair) == 0.0);
    spec.exclusions.push_back({1, 0, false});
    const ContactDomain excluded(spec, topology, x);
    CHECK(excluded.weight(excluded.slaves().slot(node), face_b, pair) == 0.0);
  }
}

TEST_CASE(
    "penetrating blocks are pushed apart by equal and opposite forces, the same with any "
    "thread count",
    "[contact][engine]") {
  const Real depth = 1e-4;
  TwoBlocks blocks(-depth);  // B's bottom 0.1 mm below A's top
  const NodalVectors& x = blocks.mesh.coordinates;
  const Index n = blocks.mesh.node_count();
  const NodalVectors velocity = NodalVectors::Zero(n, 3);
  const std::vector<Real> mass(n, 1.0), inverse_mass(n, 1.0);
  const Real dt = 1e-3;

  auto run = [&](int threads) {
    omp_set_num_threads(threads);
    contact::ContactEngine engine(ContactDomain(all_exterior(), blocks.mesh.topology(), x), {}, {},
                                  x, {});
    NodalVectors force = NodalVectors::Zero(n, 3);
    PhaseTimers timers;
    engine.update(x, velocity, 0.0, dt, {}, mass, inverse_mass, force, timers);
    return force;
  };
  const NodalVectors one = run(1);
  const NodalVectors two = run(2);
  CHECK((one - two).cwiseAbs().maxCoeff() == 0.0);

  // force_internal holds minus the contact force: block A's top nodes are pushed down (−z),
  // B's bottom up, the sum is zero, and each interface node carries its own spring k·d with
  // k = 0.5 m/Δt² (two views of 1/2 each on a node and its mirror).
  const Real k = contact::DEFAULT_PENALTY_FACTOR * 0.5 / (dt * dt);  // m_eff = 1/2
  const Index a_top = blocks.top_centre_of_a();
  const Index b_bottom = 18 + 4;
  CHECK(-one(a_top, 2) == Approx(-k * depth).epsilon(1e-6));
  CHECK(-one(b_bottom, 2) == Approx(k * depth).epsilon(1e-6));
  CHECK(std::abs(one.col(2).sum()) < 1e-9 * k * depth);
  CHECK(one.col(0).cwiseAbs().maxCoeff() < 1e-9 * k * depth);
  omp_set_num_threads(2);
}

TEST_CASE(
    "a node beside a face's edge and behind its plane touches it only when nearer to it "
    "than to clearing it sideways",
    "[contact][engine]") {
  // Shell strip folded along x = 0: element A (x in [−w, 0], flat, normal +z) and element B
  // (from x = 0, turned up by 20°), t = 0.2. Node 0 of A, at (−w, 0, 0), is behind the plane of
  // B's SPOS surface (t/2 above B) by 0.03, but 0.19 beside B's edge: it must not touch B.
  // A plate P (x, y in [0, 1], z = 0.6) and a flat shell C (x in [−2, −0.02], z = 0.55): C's
  // node Q = (−0.02, 0.5, 0.55) is behind P's SNEG surface (z = 0.5) by 0.05 and only 0.02
  // beside P's edge: Q touches P.
  const Real w = 0.2, t = 0.2, angle = 20.0 * std::acos(-1.0) / 180.0;
  test::ContactMesh mesh;
  const Real c = std::cos(angle), s = std::sin(angle);
  const Index a0 = mesh.add_node(-w, 0, 0), a1 = mesh.add_node(0, 0, 0),
              a2 = mesh.add_node(0, 1, 0), a3 = mesh.add_node(-w, 1, 0);
  const Index b1 = mesh.add_node(c, 0, s), b2 = mesh.add_node(c, 1, s);
  mesh.add_element(contact::ElementKind::Shell, {a0, a1, a2, a3});
  mesh.add_element(contact::ElementKind::Shell, {a1, b1, b2, a2});
  const Index p0 = mesh.add_node(0, 0, 0.6), p1 = mesh.add_node(1, 0, 0.6),
              p2 = mesh.add_node(1, 1, 0.6), p3 = mesh.add_node(0, 1, 0.6);
  mesh.add_element(contact::ElementKind::Shell, {p0, p1, p2, p3});  // element 2: the plate P
  const Index q = mesh.add_node(-0.02, 0.5, 0.55), q1 = mesh.add_node(-2, 0.5, 0.55),
              q2 = mesh.add_node(-2, 1.5, 0.55), q3 = mesh.add_node(-0.02, 1.5, 0.55);
  mesh.add_element(contact::ElementKind::Shell, {q, q3, q2, q1});
  const NodalVectors& x = mesh.coordinates;
  const std::vector<Real> thickness(static_cast<std::size_t>(mesh.node_count()), t);
  contact::ContactOptions options;
  options.margin = 0.35;
  contact::ContactEngine engine(ContactDomain(all_exterior(), mesh.topology(), x), {}, options, x,
                                thickness);
  engine.probe(x, thickness);
  const ContactDomain& domain = engine.domain();

  // The old rule (gap along B's normal) took node 0 as 0.13 deep in B.
  const contact::SlaveTouch& folded = engine.touch(domain.slaves().slot(a0));
  CHECK((folded.face == NO_INDEX || domain.faces()[folded.face].element != 1));
  // Q is inside P's slab by 0.05 (plus its own half thickness 0.1): gap −0.15.
  const contact::SlaveTouch& corner = engine.touch(domain.slaves().slot(q));
  REQUIRE(corner.face != NO_INDEX);
  CHECK(domain.faces()[corner.face].element == 2);
  CHECK(corner.gap == Approx(-0.15).margin(1e-12));
}

TEST_CASE(
    "a shell node does not touch the shell faces next to its own elements, even where an "
    "element is narrower than the thickness",
    "[contact][engine]") {
  // Flat strip of three S4R, 0.125 wide along x, 1 across, t = 0.25. Node 1 (x = 0.125) lies
  // in the plane of element 2 (x in [0.25, 0.375]), 0.125 beside its edge: less than its
  // penetration t (its half thickness and the face's), so the lateral rule alone took it as
  // touching element 2 a thickness deep; element 2 continues the node's own shell.
  const Real w = 0.125, t = 0.25;
  test::ContactMesh mesh;
  std::vector<Index> low, high;
  for (int i = 0; i <= 3; ++i) {
    low.push_back(mesh.add_node(w * i, 0, 0));
    high.push_back(mesh.add_node(w * i, 1, 0));
  }
  for (int i = 0; i < 3; ++i)
    mesh.add_element(contact::ElementKind::Shell, {low[i], low[i + 1], high[i + 1], high[i]});
  const NodalVectors& x = mesh.coordinates;
  const std::vector<Real> thickness(static_cast<std::size_t>(mesh.node_count()), t);
  contact::ContactOptions options;
  options.margin = 0.5;
  contact::ContactEngine engine(ContactDomain(all_exterior(), mesh.topology(), x), {}, options, x,
                                thickness);
  engine.probe(x, thickness);
  const ContactDomain& domain = engine.domain();
  for (Index node : {low[1], high[1], low[2], high[2]})
    CHECK(engine.touch(domain.slaves().slot(node)).face == NO_INDEX);
}

TEST_CASE(
    "a shell node met side-on by a shell face's round edge starts without force; one that "
    "approaches the edge is pushed from the first touch; one met in the first update is pushed "
    "as the lateral rule finds it",
    "[contact][engine][onset]") {
  // Face F: a shell in z = 0 (x, y in [0, 1]), t = 0.2, its SNEG surface at z = −0.1. Strip S
  // (y in [0.4, 0.6] + dy, z = −0.05) beside F's edge x = 1 by L: its nodes q0, q3 are 0.05
  // behind F's SNEG plane. Beside a shell's edge a shell node touches the wall's round edge:
  // gap = distance to the mid-surface edge − t/2 − own t/2, normal from the edge to the node.
  // At L = 0.1 that is sqrt(0.1² + 0.05²) − 0.2 = −0.0882 (the lateral rule of a solid node
  // and of an engine's first update: −0.15 along F's normal, the crash tube's 2715 J at 5.4 ms
  // were four such nodes beside the corner edge of a folding wall).
  const Real t = 0.2, dt = 1e-3;
  auto build = [&](Real lateral, Real dy) {
    test::ContactMesh mesh;
    const Index f0 = mesh.add_node(0, 0, 0), f1 = mesh.add_node(1, 0, 0),
                f2 = mesh.add_node(1, 1, 0), f3 = mesh.add_node(0, 1, 0);
    mesh.add_element(contact::ElementKind::Shell, {f0, f1, f2, f3});
    const Real x0 = 1.0 + lateral, z = -0.05;
    const Index q0 = mesh.add_node(x0, 0.4 + dy, z), q1 = mesh.add_node(x0 + 1, 0.4 + dy, z),
                q2 = mesh.add_node(x0 + 1, 0.6 + dy, z), q3 = mesh.add_node(x0, 0.6 + dy, z);
    mesh.add_element(contact::ElementKind::Shell, {q0, q1, q2, q3});
    return mesh;
  };
  const test::ContactMesh start = build(0.2, 0.0);
  const Index n = start.node_count();
  const std::vector<Real> thickness(static_cast<std::size_t>(n), t), mass(n, 1.0),
      inverse_mass(n, 1.0);
  contact::ContactOptions options;
  options.margin = 0.5;
  const Index q0 = 4;
  auto moved = [&](const NodalVectors& from, const Vec3& step) {
    NodalVectors x = from;
    for (Index i = 4; i < n; ++i)
      for (int d = 0; d < 3; ++d) x(i, d) += step[d];
    return x;
  };
  auto velocity = [&](const Vec3& step) {
    NodalVectors v = NodalVectors::Zero(n, 3);
    for (Index i = 4; i < n; ++i)
      for (int d = 0; d < 3; ++d) v(i, d) = step[d] / dt;
    return v;
  };
  const Real k = contact::default_penalty_stiffness(1.0, 1.0, dt);
  const Real round_gap = std::hypot(0.1, 0.05) - t;  // −0.0882
  PhaseTimers timers;

  SECTION("met side-on, moving along the edge: no force, no stored energy; sinking is resisted") {
    // S slides along y (along F's edge) from beyond F's corner, where it is clear of F, to
    // beside the edge in one increment: the approach along the edge's normal is zero, so all
    // of the depth was there before the face turned admissible.
    const test::ContactMesh beyond = build(0.1, 0.9);
    contact::ContactEngine engine(
        ContactDomain(all_exterior(), beyond.topology(), beyond.coordinates), {}, options,
        beyond.coordinates, thickness);
    NodalVectors force = NodalVectors::Zero(n, 3);
    engine.update(beyond.coordinates, NodalVectors::Zero(n, 3), 0.0, dt, thickness, mass,
                  inverse_mass, force, timers);
    const Index s = engine.domain().slaves().slot(q0);
    REQUIRE(engine.touch(s).face == NO_INDEX);
    const Vec3 slide(0, -0.9, 0);
    const NodalVectors x1 = moved(beyond.coordinates, slide);
    const contact::ContactTotals in =
        engine.update(x1, velocity(slide), dt, dt, thickness, mass, inverse_mass, force, timers);
    const contact::SlaveTouch& touch = engine.touch(s);
    REQUIRE(touch.face != NO_INDEX);
    CHECK(engine.domain().faces()[touch.face].element == 0);
    // The half of the round on F's SNEG side belongs to the SNEG face: SPOS would take the node
    // round the edge to its interior a thickness deep.
    CHECK(test::face_normal(engine.domain().faces()[touch.face], x1).dot(Vec3(0, 0, -1)) > 0.99);
    CHECK(touch.gap == Approx(round_gap).margin(1e-12));
    CHECK(touch.normal.dot(Vec3(0.1, 0, -0.05).normalized()) == Approx(1.0).epsilon(1e-12));
    CHECK(engine.normal_force(s) == 0.0);
    CHECK(engine.constraints()[s].offset == Approx(-round_gap).margin(1e-12));
    CHECK(in.stored_energy == 0.0);
    // 0.01 closer to the edge along x: the depth beyond the offset acts.
    const Vec3 sink(-0.01, 0, 0);
    const NodalVectors x2 = moved(x1, sink);
    engine.update(x2, velocity(sink), dt, dt, thickness, mass, inverse_mass, force, timers);
    CHECK(engine.touch(s).face == touch.face);
    const Real deeper = t - std::hypot(0.09, 0.05) + round_gap;
    CHECK(engine.normal_force(s) == Approx(touch.weight * k * deeper).epsilon(1e-9));
  }
  SECTION(
      "approaching the edge: pushed from the first touch, with the energy the approach put in") {
    // S moves from L = 0.2 (clear: sqrt(0.2² + 0.05²) > 0.2) to L = 0.1 in one increment,
    // along x: 0.0894 of that is approach along the edge's normal, more than the 0.0882 depth.
    contact::ContactEngine engine(
        ContactDomain(all_exterior(), start.topology(), start.coordinates), {}, options,
        start.coordinates, thickness);
    NodalVectors force = NodalVectors::Zero(n, 3);
    engine.update(start.coordinates, NodalVectors::Zero(n, 3), 0.0, dt, thickness, mass,
                  inverse_mass, force, timers);
    const Index s = engine.domain().slaves().slot(q0);
    REQUIRE(engine.normal_force(s) == 0.0);
    const Vec3 slide(-0.1, 0, 0);
    const NodalVectors x1 = moved(start.coordinates, slide);
    const contact::ContactTotals in =
        engine.update(x1, velocity(slide), dt, dt, thickness, mass, inverse_mass, force, timers);
    const contact::SlaveTouch& touch = engine.touch(s);
    REQUIRE(touch.face != NO_INDEX);
    CHECK(engine.domain().faces()[touch.face].element == 0);
    CHECK(touch.gap == Approx(round_gap).margin(1e-12));
    CHECK(engine.constraints()[s].offset == 0.0);
    CHECK(engine.normal_force(s) == Approx(touch.weight * k * -round_gap).epsilon(1e-9));
    // The springs hold no more than the work the contact forces took from the motion
    // (trapezoidal, as ALLPW books it): nothing created.
    CHECK(in.stored_energy > 0.0);
    CHECK(-in.work >= in.stored_energy);
    CHECK(-in.work == Approx(in.stored_energy).epsilon(0.02));
  }
  SECTION("the first update of an engine takes the touch as it is (C4)") {
    const test::ContactMesh near = build(0.1, 0.0);
    contact::ContactEngine engine(ContactDomain(all_exterior(), near.topology(), near.coordinates),
                                  {}, options, near.coordinates, thickness);
    NodalVectors force = NodalVectors::Zero(n, 3);
    engine.update(near.coordinates, NodalVectors::Zero(n, 3), 0.0, dt, thickness, mass,
                  inverse_mass, force, timers);
    const Index s = engine.domain().slaves().slot(q0);
    REQUIRE(engine.touch(s).face != NO_INDEX);
    CHECK(engine.normal_force(s) == Approx(engine.touch(s).weight * k * 0.15).epsilon(1e-9));
  }
}

TEST_CASE(
    "a shell node pressed into the corner of a plate and a wall's round edge holds a spring on "
    "each",
    "[contact][engine][onset]") {
  // Plate: a 2×1×1 hex block, top at z = 0. Wall W: a shell lying flat over it (x, y in
  // [0, 1], mid-surface z = 0.12, t = 0.2). Strip S (t = 0.2) comes in one increment from
  // (1.3, 0.2) to its node q0 at x = 1.15, z = 0.09: 0.01 into the plate (own half thickness)
  // and 0.047 into W's round edge side-on (normals 101° apart: not opposite, no pinch), both
  // depths within the increment's approach. With one spring the other depth would grow
  // unresisted and turn into offset at the next flip of the nearest face.
  const Real t = 0.2, dt = 1e-3, zw = 0.12;
  test::ContactMesh mesh;
  test::add_hex_block(mesh, 2, 1, 1, 1.0, Vec3(0, 0, -1));
  const Index first_wall = static_cast<Index>(mesh.kinds.size());
  const Index w0 = mesh.add_node(0, 0, zw), w1 = mesh.add_node(1, 0, zw),
              w2 = mesh.add_node(1, 1, zw), w3 = mesh.add_node(0, 1, zw);
  mesh.add_element(contact::ElementKind::Shell, {w0, w1, w2, w3});
  const Index first_strip = mesh.node_count();
  const Index q0 = mesh.add_node(1.3, 0.4, 0.2), q1 = mesh.add_node(2.3, 0.4, 0.2),
              q2 = mesh.add_node(2.3, 0.6, 0.2), q3 = mesh.add_node(1.3, 0.6, 0.2);
  mesh.add_element(contact::ElementKind::Shell, {q0, q1, q2, q3});
  const Index n = mesh.node_count();
  const std::vector<Real> thickness(static_cast<std::size_t>(n), t), mass(n, 1.0),
      inverse_mass(n, 1.0);
  contact::ContactOptions options;
  options.margin = 0.5;
  PhaseTimers timers;
  contact::ContactEngine engine(ContactDomain(all_exterior(), mesh.topology(), mesh.coordinates),
                                {}, options, mesh.coordinates, thickness);
  NodalVectors force = NodalVectors::Zero(n, 3);
  engine.update(mesh.coordinates, NodalVectors::Zero(n, 3), 0.0, dt, thickness, mass, inverse_mass,
                force, timers);
  const Index s = engine.domain().slaves().slot(q0);
  REQUIRE(engine.normal_force(s) == 0.0);
  const Vec3 step(-0.15, 0, -0.11);
  NodalVectors x1 = mesh.coordinates;
  NodalVectors v1 = NodalVectors::Zero(n, 3);
  for (Index i = first_strip; i < n; ++i)
    for (int d = 0; d < 3; ++d) {
      x1(i, d) += step[d];
      v1(i, d) = step[d] / dt;
    }
  engine.update(x1, v1, dt, dt, thickness, mass, inverse_mass, force, timers);
  const contact::SlaveTouch& first = engine.touch(s);
  const contact::SlaveTouch& second = engine.second_touch(s);
  REQUIRE(first.face != NO_INDEX);
  REQUIRE(second.face != NO_INDEX);
  const auto on_wall = [&](const contact::SlaveTouch& touch) {
    return engine.domain().faces()[touch.face].element == first_wall;
  };
  CHECK(on_wall(first) != on_wall(second));
  const contact::SlaveTouch& wall = on_wall(first) ? first : second;
  const contact::SlaveTouch& plate = on_wall(first) ? second : first;
  CHECK(wall.gap == Approx(std::hypot(0.15, zw - 0.09) - t).margin(1e-12));
  CHECK(plate.gap == Approx(-0.01).margin(1e-12));
  CHECK(plate.normal.dot(Vec3(0, 0, 1)) == Approx(1.0).epsilon(1e-12));
  CHECK(engine.constraints()[s].offset == 0.0);
  CHECK(engine.normal_force(s) > 0.0);
  CHECK(engine.second_normal_force(s) > 0.0);
}

TEST_CASE("a node never touches a face of its own hex, however squashed the hex is",
          "[contact][engine]") {
  // One hex squashed to a fifth of its height: its top nodes lie 0.2 above its bottom face,
  // within the depth limit of that face (half the height as read, 0.5), with normals (+z at
  // the top face's corners, leaning outward) against the bottom face's −z. They are corners
  // of the element whose bottom face that is: no contact (a Taylor bar's mushrooming rim made
  // 10 J springs per node of this). A separate block 0.1 below still touches as before.
  test::ContactMesh mesh;
  test::add_hex_block(mesh, 1, 1, 1, 1.0);
  test::add_hex_block(mesh, 1, 1, 1, 1.0, Vec3(0.0, 0.0, -1.05));
  const NodalVectors reference = mesh.coordinates;
  NodalVectors x = reference;
  for (Index i = 4; i < 8; ++i) x(i, 2) = 0.2;     // block 1's top nodes
  for (Index i = 12; i < 16; ++i) x(i, 2) = 0.05;  // block 2's top nodes, 0.05 into block 1
  contact::ContactOptions options;
  options.margin = 0.5;
  contact::ContactEngine engine(ContactDomain(all_exterior(), mesh.topology(), reference), {},
                                options, reference, {});
  engine.probe(x, {});
  const ContactDomain& domain = engine.domain();
  for (Index node = 4; node < 8; ++node) {
    const contact::SlaveTouch& touch = engine.touch(domain.slaves().slot(node));
    CHECK((touch.face == NO_INDEX || domain.faces()[touch.face].element != 0));
  }
  for (Index node = 12; node < 16; ++node) {
    const contact::SlaveTouch& touch = engine.touch(domain.slaves().slot(node));
    REQUIRE(touch.face != NO_INDEX);
    CHECK(domain.faces()[touch.face].element == 0);
    CHECK(touch.gap == Approx(-0.05).margin(1e-12));
  }
}

namespace {

/// An S4R sheet (t = 0.2, in z = 0) between two unit hexes: the lower one's top 0.1 − `low`
/// below the sheet's mid-plane, so that it penetrates the sheet's lower side by `low`, the
/// upper one's bottom likewise by `high`. The sheet is the slave surface of a one-sided pair,
/// the blocks its master; block nodes are heavy (1e6) and sheet nodes weigh 1.
struct Sandwich {
  test::ContactMesh mesh;
  std::vector<Real> thickness, mass, inverse_mass;
  DomainSpec spec;
  Sandwich(Real low, Real high) {
    const Real t = 0.2;
    const Index s0 = mesh.add_node(0.2, 0.2, 0), s1 = mesh.add_node(0.8, 0.2, 0),
                s2 = mesh.add_node(0.8, 0.8, 0), s3 = mesh.add_node(0.2, 0.8, 0);
    mesh.add_element(contact::ElementKind::Shell, {s0, s1, s2, s3});
    test::add_hex_block(mesh, 1, 1, 1, 1.0, Vec3(0, 0, -0.5 * t + low - 1.0));
    test::add_hex_block(mesh, 1, 1, 1, 1.0, Vec3(0, 0, 0.5 * t - high));
    const Index n = mesh.node_count();
    thickness.assign(n, 0.0);
    for (Index i = 0; i < 4; ++i) thickness[i] = t;
    mass.assign(n, 1e6);
    for (Index i = 0; i < 4; ++i) mass[i] = 1.0;
    for (Index i = 0; i < n; ++i) inverse_mass.push_back(1.0 / mass[i]);
    spec.surfaces.push_back({"SHEET", false, {{0, contact::SHELL_SNEG}, {0, contact::SHELL_SPOS}}});
    spec.surfaces.push_back({"DIES", false, {{1, 1}, {2, 0}}});  // lower top S2, upper bottom S1
    spec.inclusions.push_back({0, 1, true});
  }
};

}  // namespace

TEST_CASE("a node pinched between two faces is pushed by both, each spring from its own side",
          "[contact][engine][pinch]") {
  // The sheet's corner nodes penetrate the lower block by 0.03 and the upper one by 0.02.
  // With one spring the node would feel the nearer (lower) face alone, and flip to the upper
  // one as soon as it had been pushed past the middle: now both act, each from its side.
  const Real dt = 1e-3;
  Sandwich sandwich(0.03, 0.02);
  const NodalVectors& x = sandwich.mesh.coordinates;
  contact::ContactOptions options;
  options.margin = 0.5;
  contact::ContactEngine engine(ContactDomain(sandwich.spec, sandwich.mesh.topology(), x), {},
                                options, x, sandwich.thickness);
  NodalVectors force = NodalVectors::Zero(sandwich.mesh.node_count(), 3);
  PhaseTimers timers;
  engine.update(x, NodalVectors::Zero(sandwich.mesh.node_count(), 3), 0.0, dt, sandwich.thickness,
                sandwich.mass, sandwich.inverse_mass, force, timers);
  const Real k = contact::default_penalty_stiffness(1.0, 1e6, dt);
  for (Index node = 0; node < 4; ++node) {
    const Index s = engine.domain().slaves().slot(node);
    const contact::SlaveTouch& first = engine.touch(s);
    const contact::SlaveTouch& second = engine.second_touch(s);
    REQUIRE(first.face != NO_INDEX);
    REQUIRE(second.face != NO_INDEX);
    CHECK(first.gap == Approx(-0.03).margin(1e-12));
    CHECK(second.gap == Approx(-0.02).margin(1e-12));
    CHECK(first.normal.dot(second.normal) == Approx(-1.0).margin(1e-12));
    // Two springs, each 2k in the row-sum bound (heavy but moving corners): 4k/m·Δt² = 2 is
    // over the node budget of 1, so each spring carries half its default stiffness.
    const Real share = contact::DEFAULT_PENALTY_NODE_BUDGET / (4.0 * k * dt * dt);
    CHECK(engine.normal_force(s) == Approx(share * k * 0.03).epsilon(1e-9));
    CHECK(engine.second_normal_force(s) == Approx(share * k * 0.02).epsilon(1e-9));
    CHECK(force(node, 2) == Approx(-share * k * 0.01).epsilon(1e-9));  // net push up
  }
}

TEST_CASE("a node pressed on one side only keeps its full default spring",
          "[contact][engine][pinch]") {
  // Only the upper block penetrates (0.02); the lower one is 0.05 away: one spring, its row
  // sum 2k/m·Δt² = 1 within the node budget, so it is not scaled.
  const Real dt = 1e-3;
  Sandwich sandwich(-0.05, 0.02);
  const NodalVectors& x = sandwich.mesh.coordinates;
  contact::ContactOptions options;
  options.margin = 0.5;
  contact::ContactEngine engine(ContactDomain(sandwich.spec, sandwich.mesh.topology(), x), {},
                                options, x, sandwich.thickness);
  NodalVectors force = NodalVectors::Zero(sandwich.mesh.node_count(), 3);
  PhaseTimers timers;
  engine.update(x, NodalVectors::Zero(sandwich.mesh.node_count(), 3), 0.0, dt, sandwich.thickness,
                sandwich.mass, sandwich.inverse_mass, force, timers);
  const Real k = contact::default_penalty_stiffness(1.0, 1e6, dt);
  for (Index node = 0; node < 4; ++node) {
    const Index s = engine.domain().slaves().slot(node);
    CHECK(engine.second_touch(s).face == NO_INDEX);
    CHECK(engine.normal_force(s) == Approx(k * 0.02).epsilon(1e-9));
  }
}

TEST_CASE(
    "a solid face that turns admissible for a node already behind its plane starts without "
    "force",
    "[contact][engine][onset]") {
  // Block A: 2×2×1 unit hexes, top at z = 1. Block B: a unit cube with its corner q held at
  // (1, 1, 0.9), 0.1 below A's top, and first turned about q so that q's normal (the mean of
  // its three faces, (−1, −1, −1)/√3 in B's own frame) is horizontal: A's top face does not
  // look at q (cosine 0). In one increment B turns back about q, so q's normal leans down
  // (cosine −0.58) and A's top face becomes admissible 0.1 deep, with no approach at all (q
  // does not move). The mushrooming rim of a Taylor bar turns its nodes' normals like this.
  // Offset, no force, no energy; sinking 0.01 further is resisted.
  const Real dt = 1e-3;
  test::ContactMesh reference;
  test::add_hex_block(reference, 2, 2, 1, 1.0);
  const Index first_b = reference.node_count();
  test::add_hex_block(reference, 1, 1, 1, 1.0, Vec3(1.0, 1.0, 0.9));
  const Index n = reference.node_count();
  const Index q = first_b;  // B's node (0, 0, 0)
  const Vec3 pivot(1.0, 1.0, 0.9);
  const Vec3 corner_normal = Vec3(-1, -1, -1).normalized();
  const Eigen::Matrix3d turn =
      Eigen::Quaterniond::FromTwoVectors(corner_normal, Vec3(-1, -1, 0).normalized())
          .toRotationMatrix();
  NodalVectors x0 = reference.coordinates;
  for (Index i = first_b; i < n; ++i) {
    const Vec3 r = turn * (contact::node_point(reference.coordinates, i) - pivot) + pivot;
    for (int d = 0; d < 3; ++d) x0(i, d) = r[d];
  }
  const std::vector<Real> mass(n, 1.0), inverse_mass(n, 1.0);
  contact::ContactOptions options;
  options.margin = 0.5;
  const Real k = contact::default_penalty_stiffness(1.0, 1.0, dt);
  PhaseTimers timers;
  contact::ContactEngine engine(
      ContactDomain(all_exterior(), reference.topology(), reference.coordinates), {}, options, x0,
      {});
  NodalVectors force = NodalVectors::Zero(n, 3);
  engine.update(x0, NodalVectors::Zero(n, 3), 0.0, dt, {}, mass, inverse_mass, force, timers);
  const Index s = engine.domain().slaves().slot(q);
  REQUIRE(engine.touch(s).face == NO_INDEX);
  const NodalVectors& x1 = reference.coordinates;
  const NodalVectors v1 = (x1 - x0) / dt;
  const contact::ContactTotals in =
      engine.update(x1, v1, dt, dt, {}, mass, inverse_mass, force, timers);
  const contact::SlaveTouch& touch = engine.touch(s);
  REQUIRE(touch.face != NO_INDEX);
  CHECK(engine.domain().faces()[touch.face].element < first_b);
  CHECK(touch.gap == Approx(-0.1).margin(1e-12));
  CHECK(engine.normal_force(s) == 0.0);
  CHECK(engine.constraints()[s].offset == Approx(0.1).margin(1e-12));
  CHECK(in.stored_energy >= 0.0);
  NodalVectors x2 = x1;
  for (Index i = first_b; i < n; ++i) x2(i, 2) -= 0.01;
  NodalVectors v2 = NodalVectors::Zero(n, 3);
  for (Index i = first_b; i < n; ++i) v2(i, 2) = -0.01 / dt;
  engine.update(x2, v2, dt, dt, {}, mass, inverse_mass, force, timers);
  CHECK(engine.touch(s).face == touch.face);
  CHECK(engine.normal_force(s) == Approx(touch.weight * k * 0.01).epsilon(1e-9));
}

TEST_CASE("a rigid body's nodes touch a deformable face its corners would otherwise pass",
          "[contact][engine][rigid]") {
  // A deformable unit hex and a rigid 2×2×1 block of 0.25 elements whose bottom nodes (3×3)
  // dip 0.01 into the hex's top face, away from the hex's corners: no node of the hex is near
  // a rigid face, so only the rigid nodes' view sees the contact; its weight is 1.
  const Real dt = 1e-3;
  test::ContactMesh mesh;
  test::add_hex_block(mesh, 1, 1, 1, 1.0);
  const Index first_rigid = mesh.node_count();
  test::add_hex_block(mesh, 2, 2, 1, 0.25, Vec3(0.25, 0.25, 0.99));
  const Index n = mesh.node_count();
  const Index centre = first_rigid + 4;  // node (1, 1, 0) of the rigid block
  DomainSpec spec = all_exterior();
  spec.element_body.assign(mesh.kinds.size(), NO_INDEX);
  for (std::size_t e = 1; e < mesh.kinds.size(); ++e) spec.element_body[e] = 0;
  std::vector<Real> mass(n, 1.0), inverse_mass(n, 1.0);
  for (Index i = first_rigid; i < n; ++i) inverse_mass[i] = 0.0;
  contact::ContactOptions options;
  options.margin = 0.3;
  const NodalVectors& x = mesh.coordinates;
  contact::ContactEngine engine(ContactDomain(spec, mesh.topology(), x), {}, options, x, {});
  NodalVectors force = NodalVectors::Zero(n, 3);
  PhaseTimers timers;
  engine.update(x, NodalVectors::Zero(n, 3), 0.0, dt, {}, mass, inverse_mass, force, timers);
  const Index s = engine.domain().slaves().slot(centre);
  REQUIRE(engine.domain().slave_rigid(s));
  const contact::SlaveTouch& touch = engine.touch(s);
  REQUIRE(touch.face != NO_INDEX);
  CHECK(engine.domain().faces()[touch.face].element == 0);
  CHECK(touch.weight == 1.0);
  CHECK(touch.gap == Approx(-0.01).margin(1e-12));
  // Every bottom node of the rigid block presses with at most one default spring (the nine
  // springs on the hex's top corners share their budget, so they may be scaled down).
  const Real k = contact::default_penalty_stiffness(1.0, 1.0, dt);
  Real pressed = 0.0;
  int touching = 0;
  for (Index i = first_rigid; i < first_rigid + 9; ++i) {
    const Index slot = engine.domain().slaves().slot(i);
    if (engine.touch(slot).face == NO_INDEX) continue;
    ++touching;
    CHECK(engine.touch(slot).gap == Approx(-0.01).margin(1e-12));
    CHECK(engine.normal_force(slot) > 0.0);
    CHECK(engine.normal_force(slot) <= k * 0.01 * (1.0 + 1e-12));
    pressed += engine.normal_force(slot);
  }
  CHECK(touching == 9);
  // The hex's top corners are pushed down by the sum of those forces (the internal force
  // array holds minus the contact force).
  Real down = 0.0;
  for (Index i = 4; i < 8; ++i) down += force(i, 2);
  CHECK(down == Approx(pressed).epsilon(1e-9));
}

TEST_CASE(
    "contact at speed: a node deeper than the margin in one increment is caught, and "
    "kept down to the element behind the face; beyond it the release is counted",
    "[contact][engine][speed]") {
  // Block A (2×2×1, h = 1) under block B (2×2×1) shifted by (0.5, 0.5): B's bottom centre node
  // lies over the interior of a top face of A. B is moved down by 0.4 per increment, four
  // times the search margin and within half the element (a new touch's depth limit).
  const Real dt = 1e-3;
  test::ContactMesh mesh;
  test::add_hex_block(mesh, 2, 2, 1, 1.0);
  const Index first_b = mesh.node_count();
  test::add_hex_block(mesh, 2, 2, 1, 1.0, Vec3(0.5, 0.5, 1.0));
  const Index n = mesh.node_count();
  const Index node = first_b + 4;  // (1.5, 1.5, 1): over the interior of A's face (1..2)²
  contact::ContactOptions options;
  options.margin = 0.1;
  std::vector<Real> mass(n, 1.0), inverse_mass(n, 1.0);
  NodalVectors x = mesh.coordinates;
  contact::ContactEngine engine(ContactDomain(all_exterior(), mesh.topology(), x), {}, options, x,
                                {});
  NodalVectors force = NodalVectors::Zero(n, 3);
  NodalVectors v = NodalVectors::Zero(n, 3);
  PhaseTimers timers;
  engine.update(x, v, 0.0, dt, {}, mass, inverse_mass, force, timers);
  const Index s = engine.domain().slaves().slot(node);
  const auto step = [&](Real dz) {
    for (Index i = first_b; i < n; ++i) {
      x(i, 2) -= dz;
      v(i, 2) = -dz / dt;
    }
    force.setZero();
    return engine.update(x, v, dt, dt, {}, mass, inverse_mass, force, timers);
  };
  // 0.4 deep after one increment: found through the slab behind the face, force at once.
  contact::ContactTotals t = step(0.4);
  REQUIRE(engine.touch(s).face != NO_INDEX);
  CHECK(engine.domain().faces()[engine.touch(s).face].element < 4);
  CHECK(engine.touch(s).gap == Approx(-0.4).margin(1e-12));
  CHECK(engine.normal_force(s) > 0.0);
  CHECK(t.lost == 0);
  // 0.8 deep: beyond a new touch's limit, within the element behind the face it was pressed on.
  t = step(0.4);
  REQUIRE(engine.touch(s).face != NO_INDEX);
  CHECK(engine.touch(s).gap == Approx(-0.8).margin(1e-12));
  CHECK(engine.normal_force(s) > 0.0);
  CHECK(t.lost == 0);
  // 1.2 deep: through block A; released, and counted with its depth.
  t = step(0.4);
  CHECK(engine.touch(s).face == NO_INDEX);
  CHECK(t.lost >= 1);
  CHECK(t.lost_depth >= 1.2 - 1e-12);
  CHECK(t.lost_element_depth == Approx(1.0));
}

TEST_CASE(
    "a node held on a shell's side stays held however deep on that element; behind the "
    "mid-surface of the next element, with no face holding it, it has passed through; held "
    "behind the mid-surface, it is reported",
    "[contact][engine][speed]") {
  // Plate: two shells (x in [0, 1] and [1, 2], y in [0, 1], z = 0), t = 0.2, SPOS at z = 0.1.
  // Block: one hex of 0.4 whose bottom face starts on the plate's SPOS over the first element.
  const Real t = 0.2, dt = 1e-3;
  test::ContactMesh mesh;
  test::add_shell_plate(mesh, 2, 1, 1.0);
  const Index first_block = mesh.node_count();
  test::add_hex_block(mesh, 1, 1, 1, 0.4, Vec3(0.3, 0.3, 0.1));
  const Index n = mesh.node_count();
  std::vector<Real> thickness(static_cast<std::size_t>(n), t);
  for (Index i = first_block; i < n; ++i) thickness[i] = std::numeric_limits<Real>::quiet_NaN();
  const std::vector<Real> mass(n, 1.0), inverse_mass(n, 1.0);
  contact::ContactOptions options;
  options.margin = 0.1;
  NodalVectors x = mesh.coordinates;
  contact::ContactEngine engine(ContactDomain(all_exterior(), mesh.topology(), x), {}, options, x,
                                thickness);
  NodalVectors force = NodalVectors::Zero(n, 3);
  NodalVectors v = NodalVectors::Zero(n, 3);
  PhaseTimers timers;
  engine.update(x, v, 0.0, dt, thickness, mass, inverse_mass, force, timers);
  const auto step = [&](const Vec3& d) {
    for (Index i = first_block; i < n; ++i)
      for (int c = 0; c < 3; ++c) {
        x(i, c) += d[c];
        v(i, c) = d[c] / dt;
      }
    force.setZero();
    return engine.update(x, v, dt, dt, thickness, mass, inverse_mass, force, timers);
  };
  const Index corner = first_block + 1;  // bottom corner at (0.7, 0.3): moves onto element 1
  const Index s = engine.domain().slaves().slot(corner);
  // Pressed 0.05 into the SPOS of element 0, then 0.15 (0.05 behind the mid-surface): held.
  contact::ContactTotals totals = step(Vec3(0, 0, -0.05));
  REQUIRE(engine.touch(s).face != NO_INDEX);
  CHECK(engine.normal_force(s) > 0.0);
  totals = step(Vec3(0, 0, -0.1));
  REQUIRE(engine.touch(s).face != NO_INDEX);
  CHECK(engine.domain().faces()[engine.touch(s).face].element == 0);
  CHECK(engine.touch(s).gap == Approx(-0.15).margin(1e-12));
  CHECK(totals.passed == 0);
  // Still held, but behind the mid-surface: reported (contact too soft).
  CHECK(totals.behind >= 1);
  CHECK(totals.behind_depth == Approx(0.05).margin(1e-12));
  CHECK(totals.behind_element == 0);
  // Moved over element 1's interior, still 0.05 behind the mid-surface: element 1's SPOS is a
  // new touch deeper than its limit (half the thickness), its SNEG faces the wrong way, and
  // element 0 is beside it: no face holds it, and it lies behind the plate.
  totals = step(Vec3(0.6, 0, 0));
  CHECK(engine.touch(s).face == NO_INDEX);
  CHECK(totals.passed >= 1);
  CHECK(totals.passed_depth == Approx(0.05).margin(1e-12));
  CHECK(totals.passed_element == 0);
}

namespace {

/// A contact engine over `mesh` (all exterior, margin 0.1, unit masses, increment dt) whose
/// nodes from `first_moving` on move together: step(dz) moves them by dz along z in one
/// increment and returns the update's totals.
struct MovingPart {
  MovingPart(const test::ContactMesh& mesh, const std::vector<Real>& node_thickness,
             Index first_moving, Real increment)
      : x(mesh.coordinates),
        thickness(node_thickness),
        mass(static_cast<std::size_t>(mesh.node_count()), 1.0),
        engine(ContactDomain(all_exterior(), mesh.topology(), x), {}, margin(), x, thickness),
        force(NodalVectors::Zero(mesh.node_count(), 3)),
        v(NodalVectors::Zero(mesh.node_count(), 3)),
        first(first_moving),
        dt(increment) {
    engine.update(x, v, 0.0, dt, thickness, mass, mass, force, timers);
  }
  static contact::ContactOptions margin() {
    contact::ContactOptions options;
    options.margin = 0.1;
    return options;
  }
  contact::ContactTotals step(Real dz) {
    for (Index i = first; i < x.rows(); ++i) {
      x(i, 2) += dz;
      v(i, 2) = dz / dt;
    }
    force.setZero();
    return engine.update(x, v, dt, dt, thickness, mass, mass, force, timers);
  }
  /// The element of the face slot s touches.
  Index element_of(Index s) const { return engine.domain().faces()[engine.touch(s).face].element; }

  NodalVectors x;
  std::vector<Real> thickness, mass;  // unit masses: the inverse masses are the same
  contact::ContactEngine engine;
  NodalVectors force, v;
  PhaseTimers timers;
  Index first;
  Real dt;
};

}  // namespace

TEST_CASE(
    "a shell node driven deep into the shell face it is held on stays held there when the round "
    "edge of the next element is nearer: it is not handed to the plate's other side",
    "[contact][engine][speed]") {
  // Plate: two shells (x in [0, 1] and [1, 2], y in [0, 1], z = 0), t = 0.2. A vertical shell
  // (t = 0.02, in the plane y = 0.5) comes down with its bottom corner A at x = 0.85, 0.15
  // from the plate's shared edge: pressed in to just above the plate's mid-surface, A is
  // nearer to the round edge of element 1 (open there) than to element 0's face it went into.
  const Real t_plate = 0.2, t_blade = 0.02;
  test::ContactMesh mesh;
  test::add_shell_plate(mesh, 2, 1, 1.0);
  const Index a = mesh.add_node(0.85, 0.5, 0.15);
  const Index b = mesh.add_node(0.45, 0.5, 0.15);
  const Index c = mesh.add_node(0.45, 0.5, 0.55);
  const Index d = mesh.add_node(0.85, 0.5, 0.55);
  mesh.add_element(contact::ElementKind::Shell, {a, b, c, d});
  std::vector<Real> thickness(static_cast<std::size_t>(mesh.node_count()), t_plate);
  for (Index i = a; i < mesh.node_count(); ++i) thickness[i] = t_blade;
  MovingPart part(mesh, thickness, a, 1e-3);
  const contact::ContactEngine& engine = part.engine;
  const Index s = engine.domain().slaves().slot(a);
  // Pressed 0.01 into element 0's upper side (A at z = 0.1).
  contact::ContactTotals totals = part.step(-0.05);
  REQUIRE(engine.touch(s).face != NO_INDEX);
  CHECK(part.element_of(s) == 0);
  CHECK(engine.touch(s).gap < 0.0);
  const Vec3 side = engine.touch(s).normal;
  // Driven to 0.005 above the mid-surface: element 1's round edge is 0.05 from A (open), element
  // 0's face 0.095. Held on element 0's upper side, pressed in 0.105.
  totals = part.step(-0.095);
  REQUIRE(engine.touch(s).face != NO_INDEX);
  CHECK(part.element_of(s) == 0);
  CHECK(engine.touch(s).gap == Approx(-0.105).margin(1e-12));
  CHECK(engine.touch(s).normal.dot(side) > 0.99);
  CHECK(engine.normal_force(s) > 0.0);
  // On through the mid-surface, 0.005 behind it: still held on the upper side (pushed back up)
  // and reported as too soft; the plate's lower side does not take it.
  totals = part.step(-0.01);
  REQUIRE(engine.touch(s).face != NO_INDEX);
  CHECK(part.element_of(s) == 0);
  CHECK(engine.touch(s).normal.dot(side) > 0.99);
  CHECK(totals.passed == 0);
  CHECK(totals.behind >= 1);
  CHECK(totals.behind_depth == Approx(0.005).margin(1e-12));  // its mid-surface behind the plate's
}

TEST_CASE(
    "a node pressed into a solid face deeper than half the element behind it is reported as "
    "contact too soft, with that element's depth; shallower, it is not",
    "[contact][engine][speed]") {
  // Lower block: one hex of 1 (z in [0, 1]); upper block: one hex of 0.4 whose bottom face
  // starts on the lower block's top face, over its interior.
  test::ContactMesh mesh;
  test::add_hex_block(mesh, 1, 1, 1, 1.0);
  const Index first_block = mesh.node_count();
  test::add_hex_block(mesh, 1, 1, 1, 0.4, Vec3(0.3, 0.3, 1.0));
  const std::vector<Real> thickness(static_cast<std::size_t>(mesh.node_count()),
                                    std::numeric_limits<Real>::quiet_NaN());
  MovingPart part(mesh, thickness, first_block, 1e-3);
  const contact::ContactEngine& engine = part.engine;
  const Index s = engine.domain().slaves().slot(first_block);  // bottom corner at (0.3, 0.3, 1)
  // 0.3 into the lower block's top face (its hex is 1 deep): held, not reported.
  contact::ContactTotals totals = part.step(-0.3);
  REQUIRE(engine.touch(s).face != NO_INDEX);
  CHECK(engine.touch(s).gap == Approx(-0.3).margin(1e-12));
  CHECK(totals.behind == 0);
  // 0.6 in: still held by the face it was pressed on, past half the element: reported.
  totals = part.step(-0.3);
  REQUIRE(engine.touch(s).face != NO_INDEX);
  CHECK(engine.touch(s).gap == Approx(-0.6).margin(1e-12));
  CHECK(totals.lost == 0);
  CHECK(totals.behind == 4);  // the upper block's four bottom corners
  CHECK(totals.behind_depth == Approx(0.6).margin(1e-12));
  CHECK(totals.behind_element == 0);
  CHECK(totals.behind_element_depth == Approx(1.0).margin(1e-12));
}

TEST_CASE("the springs that push a free rigid body are bounded with the body's mass",
          "[contact][engine][rigid]") {
  // The scene above: a rigid 2×2×1 block whose nine bottom nodes dip 0.01 into a deformable
  // unit hex. Held (infinite mass in every translation) the springs are as without bodies;
  // free and light (1e-3 kg against the hex's 1 kg corners) their sum along z is the body
  // budget times the body's mass over Δt² (a bounce of ≥ 6 increments; below the node budget).
  const Real dt = 1e-3;
  test::ContactMesh mesh;
  test::add_hex_block(mesh, 1, 1, 1, 1.0);
  const Index first_rigid = mesh.node_count();
  test::add_hex_block(mesh, 2, 2, 1, 0.25, Vec3(0.25, 0.25, 0.99));
  const Index n = mesh.node_count();
  DomainSpec spec = all_exterior();
  spec.element_body.assign(mesh.kinds.size(), NO_INDEX);
  for (std::size_t e = 1; e < mesh.kinds.size(); ++e) spec.element_body[e] = 0;
  std::vector<Real> mass(n, 1.0), inverse_mass(n, 1.0);
  for (Index i = first_rigid; i < n; ++i) inverse_mass[i] = 0.0;
  std::vector<Index> node_body(n, NO_INDEX);
  for (Index i = first_rigid; i < n; ++i) node_body[i] = 0;
  const NodalVectors& x = mesh.coordinates;
  const auto pressing = [&](Real body_mass) {
    contact::ContactOptions options;
    options.margin = 0.3;
    contact::ContactEngine engine(ContactDomain(spec, mesh.topology(), x), {}, options, x, {});
    engine.set_rigid_bodies(node_body, {{body_mass, body_mass, body_mass}});
    NodalVectors force = NodalVectors::Zero(n, 3);
    PhaseTimers timers;
    engine.update(x, NodalVectors::Zero(n, 3), 0.0, dt, {}, mass, inverse_mass, force, timers);
    Real sum = 0.0;
    for (Index i = first_rigid; i < first_rigid + 9; ++i)
      sum += engine.normal_force(engine.domain().slaves().slot(i));
    return sum;
  };
  const Real held = pressing(std::numeric_limits<Real>::infinity());
  const Real light = 1e-3;
  const Real free = pressing(light);
  CHECK(held > 0.0);
  CHECK(free > 0.0);
  CHECK(free < 0.5 * held);
  // Σ k = body budget·M/Δt² with every spring 0.01 deep along z.
  CHECK(contact::DEFAULT_PENALTY_BODY_BUDGET < contact::DEFAULT_PENALTY_NODE_BUDGET);
  CHECK(free ==
        Approx(contact::DEFAULT_PENALTY_BODY_BUDGET * light / (dt * dt) * 0.01).epsilon(1e-9));
}
