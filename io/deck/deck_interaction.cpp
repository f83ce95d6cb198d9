/// \file Contact properties: *SURFACE INTERACTION with its options *FRICTION and
/// *SURFACE BEHAVIOR (Abaqus and CalculiX forms). Contact definitions that use them are in
/// deck_contact.cpp.

#include "io/deck/deck_builder.hpp"

namespace xpl::io {

namespace {

constexpr const char* LINEAR_LINE = "slope (contact pressure per unit overclosure, Pa/m)";

}  // namespace

void DeckBuilder::read_surface_interaction(const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(keyword, {{"NAME"}});
  // The optional data line (Abaqus: out-of-plane thickness of 2D models, or the area of a
  // node-based surface) has no meaning for 3D penalty contact: checked, not kept.
  if (block.data.size() > 1)
    error(block.data[1].where(), keyword, "unexpected second data line",
          "expected at most one data line (out-of-plane thickness, ignored in 3D)");
  else if (block.data.size() == 1)
    real_field(block.data.front(), keyword, 0, "out-of-plane thickness", 1.0);
  const std::optional<std::string> name = required_name(keyword, "NAME");
  if (!name) return;
  for (const SurfaceInteraction& other : m_model.surface_interactions) {
    if (other.name == *name) {
      error(keyword.where, keyword,
            "surface interaction " + *name + " is defined twice at " + location_text(other.where),
            "expected each surface interaction name once");
      return;
    }
  }
  SurfaceInteraction interaction;
  interaction.name = *name;
  interaction.where = keyword.where;
  m_model.surface_interactions.push_back(interaction);
  m_interaction = static_cast<Index>(m_model.surface_interactions.size() - 1);
  m_has_friction = m_has_behavior = false;
}

void DeckBuilder::read_friction(const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(keyword, {});
  if (m_interaction == NO_INDEX) {
    error(keyword.where, keyword, "no surface interaction to attach to",
          "expected *FRICTION right after *SURFACE INTERACTION, NAME=...");
    return;
  }
  SurfaceInteraction& interaction =
      m_model.surface_interactions[static_cast<std::size_t>(m_interaction)];
  if (m_has_friction) {
    error(keyword.where, keyword,
          "surface interaction " + interaction.name + " already has *FRICTION",
          "expected one *FRICTION per surface interaction");
    return;
  }
  m_has_friction = true;
  if (block.data.size() != 1) {
    error(keyword.where, keyword, "found " + std::to_string(block.data.size()) + " data lines",
          "expected one data line with the friction coefficient (no dependence on slip rate, "
          "pressure or temperature)");
    return;
  }
  const DeckDataLine& line = block.data.front();
  const std::optional<Real> mu = real_field(line, keyword, 0, "friction coefficient");
  if (!mu) return;
  if (*mu < 0.0) {
    error(line.where(), keyword, "friction coefficient " + number_text(*mu) + " is negative",
          "expected a coefficient >= 0");
    return;
  }
  interaction.friction = *mu;
  if (line.fields.size() > 1)
    note(line.where(), keyword,
         "only the friction coefficient is used; the other values (e.g. CalculiX's stick slope) "
         "are ignored");
}

void DeckBuilder::read_surface_behavior(const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(keyword, {{"PRESSURE-OVERCLOSURE"}});
  if (m_interaction == NO_INDEX) {
    error(keyword.where, keyword, "no surface interaction to attach to",
          "expected *SURFACE BEHAVIOR right after *SURFACE INTERACTION, NAME=...");
    return;
  }
  SurfaceInteraction& interaction =
      m_model.surface_interactions[static_cast<std::size_t>(m_interaction)];
  if (m_has_behavior) {
    error(keyword.where, keyword,
          "surface interaction " + interaction.name + " already has *SURFACE BEHAVIOR",
          "expected one *SURFACE BEHAVIOR per surface interaction");
    return;
  }
  m_has_behavior = true;
  std::string law = optional_name(keyword, "PRESSURE-OVERCLOSURE");
  if (law.empty()) law = "HARD";
  if (law != "HARD" && law != "LINEAR") {
    error(keyword.where, keyword, "PRESSURE-OVERCLOSURE=" + law + " is not supported yet",
          "supported: PRESSURE-OVERCLOSURE=HARD (the default), LINEAR");
    return;
  }
  if (block.data.size() > 1) {
    error(block.data[1].where(), keyword, "unexpected second data line",
          law == "LINEAR" ? std::string("expected one data line: ") + LINEAR_LINE
                          : "expected at most one data line");
    return;
  }
  if (law == "HARD") {
    if (!block.data.empty())
      note(block.data.front().where(), keyword,
           "the data line values are ignored: PRESSURE-OVERCLOSURE=HARD runs as penalty "
           "contact with xpl's default penalty stiffness");
    return;
  }
  if (block.data.empty()) {
    error(keyword.where, keyword, "missing pressure-overclosure slope",
          std::string("expected a data line: ") + LINEAR_LINE);
    return;
  }
  const DeckDataLine& line = block.data.front();
  const std::optional<Real> slope = real_field(line, keyword, 0, "pressure-overclosure slope");
  if (!slope) return;
  if (*slope <= 0.0) {
    error(line.where(), keyword,
          "pressure-overclosure slope " + number_text(*slope) + " is not positive",
          "expected a slope > 0 (contact pressure per unit overclosure, Pa/m)");
    return;
  }
  interaction.linear = true;
  interaction.linear_slope = *slope;
  if (line.fields.size() > 1)
    note(line.where(), keyword,
         "only the slope is used; the other values (CalculiX: sigma_inf, c0) are ignored");
}

}  // namespace xpl::io
