/// \file Point masses and rotary inertias: `*ELEMENT, TYPE=MASS|ROTARYI` (one node each) with
/// `*MASS, ELSET=` and `*ROTARY INERTIA, ELSET=`, turned into one PointInertia per node.
///
/// The solver knows only solid and shell elements, so these elements never enter the Model's
/// element arrays: the reader keeps them in a side table, and element sets carry them as
/// `point_members` beside their ordinary members (so `*ELSET` lists may mix both).

#include <map>

#include "io/deck/deck_handlers.hpp"

namespace xpl::io {

namespace {

constexpr const char* INERTIA_LINE = "I11, I22, I33[, I12, I13, I23]";

}  // namespace

void read_point_elements(DeckState& deck, const DeckBlock& block, bool rotary) {
  const DeckKeyword& keyword = block.keyword;
  const std::string type = rotary ? "ROTARYI" : "MASS";
  const std::string set_name = deck.scoped_name(optional_name(keyword, "ELSET"));
  const Index set = set_name.empty() ? NO_INDEX : element_set_index(deck, set_name, keyword.where);
  for (const DeckDataLine& line : block.data) {
    const std::optional<long long> id = integer_field(deck, line, keyword, 0, "element id");
    if (!id) continue;
    if (*id <= 0) {
      error(deck, line.where(), keyword, "element id " + std::to_string(*id) + " is not positive",
            "expected ids 1, 2, ...");
      continue;
    }
    if (line.fields.size() != 2) {
      error(deck, line.where(), keyword,
            "element " + std::to_string(*id) + " has " + std::to_string(line.fields.size() - 1) +
                " node ids",
            "expected 1 node id for " + type);
      continue;
    }
    const std::optional<long long> node = integer_field(deck, line, keyword, 1, "node id");
    if (!node) continue;
    const Index index = static_cast<Index>(deck.point_elements.size());
    const ExternalId key = DeckState::id_key(deck.scope, *id);
    if (deck.element_index.contains(key) || !deck.point_element_index.emplace(key, index).second) {
      error(deck, line.where(), keyword, "element " + std::to_string(*id) + " is defined twice",
            "expected each element id once");
      continue;
    }
    PointElement element;
    element.id = *id;
    element.node_id = DeckState::id_key(deck.scope, *node);
    element.rotary = rotary;
    element.where = line.where();
    deck.point_elements.push_back(element);
    if (set != NO_INDEX) deck.element_sets[set].point_members.push_back(index);
  }
}

void read_point_property(DeckState& deck, const DeckBlock& block, bool rotary) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(deck, keyword, {{"ELSET"}});
  std::optional<std::string> element_set = required_name(deck, keyword, "ELSET");
  if (element_set) element_set = deck.scoped_name(*element_set);
  PointProperty property;
  property.rotary = rotary;
  property.where = keyword.where;
  if (block.data.size() != 1) {
    error(deck, keyword.where, keyword,
          "found " + std::to_string(block.data.size()) + " data lines",
          rotary ? std::string("expected one data line: ") + INERTIA_LINE
                 : "expected one data line with the mass");
  } else if (!rotary) {
    const DeckDataLine& line = block.data.front();
    check_field_count(deck, line, keyword, 1, "the mass");
    const std::optional<Real> mass = real_field(deck, line, keyword, 0, "mass");
    if (mass && *mass <= 0.0)
      error(deck, line.where(), keyword, "mass " + number_text(*mass) + " is not positive",
            "expected a mass > 0");
    else if (mass)
      property.values[0] = *mass;
  } else {
    const DeckDataLine& line = block.data.front();
    check_field_count(deck, line, keyword, 6, INERTIA_LINE);
    static const char* const NAMES[6] = {"I11", "I22", "I33", "I12", "I13", "I23"};
    for (std::size_t c = 0; c < 6; ++c) {
      const std::optional<Real> value = real_field(
          deck, line, keyword, c, NAMES[c], c == 0 ? std::nullopt : std::optional<Real>(0.0));
      if (!value) continue;
      if (c < 3 && *value < 0.0)
        error(deck, line.where(), keyword,
              std::string("rotary inertia ") + NAMES[c] + " = " + number_text(*value) +
                  " is negative",
              "expected I11, I22, I33 >= 0");
      else
        property.values[c] = *value;
    }
  }
  // Recorded even with a bad value (reported above): its elements then have a property.
  if (!element_set) return;
  property.element_set = *element_set;
  deck.point_properties.push_back(property);
}

void resolve_point_inertias(DeckState& deck) {
  for (std::size_t p = 0; p < deck.point_properties.size(); ++p) {
    const PointProperty& property = deck.point_properties[p];
    const std::string keyword = property.rotary ? "*ROTARY INERTIA" : "*MASS";
    const std::string type = property.rotary ? "ROTARYI" : "MASS";
    const auto set = deck.element_set_by_name.find(property.element_set);
    if (set == deck.element_set_by_name.end()) {
      deck.errors.add(property.where, keyword, "undefined element set " + property.element_set,
                      "expected *ELSET, ELSET=" + property.element_set +
                          " or *ELEMENT, TYPE=" + type + ", ELSET=" + property.element_set);
      continue;
    }
    bool any = false, reported = false;
    for (Index e : deck.element_sets[static_cast<std::size_t>(set->second)].point_members) {
      PointElement& element = deck.point_elements[static_cast<std::size_t>(e)];
      if (element.rotary != property.rotary) continue;
      any = true;
      if (element.property == NO_INDEX) {
        element.property = static_cast<Index>(p);
      } else if (!reported) {  // one per keyword, not one per element
        reported = true;
        deck.errors.add(
            property.where, keyword,
            "element " + std::to_string(element.id) + " already has the " + keyword + " at " +
                location_text(
                    deck.point_properties[static_cast<std::size_t>(element.property)].where),
            "expected each " + type + " element in one " + keyword);
      }
    }
    if (!any)
      deck.errors.add(property.where, keyword,
                      "element set " + property.element_set + " has no " + type + " elements",
                      "expected *ELEMENT, TYPE=" + type + " elements in it");
  }

  // One entry per node, in node order: masses and inertias on the same node add up.
  std::map<Index, PointInertia> by_node;
  for (const PointElement& element : deck.point_elements) {
    const std::string keyword = element.rotary ? "*ROTARY INERTIA" : "*MASS";
    if (element.property == NO_INDEX) {
      deck.errors.add(element.where, "*ELEMENT",
                      std::string(element.rotary ? "ROTARYI" : "MASS") + " element " +
                          std::to_string(element.id) + " has no " + keyword,
                      "expected a " + keyword + ", ELSET= covering it");
      continue;
    }
    if (element.node == NO_INDEX) continue;  // undefined node, reported
    const PointProperty& property =
        deck.point_properties[static_cast<std::size_t>(element.property)];
    const auto [it, inserted] = by_node.try_emplace(element.node);
    PointInertia& inertia = it->second;
    if (inserted) {
      inertia.node = element.node;
      inertia.where = property.where;
    }
    if (property.rotary)
      for (int c = 0; c < 6; ++c) inertia.inertia[c] += property.values[c];
    else
      inertia.mass += property.values[0];
  }
  for (const auto& [node, inertia] : by_node) deck.model.point_inertias.push_back(inertia);
}

}  // namespace xpl::io
