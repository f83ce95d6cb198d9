#pragma once
/// \file The keyword table of the deck reader: every keyword it knows, where in a deck it may
/// appear and the handler that reads it. The dispatcher (read_block), the "unknown keyword"
/// message and the docs check (tests/io/deck/test_deck_keywords.cpp) all read this one table.

#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "io/deck/deck_state.hpp"

namespace xpl::io {

/// Where a keyword may appear in a deck.
enum class KeywordPlace {
  Model,  ///< model data: before the first *STEP
  /// Model data that a *PART may hold (mesh, sets, surfaces, sections): read once for each
  /// *INSTANCE of the part, in the instance's scope; also allowed in an *INSTANCE block, at the
  /// assembly level and in a flat deck.
  Part,
  ModelOrStep,  ///< model data (before the first *STEP) or history data inside a step
  Step,         ///< history data: between *STEP and *END STEP
  StepContact,  ///< general contact and its options: inside a step only (as in Abaqus/Explicit)
  Anywhere,     ///< also between steps (*STEP, *END STEP, *PREPRINT, *DIAGNOSTICS)
};

/// The option block a keyword belongs to. It leaves that block open (a *DENSITY after a
/// *MATERIAL, a *NODE OUTPUT after an *OUTPUT); every other keyword closes it.
enum class KeywordBlock { None, Material, Interaction, Output };

/// Reads one keyword block into the DeckState.
using KeywordHandler = void (*)(DeckState& deck, const DeckBlock& block);

/// One keyword the reader knows.
struct KeywordSpec {
  std::string_view name;  ///< upper case, without the star ("SOLID SECTION")
  KeywordPlace place;
  KeywordBlock block;
  /// nullptr: accepted and ignored (*PREPRINT), or handled while the lines are read (*INCLUDE).
  KeywordHandler handler;
  /// false: known only to be refused with a reason (*SHELL GENERAL SECTION), so not listed as
  /// supported.
  bool supported = true;
};

/// Every keyword the reader knows, supported ones in the order the "unknown keyword" message
/// lists them.
std::span<const KeywordSpec> keyword_table();

/// The keyword named `name` (upper case, without the star), or nullptr.
const KeywordSpec* find_keyword(std::string_view name);

/// Reads one keyword block: checks that the keyword is known and allowed where it stands
/// (reported if not), then calls its handler.
void read_block(DeckState& deck, const DeckBlock& block);

/// Reads the blocks in deck order; the blocks of a *PART are kept and read for each of its
/// instances (deck_assembly.cpp).
void read_blocks(DeckState& deck, const std::vector<DeckBlock>& blocks);

}  // namespace xpl::io
