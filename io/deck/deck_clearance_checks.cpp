/// \file Checks of a *CONTACT CLEARANCE ASSIGNMENT against the surfaces it names (SPEC C8,
/// C10): single-sided surfaces with no edge on more than two faces and consistent normals,
/// clearances >= 0 where solids are involved, slave nodes that are not all on rigid bodies.

#include <algorithm>
#include <cmath>

#include "contact/contact_faces.hpp"
#include "io/deck/deck_handlers.hpp"

namespace xpl::io {

namespace {

/// The (slave, master) surface pairs of an assignment's view that exist: none with a
/// node-based master (SPEC C13, the reader refuses a view word that asks for one).
std::vector<std::pair<Index, Index>> views_of(const Model& model,
                                              const ClearanceAssignment& assignment) {
  std::vector<std::pair<Index, Index>> views;
  switch (assignment.view) {
    case ClearanceAssignment::View::Master:
      views = {{assignment.second, assignment.first}};
      break;
    case ClearanceAssignment::View::Slave:
      views = {{assignment.first, assignment.second}};
      break;
    case ClearanceAssignment::View::Both:
      views = {{assignment.first, assignment.second}, {assignment.second, assignment.first}};
      break;
  }
  std::erase_if(views, [&](const std::pair<Index, Index>& v) {
    return model.surfaces[static_cast<std::size_t>(v.second)].type == Surface::Type::Node;
  });
  return views;
}

/// One side of a face edge: the edge's node indices (ascending) and whether the face runs
/// through it from the lower to the higher index.
struct FaceEdge {
  Index low = NO_INDEX, high = NO_INDEX;
  bool ascending = true;
  Index element = NO_INDEX;
};

}  // namespace

bool check_clearance_surface(DeckState& deck, Index surface, const SourceLocation& where,
                             const char* keyword) {
  std::uint8_t& state = deck.clearance_surface_state[static_cast<std::size_t>(surface)];
  if (state != 0) return state == 1;
  state = 2;
  const Surface& s = deck.model.surfaces[static_cast<std::size_t>(surface)];
  std::vector<ElementFace> faces = s.faces;
  const auto by_element = [](const ElementFace& a, const ElementFace& b) {
    return a.element != b.element ? a.element < b.element : a.face < b.face;
  };
  std::sort(faces.begin(), faces.end(), by_element);
  faces.erase(std::unique(faces.begin(), faces.end(),
                          [](const ElementFace& a, const ElementFace& b) {
                            return a.element == b.element && a.face == b.face;
                          }),
              faces.end());
  const auto is_shell_face = [&](const ElementFace& f) {
    return is_shell(deck.model.element_types[static_cast<std::size_t>(f.element)]);
  };
  for (std::size_t i = 1; i < faces.size(); ++i) {
    if (faces[i].element == faces[i - 1].element && is_shell_face(faces[i])) {
      deck.errors.add(where, keyword,
                      "surface " + s.name +
                          " is not single sided: it holds both SPOS and SNEG of " + "S4R element " +
                          std::to_string(deck.model.element_ids[faces[i].element]),
                      "expected one side of each shell (SPOS or SNEG; a surface line without a "
                      "face label takes both sides)");
      return false;
    }
  }

  // Faces in the outward corner order of the contact domain, as the solver will see them.
  std::vector<contact::ElementKind> kinds(static_cast<std::size_t>(deck.model.element_count()));
  for (std::size_t e = 0; e < kinds.size(); ++e)
    kinds[e] = is_shell(deck.model.element_types[e]) ? contact::ElementKind::Shell
                                                     : contact::ElementKind::Hex;
  std::vector<contact::FaceRef> refs;
  for (const ElementFace& f : faces) refs.push_back({f.element, f.face});
  const contact::ElementTopology topology{deck.model.element_offsets, deck.model.element_nodes,
                                          kinds};
  std::vector<FaceEdge> edges;
  for (const contact::ContactFace& face : contact::surface_faces(topology, refs, surface)) {
    for (std::size_t k = 0; k < 4; ++k) {
      const Index a = face.nodes[k], b = face.nodes[(k + 1) % 4];
      if (a == b || a == NO_INDEX || b == NO_INDEX) continue;  // collapsed or undefined node
      edges.push_back({std::min(a, b), std::max(a, b), a < b, face.element});
    }
  }
  std::stable_sort(edges.begin(), edges.end(), [](const FaceEdge& a, const FaceEdge& b) {
    return a.low != b.low ? a.low < b.low : a.high < b.high;
  });
  const auto edge_text = [&](const FaceEdge& edge) {
    const ExternalId a = deck.model.node_ids[static_cast<std::size_t>(edge.low)];
    const ExternalId b = deck.model.node_ids[static_cast<std::size_t>(edge.high)];
    return "the edge of nodes " + std::to_string(std::min(a, b)) + " and " +
           std::to_string(std::max(a, b));
  };
  bool crowded = false, flipped = false;
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i + 1;
    while (j < edges.size() && edges[j].low == edges[i].low && edges[j].high == edges[i].high) ++j;
    if (j - i > 2 && !crowded) {
      crowded = true;
      deck.errors.add(where, keyword,
                      "surface " + s.name + " has " + edge_text(edges[i]) + " on " +
                          std::to_string(j - i) + " of its faces",
                      "expected each edge on at most two faces of a surface with a clearance");
    } else if (j - i == 2 && edges[i].ascending == edges[i + 1].ascending && !flipped) {
      flipped = true;
      deck.errors.add(
          where, keyword,
          "surface " + s.name + " has discontinuous normals: elements " +
              std::to_string(deck.model.element_ids[edges[i].element]) + " and " +
              std::to_string(deck.model.element_ids[edges[i + 1].element]) + " run through " +
              edge_text(edges[i]) + " in the same direction",
          "expected neighbouring faces with their normals on the same side (swap SPOS and SNEG "
          "of one of them)");
    }
    i = j;
  }
  if (crowded || flipped) return false;
  state = 1;
  return true;
}

bool check_clearance_sign(DeckState& deck, const PendingClearanceAssignment& pending) {
  const ClearanceAssignment& assignment = pending.assignment;
  const char* keyword = assignment_keyword(pending.initialization);
  const ContactClearance& clearance =
      deck.model.contact_clearances[static_cast<std::size_t>(assignment.clearance)];
  const auto surface = [&](Index s) -> const Surface& {
    return deck.model.surfaces[static_cast<std::size_t>(s)];
  };
  const auto solid = [&](Index s) {
    return std::any_of(surface(s).faces.begin(), surface(s).faces.end(), [&](const ElementFace& f) {
      return is_hex(deck.model.element_types[static_cast<std::size_t>(f.element)]);
    });
  };
  const std::string expected =
      "expected a clearance >= 0 where the slave nodes or the master faces are on solids (a "
      "negative clearance is a gap below the normal of a shell surface)";
  const NodalDistribution* distribution =
      clearance.distribution == NO_INDEX
          ? nullptr
          : &deck.model.distributions[static_cast<std::size_t>(clearance.distribution)];
  if (distribution == nullptr && clearance.value >= 0.0) return true;
  for (const auto& [slave, master] : views_of(deck.model, assignment)) {
    if (!solid(slave) && !solid(master)) continue;
    const std::string between = "between surfaces " + surface(slave).name + " (slave) and " +
                                surface(master).name + " (master), and " +
                                surface(solid(slave) ? slave : master).name +
                                " is on C3D8R solid elements";
    if (distribution == nullptr) {
      deck.errors.add(assignment.where, keyword,
                      "clearance " + clearance.name + " is negative (" +
                          number_text(clearance.value) + ") " + between,
                      expected);
      return false;
    }
    // The slave nodes' own values, and the master nodes' when a slave node takes its value
    // from its master face (SPEC C8).
    const auto nodes_of = [&](Index s) {
      std::vector<Index> nodes = surface(s).nodes;  // a node-based surface's (SPEC C13)
      for (const ElementFace& f : surface(s).faces) {
        const Index* element_nodes = deck.model.nodes_of(f.element);
        const int count =
            nodes_per_element(deck.model.element_types[static_cast<std::size_t>(f.element)]);
        nodes.insert(nodes.end(), element_nodes, element_nodes + count);
      }
      std::sort(nodes.begin(), nodes.end());
      nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
      nodes.erase(std::remove(nodes.begin(), nodes.end(), NO_INDEX), nodes.end());
      return nodes;
    };
    std::vector<Index> nodes = nodes_of(slave);
    const std::vector<Real>& values = distribution->values;
    if (std::any_of(nodes.begin(), nodes.end(), [&](Index n) { return std::isnan(values[n]); })) {
      const std::vector<Index> master_nodes = nodes_of(master);
      nodes.insert(nodes.end(), master_nodes.begin(), master_nodes.end());
    }
    const auto negative =
        std::find_if(nodes.begin(), nodes.end(), [&](Index n) { return values[n] < 0.0; });
    if (negative == nodes.end()) continue;
    deck.errors.add(assignment.where, keyword,
                    "clearance " + clearance.name + " is negative (" +
                        number_text(values[*negative]) + " at node " +
                        std::to_string(deck.model.node_ids[*negative]) + " in distribution " +
                        distribution->name + ") " + between,
                    expected);
    return false;
  }
  return true;
}

bool check_clearance_slaves(DeckState& deck, const PendingClearanceAssignment& pending) {
  const ClearanceAssignment& assignment = pending.assignment;
  const char* keyword = assignment_keyword(pending.initialization);
  std::vector<char> rigid(static_cast<std::size_t>(deck.model.element_count()), 0);
  for (const RigidBody& body : deck.model.rigid_bodies)
    if (body.element_set != NO_INDEX)
      for (Index e : deck.model.element_sets[static_cast<std::size_t>(body.element_set)].members)
        rigid[static_cast<std::size_t>(e)] = 1;
  // A slave node of a rigid body moves with its reference node: nothing to adjust or offset.
  std::vector<std::string> names;
  for (const auto& [slave, master] : views_of(deck.model, assignment)) {
    const Surface& s = deck.model.surfaces[static_cast<std::size_t>(slave)];
    if (s.faces.empty() || std::any_of(s.faces.begin(), s.faces.end(), [&](const ElementFace& f) {
          return rigid[static_cast<std::size_t>(f.element)] == 0;
        }))
      return true;
    names.push_back(s.name);
  }
  const std::string problem =
      names.size() == 1 ? "slave surface " + names[0] +
                              " lies wholly on rigid bodies: the assignment has no "
                              "slave nodes"
                        : "surfaces " + names[0] + " and " + names[1] +
                              " lie wholly on rigid bodies: the assignment has no slave nodes";
  deck.errors.add(assignment.where, keyword, problem,
                  "expected a deformable slave surface (elements outside *RIGID BODY, ELSET=): "
                  "MASTER makes surface 2 the slave, SLAVE surface 1");
  return false;
}

}  // namespace xpl::io
