// The element kinds' per-element formulas (elements/element_kind.hpp), which *FIXED MASS
// SCALING and *DLOAD GRAV use, agree with their blocks: K::node_mass with the mass the block
// lumps, K::stable_increment with the increment limit of a force pass at rest (zero
// velocity, so no volumetric rate and ξ = b1), element by element on distorted meshes, and
// the critical element is the one with the smallest K::stable_increment.

#include <catch2/catch.hpp>

#include <array>
#include <limits>
#include <numeric>
#include <vector>

#include "elements/element_kind.hpp"
#include "elements/hex/hex8.hpp"
#include "elements/hex/hex8r.hpp"
#include "elements/shell/shell4r.hpp"
#include "hex_fixtures.hpp"

using namespace xpl;
using namespace xpl::elements;

static_assert(ElementKind<Hex8rBlock> && ElementKind<Hex8Block> && ElementKind<Shell4rBlock>);

namespace {

template <int N>
std::array<V3<Real>, N> corners(const NodalVectors& x, const Index* nodes) {
  std::array<V3<Real>, N> c;
  for (int a = 0; a < N; ++a) c[a] = {x(nodes[a], 0), x(nodes[a], 1), x(nodes[a], 2)};
  return c;
}

/// Checks kind K's formulas against `block` built on `x` with `props` for every element.
template <class K>
void check_kind(K& block, const NodalVectors& x, const std::vector<Index>& connectivity,
                const typename K::Properties& props, Real bulk_linear) {
  const Index n_nodes = x.rows();
  const auto n_elements = static_cast<Index>(connectivity.size() / K::NODES);
  // Lumped mass: the sum of the node shares of the elements at each node.
  std::vector<Real> mass(n_nodes, 0.0), inertia(n_nodes, 0.0), expected(n_nodes, 0.0);
  block.add_lumped_mass(x, mass, inertia);
  Real smallest = std::numeric_limits<Real>::infinity();
  Index critical = NO_INDEX;
  for (Index e = 0; e < n_elements; ++e) {
    const Index* nodes = &connectivity[static_cast<std::size_t>(e) * K::NODES];
    const auto c = corners<K::NODES>(x, nodes);
    const Real share = K::node_mass(props, c.data());
    for (int a = 0; a < K::NODES; ++a) expected[nodes[a]] += share;
    const Real dt = K::stable_increment(props, c.data(), bulk_linear);
    if (dt < smallest) {
      smallest = dt;
      critical = e;
    }
  }
  for (Index i = 0; i < n_nodes; ++i) REQUIRE(mass[i] == Approx(expected[i]).epsilon(1e-14));
  // A force pass at rest reports the smallest element estimate and its element.
  NodalVectors f = NodalVectors::Zero(n_nodes, 3), m = NodalVectors::Zero(n_nodes, 3);
  const NodalVectors zero = NodalVectors::Zero(n_nodes, 3);
  const ForcePass pass{x, zero, zero, 0.0, bulk_linear, 1.2, f, m};
  std::vector<Index> node_part(static_cast<std::size_t>(n_nodes), UNTOUCHED);
  block.mark_nodes(1, node_part);
  block.set_partition(1, boundary_nodes(node_part));
  block.forces_of_part(0, pass);
  typename K::Totals totals;
  block.add_totals(totals);
  CHECK(totals.critical_element == critical);
  CHECK(totals.stable_dt == Approx(smallest).epsilon(1e-13));
}

}  // namespace

TEST_CASE("hex kinds: node_mass and stable_increment as the blocks", "[elements][kinds]") {
  const test::HexBlockMesh mesh = test::make_block(3, 2e-3, 0.2);
  const auto n = static_cast<Index>(mesh.connectivity.size() / 8);
  std::vector<Index> rows(n);
  std::iota(rows.begin(), rows.end(), 0);
  for (Real nu : {0.3, 0.45}) {
    const HexMaterial m{7850.0, 200e9, nu, HourglassForm::Enhanced, 1.0};
    const std::vector<HexMaterial> materials(n, m);
    Hex8rBlock reduced(rows, mesh.connectivity, materials, mesh.coordinates.rows());
    check_kind(reduced, mesh.coordinates, mesh.connectivity, m, 0.06);
    Hex8Block full(rows, mesh.connectivity, materials, mesh.coordinates.rows());
    check_kind(full, mesh.coordinates, mesh.connectivity, m, 0.06);
  }
}

TEST_CASE("shell kind: node_mass and stable_increment as the block", "[elements][kinds]") {
  // A 3×3 patch of skewed, slightly warped quads.
  NodalVectors x(16, 3);
  std::vector<Index> conn;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      const int k = i + 4 * j;
      x(k, 0) = 0.01 * i + 0.002 * j + 0.0007 * ((i * 7 + j * 3) % 5);
      x(k, 1) = 0.012 * j + 0.0009 * ((i * 5 + j) % 3);
      x(k, 2) = 0.0004 * ((i + 2 * j) % 3);
    }
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      const Index a = i + 4 * j;
      for (Index v : {a, a + 1, a + 5, a + 4}) conn.push_back(v);
    }
  std::vector<Index> rows(9);
  std::iota(rows.begin(), rows.end(), 0);
  const ShellProperties p{7850.0, 200e9, 0.3, 1e-3, 5, 0.0, 1.0};
  Shell4rBlock block(rows, conn, std::vector<ShellProperties>(9, p), 16);
  check_kind(block, x, conn, p, 0.06);
}
