/// \file Contact clearances once the whole deck is read (SPEC C7–C10): the names of the
/// assignments resolved to their definitions and surfaces, and an assignment checked against
/// its step. Reading the keywords: deck_clearance.cpp.

#include <algorithm>

#include "io/deck/deck_handlers.hpp"
#include "io/deck/deck_numbers.hpp"

namespace xpl::io {

void resolve_clearances(DeckState& deck) {
  for (std::size_t c = 0; c < deck.model.contact_clearances.size(); ++c) {
    const std::string& name = deck.clearance_distributions[c];
    if (name.empty()) continue;
    ContactClearance& clearance = deck.model.contact_clearances[c];
    for (std::size_t d = 0; d < deck.model.distributions.size(); ++d)
      if (deck.model.distributions[d].name == name) clearance.distribution = static_cast<Index>(d);
    if (clearance.distribution == NO_INDEX)
      deck.errors.add(clearance.where, clearance_keyword(clearance),
                      "undefined distribution " + name,
                      "expected *DISTRIBUTION, NAME=" + name + ", LOCATION=NODE, or a number");
  }
  deck.clearance_surface_state.assign(deck.model.surfaces.size(), 0);
  for (PendingClearanceAssignment& pending : deck.clearance_assignments) {
    ClearanceAssignment& assignment = pending.assignment;
    const char* keyword = assignment_keyword(pending.initialization);
    for (std::size_t c = 0; c < deck.model.contact_clearances.size(); ++c)
      if (deck.model.contact_clearances[c].name == pending.clearance &&
          deck.model.contact_clearances[c].initialization == pending.initialization)
        assignment.clearance = static_cast<Index>(c);
    if (assignment.clearance == NO_INDEX) {
      if (pending.initialization)
        deck.errors.add(assignment.where, keyword,
                        "undefined contact initialization " + pending.clearance,
                        "expected *CONTACT INITIALIZATION DATA, NAME=" + pending.clearance);
      else
        deck.errors.add(assignment.where, keyword,
                        "undefined contact clearance " + pending.clearance,
                        "expected *CONTACT CLEARANCE, NAME=" + pending.clearance);
      continue;
    }
    const ContactClearance& definition =
        deck.model.contact_clearances[static_cast<std::size_t>(assignment.clearance)];
    // An interference fit acts on both views: the view word only directs nodal adjustments
    // of a clearance (the manual's optional item, for INITIAL CLEARANCE with ADJUST=YES).
    const bool view_fit =
        !definition.interference || assignment.view == ClearanceAssignment::View::Both;
    if (!view_fit)
      deck.errors.add(assignment.where, keyword,
                      "a view (MASTER, SLAVE, FIRST or SECOND SURFACE SFC) with interference fit " +
                          definition.name,
                      "expected no fourth field: an interference fit acts on both master-slave "
                      "views of the pair (the view directs the adjustments of INITIAL CLEARANCE "
                      "with ADJUST=YES only)");
    // Each check reports its own problem: all of them are run.
    const bool first_fit =
        check_clearance_surface(deck, assignment.first, assignment.where, keyword);
    const bool second_fit =
        check_clearance_surface(deck, assignment.second, assignment.where, keyword);
    const bool step_fit = check_clearance_step(deck, pending);
    const bool slaves_fit = check_clearance_slaves(deck, pending);
    if (!view_fit || !first_fit || !second_fit || !step_fit || !slaves_fit ||
        !check_clearance_sign(deck, pending))
      continue;
    deck.model.steps[static_cast<std::size_t>(pending.step)].contact->clearances.push_back(
        assignment);
  }
}

bool check_clearance_step(DeckState& deck, const PendingClearanceAssignment& pending) {
  const ClearanceAssignment& assignment = pending.assignment;
  const char* keyword = assignment_keyword(pending.initialization);
  const auto step = static_cast<std::size_t>(pending.step);
  const Step& here = deck.model.steps[step];
  const auto has_general = [](const std::optional<GeneralContact>& contact) {
    return contact && (contact->all_exterior || !contact->inclusions.empty());
  };
  if (!has_general(here.contact)) {
    deck.errors.add(assignment.where, keyword,
                    "step " + here.name + " has no general contact domain to assign clearances to",
                    "expected *CONTACT INCLUSIONS in the step of the *CONTACT (or an earlier one)");
    return false;
  }
  const ContactClearance& clearance =
      deck.model.contact_clearances[static_cast<std::size_t>(assignment.clearance)];
  if (step > 0 && clearance.interference) {
    deck.errors.add(assignment.where, keyword,
                    "interference fit " + clearance.name + " is assigned in step " + here.name +
                        ", which is not the first",
                    "expected an interference fit in the first step of the analysis (it is "
                    "resolved over a fraction of that step, SPEC C15)");
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
        assignment.where, keyword,
        "clearances apply only when a step's contact domain is built new; the contact in "
        "effect in step " +
            deck.model.steps[step - 1].name + " carries over into step " + here.name,
        "expected the assignment in the first step, or in a step that follows one "
        "without contact (then with ADJUST=NO)");
    return false;
  }
  if (step > 0 && clearance.adjust) {
    deck.errors.add(assignment.where, keyword,
                    "clearance " + clearance.name +
                        " moves nodes (ADJUST=YES, also the default), which only the first step "
                        "can do, and step " +
                        here.name + " is not the first",
                    "expected ADJUST=NO (contact offsets) on " +
                        std::string(clearance_keyword(clearance)) + ", NAME=" + clearance.name +
                        " for a step after the first");
    return false;
  }
  return true;
}

}  // namespace xpl::io
