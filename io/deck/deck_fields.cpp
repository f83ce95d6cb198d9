/// \file Helpers the keyword handlers share: messages, parameters, data fields, references and
/// set indices.

#include "io/deck/deck_fields.hpp"

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <utility>

#include "io/deck/deck_numbers.hpp"

namespace xpl::io {

std::string location_text(const SourceLocation& where) {
  return where.file + ":" + std::to_string(where.line);
}

std::string number_text(Real value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

DeckState::DeckState(InputErrors& errors, std::string file_name)
    : errors(errors), file_name(std::move(file_name)) {
  model.job_name = std::filesystem::path(this->file_name).stem().string();
}

void error(DeckState& deck, const SourceLocation& where, const DeckKeyword& keyword,
           const std::string& problem, const std::string& expected) {
  deck.errors.add(where, keyword.label(), problem, expected);
}

void capped_error(DeckState& deck, int& count, const SourceLocation& where,
                  const std::string& keyword, const std::string& problem,
                  const std::string& expected) {
  ++count;
  if (count <= ERROR_CAP) deck.errors.add(where, keyword, problem, expected);
}

bool check_parameters(DeckState& deck, const DeckKeyword& keyword,
                      std::initializer_list<ParameterSpec> accepted) {
  auto accepted_list = [&] {
    if (accepted.size() == 0) return std::string("accepted parameters: none");
    std::string list = "accepted parameters: ";
    bool first = true;
    for (const ParameterSpec& spec : accepted) {
      if (!first) list += ", ";
      list += spec.name;
      if (spec.takes_value) list += "=";
      first = false;
    }
    return list;
  };
  bool ok = true;
  for (std::size_t i = 0; i < keyword.parameters.size(); ++i) {
    const DeckParameter& p = keyword.parameters[i];
    const auto spec = std::find_if(accepted.begin(), accepted.end(),
                                   [&](const ParameterSpec& s) { return s.name == p.name; });
    if (spec == accepted.end()) {
      error(deck, keyword.where, keyword, "unknown parameter " + p.name, accepted_list());
      ok = false;
      continue;
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (keyword.parameters[j].name == p.name) {
        error(deck, keyword.where, keyword, "parameter " + p.name + " given twice",
              "expected it at most once");
        ok = false;
      }
    }
    if (spec->value_optional) {
      if (p.has_value && p.value.empty()) {
        error(deck, keyword.where, keyword, "parameter " + p.name + " has an empty value",
              "expected " + p.name + " alone or " + p.name + "=value");
        ok = false;
      }
    } else if (spec->takes_value && (!p.has_value || p.value.empty())) {
      error(deck, keyword.where, keyword, "parameter " + p.name + " has no value",
            "expected " + p.name + "=value");
      ok = false;
    } else if (!spec->takes_value && p.has_value) {
      error(deck, keyword.where, keyword, "parameter " + p.name + " takes no value",
            "expected the flag " + p.name + " alone");
      ok = false;
    }
  }
  return ok;
}

const DeckParameter* find_parameter(const DeckKeyword& keyword, std::string_view name) {
  for (const DeckParameter& p : keyword.parameters)
    if (p.name == name) return &p;
  return nullptr;
}

std::optional<std::string> required_name(DeckState& deck, const DeckKeyword& keyword,
                                         std::string_view name) {
  const DeckParameter* p = find_parameter(keyword, name);
  if (p == nullptr) {
    error(deck, keyword.where, keyword, "missing parameter " + std::string(name),
          "expected " + std::string(name) + "=name");
    return std::nullopt;
  }
  if (!p->has_value || p->value.empty()) return std::nullopt;  // check_parameters reported it
  return normalize_name(p->value);
}

std::string optional_name(const DeckKeyword& keyword, std::string_view name) {
  const DeckParameter* p = find_parameter(keyword, name);
  return p != nullptr && p->has_value ? normalize_name(p->value) : std::string();
}

void note(DeckState& deck, const SourceLocation& where, const DeckKeyword& keyword,
          const std::string& text) {
  deck.model.deck_messages.push_back(
      {false, location_text(where) + ": " + keyword.label() + ": " + text});
}

void expect_no_data(DeckState& deck, const DeckBlock& block) {
  if (!block.data.empty())
    error(deck, block.data.front().where(), block.keyword, "unexpected data line",
          "expected no data lines after " + block.keyword.label());
}

std::optional<Real> real_field(DeckState& deck, const DeckDataLine& line,
                               const DeckKeyword& keyword, std::size_t i, std::string_view what,
                               std::optional<Real> blank) {
  if (i >= line.fields.size() || line.fields[i].empty()) {
    if (!blank)
      error(deck, line.where(), keyword, "missing " + std::string(what), "expected a number");
    return blank;
  }
  const std::optional<Real> value = parse_real(line.fields[i]);
  if (!value)
    error(deck, line.where(), keyword,
          "bad number '" + std::string(line.fields[i]) + "' for " + std::string(what),
          "expected a real number such as 2, -1.5, 1e3 or 1.0D3");
  return value;
}

std::optional<long long> integer_field(DeckState& deck, const DeckDataLine& line,
                                       const DeckKeyword& keyword, std::size_t i,
                                       std::string_view what) {
  if (i >= line.fields.size() || line.fields[i].empty()) {
    error(deck, line.where(), keyword, "missing " + std::string(what), "expected an integer");
    return std::nullopt;
  }
  const std::optional<long long> value = parse_integer(line.fields[i]);
  if (!value)
    error(deck, line.where(), keyword,
          "bad integer '" + std::string(line.fields[i]) + "' for " + std::string(what),
          "expected an integer such as 12");
  return value;
}

bool check_field_count(DeckState& deck, const DeckDataLine& line, const DeckKeyword& keyword,
                       std::size_t count, const std::string& expected) {
  if (line.fields.size() <= count) return true;
  error(deck, line.where(), keyword,
        "too many values (" + std::to_string(line.fields.size()) + ") on the data line",
        "expected " + expected);
  return false;
}

bool check_surface_pair(DeckState& deck, const DeckDataLine& line, const DeckKeyword& keyword) {
  const bool has_slave = !line.fields.empty() && !line.fields[0].empty();
  const bool has_master = line.fields.size() > 1 && !line.fields[1].empty();
  if (has_slave && has_master) return true;
  error(deck, line.where(), keyword, has_slave ? "missing master surface" : "missing slave surface",
        "expected slave surface, master surface");
  return false;
}

DeckReference reference(const DeckDataLine& line, const DeckKeyword& keyword, std::size_t i) {
  DeckReference ref;
  if (i < line.fields.size()) ref.token = line.fields[i];
  if (!looks_numeric(ref.token)) ref.token = normalize_name(ref.token);
  ref.where = line.where();
  ref.keyword = keyword.label();
  return ref;
}

DeckReference reference(const DeckState& deck, const DeckDataLine& line, const DeckKeyword& keyword,
                        std::size_t i) {
  DeckReference ref = reference(line, keyword, i);
  if (looks_numeric(ref.token))
    ref.scope = deck.scope;
  else
    ref.token = deck.scoped_name(ref.token);
  return ref;
}

Index node_set_index(DeckState& deck, const std::string& name, const SourceLocation& where) {
  const auto [it, inserted] =
      deck.node_set_by_name.emplace(name, static_cast<Index>(deck.model.node_sets.size()));
  if (inserted) {
    deck.model.node_sets.push_back({name, {}, where});
    deck.node_sets.emplace_back();
  }
  return it->second;
}

Index element_set_index(DeckState& deck, const std::string& name, const SourceLocation& where) {
  const auto [it, inserted] =
      deck.element_set_by_name.emplace(name, static_cast<Index>(deck.model.element_sets.size()));
  if (inserted) {
    deck.model.element_sets.push_back({name, {}, where});
    deck.element_sets.emplace_back();
  }
  return it->second;
}

}  // namespace xpl::io
