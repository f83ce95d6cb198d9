/// \file Mesh keywords: *HEADING, *NODE, *ELEMENT (C3D8R, S4R), *NSET, *ELSET, *SURFACE.

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <string>

#include "common/error.hpp"
#include "io/deck/deck_handlers.hpp"
#include "io/deck/deck_numbers.hpp"

namespace xpl::io {

namespace {

std::string id_text(long long id) {
  return std::to_string(id);
}

/// Makes room for `extra` more items: exactly for the first block of a mesh (no slack in the
/// usual one-block mesh), geometrically after (no quadratic copying over many small blocks).
template <typename Container>
void reserve_more(Container& container, std::size_t capacity, std::size_t extra) {
  const std::size_t needed = container.size() + extra;
  if (needed > capacity) container.reserve(std::max(needed, 2 * capacity));
}

/// In a deck with parts, ids are keyed per instance (DeckState::id_key): reported if too large.
bool check_scoped_id(DeckState& deck, const DeckDataLine& line, const DeckKeyword& keyword,
                     long long id, const char* what) {
  if (!deck.assembly_model || id <= MAX_SCOPED_ID) return true;
  error(deck, line.where(), keyword, std::string(what) + " id " + id_text(id) + " is too large",
        "expected ids below " + id_text(MAX_SCOPED_ID + 1) + " in a deck with parts");
  return false;
}

/// Places a node of an instance: x' = a + R (x + t − a), translation first (Abaqus' order).
void place_node(const DeckInstance& instance, Real x[3]) {
  for (std::size_t c = 0; c < 3; ++c) x[c] += instance.translation[c];
  if (!instance.rotated) return;
  const Real d[3] = {x[0] - instance.axis_a[0], x[1] - instance.axis_a[1],
                     x[2] - instance.axis_a[2]};
  const std::array<Real, 9>& r = instance.rotation;
  for (std::size_t c = 0; c < 3; ++c)
    x[c] = instance.axis_a[c] + (r[3 * c] * d[0] + r[3 * c + 1] * d[1] + r[3 * c + 2] * d[2]);
}

}  // namespace

void read_heading(DeckState& deck, const DeckBlock& block) {
  check_parameters(deck, block.keyword, {});
  // The title is echoed in JOB.msg and stored in JOB.h5: control characters escaped as in
  // every message, so that it cannot move the terminal's cursor or change its colours.
  for (const DeckDataLine& line : block.data) {
    if (!deck.model.heading.empty()) deck.model.heading += '\n';
    deck.model.heading += escape_control(std::string(line.text));
  }
}

void read_node(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(deck, keyword, {{"NSET"}});
  const std::string set_name = deck.scoped_name(optional_name(keyword, "NSET"));
  const Index set = set_name.empty() ? NO_INDEX : node_set_index(deck, set_name, keyword.where);
  // A node of an instance: keyed in its scope, placed by the instance's translation and rotation.
  const DeckInstance* instance =
      deck.scope > 0 ? &deck.instances[static_cast<std::size_t>(deck.scope - 1)] : nullptr;
  const std::size_t n_lines = block.data.size();
  reserve_more(deck.model.node_ids, deck.model.node_ids.capacity(), n_lines);
  reserve_more(deck.coordinates, deck.coordinates.capacity(), 3 * n_lines);
  reserve_more(deck.node_index, deck.node_index.bucket_count(), n_lines);
  if (set != NO_INDEX)
    reserve_more(deck.node_sets[set].members, deck.node_sets[set].members.capacity(), n_lines);
  for (const DeckDataLine& line : block.data) {
    check_field_count(deck, line, keyword, 4, "id, x, y, z");
    const std::optional<long long> id = integer_field(deck, line, keyword, 0, "node id");
    if (!id) continue;
    if (*id <= 0) {
      error(deck, line.where(), keyword, "node id " + id_text(*id) + " is not positive",
            "expected ids 1, 2, ...");
      continue;
    }
    if (!check_scoped_id(deck, line, keyword, *id, "node")) continue;
    Real x[3] = {0.0, 0.0, 0.0};
    bool ok = true;
    for (std::size_t c = 0; c < 3; ++c) {
      const std::optional<Real> value =
          real_field(deck, line, keyword, c + 1, std::string("coordinate ") + "xyz"[c], 0.0);
      ok = ok && value.has_value();
      if (value) x[c] = *value;
    }
    const auto [it, inserted] =
        deck.node_index.emplace(DeckState::id_key(deck.scope, *id), deck.model.node_count());
    if (!inserted) {
      error(deck, line.where(), keyword, "node " + id_text(*id) + " is defined twice",
            "expected each node id once");
      continue;
    }
    // A bad coordinate is reported; the node still counts as defined.
    if (!ok) deck.bad_coordinate_nodes.push_back(it->second);
    if (instance != nullptr) place_node(*instance, x);
    if (deck.assembly_model) deck.node_scopes.push_back(deck.scope);
    deck.model.node_ids.push_back(*id);
    deck.coordinates.insert(deck.coordinates.end(), {x[0], x[1], x[2]});
    if (set != NO_INDEX) deck.node_sets[set].members.push_back(it->second);
  }
}

namespace {

/// Remembers the ids and ELSET= of a refused *ELEMENT block, so that the sets, sections and
/// surfaces that name them are not reported again (the refusal is the one error).
void refuse_elements(DeckState& deck, const DeckBlock& block) {
  const std::string set_name = deck.scoped_name(optional_name(block.keyword, "ELSET"));
  if (!set_name.empty()) deck.refused_element_sets.push_back(set_name);
  for (const DeckDataLine& line : block.data) {
    if (line.fields.empty()) continue;
    if (const std::optional<long long> id = parse_integer(line.fields[0]))
      deck.refused_element_ids.insert(DeckState::id_key(deck.scope, *id));
  }
}

}  // namespace

void read_element(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(deck, keyword, {{"TYPE"}, {"ELSET"}});
  const std::optional<std::string> type = required_name(deck, keyword, "TYPE");
  if (!type) return;
  ElementType element_type = ElementType::C3D8R;
  if (*type == "MASS" || *type == "ROTARYI") {
    read_point_elements(deck, block, *type == "ROTARYI");
    return;
  }
  if (is_geometry_type(*type)) {
    read_geometry_elements(deck, block, *type);
    return;
  }
  if (*type == "S4R" || *type == "S4") {
    element_type = ElementType::S4R;
  } else if (*type == "C3D8") {
    element_type = ElementType::C3D8;
  } else if (*type == "C3D8I") {
    error(deck, keyword.where, keyword, "element type C3D8I (incompatible modes) is not supported",
          "expected C3D8 (fully integrated, selectively reduced: no volumetric locking) or "
          "C3D8R; in bending with one element through the thickness C3D8R needs a few more "
          "elements, C3D8 is stiffer (shear locking)");
    refuse_elements(deck, block);
    return;
  } else if (*type != "C3D8R") {
    // One error per type, at its first block (gmsh and meshio write a block per entity).
    const bool first = std::find(deck.refused_types.begin(), deck.refused_types.end(), *type) ==
                       deck.refused_types.end();
    if (first) {
      deck.refused_types.push_back(*type);
      const std::string nearest = nearest_supported_type(*type);
      error(deck, keyword.where, keyword, "element type " + *type + " is not supported",
            (nearest.empty() ? std::string() : "nearest supported: " + nearest + "; ") +
                "supported: C3D8R, C3D8, S4R (S4 is run as S4R), MASS, ROTARYI; CPS4, CPS3, "
                "T3D2, T3D3 without a section are read as geometry");
    }
    refuse_elements(deck, block);
    return;
  }
  if (*type == "S4")
    deck.model.deck_messages.push_back(
        {false, location_text(keyword.where) + ": " + keyword.label() +
                    ": S4 elements are run as S4R (reduced integration with hourglass control)"});
  const int n_nodes = nodes_per_element(element_type);
  const std::string set_name = deck.scoped_name(optional_name(keyword, "ELSET"));
  const Index set = set_name.empty() ? NO_INDEX : element_set_index(deck, set_name, keyword.where);
  const std::size_t n_lines = block.data.size();
  reserve_more(deck.model.element_ids, deck.model.element_ids.capacity(), n_lines);
  reserve_more(deck.model.element_types, deck.model.element_types.capacity(), n_lines);
  reserve_more(deck.model.element_offsets, deck.model.element_offsets.capacity(), n_lines);
  reserve_more(deck.model.element_file, deck.model.element_file.capacity(), n_lines);
  reserve_more(deck.model.element_line, deck.model.element_line.capacity(), n_lines);
  reserve_more(deck.element_node_ids, deck.element_node_ids.capacity(),
               static_cast<std::size_t>(n_nodes) * n_lines);
  reserve_more(deck.element_index, deck.element_index.bucket_count(), n_lines);
  if (set != NO_INDEX)
    reserve_more(deck.element_sets[set].members, deck.element_sets[set].members.capacity(),
                 n_lines);
  for (const DeckDataLine& line : block.data) {
    const std::optional<long long> id = integer_field(deck, line, keyword, 0, "element id");
    if (!id) continue;
    if (*id <= 0) {
      error(deck, line.where(), keyword, "element id " + id_text(*id) + " is not positive",
            "expected ids 1, 2, ...");
      continue;
    }
    if (!check_scoped_id(deck, line, keyword, *id, "element")) continue;
    if (line.fields.size() != static_cast<std::size_t>(n_nodes) + 1) {
      error(deck, line.where(), keyword,
            "element " + id_text(*id) + " has " + std::to_string(line.fields.size() - 1) +
                " node ids",
            "expected " + std::to_string(n_nodes) + " node ids for " + *type +
                " (end a line with a comma to continue it)");
      continue;
    }
    std::array<ExternalId, 8> nodes{};
    int found = 0;
    for (int k = 1; k <= n_nodes; ++k) {
      const std::optional<long long> node =
          integer_field(deck, line, keyword, static_cast<std::size_t>(k), "node id");
      if (node && static_cast<std::size_t>(found) < nodes.size())
        nodes[static_cast<std::size_t>(found++)] = DeckState::id_key(deck.scope, *node);
    }
    if (found != n_nodes) continue;
    const ExternalId key = DeckState::id_key(deck.scope, *id);
    const auto [it, inserted] = deck.element_index.emplace(key, deck.model.element_count());
    if (!inserted ||
        (!deck.point_element_index.empty() && deck.point_element_index.contains(key)) ||
        (!deck.geometry_index.empty() && deck.geometry_index.contains(key))) {
      if (inserted) deck.element_index.erase(it);
      error(deck, line.where(), keyword, "element " + id_text(*id) + " is defined twice",
            "expected each element id once");
      continue;
    }
    if (deck.assembly_model) deck.element_scopes.push_back(deck.scope);
    deck.model.element_ids.push_back(*id);
    deck.model.element_types.push_back(element_type);
    deck.element_node_ids.insert(deck.element_node_ids.end(), nodes.begin(), nodes.begin() + found);
    deck.model.element_offsets.push_back(static_cast<Index>(deck.element_node_ids.size()));
    deck.model.add_element_source(*line.file, line.line);
    if (set != NO_INDEX) deck.element_sets[set].members.push_back(it->second);
  }
}

namespace {

/// The scope of a set's ids and names: the instance of INSTANCE= (assembly level only), else
/// the scope being read; -1 if INSTANCE= is bad (reported).
Index set_scope(DeckState& deck, const DeckKeyword& keyword) {
  const std::string instance = optional_name(keyword, "INSTANCE");
  if (instance.empty()) return deck.scope;
  if (deck.scope != 0) {
    error(deck, keyword.where, keyword, "INSTANCE= inside a part or an instance",
          "expected INSTANCE= only on sets at the assembly level");
    return -1;
  }
  for (std::size_t i = 0; i < deck.instances.size(); ++i)
    if (deck.instances[i].name == instance) return static_cast<Index>(i + 1);
  error(deck, keyword.where, keyword, "undefined instance " + instance,
        "expected INSTANCE= the name of an *INSTANCE defined before this set");
  return -1;
}

}  // namespace

void read_set(DeckState& deck, const DeckBlock& block, bool node_set) {
  const DeckKeyword& keyword = block.keyword;
  const std::string_view set_parameter = node_set ? "NSET" : "ELSET";
  // INTERNAL (CAE's mark for sets it made itself) changes nothing here.
  if (node_set)
    check_parameters(deck, keyword,
                     {{"NSET"}, {"GENERATE", false}, {"ELSET"}, {"INTERNAL", false}, {"INSTANCE"}});
  else
    check_parameters(deck, keyword,
                     {{"ELSET"}, {"GENERATE", false}, {"INTERNAL", false}, {"INSTANCE"}});
  const std::optional<std::string> name = required_name(deck, keyword, set_parameter);
  if (!name) return;
  const Index item_scope = set_scope(deck, keyword);
  if (item_scope < 0) return;
  const bool instance_given = find_parameter(keyword, "INSTANCE") != nullptr;
  const std::string set_name = deck.scoped_name(*name);
  const Index set = node_set ? node_set_index(deck, set_name, keyword.where)
                             : element_set_index(deck, set_name, keyword.where);
  std::vector<SetItem>& items = node_set ? deck.node_sets[set].items : deck.element_sets[set].items;
  SetItem base;
  base.keyword = keyword.label();
  base.where = keyword.where;

  if (node_set && find_parameter(keyword, "ELSET") != nullptr) {
    // *NSET, NSET=name, ELSET=elset: the nodes of those elements.
    SetItem item = base;
    item.kind = SetItem::Kind::NodesOfElementSet;
    item.name = deck.scoped_name(item_scope, optional_name(keyword, "ELSET"));
    if (!item.name.empty()) items.push_back(item);
    if (find_parameter(keyword, "GENERATE") != nullptr)
      error(deck, keyword.where, keyword,
            "GENERATE together with ELSET=", "expected either ELSET= or data lines");
    expect_no_data(deck, block);
    return;
  }
  if (find_parameter(keyword, "GENERATE") != nullptr) {
    for (const DeckDataLine& line : block.data) {
      check_field_count(deck, line, keyword, 3, "first, last[, increment]");
      const std::optional<long long> first = integer_field(deck, line, keyword, 0, "first id");
      const std::optional<long long> last = integer_field(deck, line, keyword, 1, "last id");
      std::optional<long long> increment = 1;
      if (line.fields.size() > 2 && !line.fields[2].empty())
        increment = integer_field(deck, line, keyword, 2, "increment");
      if (!first || !last || !increment) continue;
      if (*first <= 0 || *last < *first || *increment <= 0) {
        error(deck, line.where(), keyword,
              "bad range " + id_text(*first) + ", " + id_text(*last) + ", " + id_text(*increment),
              "expected 0 < first <= last and increment >= 1");
        continue;
      }
      if (!check_scoped_id(deck, line, keyword, *last, node_set ? "node" : "element")) continue;
      SetItem item = base;
      item.kind = SetItem::Kind::Range;
      item.where = line.where();
      item.first = DeckState::id_key(item_scope, *first);
      item.last = DeckState::id_key(item_scope, *last);
      item.increment = *increment;
      items.push_back(item);
    }
    return;
  }
  for (const DeckDataLine& line : block.data) {
    for (const std::string_view field : line.fields) {
      if (field.empty()) continue;
      SetItem item = base;
      item.where = line.where();
      const auto bad_id = [&] {
        error(deck, line.where(), keyword, "bad id '" + std::string(field) + "'",
              std::string("expected positive ") + (node_set ? "node" : "element") +
                  " ids or set names");
      };
      if (looks_numeric(field)) {
        const std::optional<long long> id = parse_integer(field);
        if (!id || *id <= 0) {
          bad_id();
          continue;
        }
        if (!check_scoped_id(deck, line, keyword, *id, node_set ? "node" : "element")) continue;
        item.kind = SetItem::Kind::Id;
        item.first = DeckState::id_key(item_scope, *id);
        items.push_back(item);
        continue;
      }
      const std::string written = normalize_name(field);
      const auto [qualified_scope, rest] = split_qualified(deck, written);
      if (qualified_scope > 0 && instance_given) {
        error(deck, line.where(), keyword,
              "instance-qualified name " + written + " in a set with INSTANCE=",
              "expected either INSTANCE= and the instance's own names or ids, or qualified "
              "names INSTANCE.NAME without INSTANCE=");
        continue;
      }
      if (qualified_scope > 0 && looks_numeric(rest)) {
        const std::optional<long long> id = parse_integer(rest);
        if (!id || *id <= 0) {
          bad_id();
          continue;
        }
        item.kind = SetItem::Kind::Id;
        item.first = DeckState::id_key(qualified_scope, *id);
      } else {
        item.kind = SetItem::Kind::SetName;
        item.name = deck.scoped_name(item_scope, written);
      }
      items.push_back(item);
    }
  }
}

void read_surface(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(deck, keyword, {{"NAME"}, {"TYPE"}, {"INTERNAL", false}});
  std::optional<std::string> name = required_name(deck, keyword, "NAME");
  if (name) name = deck.scoped_name(*name);
  const std::string type_text = optional_name(keyword, "TYPE");
  Surface surface;
  if (type_text == "NODE") {
    surface.type = Surface::Type::Node;
  } else if (!type_text.empty() && type_text != "ELEMENT") {
    error(deck, keyword.where, keyword, "surface type " + type_text + " is not supported",
          "expected TYPE=ELEMENT or TYPE=NODE");
    return;
  }
  if (!name) return;
  if (deck.model.find_surface(*name) != NO_INDEX) {
    error(deck, keyword.where, keyword, "surface " + *name + " is defined twice",
          "expected each surface name once");
    return;
  }
  surface.name = *name;
  surface.where = keyword.where;
  std::vector<PendingSurfaceItem> items;
  for (const DeckDataLine& line : block.data) {
    check_field_count(deck, line, keyword, 2,
                      surface.type == Surface::Type::Node
                          ? "node or node set[, area]"
                          : "element or element set, face S1..S6 (solids) or SPOS, SNEG (shells)");
    PendingSurfaceItem item;
    item.target = reference(deck, line, keyword, 0);
    if (surface.type == Surface::Type::Node) {
      // The optional area (Abaqus: area or weight of each node) is the node's contact area.
      if (line.fields.size() > 1 && !line.fields[1].empty()) {
        const std::optional<Real> area = real_field(deck, line, keyword, 1, "area", std::nullopt);
        if (area && (!(*area > 0.0) || !std::isfinite(*area)))
          error(deck, line.where(), keyword,
                "node area " + std::string(line.fields[1]) + " is not positive",
                "expected a positive area (m²) per node, or none");
        else if (area)
          item.node_area = *area;
      }
    } else {
      // Whether the face fits the element type is checked once the elements are known.
      const std::string face = line.fields.size() > 1 ? normalize_name(line.fields[1]) : "";
      item.label = face;
      if (face.empty()) {
        item.all_faces = true;  // both sides of shells, exposed faces of solids (as Abaqus)
      } else if (face == "SPOS" || face == "SNEG") {
        item.shell = true;
        item.face = face == "SPOS" ? SHELL_FACE_POS : SHELL_FACE_NEG;
      } else if (face.size() == 2 && face[0] == 'S' && face[1] >= '1' && face[1] <= '6') {
        item.face = face[1] - '1';
      } else {
        error(deck, line.where(), keyword, "bad face label " + face,
              "expected S1, S2, S3, S4, S5 or S6 on C3D8R elements, SPOS or SNEG on S4R "
              "elements, or none (all exposed faces, both sides of shells)");
        continue;
      }
    }
    items.push_back(item);
  }
  deck.model.surfaces.push_back(std::move(surface));
  deck.surface_items.push_back(std::move(items));
}

}  // namespace xpl::io
