/// \file The keyword table and the dispatcher that reads it.

#include "io/deck/deck_keywords.hpp"

#include <algorithm>

#include "io/deck/deck_assembly.hpp"
#include "io/deck/deck_handlers.hpp"

namespace xpl::io {

namespace {

using enum KeywordPlace;
using enum KeywordBlock;

// One-line adapters for handlers shared by two keywords.
void read_nset(DeckState& deck, const DeckBlock& block) {
  read_set(deck, block, true);
}
void read_elset(DeckState& deck, const DeckBlock& block) {
  read_set(deck, block, false);
}
void read_mass(DeckState& deck, const DeckBlock& block) {
  read_point_property(deck, block, false);
}
void read_rotary_inertia(DeckState& deck, const DeckBlock& block) {
  read_point_property(deck, block, true);
}
void read_inclusions(DeckState& deck, const DeckBlock& block) {
  read_contact_inclusions(deck, block, true);
}
void read_exclusions(DeckState& deck, const DeckBlock& block) {
  read_contact_inclusions(deck, block, false);
}
void read_node_file(DeckState& deck, const DeckBlock& block) {
  read_file_output(deck, block, true);
}
void read_el_file(DeckState& deck, const DeckBlock& block) {
  read_file_output(deck, block, false);
}

// Supported keywords in the order of the "unknown keyword" message.
constexpr KeywordSpec KEYWORDS[] = {
    {"HEADING", Model, None, read_heading},
    {"INCLUDE", Anywhere, None, nullptr},  // read_deck_blocks follows it; never dispatched
    {"PART", Model, None, read_part},
    {"END PART", Model, None, read_end_part},
    {"ASSEMBLY", Model, None, read_assembly},
    {"INSTANCE", Model, None, read_instance},
    {"END INSTANCE", Model, None, read_end_instance},
    {"END ASSEMBLY", Model, None, read_end_assembly},
    {"NODE", Part, None, read_node},
    {"ELEMENT", Part, None, read_element},
    {"NSET", Part, None, read_nset},
    {"ELSET", Part, None, read_elset},
    {"SURFACE", Part, None, read_surface},
    {"MATERIAL", Model, None, read_material},
    {"DENSITY", Model, Material, read_density},
    {"ELASTIC", Model, Material, read_elastic},
    {"PLASTIC", Model, Material, read_plastic},
    {"RATE DEPENDENT", Model, Material, read_rate_dependent},
    {"SOLID SECTION", Part, None, read_solid_section},
    {"SHELL SECTION", Part, None, read_shell_section},
    {"SHELL GENERAL SECTION", Part, None, read_shell_general_section, false},
    {"SECTION CONTROLS", Model, None, read_section_controls},
    {"MASS", Part, None, read_mass},
    {"ROTARY INERTIA", Part, None, read_rotary_inertia},
    {"RIGID BODY", Part, None, read_rigid_body},
    {"TIE", Model, None, read_tie},
    {"SURFACE INTERACTION", Model, None, read_surface_interaction},
    {"FRICTION", Model, Interaction, read_friction},
    {"SURFACE BEHAVIOR", Model, Interaction, read_surface_behavior},
    {"CONTACT PAIR", ModelOrStep, None, read_contact_pair},
    {"CONTACT CLEARANCE", ModelOrStep, None, read_contact_clearance},
    {"CONTACT INITIALIZATION DATA", ModelOrStep, None, read_contact_initialization},
    {"CLEARANCE", Model, None, read_clearance},
    {"DISTRIBUTION", Model, None, read_distribution},
    {"DISTRIBUTION TABLE", Model, None, read_distribution_table},
    {"AMPLITUDE", Model, None, read_amplitude},
    {"EQUATION", ModelOrStep, None, read_equation, false},
    {"INITIAL CONDITIONS", Model, None, read_initial_conditions},
    {"BOUNDARY", ModelOrStep, None, read_boundary},
    {"STEP", Anywhere, None, read_step},
    {"DYNAMIC", Step, None, read_dynamic},
    {"STATIC", Step, None, read_static, false},
    {"BULK VISCOSITY", Step, None, read_bulk_viscosity},
    {"FIXED MASS SCALING", Step, None, read_fixed_mass_scaling},
    {"CLOAD", Step, None, read_cload},
    {"DLOAD", Step, None, read_dload},
    {"DSLOAD", Step, None, read_dsload},
    {"CONTACT", StepContact, None, read_contact},
    {"CONTACT INCLUSIONS", StepContact, None, read_inclusions},
    {"CONTACT EXCLUSIONS", StepContact, None, read_exclusions},
    {"CONTACT PROPERTY ASSIGNMENT", StepContact, None, read_contact_property_assignment},
    {"CONTACT CONTROLS ASSIGNMENT", StepContact, None, read_contact_controls_assignment},
    {"CONTACT CLEARANCE ASSIGNMENT", StepContact, None, read_clearance_assignment},
    {"CONTACT INITIALIZATION ASSIGNMENT", StepContact, None, read_initialization_assignment},
    {"OUTPUT", Step, Output, read_output},
    {"NODE OUTPUT", Step, Output, read_node_output},
    {"ELEMENT OUTPUT", Step, Output, read_element_output},
    {"ENERGY OUTPUT", Step, Output, read_energy_output},
    {"CONTACT OUTPUT", Step, Output, read_contact_output},
    // CalculiX output requests, mapped onto *OUTPUT requests or noted.
    {"NODE FILE", Step, None, read_node_file},
    {"EL FILE", Step, None, read_el_file},
    {"NODE PRINT", Step, None, read_node_print},
    {"EL PRINT", Step, None, read_el_print},
    {"CONTACT FILE", Step, None, read_contact_file},
    {"CONTACT PRINT", Step, None, read_contact_file},
    {"END STEP", Anywhere, None, read_end_step},
    // Only echo control of the Abaqus pre-processor: nothing to do, safe to ignore.
    {"PREPRINT", Anywhere, None, nullptr},
    {"RESTART", Anywhere, None, read_restart},
    {"DIAGNOSTICS", Anywhere, None, read_diagnostics},
};

/// "*HEADING, *INCLUDE, ...": the supported keywords, for the "unknown keyword" message.
std::string supported_list() {
  std::string list;
  for (const KeywordSpec& spec : KEYWORDS) {
    if (!spec.supported) continue;
    if (!list.empty()) list += ", ";
    list += "*";
    list += spec.name;
  }
  return list;
}

}  // namespace

std::span<const KeywordSpec> keyword_table() {
  return KEYWORDS;
}

const KeywordSpec* find_keyword(std::string_view name) {
  const auto spec = std::find_if(std::begin(KEYWORDS), std::end(KEYWORDS),
                                 [&](const KeywordSpec& s) { return s.name == name; });
  return spec != std::end(KEYWORDS) ? &*spec : nullptr;
}

void read_block(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  const KeywordSpec* spec = find_keyword(keyword.name);
  const bool known = spec != nullptr;

  // *DENSITY, *ELASTIC, *PLASTIC, ... belong to the material opened just before, *FRICTION and
  // *SURFACE BEHAVIOR to the interaction, *NODE OUTPUT & co. to the latest *OUTPUT. Any other
  // keyword closes those option blocks.
  const KeywordBlock option_of = known ? spec->block : None;
  if (option_of != Material) {
    deck.material = NO_INDEX;
    deck.plastic_without_material = false;
  }
  if (option_of != Interaction) deck.interaction = NO_INDEX;
  if (option_of != Output) deck.output = NO_INDEX;

  if (!known) {
    error(deck, keyword.where, keyword, "unknown keyword " + keyword.label(),
          "supported keywords: " + supported_list());
    return;
  }
  if (!assembly_allows(deck, *spec, keyword)) return;
  const KeywordPlace place = spec->place == Part ? Model : spec->place;
  if (place == Model && deck.in_step) {
    error(deck, keyword.where, keyword, "model data cannot appear inside a step",
          "expected it before the first *STEP");
    return;
  }
  if ((place == Model || place == ModelOrStep) && !deck.in_step && !deck.model.steps.empty()) {
    error(deck, keyword.where, keyword, "model data after the first step",
          "expected all model data before the first *STEP");
    return;
  }
  if (place == StepContact && !deck.in_step) {
    error(deck, keyword.where, keyword, "general contact outside a step",
          "expected *CONTACT and its options between *STEP and *END STEP, as in "
          "Abaqus/Explicit (*CONTACT PAIR may be model data)");
    return;
  }
  if (place == Step && !deck.in_step) {
    error(deck, keyword.where, keyword, "history data outside a step",
          "expected it between *STEP and *END STEP");
    return;
  }
  if (spec->handler != nullptr) spec->handler(deck, block);
}

void read_blocks(DeckState& deck, const std::vector<DeckBlock>& blocks) {
  for (const DeckBlock& block : blocks)
    if (!collect_part_block(deck, block)) read_block(deck, block);
  close_assembly(deck);
}

}  // namespace xpl::io
