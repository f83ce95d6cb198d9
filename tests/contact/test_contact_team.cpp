#include <catch2/catch.hpp>

#include <omp.h>

#include <vector>

#include "contact/contact_domain.hpp"
#include "contact/contact_engine.hpp"
#include "contact/parallel_size.hpp"
#include "contact_fixtures.hpp"

using namespace xpl;
using contact::Vec3;

// The small models of the other engine tests run the contact pass on the calling thread
// (contact/parallel_size.hpp); this one has enough candidate faces for the search to run on
// the team, and checks that the result is still that of one thread, bit for bit.
TEST_CASE("a search large enough for the team gives one thread's forces bitwise",
          "[contact][engine]") {
  test::ContactMesh mesh;
  const int n = 40;
  const Real h = 1.0;
  // Distorted faces (Newton in the closest point), B pressed 0.05 h into A and moving down.
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

  auto run = [&](int threads, Index& candidates) {
    omp_set_num_threads(threads);
    NodalVectors x = mesh.coordinates;
    contact::ContactEngine engine(contact::ContactDomain(spec, mesh.topology(), x), {}, {}, x, {});
    std::vector<NodalVectors> forces;
    for (int increment = 0; increment < 4; ++increment) {
      NodalVectors force = NodalVectors::Zero(n_nodes, 3);
      PhaseTimers timers;
      engine.update(x, velocity, increment == 0 ? 0.0 : dt, dt, {}, mass, inverse_mass, force,
                    timers);
      forces.push_back(force);
      x += dt * velocity;
    }
    candidates = 0;
    for (Index s = 0; s < engine.domain().slaves().size(); ++s)
      candidates += static_cast<Index>(engine.broad_phase().candidates(s).size());
    return forces;
  };
  Index candidates_one = 0, candidates_two = 0;
  const std::vector<NodalVectors> one = run(1, candidates_one);
  const std::vector<NodalVectors> two = run(2, candidates_two);
  omp_set_num_threads(2);
  // The search ran on the team (its listed faces are most of these candidates).
  CHECK(candidates_two > 2 * contact::PARALLEL_MIN_CANDIDATES);
  CHECK(candidates_one == candidates_two);
  REQUIRE(one.size() == two.size());
  for (std::size_t k = 0; k < one.size(); ++k) {
    CHECK(one[k].cwiseAbs().maxCoeff() > 0.0);  // the blocks touch
    CHECK((one[k] - two[k]).cwiseAbs().maxCoeff() == 0.0);
  }
}
