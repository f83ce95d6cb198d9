/// \file Decks as mesh generators export them. gmsh writes one `*ELEMENT` block per geometric
/// entity, the faces of every physical surface as CPS4/CPS3 and the edges of every physical
/// curve as T3D2/T3D3, with an `*ELSET` per physical group. Without a section such a block is
/// geometry: not analysed, its element sets are node sets of their nodes and can define
/// element-based *SURFACEs (their faces matched to the solid or shell faces they lie on). CPS4
/// under a *SHELL SECTION run as S4R (gmsh cannot write shell names). Element names that
/// Abaqus/Explicit itself does not have (meshio writes C3D8RH, CAX4P, R3D3) are refused with the
/// nearest supported type.

#include <algorithm>
#include <array>
#include <string_view>
#include <utility>

#include "io/deck/deck_handlers.hpp"
#include "io/deck/deck_numbers.hpp"

namespace xpl::io {

namespace {

/// Nodes per geometry element type, 0 if `type` is none.
int geometry_nodes(std::string_view type) {
  if (type == "CPS4") return 4;
  if (type == "CPS3" || type == "T3D3") return 3;
  if (type == "T3D2") return 2;
  return 0;
}

bool is_edge(std::string_view type) {
  return type == "T3D2" || type == "T3D3";
}

/// The geometry elements of element set `set`, whether listed by id, range, block or nested
/// set, before the sets are resolved (for the shell sections that promote CPS4 to S4R).
void collect_geometry(const DeckState& deck, Index set, int depth, std::vector<char>& seen,
                      std::vector<Index>& out) {
  if (depth > 100 || seen[static_cast<std::size_t>(set)]) return;
  seen[static_cast<std::size_t>(set)] = 1;
  const PendingSet& pending = deck.element_sets[static_cast<std::size_t>(set)];
  out.insert(out.end(), pending.geometry_members.begin(), pending.geometry_members.end());
  for (const SetItem& item : pending.items) {
    if (item.kind == SetItem::Kind::Id) {
      const auto it = deck.geometry_index.find(item.first);
      if (it != deck.geometry_index.end()) out.push_back(it->second);
    } else if (item.kind == SetItem::Kind::Range) {
      for (const auto& [key, g] : deck.geometry_index)
        if (key >= item.first && key <= item.last && (key - item.first) % item.increment == 0)
          out.push_back(g);
    } else if (item.kind == SetItem::Kind::SetName) {
      const auto it = deck.element_set_by_name.find(item.name);
      if (it != deck.element_set_by_name.end())
        collect_geometry(deck, it->second, depth + 1, seen, out);
    }
  }
}

/// The geometry elements under the section of set `name` (upper case, scoped).
std::vector<Index> geometry_under(const DeckState& deck, const std::string& name) {
  std::vector<Index> out;
  const auto it = deck.element_set_by_name.find(name);
  if (it == deck.element_set_by_name.end()) return out;
  std::vector<char> seen(deck.element_sets.size(), 0);
  collect_geometry(deck, it->second, 0, seen, out);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

/// Sorted distinct corner nodes of a face, padded with NO_INDEX: a degenerate hex face (a
/// collapsed corner) matches a triangle.
std::array<Index, 4> face_key(std::array<Index, 4> nodes, int count) {
  const std::size_t n = count < 4 ? static_cast<std::size_t>(count) : 4;
  for (std::size_t i = 1; i < n; ++i)  // insertion sort of at most four
    for (std::size_t j = i; j > 0 && nodes[j - 1] > nodes[j]; --j)
      std::swap(nodes[j - 1], nodes[j]);
  std::size_t distinct = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (distinct == 0 || nodes[i] != nodes[distinct - 1]) nodes[distinct++] = nodes[i];
  for (std::size_t k = distinct; k < 4; ++k) nodes[k] = NO_INDEX;
  return nodes;
}

}  // namespace

bool is_geometry_type(std::string_view type) {
  return geometry_nodes(type) > 0;
}

std::string nearest_supported_type(std::string_view type) {
  const auto starts = [&](std::string_view prefix) { return type.starts_with(prefix); };
  if (starts("C3D8") || starts("SC8"))
    return "C3D8R (or C3D8); " + std::string(type) +
           (type.ends_with("H") ? " is a hybrid element of Abaqus/Standard (meshio names every "
                                  "hexahedron so)"
                                : " is not an Abaqus/Explicit element xpl reads");
  if (starts("C3D20") || starts("C3D27"))
    return "C3D8R: quadratic hexahedra are not supported; mesh with linear C3D8R/C3D8 (about "
           "twice the elements per edge)";
  if (starts("C3D4") || starts("C3D10") || starts("C3D6") || starts("C3D15"))
    return "C3D8R: xpl has no tetrahedra or wedges; mesh the solid with hexahedra";
  if (starts("CAX") || starts("CPE") || starts("CPS") || starts("CGAX"))
    return "S4R for a thin plate (CPS4 without a section is read as geometry; CPS4 under a "
           "*SHELL SECTION runs as S4R) or C3D8R one element thick; " +
           std::string(type) + " is a two-dimensional (plane or axisymmetric) element";
  if (starts("R3D") || starts("RAX") || starts("R2D"))
    return "S4R elements in a *RIGID BODY (quadrilaterals; xpl has no triangles)";
  if (starts("S3") || starts("S8") || starts("S9") || starts("STRI") || starts("S4"))
    return "S4R (four-node quadrilateral shell, reduced integration)";
  if (starts("B3") || starts("T3D") || starts("T2D") || starts("B2"))
    return "none: xpl has no beams or trusses; model the member with S4R or C3D8R";
  if (starts("M3D")) return "S4R (a membrane is a shell without bending stiffness)";
  return "";
}

void read_geometry_elements(DeckState& deck, const DeckBlock& block, const std::string& type) {
  const DeckKeyword& keyword = block.keyword;
  const int n_nodes = geometry_nodes(type);
  GeometryBlock geometry;
  geometry.type = type;
  geometry.element_set = deck.scoped_name(optional_name(keyword, "ELSET"));
  geometry.where = keyword.where;
  const Index block_index = static_cast<Index>(deck.geometry_blocks.size());
  const Index set = geometry.element_set.empty()
                        ? NO_INDEX
                        : element_set_index(deck, geometry.element_set, keyword.where);
  for (const DeckDataLine& line : block.data) {
    const std::optional<long long> id = integer_field(deck, line, keyword, 0, "element id");
    if (!id) continue;
    if (*id <= 0) {
      error(deck, line.where(), keyword, "element id " + std::to_string(*id) + " is not positive",
            "expected ids 1, 2, ...");
      continue;
    }
    if (line.fields.size() != static_cast<std::size_t>(n_nodes) + 1) {
      error(deck, line.where(), keyword,
            "element " + std::to_string(*id) + " has " + std::to_string(line.fields.size() - 1) +
                " node ids",
            "expected " + std::to_string(n_nodes) + " node ids for " + type);
      continue;
    }
    GeometryElement element;
    element.id = DeckState::id_key(deck.scope, *id);
    element.n_nodes = n_nodes;
    element.block = block_index;
    bool ok = true;
    for (int k = 0; k < n_nodes; ++k) {
      const std::optional<long long> node =
          integer_field(deck, line, keyword, static_cast<std::size_t>(k) + 1, "node id");
      ok = ok && node.has_value();
      if (node)
        element.node_ids[static_cast<std::size_t>(k)] = DeckState::id_key(deck.scope, *node);
    }
    if (!ok) continue;
    const Index index = static_cast<Index>(deck.geometry_elements.size());
    if (deck.element_index.contains(element.id) || deck.point_element_index.contains(element.id) ||
        !deck.geometry_index.emplace(element.id, index).second) {
      error(deck, line.where(), keyword, "element " + std::to_string(*id) + " is defined twice",
            "expected each element id once");
      continue;
    }
    deck.geometry_elements.push_back(element);
    ++geometry.count;
    if (set != NO_INDEX)
      deck.element_sets[static_cast<std::size_t>(set)].geometry_members.push_back(index);
  }
  deck.geometry_blocks.push_back(std::move(geometry));
}

void promote_shell_geometry(DeckState& deck) {
  if (deck.geometry_elements.empty()) return;
  std::vector<char> promote(deck.geometry_elements.size(), 0);
  const auto check = [&](const std::string& set, bool shell, const SourceLocation& where) {
    for (Index g : geometry_under(deck, set)) {
      GeometryElement& element = deck.geometry_elements[static_cast<std::size_t>(g)];
      GeometryBlock& block = deck.geometry_blocks[static_cast<std::size_t>(element.block)];
      if (shell && block.type == "CPS4") {
        promote[static_cast<std::size_t>(g)] = 1;
        continue;
      }
      if (block.section_reported) continue;
      block.section_reported = true;
      const std::string keyword = shell ? "*SHELL SECTION" : "*SOLID SECTION";
      std::string expected;
      if (is_edge(block.type))
        expected = "no section on " + block.type +
                   " edges: xpl has no trusses or beams; without a section they are geometry "
                   "(node sets of their nodes)";
      else if (shell)
        expected =
            "quadrilaterals (CPS4 under a *SHELL SECTION run as S4R): xpl has no "
            "triangular shell; remesh the surface with quadrilaterals (gmsh: Recombine)";
      else
        expected =
            "a *SHELL SECTION (CPS4 then run as S4R) or no section (geometry): " + block.type +
            " is a plane-stress element and xpl is three-dimensional";
      deck.errors.add(where, keyword,
                      block.type + " elements of the block at " + location_text(block.where) +
                          " in ELSET=" + set,
                      "expected " + expected);
    }
  };
  for (std::size_t s = 0; s < deck.shell_sections.size(); ++s)
    check(deck.shell_sections[s].element_set, true, deck.model.shell_sections[s].where);
  for (std::size_t s = 0; s < deck.sections.size(); ++s)
    check(deck.sections[s].element_set, false, deck.model.solid_sections[s].where);

  // In deck order, so that a plate of CPS4 reads exactly as the same plate of S4R.
  for (std::size_t g = 0; g < deck.geometry_elements.size(); ++g) {
    if (!promote[g]) continue;
    GeometryElement& element = deck.geometry_elements[g];
    GeometryBlock& block = deck.geometry_blocks[static_cast<std::size_t>(element.block)];
    const Index e = deck.model.element_count();
    deck.element_index.emplace(element.id, e);
    deck.geometry_index.erase(element.id);
    element.promoted = true;
    ++block.promoted;
    if (deck.assembly_model) deck.element_scopes.push_back(element.id >> SCOPE_SHIFT);
    deck.model.element_ids.push_back(deck.local_id(element.id));
    deck.model.element_types.push_back(ElementType::S4R);
    deck.element_node_ids.insert(deck.element_node_ids.end(), element.node_ids.begin(),
                                 element.node_ids.begin() + element.n_nodes);
    deck.model.element_offsets.push_back(static_cast<Index>(deck.element_node_ids.size()));
    deck.model.add_element_source(block.where.file, block.where.line);
  }
  for (const GeometryBlock& block : deck.geometry_blocks)
    if (block.promoted > 0)
      deck.model.deck_messages.push_back(
          {false, location_text(block.where) + ": *ELEMENT: " + std::to_string(block.promoted) +
                      " CPS4 elements" +
                      (block.element_set.empty() ? "" : " (ELSET=" + block.element_set + ")") +
                      " are under a *SHELL SECTION: run as S4R shells (a mesher such as gmsh "
                      "cannot write shell element names)"});
}

void geometry_node_sets(DeckState& deck) {
  if (deck.geometry_elements.empty()) return;
  std::string made;
  const std::size_t n_sets = deck.element_sets.size();
  for (std::size_t s = 0; s < n_sets; ++s) {
    const PendingSet& pending = deck.element_sets[s];
    const std::string name = deck.model.element_sets[s].name;
    if (pending.geometry_members.empty() || !deck.model.element_sets[s].members.empty() ||
        deck.node_set_by_name.contains(name))
      continue;
    std::vector<Index> nodes;
    for (Index g : pending.geometry_members) {
      const GeometryElement& element = deck.geometry_elements[static_cast<std::size_t>(g)];
      for (int k = 0; k < element.n_nodes; ++k) {
        const auto it = deck.node_index.find(element.node_ids[static_cast<std::size_t>(k)]);
        if (it != deck.node_index.end()) nodes.push_back(it->second);
      }
    }
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    const Index set = node_set_index(deck, name, deck.model.element_sets[s].where);
    made += (made.empty() ? "" : ", ") + name + " (" + std::to_string(nodes.size()) + ")";
    deck.model.node_sets[static_cast<std::size_t>(set)].members = std::move(nodes);
    deck.node_sets[static_cast<std::size_t>(set)].state = 2;
  }
  for (const GeometryBlock& block : deck.geometry_blocks)
    if (block.count > block.promoted)
      deck.model.deck_messages.push_back(
          {false, location_text(block.where) +
                      ": *ELEMENT: " + std::to_string(block.count - block.promoted) + " " +
                      block.type + " elements" +
                      (block.element_set.empty() ? "" : " (ELSET=" + block.element_set + ")") +
                      " carry no section: read as geometry, not analysed (their element sets "
                      "give node sets of their nodes" +
                      (is_edge(block.type)
                           ? std::string(")")
                           : std::string(", and their faces can define element-based *SURFACEs "
                                         "on the solid or shell faces they lie on)"))});
  if (!made.empty())
    deck.model.deck_messages.push_back(
        {false,
         deck.file_name + ": node sets made from element sets of geometry (nodes): " + made});
}

void resolve_geometry_node_ids(DeckState& deck) {
  for (const GeometryElement& element : deck.geometry_elements) {
    if (element.promoted) continue;
    for (int k = 0; k < element.n_nodes; ++k) {
      const ExternalId id = element.node_ids[static_cast<std::size_t>(k)];
      if (deck.node_index.contains(id)) continue;
      const GeometryBlock& block = deck.geometry_blocks[static_cast<std::size_t>(element.block)];
      capped_error(deck, deck.error_counts[UNDEFINED_NODES], block.where, "*ELEMENT",
                   block.type + " element " + deck.id_text(element.id) +
                       " refers to undefined node " + deck.id_text(id),
                   "expected a *NODE with id " + std::to_string(deck.local_id(id)));
      break;
    }
  }
}

std::vector<Index> geometry_of(const DeckState& deck, const DeckReference& reference) {
  if (deck.geometry_elements.empty() || reference.token.empty()) return {};
  if (looks_numeric(reference.token)) {
    const std::optional<long long> id = parse_integer(reference.token);
    if (!id) return {};
    const auto it = deck.geometry_index.find(DeckState::id_key(reference.scope, *id));
    return it == deck.geometry_index.end() ? std::vector<Index>{} : std::vector<Index>{it->second};
  }
  const auto it = deck.element_set_by_name.find(reference.token);
  if (it == deck.element_set_by_name.end()) return {};
  return deck.element_sets[static_cast<std::size_t>(it->second)].geometry_members;
}

ModelFaceIndex index_model_faces(const Model& model) {
  ModelFaceIndex index;
  for (Index e = 0; e < model.element_count(); ++e) {
    const ElementType type = model.element_types[static_cast<std::size_t>(e)];
    const Index* nodes = model.nodes_of(e);
    if (std::any_of(nodes, nodes + nodes_per_element(type), [](Index n) { return n == NO_INDEX; }))
      continue;
    if (is_shell(type)) {
      index.faces.push_back(
          {face_key({nodes[0], nodes[1], nodes[2], nodes[3]}, 4), {e, SHELL_FACE_NEG}});
      continue;
    }
    for (int f = 0; f < 6; ++f) {
      std::array<Index, 4> corners{};
      for (int k = 0; k < 4; ++k)
        corners[static_cast<std::size_t>(k)] = nodes[HEX_FACE_NODES[f][k]];
      index.faces.push_back({face_key(corners, 4), {e, static_cast<std::uint8_t>(f)}});
    }
  }
  std::sort(index.faces.begin(), index.faces.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  return index;
}

void add_geometry_faces(DeckState& deck, const ModelFaceIndex& index,
                        const std::vector<Index>& geometry, const PendingSurfaceItem& item,
                        Surface& surface) {
  const DeckReference& target = item.target;
  if (!item.all_faces) {
    deck.errors.add(target.where, target.keyword,
                    "face label " + item.label + " on geometry elements of " + target.token,
                    "expected no face label: the faces of section-less CPS4/CPS3 elements are "
                    "matched to the solid or shell faces they lie on");
    return;
  }
  Index unmatched = 0, inner = 0;
  std::string first_unmatched, first_inner;
  for (Index g : geometry) {
    const GeometryElement& element = deck.geometry_elements[static_cast<std::size_t>(g)];
    const GeometryBlock& block = deck.geometry_blocks[static_cast<std::size_t>(element.block)];
    if (is_edge(block.type)) {
      deck.errors.add(target.where, target.keyword,
                      block.type + " element " + deck.id_text(element.id) + " of " + target.token +
                          " is an edge",
                      "expected faces (CPS4, CPS3) or solid and shell elements in an element-"
                      "based surface; an edge set is a node set");
      return;
    }
    std::array<Index, 4> nodes{};
    bool complete = true;
    for (int k = 0; k < element.n_nodes; ++k) {
      const auto it = deck.node_index.find(element.node_ids[static_cast<std::size_t>(k)]);
      complete = complete && it != deck.node_index.end();
      if (complete) nodes[static_cast<std::size_t>(k)] = it->second;
    }
    if (!complete) continue;  // reported by resolve_geometry_node_ids
    const std::array<Index, 4> key = face_key(nodes, element.n_nodes);
    auto [first, last] =
        std::equal_range(index.faces.begin(), index.faces.end(), std::make_pair(key, ElementFace{}),
                         [](const auto& a, const auto& b) { return a.first < b.first; });
    const auto count = last - first;
    const bool shell =
        count > 0 &&
        is_shell(deck.model.element_types[static_cast<std::size_t>(first->second.element)]);
    if (count == 1 && shell) {
      // A shell's both sides, as a surface on a shell without a face label in Abaqus.
      surface.faces.push_back({first->second.element, SHELL_FACE_NEG});
      surface.faces.push_back({first->second.element, SHELL_FACE_POS});
    } else if (count == 1) {
      surface.faces.push_back(first->second);
    } else if (count == 0) {
      if (unmatched++ == 0) first_unmatched = deck.id_text(element.id);
    } else if (inner++ == 0) {
      first_inner = deck.id_text(element.id);
    }
  }
  const std::string what = geometry.size() == 1 ? "" : " of " + target.token;
  if (unmatched > 0)
    deck.errors.add(target.where, target.keyword,
                    std::to_string(unmatched) + " geometry faces" + what + " (first: element " +
                        first_unmatched + ") lie on no solid or shell face",
                    "expected faces whose nodes are the corner nodes of a face of a C3D8R/C3D8 "
                    "or of an S4R element");
  if (inner > 0)
    deck.errors.add(target.where, target.keyword,
                    std::to_string(inner) + " geometry faces" + what + " (first: element " +
                        first_inner + ") lie between two elements, inside the body",
                    "expected faces on the boundary of the mesh");
}

}  // namespace xpl::io
