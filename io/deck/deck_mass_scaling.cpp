/// \file *FIXED MASS SCALING (SPEC S4): FACTOR=, DT=, TYPE=BELOW MIN|UNIFORM, ELSET=.
///
/// Values that cannot be meant are refused at their line: a FACTOR below 1 removes mass (the
/// stable increment shrinks and the .msg reports a negative added mass), one above
/// MAX_FACTOR turns the scaled part into a near-rigid lump (its increment rises more than a
/// thousandfold); a DT longer than the step or shorter than MIN_DT_FRACTION of it scales to
/// an increment no run can use; an ELSET= of rigid-body elements only has nothing to scale
/// (checked once sets and rigid bodies are resolved: check_mass_scaling_sets).

#include <algorithm>
#include <cmath>
#include <vector>

#include "io/deck/deck_handlers.hpp"
#include "io/deck/deck_numbers.hpp"

namespace xpl::io {

namespace {

/// Largest mass factor accepted (the element increment rises by its square root, 1000×).
constexpr Real MAX_FACTOR = 1e6;
/// Shortest DT accepted, as a fraction of the step's time period (1e12 increments).
constexpr Real MIN_DT_FRACTION = 1e-12;
/// Bounds of DT when the step's time period is not known yet (*DYNAMIC after this line), s.
constexpr Real MIN_DT = 1e-30, MAX_DT = 1e30;

}  // namespace

void read_fixed_mass_scaling(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(deck, keyword, {{"FACTOR"}, {"DT"}, {"TYPE"}, {"ELSET"}});
  expect_no_data(deck, block);
  if (deck.model.steps.size() != 1) {
    error(deck, keyword.where, keyword,
          "fixed mass scaling in step " + std::to_string(deck.model.steps.size()),
          "expected it in the first step only (xpl scales the masses once, at the start of the "
          "analysis)");
    return;
  }
  FixedMassScaling scaling;
  scaling.where = keyword.where;
  bool ok = true;
  const auto positive = [&](const char* name, const char* example) -> std::optional<Real> {
    const DeckParameter* p = find_parameter(keyword, name);
    if (p == nullptr || !p->has_value) return std::nullopt;
    const std::optional<Real> value = parse_real(p->value);
    if (!value || !(*value > 0.0)) {
      error(deck, keyword.where, keyword, std::string("bad ") + name + "=" + p->value,
            std::string("expected a number > 0, e.g. ") + example);
      ok = false;
      return std::nullopt;
    }
    return value;
  };
  const std::optional<Real> factor = positive("FACTOR", "FACTOR=4");
  scaling.dt = positive("DT", "DT=1e-6");
  if (factor && (*factor < 1.0 || *factor > MAX_FACTOR)) {
    error(deck, keyword.where, keyword,
          "FACTOR=" + number_text(*factor) +
              (*factor < 1.0 ? " is below 1: it would remove mass (the stable increment shrinks)"
                             : " is above " + number_text(MAX_FACTOR) +
                                   ": the scaled elements would be near-rigid lumps"),
          "expected a mass factor from 1 to " + number_text(MAX_FACTOR) + ", e.g. FACTOR=4");
    ok = false;
  } else if (factor) {
    scaling.factor = *factor;
  }
  if (scaling.dt) {
    const Real period = deck.model.steps.back().time_period;  // 0: *DYNAMIC not read yet
    const Real low = period > 0.0 ? MIN_DT_FRACTION * period : MIN_DT;
    const Real high = period > 0.0 ? period : MAX_DT;
    if (*scaling.dt < low || *scaling.dt > high) {
      const std::string range = "from " + number_text(low) + " to " + number_text(high) + " s";
      error(deck, keyword.where, keyword,
            "DT=" + number_text(*scaling.dt) + " s is " +
                (*scaling.dt > high ? "longer than " : "shorter than ") +
                (period > 0.0 ? (*scaling.dt > high ? "the step time period "
                                                    : "1e-12 of the step time period ") +
                                    number_text(period) + " s"
                              : number_text(*scaling.dt > high ? high : low) + " s"),
            "expected a target stable increment " + range);
      ok = false;
      scaling.dt.reset();
    }
  }
  const std::string type = optional_name(keyword, "TYPE");
  if (type == "UNIFORM") {
    scaling.type = FixedMassScaling::Type::Uniform;
  } else if (!type.empty() && type != "BELOW MIN") {
    error(deck, keyword.where, keyword, "bad TYPE=" + type,
          "expected TYPE=BELOW MIN (default) or TYPE=UNIFORM");
    ok = false;
  }
  if (!type.empty() && !scaling.dt && ok) {
    // One error for the cause: "no scaling given" below would report the missing DT= again.
    error(deck, keyword.where, keyword,
          "TYPE=" + type + " without DT=", "expected DT=target increment with TYPE=");
    ok = false;
  }
  if (ok && !factor && !scaling.dt && find_parameter(keyword, "FACTOR") == nullptr &&
      find_parameter(keyword, "DT") == nullptr) {
    error(deck, keyword.where, keyword, "no scaling given", "expected FACTOR=, DT= or both");
    ok = false;
  }
  const std::string set = optional_name(keyword, "ELSET");
  if (!set.empty()) {
    // Sets are model data: the set must exist by the time the step names it.
    const auto it = deck.element_set_by_name.find(set);
    if (it == deck.element_set_by_name.end()) {
      error(deck, keyword.where, keyword, "undefined element set " + set,
            "expected *ELSET, ELSET=" + set + " in the model data");
      ok = false;
    } else {
      scaling.element_set = it->second;
    }
  }
  if (ok) deck.model.steps.back().mass_scaling.push_back(scaling);
}

void check_mass_scaling_sets(DeckState& deck) {
  std::vector<char> rigid;  // per element: in a rigid body's ELSET=
  for (const Step& step : deck.model.steps)
    for (const FixedMassScaling& scaling : step.mass_scaling) {
      if (scaling.element_set == NO_INDEX) continue;
      if (rigid.empty()) {
        rigid.assign(deck.model.element_ids.size(), 0);
        for (const RigidBody& body : deck.model.rigid_bodies)
          if (body.element_set != NO_INDEX)
            for (Index e :
                 deck.model.element_sets[static_cast<std::size_t>(body.element_set)].members)
              rigid[static_cast<std::size_t>(e)] = 1;
      }
      const NamedSet& set = deck.model.element_sets[static_cast<std::size_t>(scaling.element_set)];
      if (set.members.empty() || !std::all_of(set.members.begin(), set.members.end(), [&](Index e) {
            return rigid[static_cast<std::size_t>(e)] != 0;
          }))
        continue;
      deck.errors.add(
          scaling.where, "*FIXED MASS SCALING",
          "element set " + set.name + " holds only elements of rigid bodies (*RIGID BODY, ELSET=)",
          "expected a set with deformable elements: rigid bodies have no stable "
          "increment to raise");
    }
}

}  // namespace xpl::io
