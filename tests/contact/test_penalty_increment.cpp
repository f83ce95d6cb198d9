#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include "contact/contact_options.hpp"
#include "contact/penalty_increment.hpp"

using namespace xpl;
using namespace xpl::contact;

namespace {

/// Largest eigenvalue of M⁻¹K for two masses joined by a spring k: k (1/m1 + 1/m2).
Real two_mass_omega_sq(Real k, Real m1, Real m2) {
  return k * (1.0 / m1 + 1.0 / m2);
}

}  // namespace

TEST_CASE("Penalty row sums bound the contact frequency exactly face to face",
          "[contact][penalty_increment]") {
  // Node 0 (slave, 2 kg) over corner 1 of a face (1 kg) at N = (1, 0, 0, 0): one spring
  // between two masses. The row-sum bound of the lighter node is k (1 + 1)/m = 2k/m, the
  // exact ω² for equal masses and an upper bound otherwise.
  const std::vector<Real> inverse_mass{0.5, 1.0, 1.0, 1.0, 1.0};
  PenaltyStiffnessSum sum;
  sum.reset(5);
  sum.add_spring(0, {1, 2, 3, 4}, {1.0, 0.0, 0.0, 0.0}, 100.0, 3, inverse_mass);
  const PenaltyLimit limit = sum.largest(inverse_mass);
  CHECK(limit.node == 1);
  CHECK(limit.interaction == 3);
  CHECK(limit.omega_sq == Approx(200.0).epsilon(1e-14));  // 2k/m_1, rounding only
  CHECK(limit.omega_sq >= two_mass_omega_sq(100.0, 2.0, 1.0));
  // Equal masses: the bound is exact.
  const std::vector<Real> equal{1.0, 1.0, 1.0, 1.0, 1.0};
  sum.reset(5);
  sum.add_spring(0, {1, 2, 3, 4}, {1.0, 0.0, 0.0, 0.0}, 100.0, 0, equal);
  CHECK(sum.largest(equal).omega_sq == Approx(two_mass_omega_sq(100.0, 1.0, 1.0)).epsilon(1e-14));
  CHECK(sum.largest(equal).stable_dt() ==
        Approx(std::sqrt(PENALTY_INCREMENT_BUDGET / 200.0)).epsilon(1e-14));
}

TEST_CASE("A rigid master leaves the spring on the slave node alone",
          "[contact][penalty_increment]") {
  // Corners without inverse mass do not move: the slave row is k/m (a spring to ground).
  const std::vector<Real> inverse_mass{0.5, 0.0, 0.0, 0.0, 0.0};
  PenaltyStiffnessSum sum;
  sum.reset(5);
  sum.add_spring(0, {1, 2, 3, 4}, {0.25, 0.25, 0.25, 0.25}, 100.0, 0, inverse_mass);
  const PenaltyLimit limit = sum.largest(inverse_mass);
  CHECK(limit.node == 0);
  CHECK(limit.omega_sq == Approx(50.0).epsilon(1e-14));
}

TEST_CASE("Both views of a balanced pair and the corner shares add up on a node",
          "[contact][penalty_increment]") {
  // Node 0 presses on a face of corner 1 with weight ½ and node 1 on a face of corner 0 with
  // weight ½ (both views): each node carries its own half spring and a half share as a
  // corner, together the full spring k, so the bound is 2k/m as for one full spring.
  const std::vector<Real> inverse_mass{1.0, 1.0, 1.0, 1.0, 1.0, 1.0};
  PenaltyStiffnessSum sum;
  sum.reset(6);
  sum.add_spring(0, {1, 2, 3, 4}, {1.0, 0.0, 0.0, 0.0}, 50.0, 0, inverse_mass);
  sum.add_spring(1, {0, 5, 3, 4}, {1.0, 0.0, 0.0, 0.0}, 50.0, 0, inverse_mass);
  CHECK(sum.largest(inverse_mass).omega_sq == Approx(200.0).epsilon(1e-14));
  // A node in the middle of a face (N = ¼ each) takes a quarter of the span per corner.
  sum.reset(6);
  sum.add_spring(0, {1, 2, 3, 4}, {0.25, 0.25, 0.25, 0.25}, 100.0, 0, inverse_mass);
  const PenaltyLimit middle = sum.largest(inverse_mass);
  CHECK(middle.node == 0);
  CHECK(middle.omega_sq == Approx(200.0).epsilon(1e-14));
  // reset() forgets every spring.
  sum.reset(6);
  CHECK(sum.largest(inverse_mass).omega_sq == 0.0);
  CHECK(std::isinf(sum.largest(inverse_mass).stable_dt()));
}
