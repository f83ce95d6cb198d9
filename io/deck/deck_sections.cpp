/// \file Section keywords (*SOLID SECTION, *SHELL SECTION) and the assignment of sections to
/// elements once the whole deck is read: solids take a *SOLID SECTION, shells a *SHELL SECTION.

#include "io/deck/deck_handlers.hpp"
#include "io/deck/deck_numbers.hpp"

namespace xpl::io {

namespace {

/// A sanity bound: more points through the thickness than this is a typing mistake, and the
/// count must fit the Model's int.
constexpr long long MAX_INTEGRATION_POINTS = 99;

constexpr const char* SHELL_DATA_LINE = "thickness[, number of integration points]";

}  // namespace

void read_solid_section(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(deck, keyword, {{"ELSET"}, {"MATERIAL"}, {"CONTROLS"}});
  std::optional<std::string> element_set = required_name(deck, keyword, "ELSET");
  if (element_set) element_set = deck.scoped_name(*element_set);
  const std::optional<std::string> material = required_name(deck, keyword, "MATERIAL");
  // Abaqus allows one data line (a thickness-like number for solids); it means nothing here.
  if (block.data.size() > 1 || (block.data.size() == 1 && block.data.front().fields.size() > 1))
    error(deck, block.data.front().where(), keyword, "unexpected data",
          "expected at most one data line with at most one number");
  else if (block.data.size() == 1)
    real_field(deck, block.data.front(), keyword, 0, "section value", 0.0);
  if (!element_set || !material) return;
  SolidSection section;
  section.where = keyword.where;
  deck.model.solid_sections.push_back(section);
  deck.sections.push_back({*element_set, *material, optional_name(keyword, "CONTROLS")});
}

void read_shell_section(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(deck, keyword,
                   {{"ELSET"},
                    {"MATERIAL"},
                    {"OFFSET"},
                    {"CONTROLS"},
                    {"SECTION INTEGRATION"},
                    {"ROTARY INERTIA"}});
  std::optional<std::string> element_set = required_name(deck, keyword, "ELSET");
  if (element_set) element_set = deck.scoped_name(*element_set);
  const std::optional<std::string> material = required_name(deck, keyword, "MATERIAL");
  ShellSection section;
  section.where = keyword.where;

  const std::string offset = optional_name(keyword, "OFFSET");
  if (offset == "SPOS") {
    section.offset = 0.5;
  } else if (offset == "SNEG") {
    section.offset = -0.5;
  } else if (!offset.empty() && offset != "MIDSURFACE") {
    const std::optional<Real> value = looks_numeric(offset) ? parse_real(offset) : std::nullopt;
    if (!value)
      error(deck, keyword.where, keyword, "unknown OFFSET=" + offset,
            "expected OFFSET=SPOS, SNEG, MIDSURFACE or a fraction of the thickness between -0.5 "
            "and 0.5");
    else if (*value < -0.5 || *value > 0.5)
      error(deck, keyword.where, keyword,
            "OFFSET=" + number_text(*value) + " is outside [-0.5, 0.5]",
            "expected a fraction of the thickness between -0.5 (SNEG) and 0.5 (SPOS)");
    else
      section.offset = *value;
  }

  const std::string rotary = optional_name(keyword, "ROTARY INERTIA");
  if (rotary == "EXACT")
    section.rotary_exact = true;
  else if (!rotary.empty() && rotary != "ISOTROPIC")
    error(deck, keyword.where, keyword, "unknown ROTARY INERTIA=" + rotary,
          "expected ROTARY INERTIA=ISOTROPIC (the default, scaled to keep the membrane "
          "increment) or EXACT (t^2/12, with a smaller increment on thin elements)");

  const std::string integration = optional_name(keyword, "SECTION INTEGRATION");
  if (integration == "GAUSS")
    error(deck, keyword.where, keyword, "SECTION INTEGRATION=GAUSS is not supported yet",
          "supported: SECTION INTEGRATION=SIMPSON (the default)");
  else if (!integration.empty() && integration != "SIMPSON")
    error(deck, keyword.where, keyword, "unknown SECTION INTEGRATION=" + integration,
          "expected SECTION INTEGRATION=SIMPSON");

  if (block.data.empty() || block.data.front().fields.empty() ||
      block.data.front().fields[0].empty()) {
    error(deck, block.data.empty() ? keyword.where : block.data.front().where(), keyword,
          "missing shell thickness", std::string("expected a data line: ") + SHELL_DATA_LINE);
  } else {
    const DeckDataLine& line = block.data.front();
    check_field_count(deck, line, keyword, 2, SHELL_DATA_LINE);
    const std::optional<Real> thickness = real_field(deck, line, keyword, 0, "shell thickness");
    if (thickness && *thickness <= 0.0)
      error(deck, line.where(), keyword,
            "shell thickness " + number_text(*thickness) + " is not positive",
            "expected a thickness > 0");
    else if (thickness)
      section.thickness = *thickness;
    if (line.fields.size() > 1 && !line.fields[1].empty()) {
      const std::string text(line.fields[1]);
      const std::optional<long long> points = parse_integer(text);
      const std::string expected = "expected an odd number of points from 1 to " +
                                   std::to_string(MAX_INTEGRATION_POINTS) +
                                   " (Simpson's rule through the thickness), e.g. 5";
      if (!points)
        error(deck, line.where(), keyword, "bad number of integration points '" + text + "'",
              expected);
      else if (*points < 1)
        error(deck, line.where(), keyword,
              "number of integration points " + text + " is less than 1", expected);
      else if (*points > MAX_INTEGRATION_POINTS)
        error(deck, line.where(), keyword, "number of integration points " + text + " is too large",
              expected);
      else if (*points % 2 == 0)
        error(deck, line.where(), keyword, "number of integration points " + text + " is even",
              expected);
      else
        section.integration_points = static_cast<int>(*points);
    }
  }
  if (block.data.size() > 1)
    error(deck, block.data[1].where(), keyword, "unexpected second data line",
          std::string("expected one data line: ") + SHELL_DATA_LINE +
              " (composite layups are not supported)");
  // A section with bad values is still recorded: its elements then have a section, and the
  // bad value is the only error reported.
  if (!element_set || !material) return;
  deck.model.shell_sections.push_back(section);
  deck.shell_sections.push_back({*element_set, *material, optional_name(keyword, "CONTROLS")});
}

void read_shell_general_section(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  error(deck, keyword.where, keyword,
        "general shell sections (section stiffness given directly) are not supported",
        "expected *SHELL SECTION, ELSET=, MATERIAL= with the thickness on the data line");
  const std::string element_set = deck.scoped_name(optional_name(keyword, "ELSET"));
  if (!element_set.empty()) deck.refused_section_sets.push_back(element_set);
}

void resolve_sections(DeckState& deck) {
  deck.model.element_section.assign(static_cast<std::size_t>(deck.model.element_count()), NO_INDEX);
  std::vector<bool> material_checked(deck.model.materials.size(), false);
  for (std::size_t s = 0; s < deck.sections.size(); ++s) {
    SolidSection& section = deck.model.solid_sections[s];
    section.element_set =
        resolve_section_references(deck, deck.sections[s], "*SOLID SECTION", section.where,
                                   section.material, section.controls, material_checked);
    assign_section(deck, section.element_set, static_cast<Index>(s), false, section.where);
  }
  for (std::size_t s = 0; s < deck.shell_sections.size(); ++s) {
    ShellSection& section = deck.model.shell_sections[s];
    section.element_set =
        resolve_section_references(deck, deck.shell_sections[s], "*SHELL SECTION", section.where,
                                   section.material, section.controls, material_checked);
    assign_section(deck, section.element_set, static_cast<Index>(s), true, section.where);
  }

  for (const std::string& name : deck.refused_section_sets) {
    const auto set = deck.element_set_by_name.find(name);
    if (set == deck.element_set_by_name.end()) continue;
    deck.section_reported.resize(static_cast<std::size_t>(deck.model.element_count()), 0);
    for (Index e : deck.model.element_sets[static_cast<std::size_t>(set->second)].members)
      deck.section_reported[static_cast<std::size_t>(e)] = 1;
  }
  for (Index e = 0; e < deck.model.element_count(); ++e) {
    if (deck.model.element_section[static_cast<std::size_t>(e)] != NO_INDEX) continue;
    if (!deck.section_reported.empty() && deck.section_reported[static_cast<std::size_t>(e)] != 0)
      continue;
    const bool shell = is_shell(deck.model.element_types[static_cast<std::size_t>(e)]);
    capped_error(
        deck, deck.error_counts[NO_SECTION], deck.model.element_where(e), "*ELEMENT",
        "element " + std::to_string(deck.model.element_ids[e]) + " has no section",
        shell ? "expected a *SHELL SECTION covering it" : "expected a *SOLID SECTION covering it");
  }
}

Index resolve_section_references(DeckState& deck, const PendingSection& pending,
                                 const std::string& keyword, const SourceLocation& where,
                                 Index& material, Index& controls,
                                 std::vector<bool>& material_checked) {
  material = deck.model.find_material(pending.material);
  if (material == NO_INDEX) {
    deck.errors.add(where, keyword, "undefined material " + pending.material,
                    "expected *MATERIAL, NAME=" + pending.material);
  } else if (!material_checked[static_cast<std::size_t>(material)]) {
    material_checked[static_cast<std::size_t>(material)] = true;
    const Material& m = deck.model.materials[static_cast<std::size_t>(material)];
    if (!m.has_density)
      deck.errors.add(m.where, "*MATERIAL", "material " + m.name + " has no density",
                      "expected *DENSITY after *MATERIAL, NAME=" + m.name);
    if (!m.has_elastic)
      deck.errors.add(m.where, "*MATERIAL", "material " + m.name + " has no elastic data",
                      "expected *ELASTIC after *MATERIAL, NAME=" + m.name);
  }
  controls = NO_INDEX;
  if (!pending.controls.empty()) {
    for (std::size_t c = 0; c < deck.model.section_controls.size(); ++c)
      if (deck.model.section_controls[c].name == pending.controls) controls = static_cast<Index>(c);
    if (controls == NO_INDEX)
      deck.errors.add(where, keyword, "undefined section controls " + pending.controls,
                      "expected *SECTION CONTROLS, NAME=" + pending.controls);
  }
  const auto set = deck.element_set_by_name.find(pending.element_set);
  if (set == deck.element_set_by_name.end()) {
    if (deck.refused_element_set(pending.element_set)) return NO_INDEX;
    deck.errors.add(where, keyword, "undefined element set " + pending.element_set,
                    "expected *ELSET, ELSET=" + pending.element_set + " or *ELEMENT, ELSET=");
    return NO_INDEX;
  }
  return set->second;
}

void assign_section(DeckState& deck, Index set, Index section, bool shell,
                    const SourceLocation& where) {
  if (set == NO_INDEX) return;
  const std::string keyword = shell ? "*SHELL SECTION" : "*SOLID SECTION";
  for (Index e : deck.model.element_sets[static_cast<std::size_t>(set)].members) {
    const std::string element = "element " + std::to_string(deck.model.element_ids[e]);
    if (is_shell(deck.model.element_types[static_cast<std::size_t>(e)]) != shell) {
      capped_error(
          deck, deck.error_counts[WRONG_SECTION_KIND], where, keyword,
          shell ? element + " is a " +
                      element_type_name(deck.model.element_types[static_cast<std::size_t>(e)]) +
                      " solid element"
                : element + " is an S4R shell element",
          shell ? "expected a *SOLID SECTION for it (*SHELL SECTION is for S4R elements)"
                : "expected a *SHELL SECTION for it (*SOLID SECTION is for C3D8R and C3D8 "
                  "elements)");
      deck.section_reported.resize(static_cast<std::size_t>(deck.model.element_count()), 0);
      deck.section_reported[static_cast<std::size_t>(e)] = 1;
      continue;
    }
    Index& assigned = deck.model.element_section[static_cast<std::size_t>(e)];
    if (assigned != NO_INDEX) {
      // Both sections are of this element's kind (the other kind is never assigned).
      const SourceLocation& other =
          shell ? deck.model.shell_sections[static_cast<std::size_t>(assigned)].where
                : deck.model.solid_sections[static_cast<std::size_t>(assigned)].where;
      capped_error(deck, deck.error_counts[TWO_SECTIONS], where, keyword,
                   element + " already has the section at " + location_text(other),
                   "expected each element in exactly one " + keyword);
      continue;
    }
    assigned = section;
  }
}

}  // namespace xpl::io
