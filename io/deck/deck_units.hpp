#pragma once
/// \file The unit system of a deck (common/units.hpp): the `** xpl: UNITS=` comment, and the
/// check of the material data against the stated system (or SI, when none is stated).

#include <vector>

#include "common/error.hpp"
#include "io/deck/deck_lines.hpp"
#include "solver/model/model.hpp"

namespace xpl::io {

/// Reads the `** xpl:` comments of a deck: `UNITS=system` (one of UNIT_SYSTEMS; stated once,
/// or again with the same system) sets `model.units.stated`. Anything else in such a comment
/// is an error in `errors` (a misspelt setting must not pass silently).
void read_directives(const std::vector<DeckDirective>& directives, Model& model,
                     InputErrors& errors);

/// Decides how the model's numbers are labelled (Model::units) from the statement and the
/// material data: every material with a density must have, converted to SI, a density of
/// 0.1..1e7 kg/m³ and a bar wave speed sqrt(E/ρ) of 0.1..1e5 m/s to fit a system (wide
/// bounds: foams, heavy rigid plates; steel in t/mm³ is 1e-12 of the lower one). A deck that
/// states no system and fits SI is labelled SI (assumed, said so); one that states none and
/// does not fit SI gets dimension-only labels and a warning naming the systems its data fit;
/// a stated system the data do not fit keeps its labels, with a warning.
void settle_units(Model& model);

}  // namespace xpl::io
