/// \file Resolution of *SURFACE data lines into element faces or nodes once the whole deck is
/// read, including element-based lines without a face label: both sides of shells and the
/// exposed faces of solids, as Abaqus does.

#include <algorithm>
#include <array>
#include <optional>
#include <utility>

#include "io/deck/deck_handlers.hpp"

namespace xpl::io {

namespace {

/// Corner nodes of face `face` of hex `e`, sorted: equal for the two sides of a shared face.
std::array<Index, 4> hex_face_key(const Model& model, Index e, int face) {
  const Index* nodes = model.nodes_of(e);
  std::array<Index, 4> key{};
  for (int k = 0; k < 4; ++k) key[static_cast<std::size_t>(k)] = nodes[HEX_FACE_NODES[face][k]];
  std::sort(key.begin(), key.end());
  return key;
}

}  // namespace

void resolve_surfaces(DeckState& deck) {
  std::optional<ModelFaceIndex> face_index;  // built for the first line naming geometry
  for (std::size_t s = 0; s < deck.model.surfaces.size(); ++s) {
    Surface& surface = deck.model.surfaces[s];
    std::vector<Index> solids;  // of lines without a face label: one search for the surface
    for (const PendingSurfaceItem& item : deck.surface_items[s]) {
      if (surface.type == Surface::Type::Node) {
        const std::vector<Index> nodes = resolve_nodes(deck, item.target);
        surface.nodes.insert(surface.nodes.end(), nodes.begin(), nodes.end());
        surface.node_areas.insert(surface.node_areas.end(), nodes.size(), item.node_area);
        continue;
      }
      // Faces of section-less CPS4/CPS3 (mesh exports): matched to the faces they lie on.
      if (const std::vector<Index> geometry = geometry_of(deck, item.target); !geometry.empty()) {
        if (!face_index) face_index = index_model_faces(deck.model);
        add_geometry_faces(deck, *face_index, geometry, item, surface);
        const Index set = deck.model.find_element_set(item.target.token);
        if (set == NO_INDEX ||
            deck.model.element_sets[static_cast<std::size_t>(set)].members.empty())
          continue;
      }
      const std::vector<Index> elements = resolve_elements(deck, item.target);
      if (item.all_faces) {
        // Shells: both sides (a double-sided surface). Solids: the faces no other solid
        // element shares, so that a pressure or a contact surface never sits inside a body.
        for (Index e : elements) {
          if (is_shell(deck.model.element_types[static_cast<std::size_t>(e)]))
            surface.faces.insert(surface.faces.end(), {{e, SHELL_FACE_NEG}, {e, SHELL_FACE_POS}});
          else
            solids.push_back(e);
        }
        continue;
      }
      bool reported = false;  // one mismatch per data line, not one per element of a set
      for (Index e : elements) {
        const ElementType type = deck.model.element_types[static_cast<std::size_t>(e)];
        if (is_shell(type) == item.shell) {
          surface.faces.push_back({e, static_cast<std::uint8_t>(item.face)});
        } else if (!reported) {
          reported = true;
          deck.errors.add(
              item.target.where, item.target.keyword,
              "face " + item.label + " does not fit " + element_text(deck, e, item.target),
              is_shell(type) ? "expected SPOS or SNEG on S4R shell elements"
                             : "expected S1..S6 on C3D8R solid elements");
        }
      }
    }
    if (!solids.empty()) {
      std::sort(solids.begin(), solids.end());
      solids.erase(std::unique(solids.begin(), solids.end()), solids.end());
      const std::vector<ElementFace> exposed = exposed_hex_faces(deck, solids);
      surface.faces.insert(surface.faces.end(), exposed.begin(), exposed.end());
    }
    // Ascending, each node once; a node listed twice keeps the area of its last line.
    std::vector<std::pair<Index, Real>> listed;
    for (std::size_t k = 0; k < surface.nodes.size(); ++k)
      listed.emplace_back(surface.nodes[k], surface.node_areas[k]);
    std::stable_sort(listed.begin(), listed.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    surface.nodes.clear();
    surface.node_areas.clear();
    for (std::size_t k = 0; k < listed.size(); ++k) {
      if (k + 1 < listed.size() && listed[k + 1].first == listed[k].first) continue;
      surface.nodes.push_back(listed[k].first);
      surface.node_areas.push_back(listed[k].second);
    }
  }
}

std::vector<ElementFace> exposed_hex_faces(DeckState& deck, const std::vector<Index>& elements) {
  const auto is_hex = [&](Index e) {
    return xpl::is_hex(deck.model.element_types[static_cast<std::size_t>(e)]);
  };
  // A face with an undefined node (reported already) cannot be matched: skip its element.
  const auto complete = [&](Index e) {
    const Index* nodes = deck.model.nodes_of(e);
    return std::none_of(nodes, nodes + 8, [](Index n) { return n == NO_INDEX; });
  };
  // Only the faces of the given elements are stored; every C3D8R face of the model is then
  // looked up among them once. A face met once (by its own element) is exposed.
  struct Candidate {
    std::array<Index, 4> key;
    ElementFace face;
    int count = 0;
  };
  std::vector<Candidate> candidates;
  for (Index e : elements)
    if (is_hex(e) && complete(e))
      for (int f = 0; f < 6; ++f)
        candidates.push_back({hex_face_key(deck.model, e, f), {e, static_cast<std::uint8_t>(f)}});
  if (candidates.empty()) return {};
  const auto by_key = [](const Candidate& a, const Candidate& b) { return a.key < b.key; };
  std::sort(candidates.begin(), candidates.end(), by_key);
  for (Index e = 0; e < deck.model.element_count(); ++e) {
    if (!is_hex(e) || !complete(e)) continue;
    for (int f = 0; f < 6; ++f) {
      const Candidate probe{hex_face_key(deck.model, e, f), {}};
      auto [first, last] = std::equal_range(candidates.begin(), candidates.end(), probe, by_key);
      for (; first != last; ++first) ++first->count;
    }
  }
  std::vector<ElementFace> faces;
  for (const Candidate& candidate : candidates)
    if (candidate.count == 1) faces.push_back(candidate.face);
  std::sort(faces.begin(), faces.end(), [](const ElementFace& a, const ElementFace& b) {
    return a.element != b.element ? a.element < b.element : a.face < b.face;
  });
  return faces;
}

}  // namespace xpl::io
