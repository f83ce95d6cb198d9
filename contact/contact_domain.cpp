#include "contact/contact_domain.hpp"

#include <algorithm>
#include <cmath>
#include <compare>
#include <map>
#include <stdexcept>
#include <unordered_map>
#include <utility>

#include "contact/contact_options.hpp"

namespace xpl::contact {

namespace {

/// Face of a hex opposite face f (S1–S2, S3–S5, S4–S6).

Vec3 face_centre(const Index* element_nodes, int f, const NodalVectors& x) {
  Vec3 c = Vec3::Zero();
  for (int a = 0; a < 4; ++a) {
    const Index n = element_nodes[HEX_FACE_CORNERS[f][a]];
    c += Vec3(x(n, 0), x(n, 1), x(n, 2));
  }
  return 0.25 * c;
}

/// The faces of every surface, each (element, face) once, with the mask of surfaces it is in.
std::vector<ContactFace> collect_faces(const DomainSpec& spec, const ElementTopology& topology,
                                       std::vector<std::uint64_t>& mask) {
  if (spec.surfaces.size() > static_cast<std::size_t>(MAX_CONTACT_SURFACES))
    throw std::invalid_argument("ContactDomain: more than 64 contact surfaces");
  std::vector<ContactFace> faces;
  std::unordered_map<std::int64_t, Index> index;
  for (std::size_t k = 0; k < spec.surfaces.size(); ++k) {
    const DomainSurface& surface = spec.surfaces[k];
    const std::vector<ContactFace> mine =
        surface.all_exterior ? exterior_faces(topology)
                             : surface_faces(topology, surface.faces, static_cast<Index>(k));
    for (const ContactFace& f : mine) {
      const std::int64_t key = std::int64_t{f.element} * 8 + f.face;
      auto [it, added] = index.try_emplace(key, static_cast<Index>(faces.size()));
      if (added) {
        faces.push_back(f);
        faces.back().surface = static_cast<Index>(k);
        mask.push_back(0);
      }
      mask[it->second] |= std::uint64_t{1} << k;
    }
  }
  return faces;
}

bool in(std::uint64_t mask, Index surface) {
  return (mask >> surface) & 1u;
}

/// The nodes of the node-based surfaces, with their areas (POINT_NODE_DEFAULT_AREA where none
/// is given): SlaveNodes keeps those on no face as point nodes.
std::pair<std::vector<Index>, std::vector<Real>> point_nodes(const DomainSpec& spec) {
  std::pair<std::vector<Index>, std::vector<Real>> out;
  for (const DomainSurface& surface : spec.surfaces)
    for (std::size_t k = 0; k < surface.nodes.size(); ++k) {
      const Real area = k < surface.node_areas.size() ? surface.node_areas[k] : 0.0;
      out.first.push_back(surface.nodes[k]);
      out.second.push_back(area > 0.0 ? area : POINT_NODE_DEFAULT_AREA);
    }
  return out;
}

/// SlaveNodes of the faces and of the point nodes of `spec`.
SlaveNodes make_slaves(const DomainSpec& spec, const std::vector<ContactFace>& faces,
                       Index node_count) {
  const auto [nodes, areas] = point_nodes(spec);
  return SlaveNodes(faces, node_count, nodes, areas);
}

}  // namespace

ContactDomain::ContactDomain(const DomainSpec& spec, const ElementTopology& topology,
                             const NodalVectors& position)
    : m_face_mask(),
      m_faces(collect_faces(spec, topology, m_face_mask)),
      m_slaves(make_slaves(spec, m_faces, static_cast<Index>(position.rows()))),
      m_inclusions(spec.inclusions),
      m_exclusions(spec.exclusions),
      m_interactions(spec.interactions),
      m_default_interaction(spec.default_interaction) {
  const auto n_surfaces = static_cast<Index>(spec.surfaces.size());
  for (const DomainSurface& surface : spec.surfaces) m_surface_names.push_back(surface.name);
  auto check = [&](const DomainPair& p) {
    if (p.first < 0 || p.first >= n_surfaces || p.second < 0 || p.second >= n_surfaces)
      throw std::invalid_argument("ContactDomain: surface index out of range in a pair");
  };
  for (const DomainPair& p : m_inclusions) check(p);
  for (const DomainPair& p : m_exclusions) check(p);
  for (const auto& [p, interaction] : m_interactions) check(p);

  const auto n_faces = static_cast<Index>(m_faces.size());
  m_face_rigid.assign(m_faces.size(), 0);
  m_face_depth.assign(m_faces.size(), 0.0);
  for (Index f = 0; f < n_faces; ++f) {
    const ContactFace& face = m_faces[f];
    if (!spec.element_body.empty() && spec.element_body[face.element] != NO_INDEX)
      m_face_rigid[f] = 1;
    if (face.shell) continue;  // the node thickness decides, at run time
    const Index* en = topology.nodes.data() + topology.offsets[face.element];
    const Vec3 d = face_centre(en, face.face, position) -
                   face_centre(en, OPPOSITE_HEX_FACE[face.face], position);
    m_face_depth[f] = DEPTH_LIMIT_FRACTION * std::sqrt(d.dot(d));
  }

  // The surface's hex faces that share an edge: each is the other's face across it (an edge
  // of exactly two hex faces; sorted by the edge's nodes, then face and edge number).
  m_face_across.assign(m_faces.size(), {NO_INDEX, NO_INDEX, NO_INDEX, NO_INDEX});
  struct FaceEdge {
    Index low, high, face;
    int edge;
    auto operator<=>(const FaceEdge&) const = default;
  };
  std::vector<FaceEdge> edges;
  for (Index f = 0; f < n_faces; ++f)
    for (int k = 0; k < 4 && !m_faces[f].shell; ++k) {
      const Index a = m_faces[f].nodes[k], b = m_faces[f].nodes[(k + 1) % 4];
      edges.push_back({std::min(a, b), std::max(a, b), f, k});
    }
  std::sort(edges.begin(), edges.end());
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i + 1;
    while (j < edges.size() && edges[j].low == edges[i].low && edges[j].high == edges[i].high) ++j;
    if (j - i == 2) {
      m_face_across[edges[i].face][edges[i].edge] = edges[i + 1].face;
      m_face_across[edges[i + 1].face][edges[i + 1].edge] = edges[i].face;
    }
    i = j;
  }

  // Slave node masks: the surfaces of the faces around the node. A node is rigid when it
  // belongs to a rigid face, double sided when all its faces are shell sides.
  const Index n_slave = m_slaves.size();
  m_slave_mask.assign(static_cast<std::size_t>(n_slave), 0);
  m_slave_rigid.assign(static_cast<std::size_t>(n_slave), 0);
  m_slave_shell.assign(static_cast<std::size_t>(n_slave), 1);
  for (Index f = 0; f < n_faces; ++f)
    for (Index n : m_faces[f].nodes) {
      const Index s = m_slaves.slot(n);
      m_slave_mask[s] |= m_face_mask[f];
      if (m_face_rigid[f]) m_slave_rigid[s] = 1;
      if (!m_faces[f].shell) m_slave_shell[s] = 0;
    }
  // Nodes of node-based surfaces: the surface's bit; a point node is not double sided.
  for (std::size_t k = 0; k < spec.surfaces.size(); ++k)
    for (Index n : spec.surfaces[k].nodes) m_slave_mask[m_slaves.slot(n)] |= std::uint64_t{1} << k;
  for (Index s = 0; s < n_slave; ++s)
    if (m_slaves.point(s)) {
      m_slave_shell[s] = 0;
      if (!spec.rigid_node.empty() && spec.rigid_node[m_slaves.nodes()[s]] != 0)
        m_slave_rigid[s] = 1;
      ++m_point_count;
    }

  // Free shell edges: edges of exactly one shell element (each element counted once, through
  // its SPOS or, failing that, its SNEG side).
  std::map<std::pair<Index, Index>, int> edge_count;
  std::vector<char> counted(static_cast<std::size_t>(topology.element_count()), 0);
  for (const ContactFace& face : m_faces) {
    if (!face.shell || counted[face.element]) continue;
    counted[face.element] = 1;
    for (int a = 0; a < 4; ++a) {
      const Index p = face.nodes[a], q = face.nodes[(a + 1) % 4];
      ++edge_count[{std::min(p, q), std::max(p, q)}];
    }
  }
  m_slave_free_edge.assign(static_cast<std::size_t>(n_slave), 0);
  for (const auto& [edge, count] : edge_count)
    if (count == 1) {
      m_slave_free_edge[m_slaves.slot(edge.first)] = 1;
      m_slave_free_edge[m_slaves.slot(edge.second)] = 1;
    }

  m_everything = m_exclusions.empty() && m_inclusions.size() == 1 && n_surfaces == 1 &&
                 spec.surfaces[0].all_exterior && !m_inclusions[0].one_sided;
}

Real ContactDomain::weight(Index s, Index f, Index& pair) const {
  // Rigid bodies touch deformable faces with their own nodes too, each view with its full
  // weight (header comment); two rigid bodies do not touch.
  if (m_slave_rigid[s] && m_face_rigid[f]) return 0.0;
  const Real full = m_face_rigid[f] || m_slave_rigid[s] ? 1.0 : 0.5;
  if (m_everything) {
    pair = 0;
    return full;
  }
  const std::uint64_t node = m_slave_mask[s], face = m_face_mask[f];
  for (const DomainPair& p : m_exclusions)
    if ((in(node, p.first) && in(face, p.second)) || (in(node, p.second) && in(face, p.first)))
      return 0.0;
  for (std::size_t i = 0; i < m_inclusions.size(); ++i) {
    const DomainPair& p = m_inclusions[i];
    const bool forward = in(node, p.first) && in(face, p.second);
    if (p.one_sided) {
      if (!forward) continue;
      pair = static_cast<Index>(i);
      return 1.0;
    }
    if (forward || (in(node, p.second) && in(face, p.first))) {
      pair = static_cast<Index>(i);
      return full;
    }
  }
  return 0.0;
}

Index ContactDomain::slave_surface(Index s, Index f, Index pair) const {
  if (pair < 0 || pair >= static_cast<Index>(m_inclusions.size())) return NO_INDEX;
  const DomainPair& p = m_inclusions[pair];
  const bool forward = in(m_slave_mask[s], p.first) && in(m_face_mask[f], p.second);
  return forward || p.one_sided ? p.first : p.second;
}

Index ContactDomain::master_surface(Index s, Index f, Index pair) const {
  if (pair < 0 || pair >= static_cast<Index>(m_inclusions.size())) return NO_INDEX;
  const DomainPair& p = m_inclusions[pair];
  return slave_surface(s, f, pair) == p.first ? p.second : p.first;
}

Index ContactDomain::interaction(Index s, Index f) const {
  const std::uint64_t node = m_slave_mask[s], face = m_face_mask[f];
  for (const auto& [p, interaction] : m_interactions)
    if ((in(node, p.first) && in(face, p.second)) || (in(node, p.second) && in(face, p.first)))
      return interaction;
  return m_default_interaction;
}

bool ContactDomain::may_use(Index s, Index interaction) const {
  if (interaction == m_default_interaction) return true;
  const std::uint64_t node = m_slave_mask[s];
  for (const auto& [p, i] : m_interactions)
    if (i == interaction && (in(node, p.first) || in(node, p.second))) return true;
  return false;
}

}  // namespace xpl::contact
