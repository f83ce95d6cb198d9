// The contact part of the health check (issue 20, item 4): energy held by the penalty
// springs beyond ALLPW is energy created by contact, warned about once and fatal above the
// limit, while ETOTAL (which contains ALLPW) stays balanced.

#include <catch2/catch.hpp>

#include "common/error.hpp"
#include "solver/energy/contact_energy_check.hpp"

namespace {

/// A state with kinetic energy `ke` (J) and ALLPW `allpw` (J).
xpl::State state_with(xpl::Real ke, xpl::Real allpw, long increment) {
  increment += xpl::CONTACT_CHECK_WARMUP;  // past the warm-up of a step started at 0
  xpl::State s;
  s.energies.kinetic = ke;
  s.energies.contact = allpw;
  s.increment = increment;
  return s;
}

}  // namespace

TEST_CASE("springs holding what ALLPW says pass silently", "[solver][contact_energy]") {
  xpl::ContactEnergyCheck check;
  // Loading and unloading: ALLPW follows the stored energy up to a stepping error of 2 % of
  // the kinetic energy, the size the default penalty leaves on coarse decks.
  for (int i = 0; i <= 10; ++i) {
    const double stored = 0.3 * (i <= 5 ? i : 10 - i) / 5.0;
    const double lag = i > 0 ? 0.02 : 0.0;
    CHECK(check.check(state_with(1.0 - stored, stored - lag, i), stored, 7).empty());
  }
  CHECK(check.created() == Approx(0.02).margin(1e-12));
}

TEST_CASE("what the springs hold at the end of the warm-up is the baseline",
          "[solver][contact_energy]") {
  xpl::ContactEnergyCheck check;
  // An ignored overclosure pushed out in the first increments: 0.5 J unexplained at once.
  xpl::State s = state_with(1.0, -0.5, 0);
  s.increment = 1;
  CHECK(check.check(s, 0.0, 7).empty());                         // within the warm-up: not watched
  CHECK(check.check(state_with(1.5, -0.5, 0), 0.0, 7).empty());  // baseline 0.5 J
  CHECK(check.created() == Approx(0.0).margin(1e-12));
  CHECK(check.check(state_with(1.5, -0.5, 1), 0.0, 7).empty());
}

TEST_CASE("energy created by contact is warned about once, then stops the run",
          "[solver][contact_energy]") {
  xpl::ContactEnergyCheck check;
  CHECK(check.check(state_with(1.0, 0.0, 1), 0.0, 7).empty());
  // The springs hold 0.06 J that ALLPW never took: 6 % of the energy scale 1 J.
  const std::string warning = check.check(state_with(1.0, 0.0, 2), 0.06, 7);
  CHECK(warning.find("contact created energy") != std::string::npos);
  CHECK(warning.find("increment " + std::to_string(2 + xpl::CONTACT_CHECK_WARMUP)) !=
        std::string::npos);
  CHECK(check.check(state_with(1.0, 0.0, 3), 0.07, 7).empty());  // once only
  // A spring that gave back more than it took: ALLPW negative, KE grown, ETOTAL balanced.
  try {
    check.check(state_with(1.15, -0.15, 4), 0.0, 7);
    FAIL("no error");
  } catch (const xpl::SolverError& e) {
    CHECK(e.increment() == 4 + xpl::CONTACT_CHECK_WARMUP);
    CHECK(e.element_id() == 7);
    CHECK(std::string(e.what()).find("contact created energy") != std::string::npos);
  }
}
