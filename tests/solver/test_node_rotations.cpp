// NodeRotations: rotation vectors set (an imported UR) come back unchanged and compose with
// the increments of later time steps.

#include <catch2/catch.hpp>

#include <cmath>
#include <numbers>
#include <stdexcept>

#include "solver/motion/node_rotations.hpp"

using namespace xpl;

TEST_CASE("node rotations: set then rotation_vectors returns the vectors set",
          "[solver][rotations]") {
  NodalVectors set(5, 3);
  set.row(0) << 0.0, 0.0, 0.0;
  set.row(1) << 1e-12, -2e-12, 3e-12;  // tiny: sin(θ/2)/θ must not lose them
  set.row(2) << 0.3, -0.2, 0.1;
  set.row(3) << 0.0, 3.0, 0.0;   // close to π
  set.row(4) << -1.2, 0.9, 2.0;  // |θ| = 2.6
  NodeRotations rotations(5);
  rotations.set(set);
  NodalVectors back(5, 3);
  rotations.rotation_vectors(back);
  for (Index n = 0; n < 5; ++n) {
    // Round trip through cos/sin and atan2: a few ulps of the angle.
    for (int c = 0; c < 3; ++c) CHECK(back(n, c) == Approx(set(n, c)).margin(1e-15));
  }
  CHECK(back(1, 0) == Approx(1e-12).epsilon(1e-12));
}

TEST_CASE("node rotations: an angle beyond pi comes back as the same rotation",
          "[solver][rotations]") {
  NodalVectors set(1, 3);
  set.row(0) << 0.0, 0.0, 4.0;  // 4 rad about z = 2π − 4 rad about −z
  NodeRotations rotations(1);
  rotations.set(set);
  NodalVectors back(1, 3);
  rotations.rotation_vectors(back);
  CHECK(back(0, 0) == Approx(0.0).margin(1e-15));
  CHECK(back(0, 1) == Approx(0.0).margin(1e-15));
  CHECK(back(0, 2) == Approx(4.0 - 2.0 * std::numbers::pi).margin(1e-14));
}

TEST_CASE("node rotations: increments compose with a rotation set", "[solver][rotations]") {
  // About one axis, q(θ0) then Cayley increments of ω Δt add 2 atan(ω Δt / 2) each.
  NodalVectors set(2, 3);
  set.row(0) << 0.0, 0.0, 0.5;
  set.row(1) << 0.2, -0.1, 0.0;
  NodeRotations rotations(2);
  rotations.set(set);
  NodalVectors omega(2, 3);
  omega.row(0) << 0.0, 0.0, 20.0;
  omega.row(1) << 0.0, 0.0, 0.0;
  const Real dt = 1e-3;
  for (int i = 0; i < 10; ++i) rotations.advance(omega, dt);
  NodalVectors back(2, 3);
  rotations.rotation_vectors(back);
  const Real expected = 0.5 + 10 * 2.0 * std::atan(0.5 * 20.0 * dt);
  CHECK(back(0, 2) == Approx(expected).margin(1e-14));
  CHECK(back(0, 0) == Approx(0.0).margin(1e-15));
  CHECK(back(1, 0) == Approx(0.2).margin(1e-15));  // ω = 0 leaves node 1 as it was set
  CHECK(back(1, 1) == Approx(-0.1).margin(1e-15));
}

TEST_CASE("node rotations: set refuses a field of the wrong size", "[solver][rotations]") {
  NodeRotations rotations(3);
  CHECK_THROWS_AS(rotations.set(NodalVectors::Zero(2, 3)), std::invalid_argument);
}
