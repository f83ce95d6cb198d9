/// \file The model ids of an assembly: every instance's nodes and elements keep their part's
/// ids as local ids, and get model ids `k·P + local id` (instance k = 0, 1, …; P the smallest
/// power of ten above every local id; the assembly level after the instances), so that a node
/// of the second instance of a part with nodes 1..27 is 101..127 in the results. The .msg file
/// lists the instances with their offsets.

#include <limits>

#include "io/deck/deck_assembly.hpp"
#include "io/deck/deck_handlers.hpp"

namespace xpl::io {

namespace {

/// "1 node", "8 nodes".
std::string count_text(Index count, const std::string& noun) {
  return std::to_string(count) + " " + noun + (count == 1 ? "" : "s");
}

std::string vector_text(const std::array<Real, 3>& v) {
  std::string text = "(";  // appended piece by piece: GCC 12 warns (-Wrestrict) on "(" + ...
  for (std::size_t c = 0; c < 3; ++c) {
    text += number_text(v[c]);
    text += c < 2 ? ", " : ")";
  }
  return text;
}

/// "translated by (…), rotated by θ° about (a) → (b)", or "in place".
std::string placement_text(const DeckInstance& instance) {
  std::string text;
  if (instance.translation != std::array<Real, 3>{})
    text = "translated by " + vector_text(instance.translation);
  if (instance.rotated)
    text += std::string(text.empty() ? "" : ", then ") + "rotated by " +
            number_text(instance.angle) + " degrees about the axis " +
            vector_text(instance.axis_a) + " -> " + vector_text(instance.axis_b);
  return text.empty() ? "in place" : text;
}

}  // namespace

void finish_instances(DeckState& deck) {
  if (deck.instances.empty()) return;
  Model& model = deck.model;
  ExternalId largest = 0;
  for (ExternalId id : model.node_ids) largest = std::max(largest, id);
  for (ExternalId id : model.element_ids) largest = std::max(largest, id);
  ExternalId step = 10;
  while (step <= largest) step *= 10;
  const auto n_instances = static_cast<ExternalId>(deck.instances.size());
  if (n_instances + 1 > std::numeric_limits<ExternalId>::max() / step) {
    deck.errors.add_plain(deck.file_name + ": " + std::to_string(n_instances) +
                          " instances with ids up to " + std::to_string(largest) +
                          " cannot be numbered in 64 bits; expected fewer or smaller ids");
    return;
  }
  model.instances.clear();
  for (std::size_t k = 0; k < deck.instances.size(); ++k) {
    PartInstance instance;
    instance.name = deck.instances[k].name;
    instance.part = deck.instances[k].part;
    instance.node_offset = instance.element_offset = static_cast<ExternalId>(k) * step;
    instance.where = deck.instances[k].where;
    model.instances.push_back(instance);
  }
  model.assembly_node_offset = model.assembly_element_offset = n_instances * step;

  // Scope k (1-based) is instance k-1; scope 0, the assembly level, comes after the instances.
  const auto renumber = [&](std::vector<ExternalId>& ids, const std::vector<Index>& scopes,
                            std::vector<std::int32_t>& instance_of,
                            std::vector<ExternalId>& local_ids, bool nodes) {
    local_ids = ids;
    instance_of.assign(ids.size(), -1);
    for (std::size_t i = 0; i < ids.size(); ++i) {
      const Index in_scope = scopes[i];
      const ExternalId slot = in_scope == 0 ? n_instances : static_cast<ExternalId>(in_scope - 1);
      ids[i] = slot * step + local_ids[i];
      if (in_scope == 0) continue;
      instance_of[i] = static_cast<std::int32_t>(in_scope - 1);
      PartInstance& instance = model.instances[static_cast<std::size_t>(in_scope - 1)];
      ++(nodes ? instance.nodes : instance.elements);
    }
  };
  renumber(model.node_ids, deck.node_scopes, model.node_instance, model.node_local_ids, true);
  renumber(model.element_ids, deck.element_scopes, model.element_instance, model.element_local_ids,
           false);

  for (std::size_t k = 0; k < deck.instances.size(); ++k) {
    const PartInstance& instance = model.instances[k];
    model.deck_messages.push_back(
        {false, location_text(instance.where) + ": *INSTANCE: instance " + instance.name +
                    " of part " + instance.part + ": " + count_text(instance.nodes, "node") + ", " +
                    count_text(instance.elements, "element") + ", " +
                    placement_text(deck.instances[k]) + "; in the results its ids are " +
                    std::to_string(instance.node_offset) +
                    " + the part's ids (/mesh/node_local_ids, /mesh/node_instance)"});
  }
  Index assembly_nodes = 0, assembly_elements = 0;
  for (std::int32_t k : model.node_instance) assembly_nodes += k < 0 ? 1 : 0;
  for (std::int32_t k : model.element_instance) assembly_elements += k < 0 ? 1 : 0;
  if (assembly_nodes + assembly_elements > 0)
    model.deck_messages.push_back(
        {false, location_text(deck.assembly_where) +
                    ": *ASSEMBLY: " + count_text(assembly_nodes, "node") + " and " +
                    count_text(assembly_elements, "element") +
                    " at the assembly level; in the results their ids are " +
                    std::to_string(model.assembly_node_offset) + " + the deck's ids"});
}

}  // namespace xpl::io
