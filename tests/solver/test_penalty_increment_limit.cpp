// contact_increment (solver/increment/increment_control.hpp): the increment with a deck's own
// penalty stiffness (the rule in solver/increment/penalty_increment_limit.hpp).

#include <catch2/catch.hpp>

#include <cmath>

#include "contact/contact_options.hpp"
#include "solver/increment/increment_control.hpp"

using namespace xpl;

TEST_CASE("A user's spring as stiff as the default penalty leaves the increment alone",
          "[solver][penalty_increment]") {
  const Real raw = 1e-7, safety = 0.9;
  for (Real scale : {0.5, 1.0}) {
    const Real dt_e = scale * safety * raw;
    // ω_c²Δt_e² = B s²: the continuity point of the rule.
    const Real threshold = contact::PENALTY_INCREMENT_BUDGET * scale * scale / (dt_e * dt_e);
    CHECK(contact_increment(raw, dt_e, scale, threshold) == Approx(dt_e).epsilon(1e-14));
    // Softer: more than the elements allow (so the elements govern); stiffer: less.
    CHECK(contact_increment(raw, dt_e, scale, 0.5 * threshold) > dt_e);
    CHECK(contact_increment(raw, dt_e, scale, 2.0 * threshold) < dt_e);
  }
  CHECK(std::isinf(contact_increment(raw, 0.9 * raw, 1.0, 0.0)));
}

TEST_CASE("Elements and springs add in squares; a dominant spring is held to its own budget",
          "[solver][penalty_increment]") {
  const Real raw = 1e-7, dt_e = 0.9 * raw, omega_e = 2.0 / raw;
  // ω_c = ω_e: the combined frequency √2 ω_e gets the budget (2·0.9)² + B.
  const Real equal = contact_increment(raw, dt_e, 1.0, omega_e * omega_e);
  const Real budget = 1.8 * 1.8 + contact::PENALTY_INCREMENT_BUDGET;
  CHECK(equal == Approx(std::sqrt(budget / (2.0 * omega_e * omega_e))).epsilon(1e-14));
  // ω_c = 10 ω_e: the spring alone at ω_cΔt = √PENALTY_ALONE_BUDGET, scaled with s.
  const Real omega_c = 10.0 * omega_e;
  for (Real scale : {0.8, 1.0}) {
    const Real dt = contact_increment(raw, scale * dt_e, scale, omega_c * omega_c);
    CHECK(omega_c * dt == Approx(scale * std::sqrt(contact::PENALTY_ALONE_BUDGET)).epsilon(1e-14));
  }
}
