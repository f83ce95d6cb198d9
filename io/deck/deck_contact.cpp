/// \file Contact definitions: general contact in a step (*CONTACT with *CONTACT INCLUSIONS,
/// *CONTACT EXCLUSIONS, *CONTACT PROPERTY ASSIGNMENT, *CONTACT CONTROLS ASSIGNMENT) and
/// pairwise *CONTACT PAIR, as model data (CalculiX) or in a step. The surface interactions
/// they name are read in deck_interaction.cpp.

#include <algorithm>
#include <array>

#include "io/deck/deck_builder.hpp"

namespace xpl::io {

namespace {

constexpr const char* PAIR_LINE =
    "surface 1, surface 2 (surface 1 blank: all exterior faces; surface 2 blank: self contact "
    "of surface 1)";
constexpr const char* PROPERTY_LINE =
    "surface 1, surface 2, interaction name (both surfaces blank: the global default)";
constexpr const char* CONTROLS_LINE = ", , penalty scale factor";

/// CalculiX contact formulations: all run as node-to-face penalty contact.
constexpr std::array<std::string_view, 6> PAIR_TYPES = {
    "NODE TO SURFACE", "SURFACE TO SURFACE", "MORTAR", "LINMORTAR", "PGMORTAR", "PGLINMORTAR"};

}  // namespace

Index DeckBuilder::contact_surface(const std::string& name, const SourceLocation& where,
                                   const std::string& keyword) {
  const Index surface = m_model.find_surface(name);
  if (surface == NO_INDEX)
    m_errors.add(where, keyword, "undefined surface " + name, "expected *SURFACE, NAME=" + name);
  return surface;
}

Index DeckBuilder::surface_interaction(const std::string& name, const SourceLocation& where,
                                       const std::string& keyword) {
  for (std::size_t i = 0; i < m_model.surface_interactions.size(); ++i)
    if (m_model.surface_interactions[i].name == name) return static_cast<Index>(i);
  m_errors.add(where, keyword, "undefined surface interaction " + name,
               "expected *SURFACE INTERACTION, NAME=" + name);
  return NO_INDEX;
}

std::optional<SurfacePair> DeckBuilder::surface_pair(const DeckDataLine& line,
                                                     const DeckKeyword& keyword) {
  const std::string first = line.fields.empty() ? "" : normalize_name(line.fields[0]);
  const std::string second = line.fields.size() < 2 ? "" : normalize_name(line.fields[1]);
  SurfacePair pair;
  pair.where = line.where();
  bool ok = true;
  if (!first.empty()) {
    pair.first = contact_surface(first, line.where(), keyword.label());
    ok = pair.first != NO_INDEX;
  }
  if (second.empty()) {
    pair.second = pair.first;  // self contact (of all exterior faces, if both are blank)
  } else {
    pair.second = contact_surface(second, line.where(), keyword.label());
    ok = ok && pair.second != NO_INDEX;
  }
  if (!ok) return std::nullopt;
  return pair;
}

void DeckBuilder::read_contact(const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(keyword, {{"OP"}});
  expect_no_data(block);
  const std::string op = optional_name(keyword, "OP");
  if (!op.empty() && op != "MOD" && op != "NEW")  // then read as OP=MOD: no follow-up errors
    error(keyword.where, keyword, "bad OP=" + op,
          "expected OP=MOD (the default: add to the general contact of earlier steps) or OP=NEW");
  std::vector<Step>& steps = m_model.steps;
  if (steps.back().contact) {
    error(keyword.where, keyword, "second *CONTACT in step " + steps.back().name,
          "expected one *CONTACT per step, followed by its options");
    return;
  }
  // Step::contact is the complete definition in effect: start from the latest earlier one.
  GeneralContact contact;
  if (op != "NEW") {
    for (std::size_t s = steps.size() - 1; s-- > 0;) {
      if (steps[s].contact) {
        contact = *steps[s].contact;
        break;
      }
    }
  }
  // Clearance assignments act only in the step that gives them (SPEC C7, C10).
  contact.clearances.clear();
  contact.where = keyword.where;
  steps.back().contact = std::move(contact);
}

void DeckBuilder::read_diagnostics(const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(keyword, {{"CONTACT INITIAL OVERCLOSURE"}, {"DETECT CROSSED SURFACES"}});
  expect_no_data(block);
  // Model data sets the defaults of every step; a step's own setting holds from it on.
  Diagnostics diagnostics = m_in_step && !m_model.steps.empty()
                                ? m_model.diagnostics_of(static_cast<int>(m_model.steps.size()) - 1)
                                : m_model.diagnostics;
  diagnostics.where = keyword.where;
  const std::string level = optional_name(keyword, "CONTACT INITIAL OVERCLOSURE");
  if (level == "DETAIL")
    diagnostics.overclosure_detail = true;
  else if (level == "SUMMARY")
    diagnostics.overclosure_detail = false;
  else if (!level.empty())
    error(keyword.where, keyword, "bad CONTACT INITIAL OVERCLOSURE=" + level,
          "expected CONTACT INITIAL OVERCLOSURE=DETAIL (every adjusted node and offset in the "
          ".msg file) or SUMMARY (counts in the .sta file)");
  const std::string crossed = optional_name(keyword, "DETECT CROSSED SURFACES");
  if (crossed == "ON" || crossed == "YES")
    diagnostics.detect_crossed_surfaces = true;
  else if (crossed == "OFF" || crossed == "NO")
    diagnostics.detect_crossed_surfaces = false;
  else if (!crossed.empty())
    error(keyword.where, keyword, "bad DETECT CROSSED SURFACES=" + crossed,
          "expected DETECT CROSSED SURFACES=ON or OFF");
  if (m_in_step)
    m_model.steps.back().diagnostics = diagnostics;
  else
    m_model.diagnostics = diagnostics;
}

GeneralContact* DeckBuilder::open_contact(const DeckKeyword& keyword) {
  Step& step = m_model.steps.back();
  if (!step.contact) {
    error(keyword.where, keyword, "no *CONTACT in step " + step.name,
          "expected *CONTACT before " + keyword.label() + " in the same step");
    return nullptr;
  }
  return &*step.contact;
}

void DeckBuilder::read_contact_inclusions(const DeckBlock& block, bool inclusions) {
  const DeckKeyword& keyword = block.keyword;
  if (inclusions)
    check_parameters(keyword, {{"ALL EXTERIOR", false}});
  else
    check_parameters(keyword, {});
  GeneralContact* contact = open_contact(keyword);
  if (contact == nullptr) return;
  if (inclusions && find_parameter(keyword, "ALL EXTERIOR") != nullptr) {
    expect_no_data(block);
    contact->all_exterior = true;
    return;
  }
  if (block.data.empty()) {
    error(keyword.where, keyword, "no surface pairs",
          std::string(inclusions ? "expected ALL EXTERIOR or data lines: "
                                 : "expected data lines: ") +
              PAIR_LINE);
    return;
  }
  for (const DeckDataLine& line : block.data) {
    check_field_count(line, keyword, 2, PAIR_LINE);
    const std::optional<SurfacePair> pair = surface_pair(line, keyword);
    if (pair) (inclusions ? contact->inclusions : contact->exclusions).push_back(*pair);
  }
}

void DeckBuilder::read_contact_property_assignment(const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(keyword, {});
  GeneralContact* contact = open_contact(keyword);
  if (contact == nullptr) return;
  if (block.data.empty()) {
    error(keyword.where, keyword, "no assignments",
          std::string("expected data lines: ") + PROPERTY_LINE);
    return;
  }
  for (const DeckDataLine& line : block.data) {
    check_field_count(line, keyword, 3, PROPERTY_LINE);
    if (line.fields.size() < 3 || line.fields[2].empty()) {
      error(line.where(), keyword, "missing surface interaction name",
            std::string("expected ") + PROPERTY_LINE);
      continue;
    }
    const std::optional<SurfacePair> pair = surface_pair(line, keyword);
    const Index interaction =
        surface_interaction(normalize_name(line.fields[2]), line.where(), keyword.label());
    if (pair && interaction != NO_INDEX) contact->properties.emplace_back(*pair, interaction);
  }
}

void DeckBuilder::read_contact_controls_assignment(const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(keyword, {{"TYPE"}});
  GeneralContact* contact = open_contact(keyword);
  if (contact == nullptr) return;
  const std::string type = optional_name(keyword, "TYPE");
  if (type.empty()) {
    error(keyword.where, keyword, "missing parameter TYPE", "expected TYPE=SCALE PENALTY");
    return;
  }
  if (type != "SCALE PENALTY") {
    error(keyword.where, keyword, "TYPE=" + type + " is not supported yet",
          "supported: TYPE=SCALE PENALTY");
    return;
  }
  if (block.data.empty()) {
    error(keyword.where, keyword, "missing penalty scale factor",
          std::string("expected a data line: ") + CONTROLS_LINE);
    return;
  }
  for (const DeckDataLine& line : block.data) {
    check_field_count(line, keyword, 3, CONTROLS_LINE);
    if ((!line.fields.empty() && !line.fields[0].empty()) ||
        (line.fields.size() > 1 && !line.fields[1].empty())) {
      error(line.where(), keyword, "penalty scaling of a surface pair is not supported yet",
            std::string("expected both surfaces blank (the whole general contact): ") +
                CONTROLS_LINE);
      continue;
    }
    const std::optional<Real> factor = real_field(line, keyword, 2, "penalty scale factor");
    if (!factor) continue;
    if (*factor <= 0.0)
      error(line.where(), keyword,
            "penalty scale factor " + number_text(*factor) + " is not positive",
            "expected a factor > 0");
    else
      contact->penalty_scale = *factor;
  }
}

void DeckBuilder::read_contact_pair(const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(
      keyword,
      {{"INTERACTION"}, {"TYPE"}, {"SMALL SLIDING", false}, {"ADJUST"}, {"MECHANICAL CONSTRAINT"}});
  const std::optional<std::string> interaction = required_name(keyword, "INTERACTION");
  const std::string type = optional_name(keyword, "TYPE");
  if (!type.empty() && std::find(PAIR_TYPES.begin(), PAIR_TYPES.end(), type) == PAIR_TYPES.end())
    error(keyword.where, keyword, "unknown TYPE=" + type,
          "expected TYPE=NODE TO SURFACE or SURFACE TO SURFACE (CalculiX)");
  // What xpl does not do differently is said once, in the .msg file.
  std::string unused;
  const auto add_unused = [&](const std::string& text) {
    unused += (unused.empty() ? "" : ", ") + text;
  };
  if (!type.empty() && type != "NODE TO SURFACE") add_unused("TYPE=" + type);
  if (find_parameter(keyword, "SMALL SLIDING") != nullptr) add_unused("SMALL SLIDING");
  if (const std::string adjust = optional_name(keyword, "ADJUST"); !adjust.empty())
    add_unused("ADJUST=" + adjust);
  if (const std::string constraint = optional_name(keyword, "MECHANICAL CONSTRAINT");
      !constraint.empty() && constraint != "PENALTY")
    add_unused("MECHANICAL CONSTRAINT=" + constraint);
  if (!unused.empty())
    note(keyword.where, keyword, "xpl runs node-to-face penalty contact; not used: " + unused);
  if (block.data.empty()) {
    error(keyword.where, keyword, "no surface pairs",
          "expected data lines: slave surface, master surface");
    return;
  }
  const Index step = m_in_step ? static_cast<Index>(m_model.steps.size() - 1) : NO_INDEX;
  for (const DeckDataLine& line : block.data) {
    check_field_count(line, keyword, 2, "slave surface, master surface");
    const bool has_slave = !line.fields.empty() && !line.fields[0].empty();
    const bool has_master = line.fields.size() > 1 && !line.fields[1].empty();
    if (!has_slave || !has_master) {
      error(line.where(), keyword, has_slave ? "missing master surface" : "missing slave surface",
            "expected slave surface, master surface");
      continue;
    }
    if (!interaction) continue;
    m_contact_pairs.push_back({step, normalize_name(line.fields[0]), normalize_name(line.fields[1]),
                               *interaction, line.where()});
  }
}

void DeckBuilder::resolve_contact_pairs() {
  const std::string keyword = "*CONTACT PAIR";
  for (const PendingContactPair& pending : m_contact_pairs) {
    ContactPair pair;
    pair.where = pending.where;
    pair.slave = contact_surface(pending.slave, pending.where, keyword);
    pair.master = contact_surface(pending.master, pending.where, keyword);
    pair.interaction = surface_interaction(pending.interaction, pending.where, keyword);
    if (pair.master != NO_INDEX &&
        m_model.surfaces[static_cast<std::size_t>(pair.master)].type == Surface::Type::Node) {
      m_errors.add(pending.where, keyword, "master surface " + pending.master + " is node-based",
                   "expected an element-based surface (*SURFACE, TYPE=ELEMENT) as the master");
      continue;
    }
    if (pair.slave == NO_INDEX || pair.master == NO_INDEX || pair.interaction == NO_INDEX) continue;
    if (pending.step == NO_INDEX)
      m_model.contact_pairs.push_back(pair);
    else
      m_model.steps[static_cast<std::size_t>(pending.step)].contact_pairs.push_back(pair);
  }
}

}  // namespace xpl::io
