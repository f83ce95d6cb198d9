// Sleeping slots (contact_engine.hpp, "Sleeping slots"): a slot far from its listed faces is
// not searched until the motion may have brought it within a touch, and what it gives up (an
// open touch's memory, warm starts) does not change the forces once it touches.
#include <catch2/catch.hpp>

#include <cstdlib>
#include <string>
#include <vector>

#include "contact/contact_domain.hpp"
#include "contact/contact_engine.hpp"
#include "contact_fixtures.hpp"

using namespace xpl;
using contact::ContactDomain;
using contact::DomainSpec;
using contact::Vec3;

namespace {

/// Two 2×2 shell plates of 1 m elements, t = 0.1 m, 0.6 m apart (mid-surfaces), the upper one
/// moved down by `step` (m) per update for `updates` updates; the engine's mode from
/// XPL_CONTACT_SLEEP = `mode` ("" leaves it unset). Returns the engine after the last update.
contact::ContactEngine approach(const std::string& mode, Real step, int updates) {
  test::ContactMesh mesh;
  test::add_shell_plate(mesh, 2, 2, 1.0);
  const Index first_upper = mesh.node_count();
  test::add_shell_plate(mesh, 2, 2, 1.0, Vec3(0.0, 0.0, 0.6));
  const Index n = mesh.node_count();
  const std::vector<Real> thickness(static_cast<std::size_t>(n), 0.1);
  const std::vector<Real> mass(n, 1.0), inverse_mass(n, 1.0);
  DomainSpec spec;
  spec.surfaces.push_back({"ALL_EXTERIOR", true, {}});
  spec.inclusions.push_back({0, 0, false});
  contact::ContactOptions options;
  options.margin = 1.0;  // every slot lists the other plate's faces from the start
  const Real dt = 1e-3;
  NodalVectors x = mesh.coordinates;
  if (mode.empty())
    unsetenv("XPL_CONTACT_SLEEP");
  else
    setenv("XPL_CONTACT_SLEEP", mode.c_str(), 1);
  contact::ContactEngine engine(ContactDomain(spec, mesh.topology(), x), {}, options, x, thickness);
  unsetenv("XPL_CONTACT_SLEEP");
  NodalVectors force = NodalVectors::Zero(n, 3);
  NodalVectors v = NodalVectors::Zero(n, 3);
  PhaseTimers timers;
  engine.update(x, v, 0.0, dt, thickness, mass, inverse_mass, force, timers);
  for (int k = 0; k < updates; ++k) {
    for (Index i = first_upper; i < n; ++i) {
      x(i, 2) -= step;
      v(i, 2) = -step / dt;
    }
    force.setZero();
    engine.update(x, v, dt, dt, thickness, mass, inverse_mass, force, timers);
  }
  return engine;
}

}  // namespace

TEST_CASE("a slot far from its faces sleeps until the motion may bring it within a touch",
          "[contact][engine][sleep]") {
  // 0.6 apart, touching below 0.1 (both half thicknesses): 100 steps of 5 mm to the touch.
  const Real step = 0.005;
  const int updates = 104;
  const contact::ContactEngine awake = approach("off", step, updates);
  const contact::ContactEngine sleeping = approach("", step, updates);
  CHECK(awake.sleep_counts().asleep == 0);
  // Far apart, the clearance (0.6 − 0.1 − the guard 0.01) lasts 49 steps of a path of 5 mm.
  CHECK(sleeping.sleep_counts().asleep > sleeping.sleep_counts().searched);
  // Touching now, with the forces of the engine that searched every slot every time: the
  // sleeping slots woke a guard's worth (several steps) before their touch and held an open
  // touch from then on. The margin is the rounding of a closest point started elsewhere.
  const Index n_slave = sleeping.domain().slaves().size();
  Real largest = 0.0;
  for (Index s = 0; s < n_slave; ++s) largest = std::max(largest, awake.normal_force(s));
  REQUIRE(largest > 0.0);
  for (Index s = 0; s < n_slave; ++s) {
    CHECK(sleeping.normal_force(s) == Approx(awake.normal_force(s)).margin(1e-12 * largest));
    CHECK(sleeping.touch(s).face == awake.touch(s).face);
  }
}

TEST_CASE("the check mode searches the sleeping slots and finds none of them touching",
          "[contact][engine][sleep]") {
  const contact::ContactEngine checked = approach("check", 0.005, 104);
  const contact::ContactEngine plain = approach("", 0.005, 104);
  CHECK(checked.sleep_counts().checked == checked.sleep_counts().asleep);
  CHECK(checked.sleep_counts().asleep == plain.sleep_counts().asleep);
  for (Index s = 0; s < plain.domain().slaves().size(); ++s)
    CHECK(checked.normal_force(s) == plain.normal_force(s));  // the check changes nothing
}
