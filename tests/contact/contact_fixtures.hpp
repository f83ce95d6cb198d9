#pragma once
// Small meshes for the contact tests: hex blocks, shell plates, and their topology views.

#include <random>
#include <vector>

#include "contact/contact_faces.hpp"

namespace xpl::test {

/// A mixed mesh in the model's compressed-row layout, owning its arrays.
struct ContactMesh {
  NodalVectors coordinates;
  std::vector<Index> offsets{0};
  std::vector<Index> nodes;
  std::vector<contact::ElementKind> kinds;

  contact::ElementTopology topology() const { return {offsets, nodes, kinds}; }
  Index node_count() const { return static_cast<Index>(coordinates.rows()); }

  void add_element(contact::ElementKind kind, std::initializer_list<Index> element_nodes) {
    nodes.insert(nodes.end(), element_nodes);
    offsets.push_back(static_cast<Index>(nodes.size()));
    kinds.push_back(kind);
  }
  Index add_node(Real x, Real y, Real z) {
    const Index n = node_count();
    coordinates.conservativeResize(n + 1, 3);
    coordinates.row(n) << x, y, z;
    return n;
  }
  /// Room for `count` more nodes at once, their rows set by the caller in order (one
  /// resize: a node at a time copies the whole array each time).
  Index add_nodes(Index count) {
    const Index first = node_count();
    coordinates.conservativeResize(first + count, 3);
    return first;
  }
  void set_node(Index a, Real x, Real y, Real z) { coordinates.row(a) << x, y, z; }
};

/// A block of nx×ny×nz hexes of size h starting at `origin`, node (i,j,k) appended in
/// i-fastest order, each node moved by up to distortion·h per direction (fixed seed).
inline void add_hex_block(ContactMesh& mesh, int nx, int ny, int nz, Real h,
                          const contact::Vec3& origin = contact::Vec3::Zero(),
                          Real distortion = 0.0, unsigned seed = 3) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<Real> jitter(-distortion * h, distortion * h);
  const Index first = mesh.add_nodes(Index{nx + 1} * (ny + 1) * (nz + 1));
  auto node = [&](int i, int j, int k) { return first + i + (nx + 1) * (j + (ny + 1) * k); };
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i)
        mesh.set_node(node(i, j, k), origin[0] + i * h + jitter(rng),
                      origin[1] + j * h + jitter(rng), origin[2] + k * h + jitter(rng));
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        mesh.add_element(contact::ElementKind::Hex,
                         {node(i, j, k), node(i + 1, j, k), node(i + 1, j + 1, k),
                          node(i, j + 1, k), node(i, j, k + 1), node(i + 1, j, k + 1),
                          node(i + 1, j + 1, k + 1), node(i, j + 1, k + 1)});
}

/// A flat plate of nx×ny shells of size h in the plane z = origin.z, normal +z.
inline void add_shell_plate(ContactMesh& mesh, int nx, int ny, Real h,
                            const contact::Vec3& origin = contact::Vec3::Zero()) {
  const Index first = mesh.node_count();
  auto node = [&](int i, int j) { return first + i + (nx + 1) * j; };
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) mesh.add_node(origin[0] + i * h, origin[1] + j * h, origin[2]);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      mesh.add_element(contact::ElementKind::Shell,
                       {node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)});
}

/// Corner positions of a face on the mesh coordinates (no shell offset).
inline void corners_of(const contact::ContactFace& face, const NodalVectors& x,
                       contact::Vec3 corner[4]) {
  contact::face_corners(face, x, {}, corner);
}

/// Unit normal (x2 − x0) × (x3 − x1) of a face.
inline contact::Vec3 face_normal(const contact::ContactFace& face, const NodalVectors& x) {
  contact::Vec3 c[4];
  corners_of(face, x, c);
  return (c[2] - c[0]).cross(c[3] - c[1]).normalized();
}

/// Centroid of the corners of a face.
inline contact::Vec3 face_centroid(const contact::ContactFace& face, const NodalVectors& x) {
  contact::Vec3 c[4];
  corners_of(face, x, c);
  return 0.25 * (c[0] + c[1] + c[2] + c[3]);
}

/// Centroid of the nodes of element e.
inline contact::Vec3 element_centroid(const ContactMesh& mesh, Index e) {
  contact::Vec3 s = contact::Vec3::Zero();
  const Index n = mesh.offsets[e + 1] - mesh.offsets[e];
  for (Index a = mesh.offsets[e]; a < mesh.offsets[e + 1]; ++a)
    s += mesh.coordinates.row(mesh.nodes[a]).transpose();
  return s / static_cast<Real>(n);
}

}  // namespace xpl::test
