#pragma once
/// \file Helpers the keyword handlers share (deck_fields.cpp): messages in the
/// `file:LINE: *KEYWORD: problem; expected` form, parameter checks, data fields, references and
/// set indices.

#include <cstddef>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>

#include "io/deck/deck_state.hpp"

namespace xpl::io {

/// One accepted parameter of a keyword: `NAME=value` or a flag.
struct ParameterSpec {
  std::string_view name;
  bool takes_value = true;
  bool value_optional = false;  ///< both `NAME` and `NAME=value` are fine (NLGEOM)
};

/// `file:LINE`, as messages name a place in the deck.
std::string location_text(const SourceLocation& where);

/// A real number as messages show it (6 significant digits, e.g. 2.1e+11).
std::string number_text(Real value);

/// Adds `file:LINE: *KEYWORD: problem; expected` to the deck errors.
void error(DeckState& deck, const SourceLocation& where, const DeckKeyword& keyword,
           const std::string& problem, const std::string& expected);
/// Reports unknown, repeated or malformed parameters; false if any.
bool check_parameters(DeckState& deck, const DeckKeyword& keyword,
                      std::initializer_list<ParameterSpec> accepted);
/// The parameter `name` of `keyword`, or nullptr.
const DeckParameter* find_parameter(const DeckKeyword& keyword, std::string_view name);
/// Value of a required parameter, upper case and blank-collapsed; reported if missing.
std::optional<std::string> required_name(DeckState& deck, const DeckKeyword& keyword,
                                         std::string_view name);
/// Value of an optional name parameter (upper case), empty if absent.
std::string optional_name(const DeckKeyword& keyword, std::string_view name);
/// Reports a data line after a keyword that takes none.
void expect_no_data(DeckState& deck, const DeckBlock& block);
/// Adds a note (not an error) for the .msg file: `file:LINE: *KEYWORD: text`.
void note(DeckState& deck, const SourceLocation& where, const DeckKeyword& keyword,
          const std::string& text);
/// Field i of a data line as a real; empty fields give `blank` if it has a value.
std::optional<Real> real_field(DeckState& deck, const DeckDataLine& line,
                               const DeckKeyword& keyword, std::size_t i, std::string_view what,
                               std::optional<Real> blank = std::nullopt);
/// Field i of a data line as an integer (reported if missing or bad).
std::optional<long long> integer_field(DeckState& deck, const DeckDataLine& line,
                                       const DeckKeyword& keyword, std::size_t i,
                                       std::string_view what);
/// Reports a data line with more than `count` fields.
bool check_field_count(DeckState& deck, const DeckDataLine& line, const DeckKeyword& keyword,
                       std::size_t count, const std::string& expected);
/// Checks a `slave surface, master surface` line (*CONTACT PAIR, *TIE): both names present
/// (one error naming the missing one otherwise). Returns whether both are there.
bool check_surface_pair(DeckState& deck, const DeckDataLine& line, const DeckKeyword& keyword);
/// Field i of a data line as a node/element reference (id or upper-case set name).
DeckReference reference(const DeckDataLine& line, const DeckKeyword& keyword, std::size_t i);
/// The same in the scope being read: an id keeps the scope, a name is qualified with the
/// instance (part-level data read for an instance).
DeckReference reference(const DeckState& deck, const DeckDataLine& line, const DeckKeyword& keyword,
                        std::size_t i);
/// Index of the node set `name`, created (defined at `where`) if new.
Index node_set_index(DeckState& deck, const std::string& name, const SourceLocation& where);
/// Index of the element set `name`, created (defined at `where`) if new.
Index element_set_index(DeckState& deck, const std::string& name, const SourceLocation& where);
/// Adds an error unless `count` (a DeckState::error_counts entry) errors of this category were
/// already reported; finish() adds a summary of the rest.
void capped_error(DeckState& deck, int& count, const SourceLocation& where,
                  const std::string& keyword, const std::string& problem,
                  const std::string& expected);

}  // namespace xpl::io
