#include <catch2/catch.hpp>

#include <omp.h>

#include <algorithm>
#include <random>
#include <vector>

#include "contact/broad_phase.hpp"
#include "contact_fixtures.hpp"

using namespace xpl;
using contact::BroadPhase;
using contact::ContactFace;
using contact::Vec3;

namespace {

/// A cloud of small random quads (some of them shells) and loose nodes in a unit box.
struct Cloud {
  NodalVectors position;
  std::vector<ContactFace> faces;
  std::vector<Index> slaves;  // loose nodes and every face corner
  std::vector<Real> thickness;
};

Cloud make_cloud(int n_faces, int n_loose, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<Real> u(0.0, 1.0), s(-0.04, 0.04);
  Cloud c;
  c.position.resize(4 * n_faces + n_loose, 3);
  c.thickness.assign(4 * n_faces + n_loose, 0.0);
  for (int f = 0; f < n_faces; ++f) {
    const Vec3 centre(u(rng), u(rng), u(rng));
    ContactFace face;
    for (int a = 0; a < 4; ++a) {
      const Index n = 4 * f + a;
      const Vec3 x = centre + Vec3(s(rng), s(rng), s(rng));
      c.position.row(n) = x.transpose();
      face.nodes[a] = n;
      c.thickness[n] = 0.01 * u(rng);
    }
    face.element = f;
    face.shell = f % 3 == 0;
    c.faces.push_back(face);
  }
  for (int i = 0; i < n_loose; ++i)
    c.position.row(4 * n_faces + i) = Vec3(u(rng), u(rng), u(rng)).transpose();
  for (Index n = 0; n < c.position.rows(); ++n) c.slaves.push_back(n);
  return c;
}

/// Faces whose inflated box contains slave node n, by looking at every face.
std::vector<Index> brute_force(const Cloud& c, Index n, Real margin) {
  std::vector<Index> out;
  for (Index f = 0; f < static_cast<Index>(c.faces.size()); ++f) {
    const auto& fn = c.faces[f].nodes;
    if (std::find(fn.begin(), fn.end(), n) != fn.end()) continue;
    Vec3 x[4];
    contact::face_corners(c.faces[f], c.position, c.thickness, x);
    bool inside = true;
    for (int d = 0; d < 3; ++d) {
      const Real lo = std::min({x[0][d], x[1][d], x[2][d], x[3][d]}) - margin;
      const Real hi = std::max({x[0][d], x[1][d], x[2][d], x[3][d]}) + margin;
      inside = inside && c.position(n, d) >= lo && c.position(n, d) <= hi;
    }
    if (inside) out.push_back(f);
  }
  return out;
}

}  // namespace

TEST_CASE("broad phase finds exactly the faces within the margin", "[contact][broad_phase]") {
  const Real margin = GENERATE(0.005, 0.02, 0.1);
  const Cloud c = make_cloud(400, 600, 11);
  BroadPhase bp(margin);
  bp.build(c.faces, c.slaves, c.position, c.thickness);
  REQUIRE(bp.offsets().size() == c.slaves.size() + 1);
  std::size_t total = 0;
  for (Index s = 0; s < static_cast<Index>(c.slaves.size()); ++s) {
    const auto got = bp.candidates(s);
    const auto expected = brute_force(c, c.slaves[s], margin);
    REQUIRE(std::vector<Index>(got.begin(), got.end()) == expected);
    total += expected.size();
  }
  CHECK(total > 0);  // the test sees some candidates
  const auto dims = bp.grid_size();
  CHECK(double(dims[0]) * dims[1] * dims[2] <= 4.0 * 400 + 64);
}

TEST_CASE("broad phase on a flat contact domain and with no faces", "[contact][broad_phase]") {
  // Shell plate in z = 0: the grid is one bucket thick; nodes above it within the margin only.
  test::ContactMesh mesh;
  test::add_shell_plate(mesh, 4, 4, 0.25);
  const Index above = mesh.add_node(0.3, 0.3, 0.05);
  const Index far = mesh.add_node(0.3, 0.3, 0.2);
  const auto faces = contact::exterior_faces(mesh.topology());
  const Index slaves[] = {above, far};
  BroadPhase bp(0.1);
  bp.build(faces, slaves, mesh.coordinates, {});
  const auto near_faces = bp.candidates(0);
  // (0.3, 0.3) lies in the box of the 4 elements around (0.25, 0.25) within 0.1: elements
  // 0, 1, 4, 5, each with both sides.
  CHECK(std::vector<Index>(near_faces.begin(), near_faces.end()) ==
        std::vector<Index>{0, 1, 2, 3, 8, 9, 10, 11});
  CHECK(bp.candidates(1).empty());

  BroadPhase empty(0.1);
  empty.build({}, slaves, mesh.coordinates, {});
  CHECK(empty.candidates(0).empty());
  CHECK_THROWS_AS(BroadPhase(0.0), std::invalid_argument);
}

TEST_CASE("broad phase rebuilds after half a margin of motion", "[contact][broad_phase]") {
  const Real margin = 0.02;
  const Cloud c = make_cloud(50, 50, 5);
  BroadPhase bp(margin);
  CHECK(bp.needs_rebuild(c.position));  // never built
  bp.build(c.faces, c.slaves, c.position, c.thickness);
  CHECK_FALSE(bp.needs_rebuild(c.position));
  NodalVectors moved = c.position;
  moved(17, 1) += 0.49 * margin;
  CHECK_FALSE(bp.needs_rebuild(moved));
  moved(17, 1) += 0.02 * margin;
  CHECK(bp.needs_rebuild(moved));
  moved = c.position;
  moved.row(3) += Vec3(0.3, 0.3, 0.3).transpose() * margin;  // |u| = 0.52 margin
  CHECK(bp.needs_rebuild(moved));
  // Nodes on no face and on no slave list are not watched.
  Cloud partial = c;
  partial.slaves.assign(c.slaves.begin(), c.slaves.begin() + 220);  // 200 face nodes + 20
  bp.build(partial.faces, partial.slaves, partial.position, partial.thickness);
  moved = c.position;
  moved(240, 0) += 10 * margin;
  CHECK_FALSE(bp.needs_rebuild(moved));
  moved(219, 0) += 0.6 * margin;
  CHECK(bp.needs_rebuild(moved));
  CHECK(bp.build_count() == 2);
}

TEST_CASE("the rebuild decision is the max of the parts' largest motions",
          "[contact][broad_phase]") {
  // A distributed run's ranks each take the nodes they integrate and reduce by max: the same
  // number, so the same decision, as the whole positions give.
  const Real margin = 0.02;
  const Cloud c = make_cloud(60, 40, 8);
  BroadPhase bp(margin);
  CHECK(bp.largest_motion_sq(c.position) == 0.0);  // never built
  bp.build(c.faces, c.slaves, c.position, c.thickness);
  NodalVectors moved = c.position;
  std::mt19937 rng(3);
  std::uniform_real_distribution<Real> u(-0.3 * margin, 0.3 * margin);
  for (Index n = 0; n < moved.rows(); ++n)
    for (int d = 0; d < 3; ++d) moved(n, d) += u(rng);
  std::vector<char> part[3];
  for (auto& p : part) p.assign(static_cast<std::size_t>(moved.rows()), 0);
  for (Index n = 0; n < moved.rows(); ++n) part[(n * 7) % 3][n] = 1;
  Real largest = 0.0;
  for (const auto& p : part) largest = std::max(largest, bp.largest_motion_sq(moved, p));
  CHECK(largest == bp.largest_motion_sq(moved));
  CHECK(bp.exceeds_rebuild_motion(largest) == bp.needs_rebuild(moved));
  CHECK(bp.largest_motion_sq(moved, std::vector<char>(part[0].size(), 0)) == 0.0);
}

TEST_CASE("candidates stay complete until the rebuild criterion trips", "[contact][broad_phase]") {
  // After every node moves by less than margin/2, any node inside a face's (uninflated) box
  // at the new positions was a candidate of that face at the build.
  const Real margin = 0.03;
  const Cloud c = make_cloud(300, 300, 23);
  BroadPhase bp(margin);
  bp.build(c.faces, c.slaves, c.position, c.thickness);
  std::mt19937 rng(4);
  std::normal_distribution<Real> g(0.0, 1.0);
  Cloud moved = c;
  for (Index n = 0; n < moved.position.rows(); ++n) {
    Vec3 dir(g(rng), g(rng), g(rng));
    moved.position.row(n) += (0.499 * margin / dir.norm()) * dir.transpose();
  }
  REQUIRE_FALSE(bp.needs_rebuild(moved.position));
  for (Index s = 0; s < static_cast<Index>(c.slaves.size()); ++s) {
    const auto got = bp.candidates(s);
    for (Index f : brute_force(moved, c.slaves[s], 0.0))
      CHECK(std::find(got.begin(), got.end(), f) != got.end());
  }
}

TEST_CASE("broad phase results do not depend on the thread count", "[contact][broad_phase]") {
  const Cloud c = make_cloud(2000, 2000, 99);
  const int saved = omp_get_max_threads();
  std::vector<std::vector<Index>> offsets, faces;
  for (int threads : {1, 2, 3}) {
    omp_set_num_threads(threads);
    BroadPhase bp(0.02);
    bp.build(c.faces, c.slaves, c.position, c.thickness);
    offsets.push_back(bp.offsets());
    faces.push_back(bp.candidate_faces());
  }
  omp_set_num_threads(saved);
  CHECK(offsets[0] == offsets[1]);
  CHECK(offsets[0] == offsets[2]);
  CHECK(faces[0] == faces[1]);
  CHECK(faces[0] == faces[2]);
}

TEST_CASE("a scanned node's candidates do not depend on the other faces binned",
          "[contact][broad_phase]") {
  // A distributed run's rank bins only its ghost faces: those whose inflated box
  // (BroadPhase::face_box) meets the box of the nodes it scans; its nodes' lists must be the
  // whole build's, though the grid is another.
  const Real margin = 0.02;
  Cloud c = make_cloud(1500, 1500, 7);
  std::vector<char> scanned(c.slaves.size(), 0);
  Real lo[3] = {1e9, 1e9, 1e9}, hi[3] = {-1e9, -1e9, -1e9};
  for (std::size_t s = 0; s < c.slaves.size(); ++s) {
    const Index n = c.slaves[s];
    if (!(c.position(n, 0) < 0.3 && c.position(n, 1) > 0.5)) continue;
    scanned[s] = 1;
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], c.position(n, d));
      hi[d] = std::max(hi[d], c.position(n, d));
    }
  }
  std::vector<Real> depth(c.faces.size(), 0.0);
  for (std::size_t f = 0; f < c.faces.size(); f += 5) depth[f] = 0.03;
  std::vector<char> binned(c.faces.size(), 0);
  NodalVectors stale = c.position;
  stale.array() += 7.0;  // every row not of a binned face: another increment's
  std::size_t n_binned = 0;
  for (std::size_t f = 0; f < c.faces.size(); ++f) {
    Real a[3], b[3];
    BroadPhase::face_box(c.faces[f], c.position, c.thickness, depth[f], a, b);
    bool meets = true;
    for (int d = 0; d < 3; ++d) meets = meets && a[d] - margin <= hi[d] && b[d] + margin >= lo[d];
    if (!meets) continue;
    binned[f] = 1;
    ++n_binned;
    for (const Index n : c.faces[f].nodes) stale.row(n) = c.position.row(n);
  }
  for (std::size_t s = 0; s < c.slaves.size(); ++s)
    if (scanned[s] != 0) stale.row(c.slaves[s]) = c.position.row(c.slaves[s]);
  REQUIRE(n_binned > 0);
  REQUIRE(n_binned < c.faces.size() / 2);
  BroadPhase whole(margin), ghost(margin);
  whole.build(c.faces, c.slaves, c.position, c.thickness, depth, scanned);
  ghost.build(c.faces, c.slaves, stale, c.thickness, depth, scanned, binned);
  CHECK(whole.grid_size() != ghost.grid_size());
  CHECK(whole.offsets() == ghost.offsets());
  CHECK(whole.candidate_faces() == ghost.candidate_faces());
  CHECK(!whole.candidate_faces().empty());
}
