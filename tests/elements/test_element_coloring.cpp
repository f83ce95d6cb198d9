#include <catch2/catch.hpp>

#include <set>

#include "elements/parallel/element_coloring.hpp"
#include "hex_fixtures.hpp"

TEST_CASE("no two elements of a colour share a node", "[elements][coloring]") {
  const auto mesh = xpl::test::make_block(5, 1.0, 0.0);
  const auto color = xpl::elements::color_elements(
      mesh.connectivity, 8, static_cast<xpl::Index>(mesh.coordinates.rows()));
  REQUIRE(color.size() == 125);
  int n_colors = 0;
  for (int c : color) n_colors = std::max(n_colors, c + 1);
  CHECK(n_colors <= 8);  // a structured hex mesh needs 8 colours; greedy finds them
  for (int c = 0; c < n_colors; ++c) {
    std::set<xpl::Index> used;
    for (std::size_t e = 0; e < color.size(); ++e) {
      if (color[e] != c) continue;
      for (int a = 0; a < 8; ++a) CHECK(used.insert(mesh.connectivity[e * 8 + a]).second);
    }
  }
}
