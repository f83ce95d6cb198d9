#include "contact/surface_corners.hpp"

#include <algorithm>
#include <tuple>

#include "contact/contact_options.hpp"

namespace xpl::contact {

Real distance_to_segment(const Vec3& x, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const Real length2 = ab.dot(ab);
  const Real t = length2 > 0.0 ? std::clamp((x - a).dot(ab) / length2, 0.0, 1.0) : 0.0;
  return (x - (a + t * ab)).norm();
}

std::vector<std::uint8_t> corner_edges(std::span<const ContactFace> faces,
                                       const NodalVectors& position) {
  const auto n_faces = static_cast<Index>(faces.size());
  std::vector<Vec3> normal(faces.size(), Vec3::Zero());
  for (Index f = 0; f < n_faces; ++f) {
    Vec3 c[4];
    face_corners(faces[f], position, {}, c);
    const Vec3 n = (c[2] - c[0]).cross(c[3] - c[1]);
    if (n.norm() > 0.0) normal[f] = n.normalized();
  }
  struct EdgeOfFace {
    Index low, high, face;
    int edge;
    bool operator<(const EdgeOfFace& o) const {
      return std::tie(low, high, face) < std::tie(o.low, o.high, o.face);
    }
  };
  std::vector<EdgeOfFace> edges;
  edges.reserve(4 * faces.size());
  for (Index f = 0; f < n_faces; ++f)
    for (int a = 0; a < 4; ++a) {
      const Index p = faces[f].nodes[a], q = faces[f].nodes[(a + 1) % 4];
      edges.push_back({std::min(p, q), std::max(p, q), f, a});
    }
  std::sort(edges.begin(), edges.end());
  std::vector<std::uint8_t> corner(faces.size(), 0);
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i;
    while (j < edges.size() && edges[j].low == edges[i].low && edges[j].high == edges[i].high) ++j;
    for (std::size_t k = i; k < j; ++k) {
      bool continued = false;
      for (std::size_t m = i; m < j && !continued; ++m)
        continued =
            m != k && normal[edges[k].face].dot(normal[edges[m].face]) >= CROSSED_FOLD_COSINE;
      if (!continued) corner[edges[k].face] |= static_cast<std::uint8_t>(1u << edges[k].edge);
    }
    i = j;
  }
  return corner;
}

}  // namespace xpl::contact
