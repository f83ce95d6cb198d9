/// \file One node or element reference (an id, a set name, an instance-qualified id) resolved to
/// internal indices, and amplitudes by name, once the whole deck is read.

#include <optional>

#include "io/deck/deck_handlers.hpp"
#include "io/deck/deck_numbers.hpp"

namespace xpl::io {

namespace {

/// " of instance NAME" for an instance's scope, "" at the model level.
std::string scope_text(const DeckState& deck, Index scope) {
  return scope > 0 ? " of instance " + deck.instances[static_cast<std::size_t>(scope - 1)].name
                   : std::string();
}

/// An instance-qualified id (`PART-1-1.5` in a *BOUNDARY at the model level) as a reference to
/// id 5 of instance PART-1-1; nothing if `reference` is not of that form.
std::optional<DeckReference> qualified_id(const DeckState& deck, const DeckReference& reference) {
  if (reference.scope != 0) return std::nullopt;
  const auto [scope, rest] = split_qualified(deck, reference.token);
  if (scope == 0 || !looks_numeric(rest)) return std::nullopt;
  DeckReference id = reference;
  id.token = rest;
  id.scope = scope;
  return id;
}

}  // namespace

std::vector<Index> resolve_nodes(DeckState& deck, const DeckReference& reference) {
  if (reference.token.empty()) {
    deck.errors.add(reference.where, reference.keyword, "missing node or node set",
                    "expected a node id or a node set name first");
    return {};
  }
  if (looks_numeric(reference.token)) {
    const std::optional<long long> id = parse_integer(reference.token);
    const auto it =
        id ? deck.node_index.find(DeckState::id_key(reference.scope, *id)) : deck.node_index.end();
    if (it == deck.node_index.end()) {
      deck.errors.add(reference.where, reference.keyword,
                      "undefined node " + reference.token + scope_text(deck, reference.scope),
                      "expected a defined node id or a node set name");
      return {};
    }
    return {it->second};
  }
  const auto it = deck.node_set_by_name.find(reference.token);
  if (it == deck.node_set_by_name.end()) {
    if (const std::optional<DeckReference> id = qualified_id(deck, reference))
      return resolve_nodes(deck, *id);
    deck.errors.add(reference.where, reference.keyword, "undefined node set " + reference.token,
                    "expected *NSET, NSET=" + reference.token);
    return {};
  }
  return deck.model.node_sets[static_cast<std::size_t>(it->second)].members;
}

std::vector<Index> resolve_elements(DeckState& deck, const DeckReference& reference) {
  if (reference.token.empty()) {
    deck.errors.add(reference.where, reference.keyword, "missing element or element set",
                    "expected an element id or an element set name first");
    return {};
  }
  if (looks_numeric(reference.token)) {
    const std::optional<long long> id = parse_integer(reference.token);
    const ExternalId key = id ? DeckState::id_key(reference.scope, *id) : 0;
    const auto it = id ? deck.element_index.find(key) : deck.element_index.end();
    if (it == deck.element_index.end()) {
      if (id && deck.refused_element(key)) return {};
      deck.errors.add(reference.where, reference.keyword,
                      "undefined element " + reference.token + scope_text(deck, reference.scope),
                      "expected a defined element id or an element set name");
      return {};
    }
    return {it->second};
  }
  const auto it = deck.element_set_by_name.find(reference.token);
  if (it == deck.element_set_by_name.end()) {
    if (const std::optional<DeckReference> id = qualified_id(deck, reference))
      return resolve_elements(deck, *id);
    if (deck.refused_element_set(reference.token)) return {};
    deck.errors.add(reference.where, reference.keyword, "undefined element set " + reference.token,
                    "expected *ELSET, ELSET=" + reference.token);
    return {};
  }
  const std::vector<Index>& members =
      deck.model.element_sets[static_cast<std::size_t>(it->second)].members;
  if (members.empty() &&
      !deck.element_sets[static_cast<std::size_t>(it->second)].geometry_members.empty())
    deck.errors.add(reference.where, reference.keyword,
                    "element set " + reference.token +
                        " holds only geometry (elements of a block without a section)",
                    "expected analysed elements; geometry defines node sets and element-based "
                    "*SURFACEs (*SURFACE, NAME=...  with the line " +
                        reference.token + ")");
  return members;
}

std::string element_text(const DeckState& deck, Index e, const DeckReference& reference) {
  std::string text =
      std::string(element_type_name(deck.model.element_types[static_cast<std::size_t>(e)])) +
      " element " + std::to_string(deck.model.element_ids[e]);
  if (!deck.element_scopes.empty() && deck.element_scopes[static_cast<std::size_t>(e)] > 0)
    text += scope_text(deck, deck.element_scopes[static_cast<std::size_t>(e)]);
  if (!looks_numeric(reference.token)) text += " of set " + reference.token;
  return text;
}

Index resolve_amplitude(DeckState& deck, const std::string& name, const SourceLocation& where,
                        const std::string& keyword) {
  if (name.empty()) return NO_INDEX;
  const Index amplitude = deck.model.find_amplitude(name);
  if (amplitude == NO_INDEX)
    deck.errors.add(where, keyword, "undefined amplitude " + name,
                    "expected *AMPLITUDE, NAME=" + name);
  return amplitude;
}

}  // namespace xpl::io
