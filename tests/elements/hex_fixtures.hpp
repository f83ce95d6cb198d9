#pragma once
// Small meshes for element tests: a distorted block of hexes and single elements.

#include <random>
#include <vector>

#include "common/types.hpp"

namespace xpl::test {

/// A structured block of n×n×n hexes of size h, node (i,j,k) at index i + (n+1)(j + (n+1)k),
/// with every node moved by up to `distortion`·h in each direction (fixed seed).
struct HexBlockMesh {
  NodalVectors coordinates;
  std::vector<Index> connectivity;  // 8 per element, Abaqus order
  int n = 0;
  Index node(int i, int j, int k) const { return i + (n + 1) * (j + (n + 1) * k); }
};

inline HexBlockMesh make_block(int n, Real h, Real distortion, unsigned seed = 7) {
  HexBlockMesh mesh;
  mesh.n = n;
  const int m = n + 1;
  mesh.coordinates.resize(static_cast<Index>(m * m * m), 3);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<Real> jitter(-distortion * h, distortion * h);
  for (int k = 0; k < m; ++k)
    for (int j = 0; j < m; ++j)
      for (int i = 0; i < m; ++i) {
        const Index p = mesh.node(i, j, k);
        mesh.coordinates(p, 0) = i * h + jitter(rng);
        mesh.coordinates(p, 1) = j * h + jitter(rng);
        mesh.coordinates(p, 2) = k * h + jitter(rng);
      }
  // Reserved up front: also keeps GCC 12's -Wstringop-overflow from a false positive on the
  // first insert into an empty vector when n = 1 is inlined.
  mesh.connectivity.reserve(static_cast<std::size_t>(8 * n * n * n));
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const Index c[8] = {mesh.node(i, j, k),
                            mesh.node(i + 1, j, k),
                            mesh.node(i + 1, j + 1, k),
                            mesh.node(i, j + 1, k),
                            mesh.node(i, j, k + 1),
                            mesh.node(i + 1, j, k + 1),
                            mesh.node(i + 1, j + 1, k + 1),
                            mesh.node(i, j + 1, k + 1)};
        mesh.connectivity.insert(mesh.connectivity.end(), c, c + 8);
      }
  return mesh;
}

}  // namespace xpl::test
