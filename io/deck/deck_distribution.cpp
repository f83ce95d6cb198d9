/// \file *DISTRIBUTION, NAME=, LOCATION=NODE[, TABLE=] and *DISTRIBUTION TABLE: one scalar per
/// node, as a clearance per slave node needs (SPEC C8). Nodes and sets are resolved once the
/// whole deck is read; a first data line with a blank node field gives the default value.

#include <algorithm>
#include <array>
#include <limits>

#include "io/deck/deck_handlers.hpp"

namespace xpl::io {

namespace {

constexpr const char* DISTRIBUTION_LINE =
    "node or node set, value (a blank node field on the first line: the default of every node "
    "not listed)";

/// Column types of a *DISTRIBUTION TABLE that hold one scalar per node.
constexpr std::array<std::string_view, 2> SCALAR_TYPES = {"LENGTH", "SCALAR"};

}  // namespace

void read_distribution(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(deck, keyword, {{"NAME"}, {"LOCATION"}, {"TABLE"}});
  const std::optional<std::string> name = required_name(deck, keyword, "NAME");
  const std::string location = optional_name(keyword, "LOCATION");
  const std::string only_nodal =
      "expected LOCATION=NODE (only nodal distributions are read: a clearance per node)";
  if (find_parameter(keyword, "LOCATION") == nullptr)  // Abaqus' default is ELEMENT
    error(deck, keyword.where, keyword, "missing parameter LOCATION", only_nodal);
  else if (!location.empty() && location != "NODE")
    error(deck, keyword.where, keyword, "LOCATION=" + location + " is not supported", only_nodal);
  if (block.data.empty())
    error(deck, keyword.where, keyword, "no values",
          std::string("expected data lines: ") + DISTRIBUTION_LINE);
  PendingDistribution pending;
  pending.table = optional_name(keyword, "TABLE");
  bool first = true;
  for (const DeckDataLine& line : block.data) {
    const bool blank_node = line.fields.empty() || line.fields[0].empty();
    check_field_count(deck, line, keyword, 2, DISTRIBUTION_LINE);
    const std::optional<Real> value = real_field(deck, line, keyword, 1, "distribution value");
    if (blank_node && !first)
      error(deck, line.where(), keyword, "blank node field",
            "expected a node id or node set (only the first data line may leave it blank: the "
            "default value)");
    else if (value && blank_node)
      pending.default_value = *value;
    else if (value)
      pending.values.emplace_back(reference(line, keyword, 0), *value);
    first = false;
  }
  if (!name) return;
  for (const NodalDistribution& other : deck.model.distributions) {
    if (other.name == *name) {
      error(deck, keyword.where, keyword,
            "distribution " + *name + " is defined twice at " + location_text(other.where),
            "expected each distribution name once");
      return;
    }
  }
  // Kept even when a line was wrong (reported): a clearance naming it is not reported again.
  NodalDistribution distribution;
  distribution.name = *name;
  distribution.where = keyword.where;
  deck.model.distributions.push_back(std::move(distribution));
  deck.distributions.push_back(std::move(pending));
}

void read_distribution_table(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(deck, keyword, {{"NAME"}});
  const std::optional<std::string> name = required_name(deck, keyword, "NAME");
  std::vector<std::string> types;
  for (const DeckDataLine& line : block.data)
    for (std::string_view field : line.fields) types.push_back(normalize_name(field));
  const std::string expected =
      "expected one column type, LENGTH or SCALAR (a nodal distribution holds one value per "
      "node)";
  if (types.empty()) {
    error(deck, keyword.where, keyword, "no column types", expected);
  } else if (types.size() > 1) {
    std::string list;
    for (const std::string& type : types) list += (list.empty() ? "" : ", ") + type;
    error(deck, block.data.front().where(), keyword,
          std::to_string(types.size()) + " column types (" + list + ")", expected);
  } else if (std::find(SCALAR_TYPES.begin(), SCALAR_TYPES.end(), types.front()) ==
             SCALAR_TYPES.end()) {
    error(deck, block.data.front().where(), keyword, "unsupported column type " + types.front(),
          expected);
  }
  if (!name) return;
  for (const DistributionTable& other : deck.distribution_tables) {
    if (other.name == *name) {
      error(deck, keyword.where, keyword,
            "distribution table " + *name + " is defined twice at " + location_text(other.where),
            "expected each distribution table name once");
      return;
    }
  }
  // Kept even when its columns were wrong (reported): TABLE= naming it is not reported again.
  deck.distribution_tables.push_back({*name, keyword.where});
}

void resolve_distributions(DeckState& deck) {
  const auto n_nodes = static_cast<std::size_t>(deck.model.node_count());
  for (std::size_t d = 0; d < deck.distributions.size(); ++d) {
    const PendingDistribution& pending = deck.distributions[d];
    NodalDistribution& distribution = deck.model.distributions[d];
    if (!pending.table.empty() &&
        std::none_of(deck.distribution_tables.begin(), deck.distribution_tables.end(),
                     [&](const DistributionTable& t) { return t.name == pending.table; }))
      deck.errors.add(distribution.where, "*DISTRIBUTION",
                      "undefined distribution table " + pending.table,
                      "expected *DISTRIBUTION TABLE, NAME=" + pending.table + " or no TABLE=");
    distribution.values.assign(
        n_nodes, pending.default_value.value_or(std::numeric_limits<Real>::quiet_NaN()));
    for (const auto& [target, value] : pending.values)
      for (Index node : resolve_nodes(deck, target))
        distribution.values[static_cast<std::size_t>(node)] = value;
  }
}

}  // namespace xpl::io
