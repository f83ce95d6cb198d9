#include "contact/contact_faces.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "contact/parallel_size.hpp"

namespace xpl::contact {

namespace {

/// A face identified by its sorted corner nodes, independent of orientation and start.
using FaceKey = std::array<Index, 4>;

struct FaceKeyHash {
  std::size_t operator()(const FaceKey& k) const {
    std::size_t h = 1469598103934665603ull;
    for (Index n : k) h = (h ^ static_cast<std::uint32_t>(n)) * 1099511628211ull;
    return h;
  }
};

FaceKey sorted_key(const std::array<Index, 4>& nodes) {
  FaceKey k = nodes;
  std::sort(k.begin(), k.end());
  return k;
}

/// Outward corner order of hex face f: the inward Abaqus cycle reversed, same first corner.
std::array<Index, 4> hex_face_nodes(const Index* element_nodes, int f) {
  const int* c = HEX_FACE_CORNERS[f];
  return {element_nodes[c[0]], element_nodes[c[3]], element_nodes[c[2]], element_nodes[c[1]]};
}

std::array<Index, 4> shell_face_nodes(const Index* element_nodes, std::uint8_t side) {
  if (side == SHELL_SPOS)
    return {element_nodes[0], element_nodes[1], element_nodes[2], element_nodes[3]};
  return {element_nodes[0], element_nodes[3], element_nodes[2], element_nodes[1]};
}

ContactFace make_face(const std::array<Index, 4>& nodes, Index element, std::uint8_t face,
                      bool shell, Index surface) {
  ContactFace cf;
  cf.nodes = nodes;
  cf.element = element;
  cf.face = face;
  cf.shell = shell;
  cf.surface = surface;
  return cf;
}

/// Hex face f of the element with nodes `element_nodes`, with the element's other nodes.
ContactFace make_hex_face(const Index* element_nodes, std::uint8_t f, Index element,
                          Index surface) {
  ContactFace cf = make_face(hex_face_nodes(element_nodes, f), element, f, false, surface);
  const int* c = HEX_FACE_CORNERS[OPPOSITE_HEX_FACE[f]];
  for (int a = 0; a < 4; ++a) cf.back[a] = element_nodes[c[a]];
  return cf;
}

Vec3 cross_diagonals(const Vec3 corner[4]) {
  return (corner[2] - corner[0]).cross(corner[3] - corner[1]);
}

Real length(const Vec3& v) {
  return std::sqrt(v.dot(v));
}

}  // namespace

std::vector<ContactFace> exterior_faces(const ElementTopology& topology, Index surface) {
  const Index n_elements = topology.element_count();
  // How many hexes share each face; faces met twice (or more) are interior.
  std::unordered_map<FaceKey, int, FaceKeyHash> count;
  for (Index e = 0; e < n_elements; ++e) {
    if (topology.kinds[e] != ElementKind::Hex) continue;
    const Index* en = topology.nodes.data() + topology.offsets[e];
    for (int f = 0; f < 6; ++f) ++count[sorted_key(hex_face_nodes(en, f))];
  }
  std::vector<ContactFace> faces;
  for (Index e = 0; e < n_elements; ++e) {
    if (topology.kinds[e] != ElementKind::Hex) continue;
    const Index* en = topology.nodes.data() + topology.offsets[e];
    for (int f = 0; f < 6; ++f) {
      const auto nodes = hex_face_nodes(en, f);
      if (count.at(sorted_key(nodes)) == 1)
        faces.push_back(make_hex_face(en, static_cast<std::uint8_t>(f), e, surface));
    }
  }
  for (Index e = 0; e < n_elements; ++e) {
    if (topology.kinds[e] != ElementKind::Shell) continue;
    const Index* en = topology.nodes.data() + topology.offsets[e];
    for (std::uint8_t side : {SHELL_SNEG, SHELL_SPOS})
      faces.push_back(make_face(shell_face_nodes(en, side), e, side, true, surface));
  }
  return faces;
}

std::vector<ContactFace> surface_faces(const ElementTopology& topology,
                                       std::span<const FaceRef> refs, Index surface) {
  std::vector<ContactFace> faces;
  faces.reserve(refs.size());
  for (const FaceRef& r : refs) {
    if (r.element < 0 || r.element >= topology.element_count())
      throw std::invalid_argument("surface_faces: element index " + std::to_string(r.element) +
                                  " out of range");
    const Index* en = topology.nodes.data() + topology.offsets[r.element];
    switch (topology.kinds[r.element]) {
      case ElementKind::Hex:
        if (r.face > 5) break;
        faces.push_back(make_hex_face(en, r.face, r.element, surface));
        continue;
      case ElementKind::Shell:
        if (r.face > 1) break;
        faces.push_back(make_face(shell_face_nodes(en, r.face), r.element, r.face, true, surface));
        continue;
      case ElementKind::Other:
        break;
    }
    throw std::invalid_argument("surface_faces: element " + std::to_string(r.element) +
                                " has no contact face " + std::to_string(int(r.face)));
  }
  return faces;
}

void face_corners(const ContactFace& face, const NodalVectors& position,
                  std::span<const Real> node_thickness, Vec3 corner[4]) {
  for (int a = 0; a < 4; ++a) {
    const Index n = face.nodes[a];
    corner[a] = Vec3(position(n, 0), position(n, 1), position(n, 2));
  }
  if (!face.shell || node_thickness.empty()) return;
  const Vec3 n = cross_diagonals(corner);
  const Real n_len = length(n);
  if (n_len <= 0.0) return;  // collapsed face: no direction to offset along
  for (int a = 0; a < 4; ++a) corner[a] += (0.5 * node_thickness[face.nodes[a]] / n_len) * n;
}

Real quad_area(const Vec3 corner[4]) {
  return 0.5 * length(cross_diagonals(corner));
}

SlaveNodes::SlaveNodes(std::span<const ContactFace> faces, Index node_count,
                       std::span<const Index> point_nodes, std::span<const Real> point_areas)
    : m_slot(static_cast<std::size_t>(node_count), NO_INDEX) {
  if (point_areas.size() != point_nodes.size())
    throw std::invalid_argument("SlaveNodes: one area per point node expected");
  for (const ContactFace& f : faces)
    for (Index n : f.nodes) m_slot[n] = 0;
  // Point nodes (on no face) are marked 1 with their area kept per node until the slots exist.
  std::vector<Real> area_of;
  if (!point_nodes.empty()) area_of.assign(static_cast<std::size_t>(node_count), 0.0);
  for (std::size_t k = 0; k < point_nodes.size(); ++k) {
    const Index n = point_nodes[k];
    if (n < 0 || n >= node_count)
      throw std::invalid_argument("SlaveNodes: point node out of range");
    if (m_slot[n] == 0) continue;  // on a face: a slave node with its faces' area
    m_slot[n] = 1;
    area_of[n] = point_areas[k];
  }
  for (Index n = 0; n < node_count; ++n)
    if (m_slot[n] == 0 || m_slot[n] == 1) {
      if (m_slot[n] == 1) {
        m_point_area.resize(m_nodes.size(), 0.0);
        m_point_area.push_back(area_of[n]);
      }
      m_slot[n] = static_cast<Index>(m_nodes.size());
      m_nodes.push_back(n);
    }
  if (!m_point_area.empty()) m_point_area.resize(m_nodes.size(), 0.0);
  // Node -> faces, in face order; a shell's second side is skipped when its first side is
  // already listed for this node (one area per shell element). A collapsed face listing a
  // node twice also counts once per corner, which keeps the sum of areas exact.
  const auto n_faces = static_cast<Index>(faces.size());
  std::vector<std::vector<Index>> around(m_nodes.size());
  for (Index i = 0; i < n_faces; ++i) {
    for (Index n : faces[i].nodes) {
      auto& list = around[m_slot[n]];
      const bool duplicate_side =
          faces[i].shell && std::any_of(list.begin(), list.end(), [&](Index j) {
            return faces[j].shell && faces[j].element == faces[i].element &&
                   faces[j].face != faces[i].face;
          });
      if (!duplicate_side) list.push_back(i);
    }
  }
  m_face_offsets.assign(1, 0);
  for (const auto& list : around) {
    m_node_faces.insert(m_node_faces.end(), list.begin(), list.end());
    m_face_offsets.push_back(static_cast<Index>(m_node_faces.size()));
  }
  m_face_area.assign(faces.size(), 0.0);
  m_face_normal.assign(3 * faces.size(), 0.0);
  m_areas.assign(m_nodes.size(), 0.0);
  for (std::size_t s = 0; s < m_point_area.size(); ++s)
    if (m_point_area[s] > 0.0) m_areas[s] = m_point_area[s];
  m_normals.assign(3 * m_nodes.size(), 0.0);
}

void SlaveNodes::update_areas(std::span<const ContactFace> faces, const NodalVectors& position) {
  update_areas(faces, position, {}, {});
}

void SlaveNodes::update_areas(std::span<const ContactFace> faces, const NodalVectors& position,
                              std::span<const char> slot_needed,
                              std::span<const char> face_needed) {
  if (faces.size() != m_face_area.size())
    throw std::invalid_argument("SlaveNodes::update_areas: not the faces it was built from");
  const auto n_faces = static_cast<Index>(faces.size());
  const bool all_faces = face_needed.empty();
#pragma omp parallel for schedule(static) if (n_faces >= PARALLEL_MIN_SLOTS)
  for (Index i = 0; i < n_faces; ++i) {
    if (!all_faces && !face_needed[i]) continue;
    Vec3 corner[4];
    face_corners(faces[i], position, {}, corner);
    const Vec3 n = 0.5 * cross_diagonals(corner);
    m_face_area[i] = length(n);
    for (int d = 0; d < 3; ++d) m_face_normal[3 * i + d] = n[d];
  }
  const Index n_slave = size();
  const bool all_slots = slot_needed.empty();
#pragma omp parallel for schedule(static) if (n_slave >= PARALLEL_MIN_SLOTS)
  for (Index s = 0; s < n_slave; ++s) {
    if (!all_slots && !slot_needed[s]) continue;
    Real a = 0.0;
    Vec3 n = Vec3::Zero();
    for (Index k = m_face_offsets[s]; k < m_face_offsets[s + 1]; ++k) {
      const Index f = m_node_faces[k];
      a += m_face_area[f];
      n += Vec3(m_face_normal[3 * f], m_face_normal[3 * f + 1], m_face_normal[3 * f + 2]);
    }
    m_areas[s] = m_point_area.empty() || m_point_area[s] == 0.0 ? 0.25 * a : m_point_area[s];
    const Real n_len = length(n);
    if (n_len > 0.0) n /= n_len;
    for (int d = 0; d < 3; ++d) m_normals[3 * s + d] = n[d];
  }
}

}  // namespace xpl::contact
