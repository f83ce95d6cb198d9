#include "io/deck/deck_builder.hpp"

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <utility>

#include "io/deck/deck_numbers.hpp"

namespace xpl::io {

namespace {

enum class Context { Model, Step, Anywhere };

using Handler = void (*)(DeckBuilder&, const DeckBlock&);

constexpr const char* SUPPORTED_KEYWORDS =
    "*HEADING, *INCLUDE, *NODE, *ELEMENT, *NSET, *ELSET, *SURFACE, *MATERIAL, *DENSITY, "
    "*ELASTIC, *SOLID SECTION, *SHELL SECTION, *SECTION CONTROLS, *MASS, *ROTARY INERTIA, "
    "*RIGID BODY, *SURFACE INTERACTION, *FRICTION, *SURFACE BEHAVIOR, *CONTACT PAIR, "
    "*CONTACT CLEARANCE, *DISTRIBUTION, *DISTRIBUTION TABLE, *AMPLITUDE, *INITIAL CONDITIONS, "
    "*BOUNDARY, *STEP, *DYNAMIC, *BULK VISCOSITY, *CLOAD, *DLOAD, *DSLOAD, *CONTACT, "
    "*CONTACT INCLUSIONS, *CONTACT EXCLUSIONS, *CONTACT PROPERTY ASSIGNMENT, "
    "*CONTACT CONTROLS ASSIGNMENT, *CONTACT CLEARANCE ASSIGNMENT, *OUTPUT, *NODE OUTPUT, "
    "*ELEMENT OUTPUT, *ENERGY OUTPUT, *CONTACT OUTPUT, *NODE FILE, *EL FILE, *NODE PRINT, "
    "*EL PRINT, *CONTACT FILE, *CONTACT PRINT, *END STEP, *PREPRINT, *DIAGNOSTICS";

/// General contact and its options: step data (as in Abaqus/Explicit).
bool is_general_contact(const std::string& name) {
  return name == "CONTACT" || name == "CONTACT INCLUSIONS" || name == "CONTACT EXCLUSIONS" ||
         name == "CONTACT PROPERTY ASSIGNMENT" || name == "CONTACT CONTROLS ASSIGNMENT" ||
         name == "CONTACT CLEARANCE ASSIGNMENT";
}

}  // namespace

std::string location_text(const SourceLocation& where) {
  return where.file + ":" + std::to_string(where.line);
}

std::string number_text(Real value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

DeckBuilder::DeckBuilder(InputErrors& errors, std::string file_name)
    : m_errors(errors), m_file_name(std::move(file_name)) {
  m_model.job_name = std::filesystem::path(m_file_name).stem().string();
}

void DeckBuilder::read(const std::vector<DeckBlock>& blocks) {
  for (const DeckBlock& block : blocks) read_block(block);
}

void DeckBuilder::read_block(const DeckBlock& block) {
  struct Entry {
    std::string_view name;
    Context context;
    void (DeckBuilder::*handler)(const DeckBlock&);
  };
  static const Entry entries[] = {
      {"HEADING", Context::Model, &DeckBuilder::read_heading},
      {"NODE", Context::Model, &DeckBuilder::read_node},
      {"ELEMENT", Context::Model, &DeckBuilder::read_element},
      {"NSET", Context::Model, nullptr},
      {"ELSET", Context::Model, nullptr},
      {"SURFACE", Context::Model, &DeckBuilder::read_surface},
      {"MATERIAL", Context::Model, &DeckBuilder::read_material},
      {"DENSITY", Context::Model, &DeckBuilder::read_density},
      {"ELASTIC", Context::Model, &DeckBuilder::read_elastic},
      {"SOLID SECTION", Context::Model, &DeckBuilder::read_solid_section},
      {"SHELL SECTION", Context::Model, &DeckBuilder::read_shell_section},
      {"SHELL GENERAL SECTION", Context::Model, &DeckBuilder::read_shell_general_section},
      {"SECTION CONTROLS", Context::Model, &DeckBuilder::read_section_controls},
      {"MASS", Context::Model, nullptr},
      {"ROTARY INERTIA", Context::Model, nullptr},
      {"RIGID BODY", Context::Model, &DeckBuilder::read_rigid_body},
      {"SURFACE INTERACTION", Context::Model, &DeckBuilder::read_surface_interaction},
      {"FRICTION", Context::Model, &DeckBuilder::read_friction},
      {"SURFACE BEHAVIOR", Context::Model, &DeckBuilder::read_surface_behavior},
      {"CONTACT PAIR", Context::Anywhere, &DeckBuilder::read_contact_pair},
      {"CONTACT CLEARANCE", Context::Anywhere, &DeckBuilder::read_contact_clearance},
      {"DISTRIBUTION", Context::Model, &DeckBuilder::read_distribution},
      {"DISTRIBUTION TABLE", Context::Model, &DeckBuilder::read_distribution_table},
      {"AMPLITUDE", Context::Model, &DeckBuilder::read_amplitude},
      {"INITIAL CONDITIONS", Context::Model, &DeckBuilder::read_initial_conditions},
      {"BOUNDARY", Context::Anywhere, &DeckBuilder::read_boundary},
      {"STEP", Context::Anywhere, &DeckBuilder::read_step},
      {"END STEP", Context::Anywhere, &DeckBuilder::read_end_step},
      {"DYNAMIC", Context::Step, &DeckBuilder::read_dynamic},
      {"BULK VISCOSITY", Context::Step, &DeckBuilder::read_bulk_viscosity},
      {"CLOAD", Context::Step, &DeckBuilder::read_cload},
      {"DLOAD", Context::Step, &DeckBuilder::read_dload},
      {"DSLOAD", Context::Step, &DeckBuilder::read_dsload},
      {"CONTACT", Context::Step, &DeckBuilder::read_contact},
      {"CONTACT INCLUSIONS", Context::Step, nullptr},
      {"CONTACT EXCLUSIONS", Context::Step, nullptr},
      {"CONTACT PROPERTY ASSIGNMENT", Context::Step,
       &DeckBuilder::read_contact_property_assignment},
      {"CONTACT CONTROLS ASSIGNMENT", Context::Step,
       &DeckBuilder::read_contact_controls_assignment},
      {"CONTACT CLEARANCE ASSIGNMENT", Context::Step, &DeckBuilder::read_clearance_assignment},
      {"OUTPUT", Context::Step, &DeckBuilder::read_output},
      {"NODE OUTPUT", Context::Step, &DeckBuilder::read_node_output},
      {"ELEMENT OUTPUT", Context::Step, &DeckBuilder::read_element_output},
      {"ENERGY OUTPUT", Context::Step, &DeckBuilder::read_energy_output},
      {"CONTACT OUTPUT", Context::Step, &DeckBuilder::read_contact_output},
      // CalculiX output requests, mapped onto *OUTPUT requests or noted.
      {"NODE FILE", Context::Step, nullptr},
      {"EL FILE", Context::Step, nullptr},
      {"NODE PRINT", Context::Step, &DeckBuilder::read_node_print},
      {"EL PRINT", Context::Step, nullptr},
      {"CONTACT FILE", Context::Step, nullptr},
      {"CONTACT PRINT", Context::Step, nullptr},
      // Only echo control of the Abaqus pre-processor: nothing to do, safe to ignore.
      {"PREPRINT", Context::Anywhere, nullptr},
      {"DIAGNOSTICS", Context::Anywhere, &DeckBuilder::read_diagnostics},
  };
  const DeckKeyword& keyword = block.keyword;
  const std::string& name = keyword.name;
  const auto entry = std::find_if(std::begin(entries), std::end(entries),
                                  [&](const Entry& e) { return e.name == name; });

  // *DENSITY and *ELASTIC belong to the material opened just before; *NODE OUTPUT & co. to
  // the latest *OUTPUT. Any other keyword closes those option blocks.
  if (name != "DENSITY" && name != "ELASTIC") m_material = NO_INDEX;
  if (name != "FRICTION" && name != "SURFACE BEHAVIOR") m_interaction = NO_INDEX;
  const bool output_family = name == "OUTPUT" || name == "NODE OUTPUT" ||
                             name == "ELEMENT OUTPUT" || name == "ENERGY OUTPUT" ||
                             name == "CONTACT OUTPUT";
  if (!output_family) m_output = NO_INDEX;

  if (entry == std::end(entries)) {
    error(keyword.where, keyword, "unknown keyword " + keyword.label(),
          std::string("supported keywords: ") + SUPPORTED_KEYWORDS);
    return;
  }
  if (entry->context == Context::Model && m_in_step) {
    error(keyword.where, keyword, "model data cannot appear inside a step",
          "expected it before the first *STEP");
    return;
  }
  if ((entry->context == Context::Model || name == "BOUNDARY" || name == "CONTACT PAIR" ||
       name == "CONTACT CLEARANCE") &&
      !m_in_step && !m_model.steps.empty()) {
    error(keyword.where, keyword, "model data after the first step",
          "expected all model data before the first *STEP");
    return;
  }
  if (is_general_contact(name) && !m_in_step) {
    error(keyword.where, keyword, "general contact outside a step",
          "expected *CONTACT and its options between *STEP and *END STEP, as in "
          "Abaqus/Explicit (*CONTACT PAIR may be model data)");
    return;
  }
  if (entry->context == Context::Step && !m_in_step) {
    error(keyword.where, keyword, "history data outside a step",
          "expected it between *STEP and *END STEP");
    return;
  }
  if (name == "NSET" || name == "ELSET") {
    read_set(block, name == "NSET");
  } else if (name == "MASS" || name == "ROTARY INERTIA") {
    read_point_property(block, name == "ROTARY INERTIA");
  } else if (name == "CONTACT INCLUSIONS" || name == "CONTACT EXCLUSIONS") {
    read_contact_inclusions(block, name == "CONTACT INCLUSIONS");
  } else if (name == "NODE FILE" || name == "EL FILE") {
    read_file_output(block, name == "NODE FILE");
  } else if (name == "EL PRINT") {
    read_ignored_output(block, "element history output is not available in xpl; ignored");
  } else if (name == "CONTACT FILE" || name == "CONTACT PRINT") {
    read_ignored_output(block,
                        "ignored: contact results are requested with *CONTACT OUTPUT (CSTRESS, "
                        "CSTATUS, CFORCE) and the energies ALLFD, ALLPW in *ENERGY OUTPUT");
  } else if (entry->handler != nullptr) {
    (this->*(entry->handler))(block);
  }
}

void DeckBuilder::error(const SourceLocation& where, const DeckKeyword& keyword,
                        const std::string& problem, const std::string& expected) {
  m_errors.add(where, keyword.label(), problem, expected);
}

void DeckBuilder::capped_error(int& count, const SourceLocation& where, const std::string& keyword,
                               const std::string& problem, const std::string& expected) {
  ++count;
  if (count <= ERROR_CAP) m_errors.add(where, keyword, problem, expected);
}

bool DeckBuilder::check_parameters(const DeckKeyword& keyword,
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
      error(keyword.where, keyword, "unknown parameter " + p.name, accepted_list());
      ok = false;
      continue;
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (keyword.parameters[j].name == p.name) {
        error(keyword.where, keyword, "parameter " + p.name + " given twice",
              "expected it at most once");
        ok = false;
      }
    }
    if (spec->value_optional) {
      if (p.has_value && p.value.empty()) {
        error(keyword.where, keyword, "parameter " + p.name + " has an empty value",
              "expected " + p.name + " alone or " + p.name + "=value");
        ok = false;
      }
    } else if (spec->takes_value && (!p.has_value || p.value.empty())) {
      error(keyword.where, keyword, "parameter " + p.name + " has no value",
            "expected " + p.name + "=value");
      ok = false;
    } else if (!spec->takes_value && p.has_value) {
      error(keyword.where, keyword, "parameter " + p.name + " takes no value",
            "expected the flag " + p.name + " alone");
      ok = false;
    }
  }
  return ok;
}

const DeckParameter* DeckBuilder::find_parameter(const DeckKeyword& keyword,
                                                 std::string_view name) {
  for (const DeckParameter& p : keyword.parameters)
    if (p.name == name) return &p;
  return nullptr;
}

std::optional<std::string> DeckBuilder::required_name(const DeckKeyword& keyword,
                                                      std::string_view name) {
  const DeckParameter* p = find_parameter(keyword, name);
  if (p == nullptr) {
    error(keyword.where, keyword, "missing parameter " + std::string(name),
          "expected " + std::string(name) + "=name");
    return std::nullopt;
  }
  if (!p->has_value || p->value.empty()) return std::nullopt;  // check_parameters reported it
  return normalize_name(p->value);
}

std::string DeckBuilder::optional_name(const DeckKeyword& keyword, std::string_view name) {
  const DeckParameter* p = find_parameter(keyword, name);
  return p != nullptr && p->has_value ? normalize_name(p->value) : std::string();
}

void DeckBuilder::note(const SourceLocation& where, const DeckKeyword& keyword,
                       const std::string& text) {
  m_model.deck_messages.push_back(
      {false, location_text(where) + ": " + keyword.label() + ": " + text});
}

void DeckBuilder::expect_no_data(const DeckBlock& block) {
  if (!block.data.empty())
    error(block.data.front().where(), block.keyword, "unexpected data line",
          "expected no data lines after " + block.keyword.label());
}

std::optional<Real> DeckBuilder::real_field(const DeckDataLine& line, const DeckKeyword& keyword,
                                            std::size_t i, std::string_view what,
                                            std::optional<Real> blank) {
  if (i >= line.fields.size() || line.fields[i].empty()) {
    if (!blank) error(line.where(), keyword, "missing " + std::string(what), "expected a number");
    return blank;
  }
  const std::optional<Real> value = parse_real(line.fields[i]);
  if (!value)
    error(line.where(), keyword,
          "bad number '" + std::string(line.fields[i]) + "' for " + std::string(what),
          "expected a real number such as 2, -1.5, 1e3 or 1.0D3");
  return value;
}

std::optional<long long> DeckBuilder::integer_field(const DeckDataLine& line,
                                                    const DeckKeyword& keyword, std::size_t i,
                                                    std::string_view what) {
  if (i >= line.fields.size() || line.fields[i].empty()) {
    error(line.where(), keyword, "missing " + std::string(what), "expected an integer");
    return std::nullopt;
  }
  const std::optional<long long> value = parse_integer(line.fields[i]);
  if (!value)
    error(line.where(), keyword,
          "bad integer '" + std::string(line.fields[i]) + "' for " + std::string(what),
          "expected an integer such as 12");
  return value;
}

bool DeckBuilder::check_field_count(const DeckDataLine& line, const DeckKeyword& keyword,
                                    std::size_t count, const std::string& expected) {
  if (line.fields.size() <= count) return true;
  error(line.where(), keyword,
        "too many values (" + std::to_string(line.fields.size()) + ") on the data line",
        "expected " + expected);
  return false;
}

DeckReference DeckBuilder::reference(const DeckDataLine& line, const DeckKeyword& keyword,
                                     std::size_t i) {
  DeckReference ref;
  if (i < line.fields.size()) ref.token = line.fields[i];
  if (!looks_numeric(ref.token)) ref.token = normalize_name(ref.token);
  ref.where = line.where();
  ref.keyword = keyword.label();
  return ref;
}

Index DeckBuilder::node_set_index(const std::string& name, const SourceLocation& where) {
  const auto [it, inserted] =
      m_node_set_index.emplace(name, static_cast<Index>(m_model.node_sets.size()));
  if (inserted) {
    m_model.node_sets.push_back({name, {}, where});
    m_node_sets.emplace_back();
  }
  return it->second;
}

Index DeckBuilder::element_set_index(const std::string& name, const SourceLocation& where) {
  const auto [it, inserted] =
      m_element_set_index.emplace(name, static_cast<Index>(m_model.element_sets.size()));
  if (inserted) {
    m_model.element_sets.push_back({name, {}, where});
    m_element_sets.emplace_back();
  }
  return it->second;
}

}  // namespace xpl::io
