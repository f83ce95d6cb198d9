/// \file History keywords: *STEP, *END STEP, *DYNAMIC, *BULK VISCOSITY, *BOUNDARY, *CLOAD.
/// Pressures (*DLOAD, *DSLOAD) are in deck_pressure.cpp.

#include "io/deck/deck_handlers.hpp"
#include "io/deck/deck_numbers.hpp"

namespace xpl::io {

namespace {

/// Contiguous dof ranges of an Abaqus boundary type word; empty if the word is unknown.
std::vector<std::pair<int, int>> boundary_type_dofs(const std::string& word) {
  if (word == "ENCASTRE") return {{1, 6}};
  if (word == "PINNED") return {{1, 3}};
  if (word == "XSYMM") return {{1, 1}, {5, 6}};
  if (word == "YSYMM") return {{2, 2}, {4, 4}, {6, 6}};
  if (word == "ZSYMM") return {{3, 5}};
  if (word == "XASYMM") return {{2, 4}};
  if (word == "YASYMM") return {{1, 1}, {3, 3}, {5, 5}};
  if (word == "ZASYMM") return {{1, 2}, {6, 6}};
  return {};
}

}  // namespace

void read_step(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  // INC= and INCF= are CalculiX's increment limits: accepted, noted as not used.
  check_parameters(deck, keyword,
                   {{"NAME"}, {"NLGEOM", false, true}, {"AMPLITUDE"}, {"INC"}, {"INCF"}});
  if (deck.in_step) {
    error(deck, keyword.where, keyword, "a step is already open",
          "expected *END STEP before the next *STEP");
    return;
  }
  // An optional data line is the step's description in Abaqus: nothing to check.
  Step step;
  step.where = keyword.where;
  const DeckParameter* name = find_parameter(keyword, "NAME");
  step.name = name != nullptr && name->has_value && !name->value.empty()
                  ? name->value
                  : "Step-" + std::to_string(deck.model.steps.size() + 1);
  const DeckParameter* nlgeom = find_parameter(keyword, "NLGEOM");
  if (nlgeom != nullptr && nlgeom->has_value && normalize_name(nlgeom->value) != "YES") {
    error(deck, keyword.where, keyword, "NLGEOM=" + nlgeom->value + " is not supported",
          "expected NLGEOM or NLGEOM=YES (xpl is always geometrically nonlinear)");
  }
  const std::string amplitude = optional_name(keyword, "AMPLITUDE");
  if (amplitude == "RAMP") {
    step.ramp_amplitude = true;
  } else if (!amplitude.empty() && amplitude != "STEP") {
    error(deck, keyword.where, keyword, "bad AMPLITUDE=" + amplitude,
          "expected AMPLITUDE=STEP or AMPLITUDE=RAMP");
  }
  for (const char* limit : {"INC", "INCF"})
    if (const DeckParameter* p = find_parameter(keyword, limit); p != nullptr && p->has_value)
      note(deck, keyword.where, keyword,
           p->name + "=" + p->value +
               " (CalculiX's maximum number of increments) is not used: an explicit step runs "
               "until its time period");
  deck.model.steps.push_back(std::move(step));
  deck.in_step = true;
  deck.step_has_dynamic = false;
  deck.step_where = keyword.where;
}

void read_end_step(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(deck, keyword, {});
  expect_no_data(deck, block);
  if (!deck.in_step) {
    error(deck, keyword.where, keyword, "no step is open", "expected *STEP before *END STEP");
    return;
  }
  if (!deck.step_has_dynamic)
    deck.errors.add(deck.step_where, "*STEP",
                    "step " + deck.model.steps.back().name + " has no procedure",
                    "expected *DYNAMIC, EXPLICIT with the time period");
  deck.in_step = false;
}

namespace {

/// An optional positive time field of the *DYNAMIC data line: nullopt when blank; a bad or
/// non-positive value is reported with `expected`.
std::optional<Real> optional_positive(DeckState& deck, const DeckDataLine& line,
                                      const DeckKeyword& keyword, std::size_t i,
                                      const std::string& what, const std::string& expected) {
  if (i >= line.fields.size() || line.fields[i].empty()) return std::nullopt;
  const std::optional<Real> value = real_field(deck, line, keyword, i, what);
  if (!value) return std::nullopt;
  if (!(*value > 0.0)) {
    error(deck, line.where(), keyword, what + " " + number_text(*value) + " is not positive",
          expected);
    return std::nullopt;
  }
  return value;
}

}  // namespace

void read_dynamic(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  // EXPLICIT=2|3 is CalculiX's explicit structural computation; ELEMENT BY ELEMENT is Abaqus'.
  check_parameters(deck, keyword,
                   {{"EXPLICIT", false, true},
                    {"DIRECT USER CONTROL", false},
                    {"SCALE FACTOR"},
                    {"ELEMENT BY ELEMENT", false},
                    {"ALPHA"}});
  Step& step = deck.model.steps.back();
  if (deck.step_has_dynamic) {
    error(deck, keyword.where, keyword, "second procedure in step " + step.name,
          "expected one *DYNAMIC, EXPLICIT per step");
    return;
  }
  deck.step_has_dynamic = true;
  const DeckParameter* explicit_flag = find_parameter(keyword, "EXPLICIT");
  if (explicit_flag == nullptr) {
    error(deck, keyword.where, keyword, "implicit dynamics is not supported",
          "expected *DYNAMIC, EXPLICIT");
    return;
  }
  if (explicit_flag->has_value && !explicit_flag->value.empty() && explicit_flag->value != "2" &&
      explicit_flag->value != "3") {
    error(deck, keyword.where, keyword,
          "EXPLICIT=" + explicit_flag->value +
              " (CalculiX: implicit structural computation) is "
              "not supported",
          "expected EXPLICIT, EXPLICIT=2 or EXPLICIT=3");
    return;
  }
  if (const DeckParameter* alpha = find_parameter(keyword, "ALPHA");
      alpha != nullptr && alpha->has_value && !alpha->value.empty()) {
    if (!parse_real(alpha->value))
      error(deck, keyword.where, keyword, "bad ALPHA=" + alpha->value,
            "expected a number (CalculiX: the alpha of its implicit scheme, -1/3 to 0)");
    else
      note(deck, keyword.where, keyword,
           "ALPHA=" + alpha->value +
               " ignored: it sets the numerical damping of an implicit (alpha-method) step, and "
               "the explicit central-difference method has no alpha; xpl damps high "
               "frequencies with bulk viscosity (*BULK VISCOSITY)");
  }
  if (find_parameter(keyword, "ELEMENT BY ELEMENT") != nullptr)
    note(deck, keyword.where, keyword,
         "ELEMENT BY ELEMENT: the stable increment is xpl's element-by-element estimate, which a "
         "global estimate only ever shortens (meshes with few neighbours)");
  const bool direct = find_parameter(keyword, "DIRECT USER CONTROL") != nullptr;
  if (const DeckParameter* factor = find_parameter(keyword, "SCALE FACTOR");
      factor != nullptr && factor->has_value && !factor->value.empty()) {
    const std::optional<Real> value = parse_real(factor->value);
    if (!value || *value <= 0.0)
      error(deck, keyword.where, keyword, "bad SCALE FACTOR=" + factor->value,
            "expected a number > 0, e.g. SCALE FACTOR=0.9");
    else
      step.increment.scale_factor = *value;
  }
  if (block.data.size() != 1) {
    error(deck, keyword.where, keyword,
          "found " + std::to_string(block.data.size()) + " data lines",
          "expected one data line: [time increment], time period[, , maximum increment]");
    return;
  }
  // The data line as Abaqus/Explicit writes it: (1) blank, or the fixed increment with DIRECT
  // USER CONTROL, (2) time period, (3) blank, (4) maximum time increment. CalculiX writes
  // (1) initial increment, (2) time period, (3) minimum increment, (4) maximum increment,
  // (5) initial CFD increment; its explicit solver sets the increment itself, so (1) is ignored.
  const DeckDataLine& line = block.data.front();
  check_field_count(deck, line, keyword, 5,
                    "[time increment], time period[, minimum increment][, maximum increment]");
  const std::optional<Real> period = real_field(deck, line, keyword, 1, "time period");
  if (period && *period <= 0.0)
    error(deck, line.where(), keyword, "time period " + number_text(*period) + " is not positive",
          "expected a time period > 0");
  else if (period)
    step.time_period = *period;
  const std::optional<Real> increment = optional_positive(
      deck, line, keyword, 0, "time increment",
      direct ? "expected a fixed time increment > 0" : "expected a time increment > 0 or blank");
  if (direct && !increment && (line.fields.empty() || line.fields[0].empty()))
    error(deck, line.where(), keyword, "DIRECT USER CONTROL without a time increment",
          "expected the fixed time increment as the first value");
  if (direct && increment) {
    step.increment.fixed = *increment;
  } else if (increment) {
    note(deck, line.where(), keyword,
         "initial time increment " + number_text(*increment) +
             " ignored: without DIRECT USER CONTROL every increment is the stable one (as "
             "CalculiX's explicit solver does)");
  }
  if (const std::optional<Real> minimum =
          optional_positive(deck, line, keyword, 2, "minimum time increment",
                            "expected it blank, or a minimum increment > 0 (CalculiX)")) {
    deck.model.deck_messages.push_back(
        {true, location_text(line.where()) + ": " + keyword.label() + ": minimum time increment " +
                   number_text(*minimum) +
                   " (CalculiX's third value) ignored: xpl never cuts an explicit increment back "
                   "and does no selective mass scaling to reach it (*FIXED MASS SCALING, DT= "
                   "scales the mass to a target increment)"});
  }
  if (const std::optional<Real> maximum =
          optional_positive(deck, line, keyword, 3, "maximum time increment",
                            "expected it blank, or a maximum increment > 0")) {
    if (direct)
      note(deck, line.where(), keyword,
           "maximum time increment " + number_text(*maximum) +
               " not used: DIRECT USER CONTROL fixes the increment");
    else
      step.increment.max = *maximum;
  }
  if (const std::optional<Real> cfd =
          optional_positive(deck, line, keyword, 4, "initial CFD time increment",
                            "expected it blank, or an increment > 0 (CalculiX)"))
    note(deck, line.where(), keyword,
         "initial CFD time increment " + number_text(*cfd) + " ignored (xpl has no fluid)");
}

void read_bulk_viscosity(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(deck, keyword, {});
  if (block.data.size() != 1) {
    error(deck, keyword.where, keyword,
          "found " + std::to_string(block.data.size()) + " data lines",
          "expected one data line: b1, b2");
    return;
  }
  Step& step = deck.model.steps.back();
  const DeckDataLine& line = block.data.front();
  check_field_count(deck, line, keyword, 2, "b1, b2");
  const std::optional<Real> linear = real_field(deck, line, keyword, 0, "b1", step.bulk_linear);
  const std::optional<Real> quadratic =
      real_field(deck, line, keyword, 1, "b2", step.bulk_quadratic);
  if (linear && *linear < 0.0)
    error(deck, line.where(), keyword, "b1 " + number_text(*linear) + " is negative",
          "expected b1 >= 0");
  else if (linear)
    step.bulk_linear = *linear;
  if (quadratic && *quadratic < 0.0)
    error(deck, line.where(), keyword, "b2 " + number_text(*quadratic) + " is negative",
          "expected b2 >= 0");
  else if (quadratic)
    step.bulk_quadratic = *quadratic;
}

void read_boundary(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(deck, keyword, {{"TYPE"}, {"AMPLITUDE"}, {"OP"}});
  const Index step = deck.in_step ? static_cast<Index>(deck.model.steps.size() - 1) : NO_INDEX;
  BoundaryCondition condition;
  const std::string type = optional_name(keyword, "TYPE");
  if (type == "VELOCITY") {
    condition.type = BoundaryType::Velocity;
  } else if (!type.empty() && type != "DISPLACEMENT") {
    error(deck, keyword.where, keyword, "boundary type " + type + " is not supported",
          "expected TYPE=DISPLACEMENT or TYPE=VELOCITY");
    return;
  }
  const std::string op = optional_name(keyword, "OP");
  if (!op.empty() && op != "MOD" && op != "NEW") {
    error(deck, keyword.where, keyword, "bad OP=" + op, "expected OP=MOD or OP=NEW");
    return;
  }
  if (!op.empty() && step == NO_INDEX) {
    error(deck, keyword.where, keyword, "OP= outside a step",
          "expected OP= only on a *BOUNDARY inside a step");
    return;
  }
  if (op == "NEW") deck.model.steps.back().boundaries_reset = true;
  const std::string amplitude = optional_name(keyword, "AMPLITUDE");
  for (const DeckDataLine& line : block.data) {
    std::vector<std::pair<int, int>> ranges;
    Real value = 0.0;
    if (line.fields.size() < 2 || line.fields[1].empty()) {
      error(deck, line.where(), keyword, "missing dof",
            "expected node or node set, first dof[, last dof[, value]] or a type such as "
            "ENCASTRE");
      continue;
    }
    if (!looks_numeric(line.fields[1])) {
      const std::string word = normalize_name(line.fields[1]);
      ranges = boundary_type_dofs(word);
      if (ranges.empty()) {
        error(deck, line.where(), keyword, "unknown boundary type " + word,
              "expected a dof number or ENCASTRE, PINNED, XSYMM, YSYMM, ZSYMM, XASYMM, YASYMM, "
              "ZASYMM");
        continue;
      }
      check_field_count(deck, line, keyword, 2, "node or node set, type");
    } else {
      check_field_count(deck, line, keyword, 4, "node or node set, first dof[, last dof[, value]]");
      const std::optional<long long> first = integer_field(deck, line, keyword, 1, "first dof");
      std::optional<long long> last = first;
      if (line.fields.size() > 2 && !line.fields[2].empty())
        last = integer_field(deck, line, keyword, 2, "last dof");
      const std::optional<Real> magnitude = real_field(deck, line, keyword, 3, "value", 0.0);
      if (!first || !last || !magnitude) continue;
      if (*first < 1 || *first > 6 || *last < 1 || *last > 6 || *last < *first) {
        error(deck, line.where(), keyword,
              "bad dof range " + std::to_string(*first) + ".." + std::to_string(*last),
              "expected 1 <= first dof <= last dof <= 6");
        continue;
      }
      ranges = {{static_cast<int>(*first), static_cast<int>(*last)}};
      value = *magnitude;
    }
    for (const auto& [first, last] : ranges) {
      PendingBoundary pending;
      pending.step = step;
      pending.target = reference(line, keyword, 0);
      pending.condition.first_dof = first;
      pending.condition.last_dof = last;
      pending.condition.value = value;
      pending.condition.type = condition.type;
      pending.condition.where = line.where();
      pending.amplitude = amplitude;
      deck.boundaries.push_back(std::move(pending));
    }
  }
}

bool read_load_op(DeckState& deck, const DeckKeyword& keyword, bool& reset) {
  const std::string op = optional_name(keyword, "OP");
  if (!op.empty() && op != "MOD" && op != "NEW") {
    error(deck, keyword.where, keyword, "bad OP=" + op, "expected OP=MOD or OP=NEW");
    return false;
  }
  if (op == "NEW") reset = true;
  return true;
}

void read_cload(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(deck, keyword, {{"AMPLITUDE"}, {"OP"}});
  if (!read_load_op(deck, keyword, deck.model.steps.back().loads_reset)) return;
  const std::string amplitude = optional_name(keyword, "AMPLITUDE");
  for (const DeckDataLine& line : block.data) {
    check_field_count(deck, line, keyword, 3, "node or node set, dof, magnitude");
    const std::optional<long long> dof = integer_field(deck, line, keyword, 1, "dof");
    const std::optional<Real> value = real_field(deck, line, keyword, 2, "magnitude");
    if (!dof || !value) continue;
    if (*dof < 1 || *dof > 3) {
      error(deck, line.where(), keyword, "dof " + std::to_string(*dof) + " is out of range",
            "expected dof 1, 2 or 3 (forces only)");
      continue;
    }
    PendingLoad pending;
    pending.step = static_cast<Index>(deck.model.steps.size() - 1);
    pending.target = reference(line, keyword, 0);
    pending.load.dof = static_cast<int>(*dof);
    pending.load.value = *value;
    pending.load.where = line.where();
    pending.amplitude = amplitude;
    deck.loads.push_back(std::move(pending));
  }
}

}  // namespace xpl::io
