/// \file *RIGID BODY, REF NODE=, ELSET=[, PIN NSET=][, TIE NSET=]: read as model data, its
/// node and sets resolved once the whole deck is read. The elements keep their sections: their
/// mass comes from the section density, as in Abaqus.

#include <algorithm>

#include "io/deck/deck_handlers.hpp"
#include "io/deck/deck_numbers.hpp"

namespace xpl::io {

void read_rigid_body(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(deck, keyword, {{"REF NODE"}, {"ELSET"}, {"PIN NSET"}, {"TIE NSET"}});
  expect_no_data(deck, block);
  const DeckParameter* reference = find_parameter(keyword, "REF NODE");
  if (reference == nullptr) {
    error(deck, keyword.where, keyword, "missing parameter REF NODE",
          "expected REF NODE=node id (or a node set of one node)");
    return;
  }
  if (!reference->has_value || reference->value.empty()) return;  // check_parameters reported it
  PendingRigidBody pending;
  pending.reference_node.token = looks_numeric(reference->value)
                                     ? reference->value
                                     : deck.scoped_name(normalize_name(reference->value));
  pending.reference_node.scope = looks_numeric(reference->value) ? deck.scope : 0;
  pending.reference_node.where = keyword.where;
  pending.reference_node.keyword = keyword.label();
  pending.element_set = deck.scoped_name(optional_name(keyword, "ELSET"));
  pending.pin_node_set = deck.scoped_name(optional_name(keyword, "PIN NSET"));
  pending.tie_node_set = deck.scoped_name(optional_name(keyword, "TIE NSET"));
  if (pending.element_set.empty() && pending.pin_node_set.empty() && pending.tie_node_set.empty()) {
    error(deck, keyword.where, keyword, "no ELSET, PIN NSET or TIE NSET",
          "expected the elements (ELSET=) or nodes (PIN NSET=, TIE NSET=) of the rigid body");
    return;
  }
  RigidBody body;
  body.where = keyword.where;
  deck.model.rigid_bodies.push_back(body);
  deck.rigid_bodies.push_back(std::move(pending));
}

void resolve_rigid_bodies(DeckState& deck) {
  // Rigid body of each element (NO_INDEX: deformable); sized only when there are bodies.
  std::vector<Index> body_of;
  if (!deck.rigid_bodies.empty())
    body_of.assign(static_cast<std::size_t>(deck.model.element_count()), NO_INDEX);
  std::vector<bool> valid(deck.rigid_bodies.size(), true);

  for (std::size_t b = 0; b < deck.rigid_bodies.size(); ++b) {
    const PendingRigidBody& pending = deck.rigid_bodies[b];
    RigidBody& body = deck.model.rigid_bodies[b];
    const DeckReference& reference = pending.reference_node;
    const std::string keyword = "*RIGID BODY";

    if (looks_numeric(reference.token)) {
      const std::optional<long long> id = parse_integer(reference.token);
      const auto it = id ? deck.node_index.find(DeckState::id_key(reference.scope, *id))
                         : deck.node_index.end();
      if (it == deck.node_index.end())
        deck.errors.add(body.where, keyword, "undefined reference node " + reference.token,
                        "expected REF NODE= a defined node id or a node set of one node");
      else
        body.reference_node = it->second;
    } else {
      const Index set = deck.model.find_node_set(reference.token);
      if (set == NO_INDEX) {
        deck.errors.add(body.where, keyword, "undefined reference node set " + reference.token,
                        "expected REF NODE= a defined node id or a node set of one node");
      } else {
        const std::vector<Index>& nodes =
            deck.model.node_sets[static_cast<std::size_t>(set)].members;
        if (nodes.size() == 1)
          body.reference_node = nodes.front();
        else
          deck.errors.add(body.where, keyword,
                          "reference node set " + reference.token + " has " +
                              std::to_string(nodes.size()) + " nodes",
                          "expected REF NODE= a node id or a node set of exactly one node");
      }
    }
    const auto node_set = [&](const std::string& name, const std::string& parameter) {
      if (name.empty()) return NO_INDEX;
      const Index set = deck.model.find_node_set(name);
      if (set == NO_INDEX)
        deck.errors.add(body.where, keyword, "undefined node set " + name + " (" + parameter + "=)",
                        "expected *NSET, NSET=" + name);
      return set;
    };
    body.pin_node_set = node_set(pending.pin_node_set, "PIN NSET");
    body.tie_node_set = node_set(pending.tie_node_set, "TIE NSET");
    if (pending.element_set.empty()) continue;
    body.element_set = deck.model.find_element_set(pending.element_set);
    if (body.element_set == NO_INDEX) {
      deck.errors.add(body.where, keyword, "undefined element set " + pending.element_set,
                      "expected *ELSET, ELSET=" + pending.element_set + " or *ELEMENT, ELSET=");
      continue;
    }
    bool reported = false;  // one overlap per body, not one per shared element
    for (Index e : deck.model.element_sets[static_cast<std::size_t>(body.element_set)].members) {
      Index& owner = body_of[static_cast<std::size_t>(e)];
      if (owner == NO_INDEX || owner == static_cast<Index>(b)) {
        owner = static_cast<Index>(b);
      } else if (!reported) {
        reported = true;
        valid[b] = false;
        deck.errors.add(
            body.where, keyword,
            "element " + std::to_string(deck.model.element_ids[e]) +
                " is already in the rigid body at " +
                location_text(deck.model.rigid_bodies[static_cast<std::size_t>(owner)].where),
            "expected each element in at most one *RIGID BODY");
      }
    }
  }

  // A reference node on a deformable element would tie that element to the body's motion
  // without making it rigid: Abaqus refuses it too.
  for (std::size_t b = 0; b < deck.rigid_bodies.size(); ++b) {
    const RigidBody& body = deck.model.rigid_bodies[b];
    if (body.reference_node == NO_INDEX || !valid[b]) continue;
    for (Index e = 0; e < deck.model.element_count(); ++e) {
      if (body_of[static_cast<std::size_t>(e)] != NO_INDEX) continue;
      const Index* nodes = deck.model.nodes_of(e);
      const Index n = deck.model.element_offsets[e + 1] - deck.model.element_offsets[e];
      if (std::find(nodes, nodes + n, body.reference_node) == nodes + n) continue;
      deck.errors.add(
          body.where, "*RIGID BODY",
          "reference node " +
              std::to_string(deck.model.node_ids[static_cast<std::size_t>(body.reference_node)]) +
              " belongs to deformable element " + std::to_string(deck.model.element_ids[e]),
          "expected a reference node that no element outside a rigid body uses (e.g. a "
          "node of its own)");
      break;
    }
  }
}

}  // namespace xpl::io
