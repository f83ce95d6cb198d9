/// \file Output request keywords: *OUTPUT, *NODE OUTPUT, *ELEMENT OUTPUT, *ENERGY OUTPUT,
/// *CONTACT OUTPUT. CalculiX's *NODE FILE & co. are in deck_calculix_output.cpp.

#include <algorithm>
#include <array>

#include "io/deck/deck_handlers.hpp"
#include "io/deck/deck_numbers.hpp"
#include "io/deck/deck_output_variables.hpp"

namespace xpl::io {

namespace {

/// A second *NODE OUTPUT (or *ELEMENT OUTPUT) under one *OUTPUT may name another set:
/// it becomes a request of its own with the same frequency.
OutputRequest& open_request(Step& step, Index& output, bool node) {
  OutputRequest& current = step.outputs[static_cast<std::size_t>(output)];
  const bool taken = node ? !current.node_variables.empty() : !current.element_variables.empty();
  if (!taken) return current;
  OutputRequest fresh;
  fresh.kind = current.kind;
  fresh.number_interval = current.number_interval;
  fresh.time_interval = current.time_interval;
  fresh.where = current.where;
  step.outputs.push_back(std::move(fresh));
  output = static_cast<Index>(step.outputs.size() - 1);
  return step.outputs.back();
}

}  // namespace

void read_output(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(
      deck, keyword,
      {{"FIELD", false}, {"HISTORY", false}, {"NUMBER INTERVAL"}, {"TIME INTERVAL"}, {"VARIABLE"}});
  expect_no_data(deck, block);
  const bool field = find_parameter(keyword, "FIELD") != nullptr;
  const bool history = find_parameter(keyword, "HISTORY") != nullptr;
  if (field == history) {
    error(deck, keyword.where, keyword,
          field ? "both FIELD and HISTORY" : "neither FIELD nor HISTORY",
          "expected *OUTPUT, FIELD or *OUTPUT, HISTORY");
    return;
  }
  OutputRequest request;
  request.kind = field ? OutputRequest::Kind::Field : OutputRequest::Kind::History;
  request.where = keyword.where;
  const DeckParameter* number = find_parameter(keyword, "NUMBER INTERVAL");
  const DeckParameter* time = find_parameter(keyword, "TIME INTERVAL");
  if (number != nullptr && time != nullptr) {
    error(deck, keyword.where, keyword, "both NUMBER INTERVAL and TIME INTERVAL",
          "expected at most one of them");
    return;
  }
  if (number != nullptr && number->has_value) {
    const std::optional<long long> n = parse_integer(number->value);
    if (!n || *n <= 0 || *n > 1000000000)
      error(deck, keyword.where, keyword, "bad NUMBER INTERVAL=" + number->value,
            "expected a positive integer");
    else
      request.number_interval = static_cast<int>(*n);
  } else if (time != nullptr && time->has_value) {
    const std::optional<Real> t = parse_real(time->value);
    if (!t || *t <= 0.0)
      error(deck, keyword.where, keyword, "bad TIME INTERVAL=" + time->value,
            "expected a time interval > 0");
    else
      request.time_interval = *t;
  } else if (number == nullptr && time == nullptr) {
    request.number_interval = field ? 20 : 200;  // the Abaqus/Explicit defaults
  }
  const std::string variable = optional_name(keyword, "VARIABLE");
  if (variable == "PRESELECT") {
    if (field) {
      for (std::string_view name : PRESELECT_NODE_VARIABLES)
        request.node_variables.emplace_back(name);
      for (std::string_view name : PRESELECT_ELEMENT_VARIABLES)
        request.element_variables.emplace_back(name);
    } else {
      request.energy = true;
    }
  } else if (!variable.empty()) {
    error(deck, keyword.where, keyword, "VARIABLE=" + variable + " is not supported",
          "expected VARIABLE=PRESELECT or explicit *NODE/*ELEMENT/*ENERGY OUTPUT lists");
  }
  Step& step = deck.model.steps.back();
  step.outputs.push_back(std::move(request));
  deck.output = static_cast<Index>(step.outputs.size() - 1);
}

void read_node_output(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(deck, keyword, {{"NSET"}});
  if (deck.output == NO_INDEX) {
    error(deck, keyword.where, keyword, "no *OUTPUT to attach to",
          "expected *OUTPUT, FIELD or *OUTPUT, HISTORY just before");
    return;
  }
  Step& step = deck.model.steps.back();
  const bool history =
      step.outputs[static_cast<std::size_t>(deck.output)].kind == OutputRequest::Kind::History;
  const std::string set = optional_name(keyword, "NSET");
  if (history && set.empty()) {
    error(deck, keyword.where, keyword, "history node output needs a node set",
          "expected *NODE OUTPUT, NSET=name");
    return;
  }
  std::vector<std::string> variables;
  for (const DeckDataLine& line : block.data) {
    for (const std::string_view field : line.fields) {
      if (field.empty()) continue;
      const std::string name = normalize_name(field);
      const bool known = history ? add_history_node_variable(variables, name)
                                 : contains(FIELD_NODE_VARIABLES, name);
      if (!known) {
        error(deck, line.where(), keyword, "unknown output variable " + name,
              history ? "expected one of " + joined(FIELD_NODE_VARIABLES) +
                            " or a component such as U1, RF3, UR2, RM1"
                      : "expected one of " + joined(FIELD_NODE_VARIABLES));
      } else if (!history) {
        add_unique(variables, name);
      }
    }
  }
  if (block.data.empty()) {
    error(deck, keyword.where, keyword, "no output variables",
          "expected a data line such as U, V, RF");
    return;
  }
  OutputRequest& request = open_request(step, deck.output, true);
  for (const std::string& name : variables) add_unique(request.node_variables, name);
  if (!set.empty())
    deck.output_sets.push_back({static_cast<Index>(deck.model.steps.size() - 1), deck.output, true,
                                DeckReference{set, keyword.where, keyword.label()}});
}

std::vector<std::string> read_names(DeckState& deck, const DeckBlock& block,
                                    std::span<const std::string_view> known,
                                    const std::string& what) {
  std::vector<std::string> names;
  for (const DeckDataLine& line : block.data) {
    for (const std::string_view field : line.fields) {
      if (field.empty()) continue;
      const std::string name = normalize_name(field);
      if (std::find(known.begin(), known.end(), name) != known.end()) {
        add_unique(names, name);
        continue;
      }
      std::string list;
      for (std::string_view k : known) list += (list.empty() ? "" : ", ") + std::string(k);
      error(deck, line.where(), block.keyword, "unknown " + what + " " + name,
            "expected one of " + list);
    }
  }
  return names;
}

void read_element_output(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  // DIRECTIONS only adds local material directions to Abaqus' ODB; harmless to accept.
  check_parameters(deck, keyword, {{"ELSET"}, {"DIRECTIONS"}});
  if (deck.output == NO_INDEX) {
    error(deck, keyword.where, keyword, "no *OUTPUT to attach to",
          "expected *OUTPUT, FIELD just before");
    return;
  }
  Step& step = deck.model.steps.back();
  if (step.outputs[static_cast<std::size_t>(deck.output)].kind == OutputRequest::Kind::History) {
    error(deck, keyword.where, keyword, "element history output is not supported yet",
          "expected *ELEMENT OUTPUT under *OUTPUT, FIELD");
    return;
  }
  const std::vector<std::string> variables =
      read_names(deck, block, ELEMENT_VARIABLES, "output variable");
  if (block.data.empty()) {
    error(deck, keyword.where, keyword, "no output variables",
          "expected a data line such as S, EVOL");
    return;
  }
  OutputRequest& request = open_request(step, deck.output, false);
  for (const std::string& name : variables) add_unique(request.element_variables, name);
  const std::string set = optional_name(keyword, "ELSET");
  if (!set.empty())
    deck.output_sets.push_back({static_cast<Index>(deck.model.steps.size() - 1), deck.output, false,
                                DeckReference{set, keyword.where, keyword.label()}});
}

void read_energy_output(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(deck, keyword, {{"VARIABLE"}});
  if (deck.output == NO_INDEX) {
    error(deck, keyword.where, keyword, "no *OUTPUT to attach to",
          "expected *OUTPUT, HISTORY just before");
    return;
  }
  OutputRequest& request = deck.model.steps.back().outputs[static_cast<std::size_t>(deck.output)];
  if (request.kind != OutputRequest::Kind::History) {
    error(deck, keyword.where, keyword, "energy output is history output",
          "expected *ENERGY OUTPUT under *OUTPUT, HISTORY");
    return;
  }
  const std::string variable = optional_name(keyword, "VARIABLE");
  if (!variable.empty() && variable != "PRESELECT" && variable != "ALL") {
    error(deck, keyword.where, keyword, "bad VARIABLE=" + variable,
          "expected VARIABLE=PRESELECT or VARIABLE=ALL");
    return;
  }
  const std::vector<std::string> variables =
      read_names(deck, block, ENERGY_VARIABLES, "energy variable");
  const bool all_already = request.energy && request.energy_variables.empty();
  request.energy = true;
  if (variables.empty() || !variable.empty() || all_already) {
    request.energy_variables.clear();  // empty list: every energy
  } else {
    for (const std::string& name : variables) add_unique(request.energy_variables, name);
  }
}

void read_contact_output(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(deck, keyword, {{"GENERAL CONTACT", false}, {"VARIABLE"}});
  if (deck.output == NO_INDEX) {
    error(deck, keyword.where, keyword, "no *OUTPUT to attach to",
          "expected *OUTPUT, FIELD just before");
    return;
  }
  OutputRequest& request = deck.model.steps.back().outputs[static_cast<std::size_t>(deck.output)];
  if (request.kind != OutputRequest::Kind::Field) {
    error(deck, keyword.where, keyword, "contact history output is not supported yet",
          "expected *CONTACT OUTPUT under *OUTPUT, FIELD (contact energies: ALLFD, ALLPW in "
          "*ENERGY OUTPUT)");
    return;
  }
  const std::string variable = optional_name(keyword, "VARIABLE");
  if (!variable.empty() && variable != "PRESELECT" && variable != "ALL") {
    error(deck, keyword.where, keyword, "bad VARIABLE=" + variable,
          "expected VARIABLE=PRESELECT or VARIABLE=ALL");
    return;
  }
  std::vector<std::string> variables =
      read_names(deck, block, CONTACT_VARIABLES, "contact output variable");
  if (!variable.empty()) {
    for (std::string_view name : CONTACT_VARIABLES) add_unique(variables, std::string(name));
  } else if (block.data.empty()) {
    error(deck, keyword.where, keyword, "no output variables",
          "expected a data line such as CSTRESS, CSTATUS, or VARIABLE=PRESELECT");
    return;
  }
  for (const std::string& name : variables) add_unique(request.contact_variables, name);
}

}  // namespace xpl::io
