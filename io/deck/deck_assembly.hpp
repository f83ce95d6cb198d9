#pragma once
/// \file Parts, assemblies and instances (deck_assembly.cpp, deck_instances.cpp): how the
/// keyword dispatcher keeps the blocks of a *PART and where part-level data may stand, and how
/// the ids of the instances become the model's.

#include "io/deck/deck_keywords.hpp"
#include "io/deck/deck_state.hpp"

namespace xpl::io {

/// Keeps `block` for the open *PART (a part-level keyword, read later for each instance) and
/// returns true; false when the block is to be read now: no part is open, the keyword ends the
/// part, or it is model data read once (a *MATERIAL in a part). Keywords a part cannot hold
/// (history data, loads) are reported and dropped (true).
bool collect_part_block(DeckState& deck, const DeckBlock& block);

/// Checks keyword `spec` where the deck stands with respect to *ASSEMBLY and *INSTANCE: an
/// instance block holds only part-level data, a step cannot start inside an assembly (reported,
/// then read). False: skip the block (a line of a refused *INSTANCE's block).
bool assembly_allows(DeckState& deck, const KeywordSpec& spec, const DeckKeyword& keyword);

/// At the end of the deck: a *PART, *INSTANCE or *ASSEMBLY left open is reported.
void close_assembly(DeckState& deck);

/// At the end of finish(): gives the nodes and elements of an assembly model their model ids
/// (instance offsets, PartInstance), keeps their local ids and instances in the Model and lists
/// the instances in the .msg notes. Nothing for a deck without instances.
void finish_instances(DeckState& deck);

}  // namespace xpl::io
