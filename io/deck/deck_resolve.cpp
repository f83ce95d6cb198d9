/// \file Resolution of references once the whole deck is read: element nodes, sets, initial
/// conditions, boundary conditions, loads and output sets (a node or element reference itself
/// in deck_references.cpp). Sections are resolved in
/// deck_sections.cpp, surfaces in deck_surfaces.cpp, pressures and gravity in
/// deck_pressure.cpp, contact pairs in deck_contact.cpp, rigid bodies in deck_rigid.cpp, point
/// masses in deck_point_mass.cpp, distributions in deck_distribution.cpp, clearances in
/// deck_clearance.cpp, element shapes checked in deck_geometry.cpp.

#include <algorithm>
#include <cmath>

#include "io/deck/deck_assembly.hpp"
#include "io/deck/deck_handlers.hpp"
#include "io/deck/deck_numbers.hpp"

namespace xpl::io {

namespace {

/// Deeper set-of-set chains are almost certainly a mistake (and would deepen the recursion).
constexpr int MAX_SET_NESTING = 100;

}  // namespace

Model finish(DeckState& deck) {
  if (deck.in_step) {
    deck.errors.add(deck.step_where, "*STEP",
                    "step " + deck.model.steps.back().name + " is not closed",
                    "expected *END STEP");
    if (!deck.step_has_dynamic)
      deck.errors.add(deck.step_where, "*STEP",
                      "step " + deck.model.steps.back().name + " has no procedure",
                      "expected *DYNAMIC, EXPLICIT with the time period");
  }
  if (deck.model.steps.empty())
    deck.errors.add_plain(deck.file_name + ": the deck has no step; expected a *STEP with " +
                          "*DYNAMIC, EXPLICIT and *END STEP after the model data");

  const Index n_nodes = deck.model.node_count();
  deck.model.coordinates.resize(n_nodes, 3);
  for (Index i = 0; i < n_nodes; ++i)
    for (int c = 0; c < 3; ++c)
      deck.model.coordinates(i, c) = deck.coordinates[static_cast<std::size_t>(3 * i + c)];
  if (!deck.velocities.empty()) {  // else empty: no two zero arrays kept for the run (issue 38)
    deck.model.initial_velocity = NodalVectors::Zero(n_nodes, 3);
    deck.model.initial_angular_velocity = NodalVectors::Zero(n_nodes, 3);
  }

  promote_shell_geometry(deck);  // before anything counts the elements
  resolve_element_nodes(deck);
  resolve_geometry_node_ids(deck);
  resolve_sets(deck, false);  // element sets first: *NSET, ELSET= needs them
  geometry_node_sets(deck);
  resolve_sets(deck, true);
  check_plastic_materials(deck);  // before the sections check the materials
  resolve_sections(deck);
  resolve_surfaces(deck);
  resolve_initial_velocity(deck);
  resolve_steps(deck);
  resolve_pressures(deck);
  resolve_gravity(deck);
  resolve_contact_pairs(deck);
  resolve_rigid_bodies(deck);
  check_mass_scaling_sets(deck);  // after rigid bodies
  resolve_ties(deck);             // after rigid bodies and steps (node conflicts)
  resolve_point_inertias(deck);
  resolve_distributions(deck);
  resolve_clearances(deck);  // after surfaces, contact pairs, rigid bodies and distributions
  resolve_pair_clearances(deck);
  check_element_geometry(deck);

  const char* categories[ERROR_CATEGORIES] = {"elements with undefined nodes",
                                              "elements without a section",
                                              "elements in two sections",
                                              "elements with a section of the wrong kind",
                                              "inverted elements",
                                              "degenerate elements"};
  for (int k = 0; k < ERROR_CATEGORIES; ++k) {
    if (deck.error_counts[k] > ERROR_CAP)
      deck.errors.add_plain(deck.file_name + ": " +
                            std::to_string(deck.error_counts[k] - ERROR_CAP) + " more " +
                            categories[k] + " not listed");
  }
  finish_instances(deck);  // last: the messages above name the ids as the deck wrote them
  return std::move(deck.model);
}

void resolve_element_nodes(DeckState& deck) {
  deck.model.element_nodes.assign(deck.element_node_ids.size(), NO_INDEX);
  for (Index e = 0; e < deck.model.element_count(); ++e) {
    bool reported = false;
    for (Index k = deck.model.element_offsets[e]; k < deck.model.element_offsets[e + 1]; ++k) {
      const ExternalId id = deck.element_node_ids[static_cast<std::size_t>(k)];
      const auto it = deck.node_index.find(id);
      if (it != deck.node_index.end()) {
        deck.model.element_nodes[static_cast<std::size_t>(k)] = it->second;
      } else if (!reported) {
        capped_error(deck, deck.error_counts[UNDEFINED_NODES], deck.model.element_where(e),
                     "*ELEMENT",
                     "element " + std::to_string(deck.model.element_ids[e]) +
                         " refers to undefined node " + deck.id_text(id),
                     "expected a *NODE with id " + std::to_string(deck.local_id(id)));
        reported = true;
      }
    }
  }
  for (PointElement& element : deck.point_elements) {
    const auto it = deck.node_index.find(element.node_id);
    if (it != deck.node_index.end())
      element.node = it->second;
    else
      capped_error(deck, deck.error_counts[UNDEFINED_NODES], element.where, "*ELEMENT",
                   "element " + std::to_string(element.id) + " refers to undefined node " +
                       deck.id_text(element.node_id),
                   "expected a *NODE with id " + std::to_string(deck.local_id(element.node_id)));
  }
}

void resolve_sets(DeckState& deck, bool node_sets) {
  const std::size_t count = node_sets ? deck.node_sets.size() : deck.element_sets.size();
  for (std::size_t s = 0; s < count; ++s) resolve_set(deck, node_sets, static_cast<Index>(s), 0);
}

namespace {

/// What one set collects while its items are resolved: the Model's members and, beside them
/// in an element set, MASS/ROTARYI elements (`points`) and geometry elements (section-less
/// CPS4 & co.; those run as S4R are members).
struct SetMembers {
  DeckState& deck;
  bool node_sets;
  std::string what;  ///< "node" or "element"
  std::vector<Index> members;
  std::vector<Index>& points;
  std::vector<Index> geometry;
  bool has_points;
  bool has_geometry;

  std::size_t count() const { return members.size() + points.size() + geometry.size(); }
};

/// One id: a member, a point or geometry element, or an error (unless a refused element).
void add_id(SetMembers& m, const SetItem& item) {
  DeckState& deck = m.deck;
  const auto& ids = m.node_sets ? deck.node_index : deck.element_index;
  const auto it = ids.find(item.first);
  const auto point =
      m.has_points ? deck.point_element_index.find(item.first) : deck.point_element_index.end();
  const auto shape =
      m.has_geometry ? deck.geometry_index.find(item.first) : deck.geometry_index.end();
  if (it != ids.end())
    m.members.push_back(it->second);
  else if (point != deck.point_element_index.end())
    m.points.push_back(point->second);
  else if (shape != deck.geometry_index.end())
    m.geometry.push_back(shape->second);
  else if (m.node_sets || !deck.refused_element(item.first))
    deck.errors.add(item.where, item.keyword,
                    "undefined " + m.what + " " + deck.id_text(item.first),
                    "expected a defined " + m.what + " id");
}

/// A range (GENERATE): the ids of the range that are defined; undefined ones are skipped
/// (sparse numbering), and the cost is bounded by the smaller of the range and the number of
/// defined ids. A range with no defined id is an error (unless it holds a refused element).
void add_range(SetMembers& m, const SetItem& item) {
  DeckState& deck = m.deck;
  const auto& ids = m.node_sets ? deck.node_index : deck.element_index;
  const std::size_t before = m.count();
  const long long span = (item.last - item.first) / item.increment + 1;
  if (static_cast<unsigned long long>(span) <= ids.size()) {
    for (long long id = item.first; id <= item.last; id += item.increment) {
      const auto it = ids.find(id);
      if (it != ids.end()) m.members.push_back(it->second);
    }
  } else {
    for (const auto& [id, index] : ids)
      if (id >= item.first && id <= item.last && (id - item.first) % item.increment == 0)
        m.members.push_back(index);
  }
  if (m.has_points)
    for (const auto& [id, index] : deck.point_element_index)
      if (id >= item.first && id <= item.last && (id - item.first) % item.increment == 0)
        m.points.push_back(index);
  if (m.has_geometry)
    for (const auto& [id, index] : deck.geometry_index)
      if (id >= item.first && id <= item.last && (id - item.first) % item.increment == 0)
        m.geometry.push_back(index);
  const auto refused = [&] {
    for (ExternalId id : deck.refused_element_ids)
      if (id >= item.first && id <= item.last && (id - item.first) % item.increment == 0)
        return true;
    return false;
  };
  if (m.count() == before && (m.node_sets || !refused()))
    deck.errors.add(item.where, item.keyword,
                    "range " + std::to_string(deck.local_id(item.first)) + ".." +
                        deck.id_text(item.last) + " contains no defined " + m.what,
                    "expected a range over defined " + m.what + " ids");
}

/// A set included by name into set `set` (at nesting `depth`): resolved first, then its
/// members taken over; an undefined or circular one is an error.
void add_set(SetMembers& m, const SetItem& item, Index set, int depth) {
  DeckState& deck = m.deck;
  const bool node_sets = m.node_sets;
  const auto& names = node_sets ? deck.node_set_by_name : deck.element_set_by_name;
  std::vector<NamedSet>& sets = node_sets ? deck.model.node_sets : deck.model.element_sets;
  const auto it = names.find(item.name);
  const std::string set_keyword = node_sets ? "*NSET, NSET=" : "*ELSET, ELSET=";
  if (it == names.end()) {
    if (!node_sets && deck.refused_element_set(item.name)) return;
    deck.errors.add(item.where, item.keyword, "undefined " + m.what + " set " + item.name,
                    "expected " + set_keyword + item.name);
    return;
  }
  const PendingSet& other = node_sets ? deck.node_sets[it->second] : deck.element_sets[it->second];
  if (other.state == 1 || depth >= MAX_SET_NESTING) {
    deck.errors.add(item.where, item.keyword,
                    m.what + " set " + sets[set].name + " includes " + item.name +
                        ", which includes " + sets[set].name + " again",
                    "expected sets without circular references");
    return;
  }
  resolve_set(deck, node_sets, it->second, depth + 1);
  const std::vector<Index>& included = sets[static_cast<std::size_t>(it->second)].members;
  m.members.insert(m.members.end(), included.begin(), included.end());
  if (!node_sets) {
    const std::vector<Index>& other_points = deck.element_sets[it->second].point_members;
    m.points.insert(m.points.end(), other_points.begin(), other_points.end());
    const std::vector<Index>& other_shapes = deck.element_sets[it->second].geometry_members;
    m.geometry.insert(m.geometry.end(), other_shapes.begin(), other_shapes.end());
  }
}

/// The nodes of an element set (its elements, point elements and geometry elements).
void add_nodes_of_element_set(SetMembers& m, const SetItem& item) {
  DeckState& deck = m.deck;
  const auto it = deck.element_set_by_name.find(item.name);
  if (it == deck.element_set_by_name.end()) {
    if (deck.refused_element_set(item.name)) return;
    deck.errors.add(item.where, item.keyword, "undefined element set " + item.name,
                    "expected *ELSET, ELSET=" + item.name);
    return;
  }
  for (Index e : deck.model.element_sets[static_cast<std::size_t>(it->second)].members)
    for (Index k = deck.model.element_offsets[e]; k < deck.model.element_offsets[e + 1]; ++k)
      if (deck.model.element_nodes[k] != NO_INDEX) m.members.push_back(deck.model.element_nodes[k]);
  for (Index p : deck.element_sets[it->second].point_members)
    if (deck.point_elements[static_cast<std::size_t>(p)].node != NO_INDEX)
      m.members.push_back(deck.point_elements[static_cast<std::size_t>(p)].node);
  for (Index g : deck.element_sets[it->second].geometry_members) {
    const GeometryElement& shape = deck.geometry_elements[static_cast<std::size_t>(g)];
    for (int k = 0; k < shape.n_nodes; ++k) {
      const auto node = deck.node_index.find(shape.node_ids[static_cast<std::size_t>(k)]);
      if (node != deck.node_index.end()) m.members.push_back(node->second);
    }
  }
}

void sort_unique(std::vector<Index>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

}  // namespace

void resolve_set(DeckState& deck, bool node_sets, Index set, int depth) {
  PendingSet& pending = node_sets ? deck.node_sets[set] : deck.element_sets[set];
  if (pending.state != 0) return;
  pending.state = 1;
  SetMembers m{deck,
               node_sets,
               node_sets ? "node" : "element",
               std::move(pending.members),
               pending.point_members,
               {},
               !node_sets && !deck.point_element_index.empty(),
               !node_sets && !deck.geometry_elements.empty()};
  for (Index g : pending.geometry_members) {
    const GeometryElement& element = deck.geometry_elements[static_cast<std::size_t>(g)];
    if (element.promoted)
      m.members.push_back(deck.element_index.at(element.id));
    else
      m.geometry.push_back(g);
  }
  for (const SetItem& item : pending.items) {
    switch (item.kind) {
      case SetItem::Kind::Id:
        add_id(m, item);
        break;
      case SetItem::Kind::Range:
        add_range(m, item);
        break;
      case SetItem::Kind::SetName:
        add_set(m, item, set, depth);
        break;
      case SetItem::Kind::NodesOfElementSet:
        add_nodes_of_element_set(m, item);
        break;
    }
  }
  std::vector<NamedSet>& sets = node_sets ? deck.model.node_sets : deck.model.element_sets;
  sort_unique(m.members);
  sets[static_cast<std::size_t>(set)].members = std::move(m.members);
  sort_unique(m.points);
  sort_unique(m.geometry);
  pending.geometry_members = std::move(m.geometry);
  pending.state = 2;
}

void resolve_initial_velocity(DeckState& deck) {
  Model& model = deck.model;
  // Rotational dofs exist on shell nodes only (rigid-body reference nodes take their motion
  // from the body's members, not from initial conditions).
  std::vector<char> rotates(static_cast<std::size_t>(model.node_count()), 0);
  for (Index e = 0; e < model.element_count(); ++e) {
    if (!is_shell(model.element_types[e])) continue;
    const Index* nodes = model.nodes_of(e);
    for (Index k = 0; k < model.element_offsets[e + 1] - model.element_offsets[e]; ++k)
      if (nodes[k] >= 0 && nodes[k] < model.node_count()) rotates[nodes[k]] = 1;
  }
  for (const PendingVelocity& pending : deck.velocities) {
    const std::vector<Index> nodes = resolve_nodes(deck, pending.target);
    const bool rotational = pending.rotating || pending.dof > 3;
    if (!pending.rotating && pending.dof > 3) {
      Index without = NO_INDEX;
      for (Index node : nodes)
        if (!rotates[node]) {
          without = node;
          break;
        }
      if (without != NO_INDEX) {
        deck.errors.add(pending.target.where, pending.target.keyword,
                        "dof " + std::to_string(pending.dof) + " on node " +
                            std::to_string(model.node_ids[without]) +
                            ", which has no rotational dofs (it is on no shell element)",
                        "expected dofs 4-6 on shell nodes only; dofs 1-3 for other nodes");
        continue;
      }
    }
    if (!pending.rotating) {
      for (Index node : nodes) {
        if (pending.dof <= 3)
          model.initial_velocity(node, pending.dof - 1) = pending.value;
        else
          model.initial_angular_velocity(node, pending.dof - 4) = pending.value;
      }
      continue;
    }
    // Rigid spin ω ê about the axis through a along ê = (b − a)/|b − a|: v = ω ê × (x − a),
    // added to what TYPE=VELOCITY gives; shell nodes also get the angular velocity ω ê.
    Real axis[3] = {pending.b[0] - pending.a[0], pending.b[1] - pending.a[1],
                    pending.b[2] - pending.a[2]};
    const Real length = std::sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    for (Real& c : axis) c *= pending.omega / length;
    for (Index node : nodes) {
      const Real r[3] = {model.coordinates(node, 0) - pending.a[0],
                         model.coordinates(node, 1) - pending.a[1],
                         model.coordinates(node, 2) - pending.a[2]};
      model.initial_velocity(node, 0) += axis[1] * r[2] - axis[2] * r[1];
      model.initial_velocity(node, 1) += axis[2] * r[0] - axis[0] * r[2];
      model.initial_velocity(node, 2) += axis[0] * r[1] - axis[1] * r[0];
      if (rotational && rotates[node])
        for (int c = 0; c < 3; ++c) model.initial_angular_velocity(node, c) += axis[c];
    }
  }
}

void resolve_steps(DeckState& deck) {
  // Model-level *BOUNDARY (before the first *STEP) is propagated as part of the first step,
  // ahead of that step's own conditions; OP=NEW in the first step removes them, as in Abaqus.
  for (const PendingBoundary& pending : deck.boundaries) {
    if (deck.model.steps.empty()) break;
    const bool model_level = pending.step == NO_INDEX;
    Step& step = deck.model.steps[static_cast<std::size_t>(model_level ? 0 : pending.step)];
    if (model_level && step.boundaries_reset) continue;
    const Index amplitude =
        resolve_amplitude(deck, pending.amplitude, pending.condition.where, pending.target.keyword);
    for (Index node : resolve_nodes(deck, pending.target)) {
      BoundaryCondition condition = pending.condition;
      condition.node = node;
      condition.amplitude = amplitude;
      step.boundaries.push_back(condition);
    }
  }
  for (const PendingLoad& pending : deck.loads) {
    Step& step = deck.model.steps[static_cast<std::size_t>(pending.step)];
    const Index amplitude =
        resolve_amplitude(deck, pending.amplitude, pending.load.where, pending.target.keyword);
    for (Index node : resolve_nodes(deck, pending.target)) {
      ConcentratedLoad load = pending.load;
      load.node = node;
      load.amplitude = amplitude;
      step.loads.push_back(load);
    }
  }
  for (const PendingOutputSet& pending : deck.output_sets) {
    OutputRequest& request = deck.model.steps[static_cast<std::size_t>(pending.step)]
                                 .outputs[static_cast<std::size_t>(pending.output)];
    const auto& names = pending.node ? deck.node_set_by_name : deck.element_set_by_name;
    const auto it = names.find(pending.set.token);
    if (it == names.end()) {
      deck.errors.add(pending.set.where, pending.set.keyword,
                      std::string("undefined ") + (pending.node ? "node" : "element") + " set " +
                          pending.set.token,
                      std::string("expected ") +
                          (pending.node ? "*NSET, NSET=" : "*ELSET, ELSET=") + pending.set.token);
      continue;
    }
    // An output request on an empty set would write a series of width 0. A set defined
    // without data is reported here; one whose items all failed already has its errors.
    const std::vector<NamedSet>& sets =
        pending.node ? deck.model.node_sets : deck.model.element_sets;
    const PendingSet& defined = pending.node
                                    ? deck.node_sets[static_cast<std::size_t>(it->second)]
                                    : deck.element_sets[static_cast<std::size_t>(it->second)];
    if (sets[static_cast<std::size_t>(it->second)].members.empty() &&
        (defined.items.empty() || deck.errors.empty())) {
      deck.errors.add(pending.set.where, pending.set.keyword,
                      std::string(pending.node ? "node" : "element") + " set " + pending.set.token +
                          " is empty",
                      std::string("expected a set with at least one ") +
                          (pending.node ? "node" : "element") + " to write output for");
      continue;
    }
    (pending.node ? request.node_set : request.element_set) = it->second;
  }
}

}  // namespace xpl::io
