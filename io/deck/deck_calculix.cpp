/// \file CalculiX keywords with an explicit meaning xpl can give, or a clear refusal:
/// `*CLEARANCE` (a contact pair's gap, run as xpl's clearance with ADJUST=NO), `*STATIC` and
/// `*EQUATION` (refused, one error each). `*CONTACT PAIR, TYPE=MASSLESS` and `*DYNAMIC, ALPHA=`
/// are read with their keywords (deck_contact.cpp, deck_step.cpp).

#include "io/deck/deck_handlers.hpp"
#include "io/deck/deck_numbers.hpp"

namespace xpl::io {

void read_static(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  // Counts as the step's procedure: no second error that the step has none.
  deck.step_has_dynamic = true;
  error(deck, keyword.where, keyword, "static analysis is not supported",
        "expected *DYNAMIC, EXPLICIT: xpl integrates explicitly in time (a quasi-static load "
        "can be run as a slow explicit step, with *FIXED MASS SCALING if it is long)");
}

void read_equation(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  error(deck, keyword.where, keyword, "linear constraint equations are not supported",
        "expected *TIE (a surface bound to another), *RIGID BODY or *BOUNDARY for what the "
        "equations hold together");
}

void read_clearance(DeckState& deck, const DeckBlock& block) {
  const DeckKeyword& keyword = block.keyword;
  check_parameters(deck, keyword, {{"MASTER"}, {"SLAVE"}, {"VALUE"}});
  expect_no_data(deck, block);
  const std::optional<std::string> master = required_name(deck, keyword, "MASTER");
  const std::optional<std::string> slave = required_name(deck, keyword, "SLAVE");
  const DeckParameter* value = find_parameter(keyword, "VALUE");
  if (value == nullptr) {
    error(deck, keyword.where, keyword, "missing parameter VALUE",
          "expected VALUE=the clearance (gap) between the surfaces");
    return;
  }
  if (!value->has_value || value->value.empty()) return;  // check_parameters reported it
  const std::optional<Real> number = parse_real(value->value);
  if (!number) {
    error(deck, keyword.where, keyword, "bad VALUE=" + value->value,
          "expected a number, the gap between the surfaces");
    return;
  }
  if (*number < 0.0) {
    error(deck, keyword.where, keyword,
          "VALUE=" + value->value + " is an interference (a negative clearance)",
          "expected VALUE >= 0: xpl's clearance is a gap; an initial overclosure of the pair is "
          "removed in the first step without *CLEARANCE (SPEC C2)");
    return;
  }
  if (!master || !slave) return;
  deck.pair_clearances.push_back({*master, *slave, *number, keyword.where});
}

void resolve_pair_clearances(DeckState& deck) {
  const std::string keyword = "*CLEARANCE";
  for (const PendingPairClearance& pending : deck.pair_clearances) {
    const Index slave = contact_surface(deck, pending.slave, pending.where, keyword);
    const Index master = contact_surface(deck, pending.master, pending.where, keyword);
    if (slave == NO_INDEX || master == NO_INDEX) continue;
    // The pair must be in effect from the first step: model data or first-step *CONTACT PAIR.
    bool paired = false;
    const auto matches = [&](const ContactPair& pair) {
      return pair.slave == slave && pair.master == master;
    };
    for (const ContactPair& pair : deck.model.contact_pairs) paired = paired || matches(pair);
    if (!deck.model.steps.empty())
      for (const ContactPair& pair : deck.model.steps.front().contact_pairs)
        paired = paired || matches(pair);
    if (!paired) {
      deck.errors.add(pending.where, keyword,
                      "no *CONTACT PAIR with slave " + pending.slave + " and master " +
                          pending.master + " in the model data or the first step",
                      "expected *CLEARANCE for a contact pair in effect from the start");
      continue;
    }
    bool solid = true;
    for (Index s : {slave, master})
      for (const ElementFace& face : deck.model.surfaces[static_cast<std::size_t>(s)].faces)
        solid =
            solid && !is_shell(deck.model.element_types[static_cast<std::size_t>(face.element)]);
    if (!solid ||
        deck.model.surfaces[static_cast<std::size_t>(slave)].type == Surface::Type::Node) {
      deck.errors.add(pending.where, keyword,
                      "a clearance between " + pending.slave + " and " + pending.master +
                          ", which are not both element-based solid surfaces",
                      "expected faces of solid elements on both sides, where a clearance means "
                      "one gap (on shells xpl's clearance sign means a side of the shell)");
      continue;
    }
    // A deck without a step has been refused already (nothing to carry the assignment).
    if (deck.model.steps.empty()) continue;
    ContactClearance clearance;
    clearance.name = "*CLEARANCE " + pending.slave + "/" + pending.master;
    clearance.adjust = false;
    clearance.value = pending.value;
    clearance.where = pending.where;
    ClearanceAssignment assignment;
    assignment.first = slave;
    assignment.second = master;
    assignment.view = ClearanceAssignment::View::Slave;
    assignment.clearance = static_cast<Index>(deck.model.contact_clearances.size());
    assignment.where = pending.where;
    deck.model.contact_clearances.push_back(clearance);
    Step& first = deck.model.steps.front();
    if (!first.contact) {
      // No general contact: an empty definition carries the assignment (the solver builds the
      // contact domain of the pairs and applies the clearance views to it).
      first.contact.emplace();
      first.contact->where = pending.where;
    }
    first.contact->clearances.push_back(assignment);
    deck.model.deck_messages.push_back(
        {false, location_text(pending.where) + ": *CLEARANCE: VALUE=" + number_text(pending.value) +
                    " runs as xpl's contact clearance with ADJUST=NO (SPEC C7): each slave node "
                    "of " +
                    pending.slave + " touches " + pending.master + " once it has closed by " +
                    number_text(pending.value) +
                    ", whatever its gap in the mesh (a permanent contact offset), as CalculiX "
                    "puts the clearance in place of the geometric gap"});
  }
}

}  // namespace xpl::io
