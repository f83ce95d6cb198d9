#include <catch2/catch.hpp>

#include <omp.h>

#include <vector>

#include "contact/contact_domain.hpp"
#include "contact/contact_engine.hpp"
#include "contact/parallel_size.hpp"
#include "contact_fixtures.hpp"

using namespace xpl;
using contact::Vec3;

namespace {

struct TeamRun {
  std::vector<NodalVectors> forces;
  Index candidates = 0;
  Index slots = 0;
  Index faces = 0;
};

/// Two n × n × 1 blocks of distorted hexes (Newton in the closest point), B pressed 0.05 h
/// into A and moving down; four contact updates on `threads` threads.
TeamRun press_blocks(int n, int threads) {
  test::ContactMesh mesh;
  const Real h = 1.0;
  test::add_hex_block(mesh, n, n, 1, h, Vec3::Zero(), 0.05, 3);
  test::add_hex_block(mesh, n, n, 1, h, Vec3(0.0, 0.0, h - 0.05 * h), 0.05, 5);
  const Index n_nodes = mesh.node_count();
  const Index first_b = n_nodes / 2;
  NodalVectors velocity = NodalVectors::Zero(n_nodes, 3);
  for (Index a = first_b; a < n_nodes; ++a) velocity(a, 2) = -0.01;
  const std::vector<Real> mass(n_nodes, 1.0), inverse_mass(n_nodes, 1.0);
  const Real dt = 1e-3;
  contact::DomainSpec spec;
  spec.surfaces.push_back({"ALL_EXTERIOR", true, {}});
  spec.inclusions.push_back({0, 0, false});

  omp_set_num_threads(threads);
  NodalVectors x = mesh.coordinates;
  contact::ContactEngine engine(contact::ContactDomain(spec, mesh.topology(), x), {}, {}, x, {});
  TeamRun run;
  for (int increment = 0; increment < 4; ++increment) {
    NodalVectors force = NodalVectors::Zero(n_nodes, 3);
    PhaseTimers timers;
    engine.update(x, velocity, increment == 0 ? 0.0 : dt, dt, {}, mass, inverse_mass, force,
                  timers);
    run.forces.push_back(force);
    x += dt * velocity;
  }
  omp_set_num_threads(2);
  run.slots = engine.domain().slaves().size();
  run.faces = static_cast<Index>(engine.domain().faces().size());
  for (Index s = 0; s < run.slots; ++s)
    run.candidates += static_cast<Index>(engine.broad_phase().candidates(s).size());
  return run;
}

void check_bitwise(const TeamRun& one, const TeamRun& two) {
  CHECK(one.candidates == two.candidates);
  REQUIRE(one.forces.size() == two.forces.size());
  for (std::size_t k = 0; k < one.forces.size(); ++k) {
    CHECK(one.forces[k].cwiseAbs().maxCoeff() > 0.0);  // the blocks touch
    CHECK((one.forces[k] - two.forces[k]).cwiseAbs().maxCoeff() == 0.0);
  }
}

}  // namespace

// The small models of the other engine tests run the contact pass on the calling thread
// (contact/parallel_size.hpp); this one has enough candidate faces for the search to run on
// the team, and checks that the result is still that of one thread, bit for bit.
TEST_CASE("a search large enough for the team gives one thread's forces bitwise",
          "[contact][engine]") {
  const TeamRun one = press_blocks(40, 1);
  const TeamRun two = press_blocks(40, 2);
  // The search ran on the team (its listed faces are most of these candidates).
  CHECK(two.candidates > 2 * contact::PARALLEL_MIN_CANDIDATES);
  check_bitwise(one, two);
}

// Large enough for the light loops too (the rebuild check, face and node areas, the springs:
// PARALLEL_MIN_SLOTS items), so that every loop of the contact pass runs on the team. The
// springs visit the slots with listed faces only (contact_engine.hpp, "Quiet slots"): the two
// pressed faces of 131² nodes each.
TEST_CASE("a contact pass with every loop on the team gives one thread's forces bitwise",
          "[contact][engine]") {
  const TeamRun one = press_blocks(130, 1);
  const TeamRun two = press_blocks(130, 2);
  CHECK(two.slots > contact::PARALLEL_MIN_SLOTS);
  CHECK(two.faces > contact::PARALLEL_MIN_SLOTS);
  check_bitwise(one, two);
}
