/// \file *FIXED MASS SCALING (SPEC S4): FACTOR=, DT=, TYPE=BELOW MIN|UNIFORM, ELSET=.

#include "io/deck/deck_handlers.hpp"
#include "io/deck/deck_numbers.hpp"

namespace xpl::io {

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
  if (factor) scaling.factor = *factor;
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

}  // namespace xpl::io
