/// \file Contact properties: *SURFACE INTERACTION with its options *FRICTION and
/// *SURFACE BEHAVIOR (Abaqus and CalculiX forms). Contact definitions that use them are in
/// deck_contact.cpp.

#include "io/deck/deck_handlers.hpp"

namespace xpl::io {

namespace {

constexpr const char* LINEAR_LINE = "slope (contact pressure per unit overclosure, Pa/m)";

}  // namespace

void read_surface_interaction(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(deck, keyword, {{"NAME"}});
  // The optional data line (Abaqus: out-of-plane thickness of 2D models, or the area of a
  // node-based surface) has no meaning for 3D penalty contact: checked, not kept.
  if (block.data.size() > 1)
    error(deck, block.data[1].where(), keyword, "unexpected second data line",
          "expected at most one data line (out-of-plane thickness, ignored in 3D)");
  else if (block.data.size() == 1)
    real_field(deck, block.data.front(), keyword, 0, "out-of-plane thickness", 1.0);
  const std::optional<std::string> name = required_name(deck, keyword, "NAME");
  if (!name) return;
  for (const SurfaceInteraction& other : deck.model.surface_interactions) {
    if (other.name == *name) {
      error(deck, keyword.where, keyword,
            "surface interaction " + *name + " is defined twice at " + location_text(other.where),
            "expected each surface interaction name once");
      return;
    }
  }
  SurfaceInteraction interaction;
  interaction.name = *name;
  interaction.where = keyword.where;
  deck.model.surface_interactions.push_back(interaction);
  deck.interaction = static_cast<Index>(deck.model.surface_interactions.size() - 1);
  deck.has_friction = deck.has_behavior = false;
}

void read_friction(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(deck, keyword, {});
  if (deck.interaction == NO_INDEX) {
    error(deck, keyword.where, keyword, "no surface interaction to attach to",
          "expected *FRICTION right after *SURFACE INTERACTION, NAME=...");
    return;
  }
  SurfaceInteraction& interaction =
      deck.model.surface_interactions[static_cast<std::size_t>(deck.interaction)];
  if (deck.has_friction) {
    error(deck, keyword.where, keyword,
          "surface interaction " + interaction.name + " already has *FRICTION",
          "expected one *FRICTION per surface interaction");
    return;
  }
  deck.has_friction = true;
  if (block.data.size() != 1) {
    error(deck, keyword.where, keyword,
          "found " + std::to_string(block.data.size()) + " data lines",
          "expected one data line with the friction coefficient (no dependence on slip rate, "
          "pressure or temperature)");
    return;
  }
  const DeckDataLine& line = block.data.front();
  const std::optional<Real> mu = real_field(deck, line, keyword, 0, "friction coefficient");
  if (!mu) return;
  if (*mu < 0.0) {
    error(deck, line.where(), keyword, "friction coefficient " + number_text(*mu) + " is negative",
          "expected a coefficient >= 0");
    return;
  }
  interaction.friction = *mu;
  if (line.fields.size() > 1)
    note(deck, line.where(), keyword,
         "only the friction coefficient is used; the other values (e.g. CalculiX's stick slope) "
         "are ignored");
}

void read_surface_behavior(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(deck, keyword, {{"PRESSURE-OVERCLOSURE"}});
  if (deck.interaction == NO_INDEX) {
    error(deck, keyword.where, keyword, "no surface interaction to attach to",
          "expected *SURFACE BEHAVIOR right after *SURFACE INTERACTION, NAME=...");
    return;
  }
  SurfaceInteraction& interaction =
      deck.model.surface_interactions[static_cast<std::size_t>(deck.interaction)];
  if (deck.has_behavior) {
    error(deck, keyword.where, keyword,
          "surface interaction " + interaction.name + " already has *SURFACE BEHAVIOR",
          "expected one *SURFACE BEHAVIOR per surface interaction");
    return;
  }
  deck.has_behavior = true;
  std::string law = optional_name(keyword, "PRESSURE-OVERCLOSURE");
  if (law.empty()) law = "HARD";
  if (law != "HARD" && law != "LINEAR") {
    error(deck, keyword.where, keyword, "PRESSURE-OVERCLOSURE=" + law + " is not supported yet",
          "supported: PRESSURE-OVERCLOSURE=HARD (the default), LINEAR");
    return;
  }
  if (block.data.size() > 1) {
    error(deck, block.data[1].where(), keyword, "unexpected second data line",
          law == "LINEAR" ? std::string("expected one data line: ") + LINEAR_LINE
                          : "expected at most one data line");
    return;
  }
  if (law == "HARD") {
    if (!block.data.empty())
      note(deck, block.data.front().where(), keyword,
           "the data line values are ignored: PRESSURE-OVERCLOSURE=HARD runs as penalty "
           "contact with xpl's default penalty stiffness");
    return;
  }
  if (block.data.empty()) {
    error(deck, keyword.where, keyword, "missing pressure-overclosure slope",
          std::string("expected a data line: ") + LINEAR_LINE);
    return;
  }
  const DeckDataLine& line = block.data.front();
  const std::optional<Real> slope =
      real_field(deck, line, keyword, 0, "pressure-overclosure slope");
  if (!slope) return;
  if (*slope <= 0.0) {
    error(deck, line.where(), keyword,
          "pressure-overclosure slope " + number_text(*slope) + " is not positive",
          "expected a slope > 0 (contact pressure per unit overclosure, Pa/m)");
    return;
  }
  interaction.linear = true;
  interaction.linear_slope = *slope;
  if (line.fields.size() > 1)
    note(deck, line.where(), keyword,
         "only the slope is used; the other values (CalculiX: sigma_inf, c0) are ignored");
}

}  // namespace xpl::io
