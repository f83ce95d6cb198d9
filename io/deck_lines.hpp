#pragma once
/// \file Lexical layer of the deck reader: lines → keyword blocks with parameters and data
/// fields. Handles `**` comments, blank lines, comma continuation, quotes and *INCLUDE.

#include <string>
#include <vector>

#include "common/error.hpp"

namespace xpl::io {

/// One keyword parameter: `NAME=value` or a flag (`has_value` false).
struct DeckParameter {
  std::string name;   ///< upper case, inner blanks collapsed ("NUMBER INTERVAL")
  std::string value;  ///< as written (case kept, quotes removed, trimmed)
  bool has_value = false;
};

/// A keyword line, e.g. `*NODE, NSET=ALL`.
struct DeckKeyword {
  std::string name;  ///< upper case without the star, inner blanks collapsed ("SOLID SECTION")
  std::vector<DeckParameter> parameters;
  SourceLocation where;
  /// The name with its star, as used in messages ("*SOLID SECTION").
  std::string label() const { return "*" + name; }
};

/// A data line, continuation lines already joined.
struct DeckDataLine {
  std::vector<std::string> fields;  ///< comma-separated, trimmed, quotes removed
  std::string text;                 ///< the raw line (used by *HEADING)
  SourceLocation where;             ///< the first physical line
};

/// A keyword line with the data lines that follow it.
struct DeckBlock {
  DeckKeyword keyword;
  std::vector<DeckDataLine> data;
};

/// Splits deck text into blocks, following *INCLUDE (relative to the directory of
/// `file_name`; an included file may hold only data lines, which continue the open block).
/// Problems are added to `errors`; the blocks that could be read are returned.
std::vector<DeckBlock> read_deck_blocks(const std::string& text, const std::string& file_name,
                                        InputErrors& errors);

/// Upper case with runs of blanks collapsed to one and ends trimmed ("step  time" → "STEP TIME").
std::string normalize_name(const std::string& text);

}  // namespace xpl::io
