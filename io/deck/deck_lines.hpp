#pragma once
/// \file Lexical layer of the deck reader: lines → keyword blocks with parameters and data
/// fields. Handles `**` comments, blank lines, comma continuation, quotes and *INCLUDE.
///
/// Data lines are kept compact (a view of their text, a file index and a line number: a
/// large mesh is read without a heap allocation per line); their fields are split when the
/// keyword handlers visit them. The text they view is owned by the caller (the main deck) and by a
/// DeckStorage (included files, joined continuation lines), which must outlive the blocks.

#include <cstddef>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <string>
#include <string_view>
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

/// A comment line addressed to xpl, `** xpl: NAME=value, ...` (Abaqus ignores it): the text
/// after "xpl:" and where it stands.
struct DeckDirective {
  std::string text;
  SourceLocation where;
};

/// Owns the text that data lines view besides the main deck: included files, their names and
/// continuation lines joined into one. Elements never move once added. Also collects the
/// `** xpl:` comments of the deck and its included files, in the order they are read.
class DeckStorage {
 public:
  /// The `** xpl:` comments read so far.
  std::vector<DeckDirective> directives;

  /// Stores a file name; returns its index.
  std::uint32_t add_file(std::string name);
  const std::string& file(std::uint32_t index) const { return m_files[index]; }
  /// Stores `text`; returns a view of the stored copy.
  std::string_view keep(std::string text);

 private:
  std::deque<std::string> m_files;
  std::deque<std::string> m_texts;
};

/// A data line as visited by the keyword handlers, continuation lines already joined.
struct DeckDataLine {
  std::vector<std::string_view> fields;  ///< comma-separated, trimmed, quotes removed
  std::string_view text;                 ///< the raw line (used by *HEADING)
  const std::string* file = nullptr;     ///< the file, as named in messages
  int line = 0;                          ///< the first physical line, 1-based
  /// The first physical line.
  SourceLocation where() const { return {*file, line}; }
};

/// The data lines of a block: stored compactly, split into fields when visited.
class DeckData {
 public:
  /// Stored form of one data line.
  struct Record {
    std::string_view text;
    std::uint32_t file = 0;  ///< index in the DeckStorage
    int line = 0;
  };

  /// Visits the lines in order; the line it refers to is valid until the iterator moves.
  class Iterator {
   public:
    Iterator(const DeckData* data, std::size_t index) : m_data(data), m_index(index) {}
    const DeckDataLine& operator*() const {
      if (!m_loaded) m_data->load(m_index, m_line);
      m_loaded = true;
      return m_line;
    }
    const DeckDataLine* operator->() const { return &**this; }
    Iterator& operator++() {
      ++m_index;
      m_loaded = false;
      return *this;
    }
    bool operator==(const Iterator& other) const { return m_index == other.m_index; }

   private:
    const DeckData* m_data;
    std::size_t m_index;
    mutable DeckDataLine m_line;
    mutable bool m_loaded = false;
  };

  explicit DeckData(const DeckStorage* storage = nullptr) : m_storage(storage) {}
  void push_back(const Record& record) { m_records.push_back(record); }
  std::size_t size() const { return m_records.size(); }
  bool empty() const { return m_records.empty(); }
  DeckDataLine operator[](std::size_t i) const {
    DeckDataLine line;
    load(i, line);
    return line;
  }
  DeckDataLine front() const { return (*this)[0]; }
  Iterator begin() const { return {this, 0}; }
  Iterator end() const { return {this, m_records.size()}; }
  /// Splits line i into `line`, reusing its field storage.
  void load(std::size_t i, DeckDataLine& line) const;

 private:
  const DeckStorage* m_storage;
  std::vector<Record> m_records;
};

/// A keyword line with the data lines that follow it.
struct DeckBlock {
  DeckKeyword keyword;
  DeckData data;
};

/// Splits deck text into blocks, following *INCLUDE (relative to the directory of
/// `file_name`; an included file may hold only data lines, which continue the open block).
/// A file that includes itself, directly or through others, is one error naming the chain;
/// included files are read with read_deck_file's limits.
/// Problems are added to `errors`; the blocks that could be read are returned. They view
/// `text` and `storage`, which must outlive them.
std::vector<DeckBlock> read_deck_blocks(std::string_view text, const std::string& file_name,
                                        DeckStorage& storage, InputErrors& errors);

/// One `NAME=value` or flag field of a keyword line (quotes removed, value trimmed). Also used
/// for data lines that a keyword reads as more parameters (*CONTACT CLEARANCE).
DeckParameter parse_parameter(std::string_view field);

/// Upper case with runs of blanks collapsed to one and ends trimmed ("step  time" → "STEP TIME").
std::string normalize_name(std::string_view text);

}  // namespace xpl::io
