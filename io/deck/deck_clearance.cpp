/// \file Contact clearances (SPEC C7–C10): *CONTACT CLEARANCE (model or step data) and
/// *CONTACT CLEARANCE ASSIGNMENT (an option of *CONTACT). Names are resolved once the whole
/// deck is read, so a clearance may be defined after the assignment that uses it; the checks
/// of the surfaces themselves are in deck_clearance_checks.cpp, the resolution of the names in
/// deck_clearance_resolve.cpp.

#include <algorithm>

#include "io/deck/deck_handlers.hpp"
#include "io/deck/deck_numbers.hpp"

namespace xpl::io {

namespace {

constexpr const char* CLEARANCE_LINE = "surface 1, surface 2, clearance name[, MASTER|SLAVE]";
constexpr const char* INITIALIZATION_LINE =
    "surface 1, surface 2, initialization name[, MASTER|SLAVE|FIRST SURFACE SFC|SECOND SURFACE "
    "SFC]";

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

/// A parameter with the line that gave it.
using Located = std::pair<DeckParameter, SourceLocation>;

/// The parameters of the keyword line, then those of its parameter data lines (each checked
/// against `more_accepted`), each with its line; other data lines are reported.
std::vector<Located> gather_parameters(DeckState& deck, const DeckBlock& block,
                                       std::initializer_list<ParameterSpec> more_accepted,
                                       const std::string& hint) {
  const DeckKeyword& keyword = block.keyword;
  std::vector<Located> parameters;
  for (const DeckParameter& p : keyword.parameters) parameters.emplace_back(p, keyword.where);
  for (const DeckDataLine& line : block.data) {
    if (!is_parameter_line(line)) {
      error(deck, line.where(), keyword, "unexpected data line",
            "expected no data lines, or a line of more parameters such as SEARCH ABOVE=0.0 (" +
                hint + ")");
      continue;
    }
    DeckKeyword more{keyword.name, {}, line.where()};
    for (std::string_view field : line.fields)
      if (!field.empty()) more.parameters.push_back(parse_parameter(field));
    if (!check_parameters(deck, more, more_accepted)) continue;
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
  return parameters;
}

/// The parameter `name` (with or without a value), or nothing.
const Located* find_located(const std::vector<Located>& parameters, std::string_view name) {
  for (const Located& entry : parameters)
    if (entry.first.name == name) return &entry;
  return nullptr;
}

/// The parameter `name` with a value; nothing if it is absent or has no value (then
/// check_parameters reported it).
const Located* value_of(const std::vector<Located>& parameters, std::string_view name) {
  const Located* entry = find_located(parameters, name);
  return entry != nullptr && entry->first.has_value && !entry->first.value.empty() ? entry
                                                                                   : nullptr;
}

/// ADJUST=, the clearance value or distribution of parameter `value_name`, SEARCH ABOVE= and
/// SEARCH BELOW=: what both spellings share, read into `clearance` and `distribution`.
void read_shared(DeckState& deck, const DeckKeyword& keyword,
                 const std::vector<Located>& parameters, const std::string& value_name,
                 ContactClearance& clearance, std::string& distribution) {
  if (const Located* adjust = value_of(parameters, "ADJUST")) {
    const std::string word = normalize_name(adjust->first.value);
    if (word == "YES" || word == "NO")
      clearance.adjust = word == "YES";
    else
      error(deck, adjust->second, keyword, "bad ADJUST=" + adjust->first.value,
            "expected ADJUST=YES (move the slave nodes, strain free, in the first step; the "
            "default) or ADJUST=NO (permanent contact offsets)");
  }
  if (const Located* value = value_of(parameters, value_name)) {
    const std::string& text = value->first.value;
    if (const std::optional<Real> number = parse_real(text))
      clearance.value = *number;
    else if (looks_numeric(text))
      error(deck, value->second, keyword, "bad number '" + text + "' for " + value_name,
            "expected a real number such as 0.5 or 1e-3, or the name of a *DISTRIBUTION");
    else
      distribution = normalize_name(text);
  }
  const std::pair<std::string, std::optional<Real>*> zones[] = {
      {"SEARCH ABOVE", &clearance.search_above}, {"SEARCH BELOW", &clearance.search_below}};
  for (const auto& [parameter, zone] : zones) {
    const Located* search = value_of(parameters, parameter);
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
}

/// Adds the definition `clearance` named `name` (reported if the name is taken in its
/// spelling).
void add_definition(DeckState& deck, const DeckKeyword& keyword, const std::string& name,
                    ContactClearance clearance, const std::string& distribution) {
  for (const ContactClearance& other : deck.model.contact_clearances) {
    if (other.name == name && other.initialization == clearance.initialization) {
      error(
          deck, keyword.where, keyword,
          std::string(clearance.initialization ? "contact initialization " : "contact clearance ") +
              name + " is defined twice at " + location_text(other.where),
          std::string("expected each ") +
              (clearance.initialization ? "contact initialization" : "contact clearance") +
              " name once");
      return;
    }
  }
  clearance.name = name;
  clearance.where = keyword.where;
  deck.model.contact_clearances.push_back(std::move(clearance));
  deck.clearance_distributions.push_back(distribution);
}

/// The data lines of an assignment in either spelling (SPEC C10, C14).
void read_assignment(DeckState& deck, const DeckBlock& block, bool initialization) {
  const DeckKeyword& keyword = block.keyword;
  const char* line_text = initialization ? INITIALIZATION_LINE : CLEARANCE_LINE;
  const std::string what = initialization ? "initialization name" : "clearance name";
  check_parameters(deck, keyword, {});
  GeneralContact* contact = open_contact(deck, keyword);
  if (contact == nullptr) return;
  if (block.data.empty()) {
    error(deck, keyword.where, keyword, "no assignments",
          std::string("expected data lines: ") + line_text);
    return;
  }
  const auto field = [](const DeckDataLine& line, std::size_t i) {
    return i < line.fields.size() ? normalize_name(line.fields[i]) : std::string();
  };
  for (const DeckDataLine& line : block.data) {
    check_field_count(deck, line, keyword, 4, line_text);
    const std::string first = field(line, 0), second = field(line, 1), name = field(line, 2),
                      view = field(line, 3);
    PendingClearanceAssignment pending;
    pending.step = static_cast<Index>(deck.model.steps.size() - 1);
    pending.clearance = name;
    pending.initialization = initialization;
    ClearanceAssignment& assignment = pending.assignment;
    assignment.where = line.where();
    bool ok = true;
    const auto missing = [&](const std::string& field_name) {
      error(deck, line.where(), keyword, "missing " + field_name,
            std::string("expected ") + line_text);
      ok = false;
    };
    if (first.empty()) missing("surface 1");
    if (second.empty()) missing("surface 2");
    if (name.empty()) missing(what);
    // FIRST SURFACE SFC: the first surface behaves as the secondary (slave) surface of a pure
    // main-secondary interaction, as SLAVE; SECOND SURFACE SFC: the second one, as MASTER.
    if (view == "MASTER" || (initialization && view == "SECOND SURFACE SFC")) {
      assignment.view = ClearanceAssignment::View::Master;
    } else if (view == "SLAVE" || (initialization && view == "FIRST SURFACE SFC")) {
      assignment.view = ClearanceAssignment::View::Slave;
    } else if (!view.empty()) {
      error(deck, line.where(), keyword, "bad view '" + view + "'",
            std::string("expected MASTER (surface 1 is the master: only the nodes of surface 2 "
                        "move), SLAVE (surface 1 is the slave)") +
                (initialization ? ", SECOND SURFACE SFC (as MASTER), FIRST SURFACE SFC (as SLAVE)"
                                : "") +
                " or nothing (both views)");
      ok = false;
    }
    if (!first.empty() && first == second) {
      error(deck, line.where(), keyword, "self contact of surface " + first,
            std::string("expected two different surfaces (") +
                (initialization ? "contact initializations" : "clearances") +
                " do not apply to self contact)");
      continue;
    }
    for (const auto& [surface_name, index] :
         {std::pair{first, &assignment.first}, std::pair{second, &assignment.second}}) {
      if (surface_name.empty()) continue;
      *index = contact_surface(deck, surface_name, line.where(), keyword.label());
      if (*index == NO_INDEX) ok = false;
    }
    // A node-based surface (SPEC C13) is slave only: between its nodes and the faces of an
    // element-based surface one view exists, which no view word may turn round.
    const auto node_based = [&](Index surface) {
      return surface != NO_INDEX &&
             deck.model.surfaces[static_cast<std::size_t>(surface)].type == Surface::Type::Node;
    };
    const std::string node_expected =
        "expected a node-based surface (*SURFACE, TYPE=NODE) as the slave of an element-based "
        "surface: no view (the one view that exists), MASTER with the node-based surface second "
        "or SLAVE with it first (a node-based surface has no faces to be a master)";
    if (node_based(assignment.first) && node_based(assignment.second)) {
      error(
          deck, line.where(), keyword,
          "surfaces " + first + " and " + second + " are both node-based: neither can be a master",
          node_expected);
      ok = false;
    } else if (const bool first_master = assignment.view == ClearanceAssignment::View::Master;
               assignment.view != ClearanceAssignment::View::Both &&
               node_based(first_master ? assignment.first : assignment.second)) {
      error(deck, line.where(), keyword,
            "surface " + (first_master ? first : second) +
                " is node-based and would act as a master (" + view + ")",
            node_expected);
      ok = false;
    }
    if (ok) deck.clearance_assignments.push_back(std::move(pending));
  }
}

}  // namespace

void read_contact_clearance(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(deck, keyword,
                   {{"NAME"}, {"ADJUST"}, {"CLEARANCE"}, {"SEARCH ABOVE"}, {"SEARCH BELOW"}});
  const std::optional<std::string> name = required_name(deck, keyword, "NAME");
  const std::vector<Located> parameters = gather_parameters(
      deck, block, {{"ADJUST"}, {"CLEARANCE"}, {"SEARCH ABOVE"}, {"SEARCH BELOW"}},
      "ADJUST=, CLEARANCE=, SEARCH ABOVE=, SEARCH BELOW=");
  ContactClearance clearance;
  std::string distribution;
  read_shared(deck, keyword, parameters, "CLEARANCE", clearance, distribution);
  if (name) add_definition(deck, keyword, *name, clearance, distribution);
}

void read_contact_initialization(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(deck, keyword,
                   {{"NAME"},
                    {"INITIAL CLEARANCE"},
                    {"INTERFERENCE FIT", true, true},
                    {"ADJUST"},
                    {"SEARCH ABOVE"},
                    {"SEARCH BELOW"},
                    {"MINIMUM DISTANCE"},
                    {"STEP FRACTION"}});
  const std::optional<std::string> name = required_name(deck, keyword, "NAME");
  const std::vector<Located> parameters = gather_parameters(
      deck, block,
      {{"INITIAL CLEARANCE"},
       {"INTERFERENCE FIT"},
       {"ADJUST"},
       {"SEARCH ABOVE"},
       {"SEARCH BELOW"},
       {"MINIMUM DISTANCE"},
       {"STEP FRACTION"}},
      "INITIAL CLEARANCE=, INTERFERENCE FIT=, ADJUST=, SEARCH ABOVE=, SEARCH BELOW=, MINIMUM "
      "DISTANCE=, STEP FRACTION=");
  ContactClearance clearance;
  clearance.initialization = true;
  std::string distribution;
  read_shared(deck, keyword, parameters, "INITIAL CLEARANCE", clearance, distribution);

  const Located* interference = find_located(parameters, "INTERFERENCE FIT");
  const Located* initial = find_located(parameters, "INITIAL CLEARANCE");
  if (interference != nullptr && initial != nullptr)
    error(deck, interference->second, keyword,
          "INITIAL CLEARANCE and INTERFERENCE FIT are both given",
          "expected one of them (they are mutually exclusive): INITIAL CLEARANCE=c for a gap, "
          "INTERFERENCE FIT[=h] to resolve overclosures over the first step");
  if (interference != nullptr) {
    clearance.interference = true;
    // Without a distance nothing is moved: the overclosures as read are the interference.
    clearance.adjust = false;
    if (interference->first.has_value) {
      const std::string& text = interference->first.value;
      const std::optional<Real> h = parse_real(text);
      if (!h)
        error(deck, interference->second, keyword, "bad number '" + text + "' for INTERFERENCE FIT",
              "expected INTERFERENCE FIT alone (the overclosures as read) or INTERFERENCE FIT=h "
              "with an interference distance h > 0");
      else if (!(*h > 0.0))
        error(deck, interference->second, keyword,
              "INTERFERENCE FIT=" + text + (*h < 0.0 ? " is negative" : " is zero"),
              "expected an interference distance h > 0 (an overclosure), or INTERFERENCE FIT "
              "alone to take the overclosures as read");
      else
        clearance.interference_distance = *h;
      // With a distance the nodes are moved to it unless ADJUST=NO.
      const Located* adjust = value_of(parameters, "ADJUST");
      clearance.adjust = adjust == nullptr || normalize_name(adjust->first.value) == "YES";
    }
  }
  if (const Located* fraction = find_located(parameters, "STEP FRACTION")) {
    const std::optional<Real> f =
        fraction->first.has_value ? parse_real(fraction->first.value) : std::nullopt;
    if (interference == nullptr)
      error(deck, fraction->second, keyword, "STEP FRACTION without INTERFERENCE FIT",
            "expected STEP FRACTION only with INTERFERENCE FIT (the fraction of the first step "
            "over which the interference is resolved)");
    else if (!f || !(*f > 0.0 && *f <= 1.0))
      error(deck, fraction->second, keyword,
            "STEP FRACTION=" + fraction->first.value + " is outside (0, 1]",
            "expected a fraction of the step time 0 < f <= 1 (default 1: the whole first step)");
    else
      clearance.step_fraction = *f;
  }
  if (const Located* minimum = find_located(parameters, "MINIMUM DISTANCE")) {
    const std::string word = normalize_name(minimum->first.value);
    if (word == "YES" || word == "NO")
      note(deck, minimum->second, keyword,
           "MINIMUM DISTANCE=" + word +
               " accepted without effect: it switches the localized contact damping of "
               "Abaqus/Standard where surfaces touch at a single point, which xpl (explicit, "
               "penalty contact) does not have");
    else
      error(deck, minimum->second, keyword, "bad MINIMUM DISTANCE=" + minimum->first.value,
            "expected MINIMUM DISTANCE=YES or NO");
  }
  if (name) add_definition(deck, keyword, *name, clearance, distribution);
}

void read_clearance_assignment(DeckState& deck, const DeckBlock& block) {
  read_assignment(deck, block, false);
}

void read_initialization_assignment(DeckState& deck, const DeckBlock& block) {
  read_assignment(deck, block, true);
}

}  // namespace xpl::io
