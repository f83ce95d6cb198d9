// Number parsing of deck fields and the corner-Jacobian check of hexahedra.

#include <catch2/catch.hpp>

#include "io/deck/deck_geometry.hpp"
#include "io/deck/deck_numbers.hpp"

using namespace xpl;

TEST_CASE("reals: Fortran exponents and short forms are accepted", "[io][deck][numbers]") {
  CHECK(io::parse_real("1.0D3") == 1000.0);
  CHECK(io::parse_real("2.5d-1") == 0.25);
  CHECK(io::parse_real("1e3") == 1000.0);
  CHECK(io::parse_real("1.") == 1.0);
  CHECK(io::parse_real(".5") == 0.5);
  CHECK(io::parse_real("-.5E+1") == -5.0);
  CHECK(io::parse_real("+7") == 7.0);
}

TEST_CASE("reals: malformed tokens are rejected", "[io][deck][numbers]") {
  for (const char* bad : {"1.0e", "abc", "", ".", "-", "1,5", "1.0.0", "inf", "nan", "0x10",
                          "1e999", "1 0", "e5", "1D"})
    CHECK_FALSE(io::parse_real(bad).has_value());
}

TEST_CASE("integers", "[io][deck][numbers]") {
  CHECK(io::parse_integer("1000000000000") == 1000000000000LL);
  CHECK(io::parse_integer("+12") == 12);
  CHECK(io::parse_integer("-3") == -3);
  // Integral floats, as mesh exporters write ids (issue 34); a fraction or exponent is not one.
  CHECK(io::parse_integer("1.0") == 1);
  CHECK(io::parse_integer("12.") == 12);
  CHECK(io::parse_integer("-3.000") == -3);
  CHECK_FALSE(io::parse_integer("1.5").has_value());
  CHECK_FALSE(io::parse_integer("1.01").has_value());
  CHECK_FALSE(io::parse_integer("1.0e3").has_value());
  CHECK_FALSE(io::parse_integer(".0").has_value());
  CHECK_FALSE(io::parse_integer("1..0").has_value());
  CHECK_FALSE(io::parse_integer("12a").has_value());
  CHECK_FALSE(io::parse_integer("99999999999999999999").has_value());
  CHECK(io::looks_numeric("12"));
  CHECK_FALSE(io::looks_numeric("SET12"));
}

namespace {

std::array<Eigen::Vector3d, 8> unit_cube() {
  return {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(1, 1, 0),
          Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(1, 0, 1),
          Eigen::Vector3d(1, 1, 1), Eigen::Vector3d(0, 1, 1)};
}

}  // namespace

TEST_CASE("corner Jacobians of a scaled brick equal its volume", "[io][deck][geometry]") {
  auto x = unit_cube();
  for (auto& p : x) p = Eigen::Vector3d(2.0 * p.x(), 3.0 * p.y(), 0.5 * p.z());
  const io::CornerJacobian j = io::smallest_corner_jacobian(x);
  // Exact in floating point: products of 2, 3 and 0.5.
  CHECK(j.determinant == 3.0);
}

TEST_CASE("a single collapsed or folded corner is found", "[io][deck][geometry]") {
  auto x = unit_cube();
  x[6] = Eigen::Vector3d(0.2, 0.2, 0.2);  // node 7 pushed through the element
  const io::CornerJacobian folded = io::smallest_corner_jacobian(x);
  CHECK(folded.determinant < 0.0);
  CHECK(folded.corner == 6);
  auto mirrored = unit_cube();
  std::swap(mirrored[1], mirrored[3]);  // bottom face clockwise: whole element inverted
  std::swap(mirrored[5], mirrored[7]);
  CHECK(io::smallest_corner_jacobian(mirrored).determinant == -1.0);
}
