/// \file Contact definitions: general contact in a step (*CONTACT with *CONTACT INCLUSIONS,
/// *CONTACT EXCLUSIONS, *CONTACT PROPERTY ASSIGNMENT, *CONTACT CONTROLS ASSIGNMENT) and
/// pairwise *CONTACT PAIR, as model data (CalculiX) or in a step. The surface interactions
/// they name are read in deck_interaction.cpp.

#include <algorithm>
#include <array>

#include "io/deck/deck_handlers.hpp"

namespace xpl::io {

namespace {

constexpr const char* PAIR_LINE =
    "surface 1, surface 2 (surface 1 blank: all exterior faces; surface 2 blank: self contact "
    "of surface 1)";
constexpr const char* PROPERTY_LINE =
    "surface 1, surface 2, interaction name (both surfaces blank: the global default)";
constexpr const char* CONTROLS_LINE = ", , penalty scale factor";

/// CalculiX contact formulations: all run as node-to-face penalty contact.
constexpr std::array<std::string_view, 7> PAIR_TYPES = {
    "NODE TO SURFACE", "SURFACE TO SURFACE", "MORTAR",  "LINMORTAR",
    "PGMORTAR",        "PGLINMORTAR",        "MASSLESS"};

}  // namespace

Index contact_surface(DeckState& deck, const std::string& name, const SourceLocation& where,
                      const std::string& keyword) {
  const Index surface = deck.model.find_surface(name);
  if (surface == NO_INDEX)
    deck.errors.add(where, keyword, "undefined surface " + name, "expected *SURFACE, NAME=" + name);
  return surface;
}

Index surface_interaction(DeckState& deck, const std::string& name, const SourceLocation& where,
                          const std::string& keyword) {
  for (std::size_t i = 0; i < deck.model.surface_interactions.size(); ++i)
    if (deck.model.surface_interactions[i].name == name) return static_cast<Index>(i);
  deck.errors.add(where, keyword, "undefined surface interaction " + name,
                  "expected *SURFACE INTERACTION, NAME=" + name);
  return NO_INDEX;
}

namespace {

/// Whether surface k (NO_INDEX: all exterior faces) is a `*SURFACE, TYPE=NODE`.
bool node_based(const DeckState& deck, Index k) {
  return k != NO_INDEX &&
         deck.model.surfaces[static_cast<std::size_t>(k)].type == Surface::Type::Node;
}

}  // namespace

std::optional<SurfacePair> surface_pair(DeckState& deck, const DeckDataLine& line,
                                        const DeckKeyword& keyword) {
  const std::string first = line.fields.empty() ? "" : normalize_name(line.fields[0]);
  const std::string second = line.fields.size() < 2 ? "" : normalize_name(line.fields[1]);
  SurfacePair pair;
  pair.where = line.where();
  bool ok = true;
  if (!first.empty()) {
    pair.first = contact_surface(deck, first, line.where(), keyword.label());
    ok = pair.first != NO_INDEX;
  }
  if (second.empty()) {
    pair.second = pair.first;  // self contact (of all exterior faces, if both are blank)
  } else {
    pair.second = contact_surface(deck, second, line.where(), keyword.label());
    ok = ok && pair.second != NO_INDEX;
  }
  if (!ok) return std::nullopt;
  return pair;
}

namespace {

/// "A, B" or "A (self contact)" ("all exterior faces" for a blank surface), as messages name
/// a pair.
std::string pair_text(const DeckState& deck, const SurfacePair& pair) {
  const auto name = [&](Index s) {
    return s == NO_INDEX ? std::string("all exterior faces")
                         : deck.model.surfaces[static_cast<std::size_t>(s)].name;
  };
  if (pair.first == pair.second) return name(pair.first) + " (self contact)";
  return name(pair.first) + ", " + name(pair.second);
}

/// Whether `pair` of the current step's general contact came from an earlier step's
/// definition (OP=MOD), not from a line of this step.
bool inherited(const DeckState& deck, const SurfacePair& pair, bool inclusions) {
  const std::vector<Step>& steps = deck.model.steps;
  for (std::size_t s = 0; s + 1 < steps.size(); ++s) {
    if (!steps[s].contact) continue;
    const std::vector<SurfacePair>& earlier =
        inclusions ? steps[s].contact->inclusions : steps[s].contact->exclusions;
    for (const SurfacePair& p : earlier)
      if (p.where.line == pair.where.line && p.where.file == pair.where.file) return true;
  }
  return false;
}

}  // namespace

void read_contact(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(deck, keyword, {{"OP"}});
  expect_no_data(deck, block);
  const std::string op = optional_name(keyword, "OP");
  if (!op.empty() && op != "MOD" && op != "NEW")  // then read as OP=MOD: no follow-up errors
    error(deck, keyword.where, keyword, "bad OP=" + op,
          "expected OP=MOD (the default: add to the general contact of earlier steps) or OP=NEW");
  std::vector<Step>& steps = deck.model.steps;
  if (steps.back().contact) {
    error(deck, keyword.where, keyword, "second *CONTACT in step " + steps.back().name,
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

void read_diagnostics(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(deck, keyword, {{"CONTACT INITIAL OVERCLOSURE"}, {"DETECT CROSSED SURFACES"}});
  expect_no_data(deck, block);
  // Model data sets the defaults of every step; a step's own setting holds from it on.
  Diagnostics diagnostics =
      deck.in_step && !deck.model.steps.empty()
          ? deck.model.diagnostics_of(static_cast<int>(deck.model.steps.size()) - 1)
          : deck.model.diagnostics;
  diagnostics.where = keyword.where;
  const std::string level = optional_name(keyword, "CONTACT INITIAL OVERCLOSURE");
  if (level == "DETAIL")
    diagnostics.overclosure_detail = true;
  else if (level == "SUMMARY")
    diagnostics.overclosure_detail = false;
  else if (!level.empty())
    error(deck, keyword.where, keyword, "bad CONTACT INITIAL OVERCLOSURE=" + level,
          "expected CONTACT INITIAL OVERCLOSURE=DETAIL (every adjusted node and offset in the "
          ".msg file) or SUMMARY (counts in the .sta file)");
  const std::string crossed = optional_name(keyword, "DETECT CROSSED SURFACES");
  if (crossed == "ON" || crossed == "YES")
    diagnostics.detect_crossed_surfaces = true;
  else if (crossed == "OFF" || crossed == "NO")
    diagnostics.detect_crossed_surfaces = false;
  else if (!crossed.empty())
    error(deck, keyword.where, keyword, "bad DETECT CROSSED SURFACES=" + crossed,
          "expected DETECT CROSSED SURFACES=ON or OFF");
  if (deck.in_step)
    deck.model.steps.back().diagnostics = diagnostics;
  else
    deck.model.diagnostics = diagnostics;
}

GeneralContact* open_contact(DeckState& deck, const DeckKeyword& keyword) {
  Step& step = deck.model.steps.back();
  if (!step.contact) {
    error(deck, keyword.where, keyword, "no *CONTACT in step " + step.name,
          "expected *CONTACT before " + keyword.label() + " in the same step");
    return nullptr;
  }
  return &*step.contact;
}

void read_contact_inclusions(DeckState& deck, const DeckBlock& block, bool inclusions) {
  const DeckKeyword& keyword = block.keyword;
  if (inclusions)
    check_parameters(deck, keyword, {{"ALL EXTERIOR", false}});
  else
    check_parameters(deck, keyword, {});
  GeneralContact* contact = open_contact(deck, keyword);
  if (contact == nullptr) return;
  if (inclusions && find_parameter(keyword, "ALL EXTERIOR") != nullptr) {
    expect_no_data(deck, block);
    contact->all_exterior = true;
    return;
  }
  if (block.data.empty()) {
    error(deck, keyword.where, keyword, "no surface pairs",
          std::string(inclusions ? "expected ALL EXTERIOR or data lines: "
                                 : "expected data lines: ") +
              PAIR_LINE);
    return;
  }
  std::vector<SurfacePair>& pairs = inclusions ? contact->inclusions : contact->exclusions;
  for (const DeckDataLine& line : block.data) {
    check_field_count(deck, line, keyword, 2, PAIR_LINE);
    const std::optional<SurfacePair> pair = surface_pair(deck, line, keyword);
    if (!pair) continue;
    if (inclusions && node_based(deck, pair->first) && node_based(deck, pair->second)) {
      // A node-based surface has nodes only: it is the slave of its pair (SPEC C13), so its
      // partner must bring faces.
      error(
          deck, line.where(), keyword,
          "node-based surface " + deck.model.surfaces[static_cast<std::size_t>(pair->second)].name +
              " would act as a master" +
              (pair->first == pair->second ? " (self contact)" : " (both surfaces are node-based)"),
          "expected an element-based surface (*SURFACE, TYPE=ELEMENT) or a blank first field "
          "(all exterior faces) opposite a node-based surface, which is slave only");
      continue;
    }
    const auto same = std::find_if(pairs.begin(), pairs.end(), [&](const SurfacePair& p) {
      return (p.first == pair->first && p.second == pair->second) ||
             (p.first == pair->second && p.second == pair->first);
    });
    if (same == pairs.end()) {
      pairs.push_back(*pair);
    } else if (inherited(deck, *same, inclusions)) {
      // OP=MOD adds to the earlier steps' definition, which already holds the pair.
      note(deck, line.where(), keyword,
           "the pair " + pair_text(deck, *pair) + " is in effect since " +
               location_text(same->where) + "; given again, it changes nothing");
      same->where = pair->where;  // now given in this step: a third time is an error
    } else {
      error(deck, line.where(), keyword,
            "the pair " + pair_text(deck, *pair) + " is given twice in step " +
                deck.model.steps.back().name + " (first at " + location_text(same->where) + ")",
            "expected each surface pair once per step");
    }
  }
}

void read_contact_property_assignment(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(deck, keyword, {});
  GeneralContact* contact = open_contact(deck, keyword);
  if (contact == nullptr) return;
  if (block.data.empty()) {
    error(deck, keyword.where, keyword, "no assignments",
          std::string("expected data lines: ") + PROPERTY_LINE);
    return;
  }
  for (const DeckDataLine& line : block.data) {
    check_field_count(deck, line, keyword, 3, PROPERTY_LINE);
    if (line.fields.size() < 3 || line.fields[2].empty()) {
      error(deck, line.where(), keyword, "missing surface interaction name",
            std::string("expected ") + PROPERTY_LINE);
      continue;
    }
    const std::optional<SurfacePair> pair = surface_pair(deck, line, keyword);
    const Index interaction =
        surface_interaction(deck, normalize_name(line.fields[2]), line.where(), keyword.label());
    if (pair && interaction != NO_INDEX) contact->properties.emplace_back(*pair, interaction);
  }
}

void read_contact_controls_assignment(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(deck, keyword, {{"TYPE"}});
  GeneralContact* contact = open_contact(deck, keyword);
  if (contact == nullptr) return;
  const std::string type = optional_name(keyword, "TYPE");
  if (type.empty()) {
    error(deck, keyword.where, keyword, "missing parameter TYPE", "expected TYPE=SCALE PENALTY");
    return;
  }
  if (type != "SCALE PENALTY") {
    error(deck, keyword.where, keyword, "TYPE=" + type + " is not supported yet",
          "supported: TYPE=SCALE PENALTY");
    return;
  }
  if (block.data.empty()) {
    error(deck, keyword.where, keyword, "missing penalty scale factor",
          std::string("expected a data line: ") + CONTROLS_LINE);
    return;
  }
  for (const DeckDataLine& line : block.data) {
    check_field_count(deck, line, keyword, 3, CONTROLS_LINE);
    if ((!line.fields.empty() && !line.fields[0].empty()) ||
        (line.fields.size() > 1 && !line.fields[1].empty())) {
      error(deck, line.where(), keyword, "penalty scaling of a surface pair is not supported yet",
            std::string("expected both surfaces blank (the whole general contact): ") +
                CONTROLS_LINE);
      continue;
    }
    const std::optional<Real> factor = real_field(deck, line, keyword, 2, "penalty scale factor");
    if (!factor) continue;
    if (*factor <= 0.0)
      error(deck, line.where(), keyword,
            "penalty scale factor " + number_text(*factor) + " is not positive",
            "expected a factor > 0");
    else
      contact->penalty_scale = *factor;
  }
}

void read_contact_pair(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(
      deck, keyword,
      {{"INTERACTION"}, {"TYPE"}, {"SMALL SLIDING", false}, {"ADJUST"}, {"MECHANICAL CONSTRAINT"}});
  const std::optional<std::string> interaction = required_name(deck, keyword, "INTERACTION");
  const std::string type = optional_name(keyword, "TYPE");
  if (!type.empty() && std::find(PAIR_TYPES.begin(), PAIR_TYPES.end(), type) == PAIR_TYPES.end())
    error(deck, keyword.where, keyword, "unknown TYPE=" + type,
          "expected TYPE=NODE TO SURFACE, SURFACE TO SURFACE or MASSLESS (CalculiX)");
  // What xpl does not do differently is said once, in the .msg file.
  std::string unused;
  const auto add_unused = [&](const std::string& text) {
    unused += (unused.empty() ? "" : ", ") + text;
  };
  if (type == "MASSLESS")
    note(deck, keyword.where, keyword,
         "TYPE=MASSLESS (CalculiX's explicit contact: massless slave nodes held on the master "
         "surface by contact forces solved each increment, no penetration) runs as xpl's "
         "node-to-face penalty contact: the slave nodes keep their mass, and a penalty spring "
         "(the default stiffness, or the *SURFACE BEHAVIOR LINEAR slope) pushes back in "
         "proportion to a small penetration");
  else if (!type.empty() && type != "NODE TO SURFACE")
    add_unused("TYPE=" + type);
  if (find_parameter(keyword, "SMALL SLIDING") != nullptr) add_unused("SMALL SLIDING");
  if (const std::string adjust = optional_name(keyword, "ADJUST"); !adjust.empty())
    add_unused("ADJUST=" + adjust);
  if (const std::string constraint = optional_name(keyword, "MECHANICAL CONSTRAINT");
      !constraint.empty() && constraint != "PENALTY")
    add_unused("MECHANICAL CONSTRAINT=" + constraint);
  if (!unused.empty())
    note(deck, keyword.where, keyword,
         "xpl runs node-to-face penalty contact; not used: " + unused);
  if (block.data.empty()) {
    error(deck, keyword.where, keyword, "no surface pairs",
          "expected data lines: slave surface, master surface");
    return;
  }
  const Index step = deck.in_step ? static_cast<Index>(deck.model.steps.size() - 1) : NO_INDEX;
  for (const DeckDataLine& line : block.data) {
    check_field_count(deck, line, keyword, 2, "slave surface, master surface");
    if (!check_surface_pair(deck, line, keyword)) continue;
    if (!interaction) continue;
    deck.contact_pairs.push_back({step, normalize_name(line.fields[0]),
                                  normalize_name(line.fields[1]), *interaction, line.where()});
  }
}

void resolve_contact_pairs(DeckState& deck) {
  const std::string keyword = "*CONTACT PAIR";
  for (const PendingContactPair& pending : deck.contact_pairs) {
    ContactPair pair;
    pair.where = pending.where;
    pair.slave = contact_surface(deck, pending.slave, pending.where, keyword);
    pair.master = contact_surface(deck, pending.master, pending.where, keyword);
    pair.interaction = surface_interaction(deck, pending.interaction, pending.where, keyword);
    if (pair.master != NO_INDEX &&
        deck.model.surfaces[static_cast<std::size_t>(pair.master)].type == Surface::Type::Node) {
      deck.errors.add(pending.where, keyword, "master surface " + pending.master + " is node-based",
                      "expected an element-based surface (*SURFACE, TYPE=ELEMENT) as the master");
      continue;
    }
    if (pair.slave == NO_INDEX || pair.master == NO_INDEX || pair.interaction == NO_INDEX) continue;
    if (pending.step == NO_INDEX)
      deck.model.contact_pairs.push_back(pair);
    else
      deck.model.steps[static_cast<std::size_t>(pending.step)].contact_pairs.push_back(pair);
  }
}

}  // namespace xpl::io
