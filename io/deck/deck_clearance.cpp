/// \file Contact clearances (SPEC C7–C10): *CONTACT CLEARANCE (model or step data) and
/// *CONTACT CLEARANCE ASSIGNMENT (an option of *CONTACT). Names are resolved once the whole
/// deck is read, so a clearance may be defined after the assignment that uses it; the checks
/// of the surfaces themselves are in deck_clearance_checks.cpp.

#include <algorithm>

#include "io/deck/deck_handlers.hpp"
#include "io/deck/deck_numbers.hpp"

namespace xpl::io {

namespace {

constexpr const char* ASSIGNMENT_LINE = "surface 1, surface 2, clearance name[, MASTER|SLAVE]";
constexpr const char* ASSIGNMENT_KEYWORD = "*CONTACT CLEARANCE ASSIGNMENT";

/// Whether every field of a data line is `NAME=value`: the manual's first *CONTACT CLEARANCE
/// example writes `SEARCH ABOVE=0.0` on the line after a keyword line without a trailing
/// comma, so such a line is read as more parameters of the keyword.
bool is_parameter_line(const DeckDataLine& line) {
  bool any = false;
  for (std::string_view field : line.fields) {
    if (field.empty()) continue;
    if (field.find('=') == std::string_view::npos) return false;
    any = true;
  }
  return any;
}

}  // namespace

void read_contact_clearance(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(deck, keyword,
                   {{"NAME"}, {"ADJUST"}, {"CLEARANCE"}, {"SEARCH ABOVE"}, {"SEARCH BELOW"}});
  const std::optional<std::string> name = required_name(deck, keyword, "NAME");
  // Parameters of the keyword line, then those of parameter data lines, each with its line.
  std::vector<std::pair<DeckParameter, SourceLocation>> parameters;
  for (const DeckParameter& p : keyword.parameters) parameters.emplace_back(p, keyword.where);
  for (const DeckDataLine& line : block.data) {
    if (!is_parameter_line(line)) {
      error(deck, line.where(), keyword, "unexpected data line",
            "expected no data lines, or a line of more parameters such as SEARCH ABOVE=0.0 "
            "(ADJUST=, CLEARANCE=, SEARCH ABOVE=, SEARCH BELOW=)");
      continue;
    }
    DeckKeyword more{keyword.name, {}, line.where()};
    for (std::string_view field : line.fields)
      if (!field.empty()) more.parameters.push_back(parse_parameter(field));
    if (!check_parameters(deck, more,
                          {{"ADJUST"}, {"CLEARANCE"}, {"SEARCH ABOVE"}, {"SEARCH BELOW"}}))
      continue;
    for (const DeckParameter& p : more.parameters) {
      const bool repeated = std::any_of(parameters.begin(), parameters.end(),
                                        [&](const auto& q) { return q.first.name == p.name; });
      if (repeated)
        error(deck, line.where(), keyword, "parameter " + p.name + " given twice",
              "expected it at most once");
      else
        parameters.emplace_back(p, line.where());
    }
  }
  // A parameter with the line that gave it; nothing if it is absent or has no value (then
  // check_parameters reported it).
  const auto value_of =
      [&](std::string_view name) -> const std::pair<DeckParameter, SourceLocation>* {
    for (const auto& entry : parameters)
      if (entry.first.name == name && entry.first.has_value && !entry.first.value.empty())
        return &entry;
    return nullptr;
  };

  ContactClearance clearance;
  clearance.where = keyword.where;
  std::string distribution;
  if (const auto* adjust = value_of("ADJUST")) {
    const std::string word = normalize_name(adjust->first.value);
    if (word == "YES" || word == "NO")
      clearance.adjust = word == "YES";
    else
      error(deck, adjust->second, keyword, "bad ADJUST=" + adjust->first.value,
            "expected ADJUST=YES (move the slave nodes, strain free, in the first step; the "
            "default) or ADJUST=NO (permanent contact offsets)");
  }
  if (const auto* value = value_of("CLEARANCE")) {
    const std::string& text = value->first.value;
    if (const std::optional<Real> number = parse_real(text))
      clearance.value = *number;
    else if (looks_numeric(text))
      error(deck, value->second, keyword, "bad number '" + text + "' for CLEARANCE",
            "expected a real number such as 0.5 or 1e-3, or the name of a *DISTRIBUTION");
    else
      distribution = normalize_name(text);
  }
  const std::pair<std::string, std::optional<Real>*> zones[] = {
      {"SEARCH ABOVE", &clearance.search_above}, {"SEARCH BELOW", &clearance.search_below}};
  for (const auto& [parameter, zone] : zones) {
    const auto* search = value_of(parameter);
    if (search == nullptr) continue;
    const std::optional<Real> number = parse_real(search->first.value);
    if (!number)
      error(deck, search->second, keyword,
            "bad number '" + search->first.value + "' for " + parameter,
            "expected a search distance >= 0 such as 0.2");
    else if (*number < 0.0)
      error(deck, search->second, keyword, parameter + "=" + search->first.value + " is negative",
            "expected a search distance >= 0");
    else
      *zone = *number;
  }
  if (!name) return;
  for (const ContactClearance& other : deck.model.contact_clearances) {
    if (other.name == *name) {
      error(deck, keyword.where, keyword,
            "contact clearance " + *name + " is defined twice at " + location_text(other.where),
            "expected each contact clearance name once");
      return;
    }
  }
  clearance.name = *name;
  deck.model.contact_clearances.push_back(clearance);
  deck.clearance_distributions.push_back(distribution);
}

void read_clearance_assignment(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(deck, keyword, {});
  GeneralContact* contact = open_contact(deck, keyword);
  if (contact == nullptr) return;
  if (block.data.empty()) {
    error(deck, keyword.where, keyword, "no assignments",
          std::string("expected data lines: ") + ASSIGNMENT_LINE);
    return;
  }
  const auto field = [](const DeckDataLine& line, std::size_t i) {
    return i < line.fields.size() ? normalize_name(line.fields[i]) : std::string();
  };
  for (const DeckDataLine& line : block.data) {
    check_field_count(deck, line, keyword, 4, ASSIGNMENT_LINE);
    const std::string first = field(line, 0), second = field(line, 1), name = field(line, 2),
                      view = field(line, 3);
    PendingClearanceAssignment pending;
    pending.step = static_cast<Index>(deck.model.steps.size() - 1);
    pending.clearance = name;
    ClearanceAssignment& assignment = pending.assignment;
    assignment.where = line.where();
    bool ok = true;
    const auto missing = [&](const std::string& what) {
      error(deck, line.where(), keyword, "missing " + what,
            std::string("expected ") + ASSIGNMENT_LINE);
      ok = false;
    };
    if (first.empty()) missing("surface 1");
    if (second.empty()) missing("surface 2");
    if (name.empty()) missing("clearance name");
    if (view == "MASTER") {
      assignment.view = ClearanceAssignment::View::Master;
    } else if (view == "SLAVE") {
      assignment.view = ClearanceAssignment::View::Slave;
    } else if (!view.empty()) {
      error(deck, line.where(), keyword, "bad view '" + view + "'",
            "expected MASTER (surface 1 is the master: only the nodes of surface 2 move), SLAVE "
            "(surface 1 is the slave) or nothing (both views)");
      ok = false;
    }
    if (!first.empty() && first == second) {
      error(deck, line.where(), keyword, "self contact of surface " + first,
            "expected two different surfaces (clearances do not apply to self contact)");
      continue;
    }
    for (const auto& [surface_name, index] :
         {std::pair{first, &assignment.first}, std::pair{second, &assignment.second}}) {
      if (surface_name.empty()) continue;
      *index = contact_surface(deck, surface_name, line.where(), keyword.label());
      if (*index == NO_INDEX) {
        ok = false;
      } else if (deck.model.surfaces[static_cast<std::size_t>(*index)].type ==
                 Surface::Type::Node) {
        error(deck, line.where(), keyword, "surface " + surface_name + " is node-based",
              "expected element-based surfaces (*SURFACE, TYPE=ELEMENT): clearances are "
              "assigned to node-to-face interactions");
        ok = false;
      }
    }
    if (ok) deck.clearance_assignments.push_back(std::move(pending));
  }
}

void resolve_clearances(DeckState& deck) {
  for (std::size_t c = 0; c < deck.model.contact_clearances.size(); ++c) {
    const std::string& name = deck.clearance_distributions[c];
    if (name.empty()) continue;
    ContactClearance& clearance = deck.model.contact_clearances[c];
    for (std::size_t d = 0; d < deck.model.distributions.size(); ++d)
      if (deck.model.distributions[d].name == name) clearance.distribution = static_cast<Index>(d);
    if (clearance.distribution == NO_INDEX)
      deck.errors.add(clearance.where, "*CONTACT CLEARANCE", "undefined distribution " + name,
                      "expected *DISTRIBUTION, NAME=" + name + ", LOCATION=NODE, or a number");
  }
  deck.clearance_surface_state.assign(deck.model.surfaces.size(), 0);
  for (PendingClearanceAssignment& pending : deck.clearance_assignments) {
    ClearanceAssignment& assignment = pending.assignment;
    for (std::size_t c = 0; c < deck.model.contact_clearances.size(); ++c)
      if (deck.model.contact_clearances[c].name == pending.clearance)
        assignment.clearance = static_cast<Index>(c);
    if (assignment.clearance == NO_INDEX) {
      deck.errors.add(assignment.where, ASSIGNMENT_KEYWORD,
                      "undefined contact clearance " + pending.clearance,
                      "expected *CONTACT CLEARANCE, NAME=" + pending.clearance);
      continue;
    }
    // Each check reports its own problem: all of them are run.
    const bool first_fit = check_clearance_surface(deck, assignment.first, assignment.where);
    const bool second_fit = check_clearance_surface(deck, assignment.second, assignment.where);
    const bool step_fit = check_clearance_step(deck, pending);
    const bool slaves_fit = check_clearance_slaves(deck, pending);
    if (!first_fit || !second_fit || !step_fit || !slaves_fit ||
        !check_clearance_sign(deck, pending))
      continue;
    deck.model.steps[static_cast<std::size_t>(pending.step)].contact->clearances.push_back(
        assignment);
  }
}

bool check_clearance_step(DeckState& deck, const PendingClearanceAssignment& pending) {
  const ClearanceAssignment& assignment = pending.assignment;
  const auto step = static_cast<std::size_t>(pending.step);
  const Step& here = deck.model.steps[step];
  const auto has_general = [](const std::optional<GeneralContact>& contact) {
    return contact && (contact->all_exterior || !contact->inclusions.empty());
  };
  if (!has_general(here.contact)) {
    deck.errors.add(assignment.where, ASSIGNMENT_KEYWORD,
                    "step " + here.name + " has no general contact domain to assign clearances to",
                    "expected *CONTACT INCLUSIONS in the step of the *CONTACT (or an earlier one)");
    return false;
  }
  // A step builds its contact domain new when no contact was in effect in the step before (the
  // seed's rule, and the solver's: it then starts without a previous contact engine). Contact
  // in effect: the latest *CONTACT so far, if it has inclusions, or any contact pair.
  bool earlier_contact = false;
  if (step > 0) {
    earlier_contact = !deck.model.contact_pairs.empty();
    const std::optional<GeneralContact>* general = nullptr;
    for (std::size_t k = 0; k < step; ++k) {
      if (!deck.model.steps[k].contact_pairs.empty()) earlier_contact = true;
      if (deck.model.steps[k].contact) general = &deck.model.steps[k].contact;
    }
    if (general != nullptr && has_general(*general)) earlier_contact = true;
  }
  if (earlier_contact) {
    deck.errors.add(
        assignment.where, ASSIGNMENT_KEYWORD,
        "clearances apply only when a step's contact domain is built new; the contact in "
        "effect in step " +
            deck.model.steps[step - 1].name + " carries over into step " + here.name,
        "expected the assignment in the first step, or in a step that follows one "
        "without contact (then with ADJUST=NO)");
    return false;
  }
  const ContactClearance& clearance =
      deck.model.contact_clearances[static_cast<std::size_t>(assignment.clearance)];
  if (step > 0 && clearance.adjust) {
    deck.errors.add(assignment.where, ASSIGNMENT_KEYWORD,
                    "clearance " + clearance.name +
                        " moves nodes (ADJUST=YES, also the default), which only the first step "
                        "can do, and step " +
                        here.name + " is not the first",
                    "expected ADJUST=NO (contact offsets) on *CONTACT CLEARANCE, NAME=" +
                        clearance.name + " for a step after the first");
    return false;
  }
  return true;
}

}  // namespace xpl::io
