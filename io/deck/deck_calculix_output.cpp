/// \file CalculiX output keywords in a step: *NODE FILE and *EL FILE become field output
/// requests, *NODE PRINT a history request, each with the variables xpl writes; *EL PRINT,
/// *CONTACT FILE and *CONTACT PRINT are accepted and ignored. Everything dropped or not used
/// is said in a note (.msg file), so that a CalculiX deck runs without edits and without
/// surprises.
///
/// CalculiX writes every FREQUENCY=n-th increment; an explicit run has thousands of them, so
/// the requests take the Abaqus/Explicit defaults instead (20 field frames, 200 history
/// points per step), and FREQUENCY= is noted as not used.

#include "io/deck/deck_handlers.hpp"
#include "io/deck/deck_output_variables.hpp"

namespace xpl::io {

namespace {

std::string joined(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

/// "FREQUENCY=100, OUTPUT=3D": the parameters other than the set, which xpl does not use.
std::string unused_parameters(const DeckKeyword& keyword, std::string_view set_parameter) {
  std::vector<std::string> unused;
  for (const DeckParameter& p : keyword.parameters)
    if (p.name != set_parameter) unused.push_back(p.has_value ? p.name + "=" + p.value : p.name);
  return joined(unused);
}

}  // namespace

void read_file_output(DeckState& deck, const DeckBlock& block, bool node) {
  const DeckKeyword& keyword = block.keyword;
  const std::string_view set_parameter = node ? "NSET" : "ELSET";
  if (node)
    check_parameters(deck, keyword,
                     {{"NSET"},
                      {"FREQUENCY"},
                      {"FREQUENCYF"},
                      {"OUTPUT"},
                      {"GLOBAL"},
                      {"TIME POINTS"},
                      {"LAST ITERATIONS", false},
                      {"CONTACT ELEMENTS", false}});
  else
    check_parameters(deck, keyword,
                     {{"ELSET"},
                      {"NSET"},  // CalculiX: nodes of the extrapolated output; noted, not used
                      {"FREQUENCY"},
                      {"FREQUENCYF"},
                      {"OUTPUT"},
                      {"POSITION"},
                      {"GLOBAL"},
                      {"TIME POINTS"},
                      {"LAST ITERATIONS", false},
                      {"CONTACT ELEMENTS", false},
                      {"SECTION FORCES", false}});
  if (block.data.empty()) {
    error(deck, keyword.where, keyword, "no output variables",
          node ? "expected a data line such as U, RF" : "expected a data line such as S");
    return;
  }
  std::vector<std::string> variables, dropped;
  for (const DeckDataLine& line : block.data) {
    for (const std::string_view field : line.fields) {
      if (field.empty()) continue;
      const std::string name = normalize_name(field);
      const bool known =
          node ? contains(FIELD_NODE_VARIABLES, name) : contains(ELEMENT_VARIABLES, name);
      add_unique(known ? variables : dropped, name);
    }
  }
  std::string text;
  const std::string set = optional_name(keyword, set_parameter);
  if (variables.empty()) {
    text = "nothing written: no variable is available in xpl";
  } else {
    text = std::string("read as *OUTPUT, FIELD, NUMBER INTERVAL=20 with ") +
           (node ? "*NODE OUTPUT" : "*ELEMENT OUTPUT") +
           (set.empty() ? "" : ", " + std::string(set_parameter) + "=" + set) + ": " +
           joined(variables);
    Step& step = deck.model.steps.back();
    OutputRequest request;
    request.kind = OutputRequest::Kind::Field;
    request.number_interval = 20;  // the Abaqus/Explicit default
    (node ? request.node_variables : request.element_variables) = variables;
    request.where = keyword.where;
    step.outputs.push_back(std::move(request));
    if (!set.empty())
      deck.output_sets.push_back({static_cast<Index>(deck.model.steps.size() - 1),
                                  static_cast<Index>(step.outputs.size() - 1), node,
                                  DeckReference{set, keyword.where, keyword.label()}});
  }
  if (!dropped.empty()) text += "; dropped (not available in xpl): " + joined(dropped);
  if (const std::string unused = unused_parameters(keyword, set_parameter); !unused.empty())
    text += "; not used: " + unused;
  note(deck, keyword.where, keyword, text);
}

void read_node_print(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(deck, keyword,
                   {{"NSET"},
                    {"FREQUENCY"},
                    {"FREQUENCYF"},
                    {"TOTALS"},
                    {"GLOBAL"},
                    {"TIME POINTS"},
                    {"LAST ITERATIONS", false},
                    {"CONTACT ELEMENTS", false}});
  const std::optional<std::string> set = required_name(deck, keyword, "NSET");
  if (block.data.empty()) {
    error(deck, keyword.where, keyword, "no output variables",
          "expected a data line such as U, RF");
    return;
  }
  std::vector<std::string> components, variables, dropped;
  for (const DeckDataLine& line : block.data) {
    for (const std::string_view field : line.fields) {
      if (field.empty()) continue;
      const std::string name = normalize_name(field);
      add_unique(add_history_node_variable(components, name) ? variables : dropped, name);
    }
  }
  if (!set) return;
  std::string text;
  if (variables.empty()) {
    text = "nothing written: no variable is available in xpl";
  } else {
    text = "read as *OUTPUT, HISTORY, NUMBER INTERVAL=200 with *NODE OUTPUT, NSET=" + *set + ": " +
           joined(variables);
    Step& step = deck.model.steps.back();
    OutputRequest request;
    request.kind = OutputRequest::Kind::History;
    request.number_interval = 200;  // the Abaqus/Explicit default
    request.node_variables = components;
    request.where = keyword.where;
    step.outputs.push_back(std::move(request));
    deck.output_sets.push_back({static_cast<Index>(deck.model.steps.size() - 1),
                                static_cast<Index>(step.outputs.size() - 1), true,
                                DeckReference{*set, keyword.where, keyword.label()}});
  }
  if (!dropped.empty()) text += "; dropped (not available in xpl): " + joined(dropped);
  if (const std::string unused = unused_parameters(keyword, "NSET"); !unused.empty())
    text += "; not used: " + unused;
  note(deck, keyword.where, keyword, text);
}

void read_ignored_output(DeckState& deck, const DeckBlock& block, const std::string& why) {
  // Neither parameters nor data lines are checked: nothing of the keyword is used.
  note(deck, block.keyword.where, block.keyword, why);
}

void read_el_print(DeckState& deck, const DeckBlock& block) {
  read_ignored_output(deck, block, "element history output is not available in xpl; ignored");
}

void read_contact_file(DeckState& deck, const DeckBlock& block) {
  read_ignored_output(deck, block,
                      "ignored: contact results are requested with *CONTACT OUTPUT (CSTRESS, "
                      "CSTATUS, CFORCE) and the energies ALLFD, ALLPW in *ENERGY OUTPUT");
}

}  // namespace xpl::io
