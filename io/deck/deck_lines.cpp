#include "io/deck/deck_lines.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <optional>
#include <string>

#include "io/deck/deck_file.hpp"
#include "io/deck/deck_keywords.hpp"
#include "solver/model/model.hpp"

namespace xpl::io {

namespace {

/// Deeper nesting of *INCLUDE without a cycle is almost certainly a mistake.
constexpr int MAX_INCLUDE_DEPTH = 16;
/// Most included files one deck reads (a file may be included many times without a cycle:
/// ten levels of a file including the next twice read 2^10 files).
constexpr int MAX_INCLUDED_FILES = 10000;

bool is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
}

std::string_view trim(std::string_view text) {
  std::size_t begin = 0, end = text.size();
  while (begin < end && is_blank(text[begin])) ++begin;
  while (end > begin && is_blank(text[end - 1])) --end;
  return text.substr(begin, end - begin);
}

/// Removes one pair of surrounding double quotes.
std::string_view unquote(std::string_view text) {
  if (text.size() >= 2 && text.front() == '"' && text.back() == '"')
    return text.substr(1, text.size() - 2);
  return text;
}

/// Splits at commas outside double quotes into `fields` (cleared first); fields trimmed and
/// unquoted. A single trailing empty field (the line ended with a comma) is dropped. Returns
/// whether a quote is left open.
bool split_fields(std::string_view line, std::vector<std::string_view>& fields) {
  fields.clear();
  bool quoted = false;
  std::size_t start = 0;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      fields.push_back(unquote(trim(line.substr(start, i - start))));
      start = i + 1;
    }
  }
  fields.push_back(unquote(trim(line.substr(start))));
  if (fields.size() > 1 && fields.back().empty()) fields.pop_back();
  return quoted;
}

/// Whether the quotes of a line leave one open (what split_fields reports), without splitting.
bool unterminated_quote(std::string_view line) {
  return std::count(line.begin(), line.end(), '"') % 2 != 0;
}

/// A significant physical line: trimmed, not blank, not a comment; 1-based number.
struct PhysicalLine {
  std::string_view text;
  int number = 0;
};

/// The text after "xpl:" of a comment line `** xpl: ...` (case-insensitive, blanks allowed
/// after the stars), or nothing.
std::optional<std::string_view> xpl_directive(std::string_view comment) {
  std::string_view rest = comment.substr(2);
  while (!rest.empty() && (rest.front() == '*' || is_blank(rest.front()))) rest.remove_prefix(1);
  if (rest.size() < 4 || to_upper(std::string(rest.substr(0, 4))) != "XPL:") return std::nullopt;
  return trim(rest.substr(4));
}

/// Walks the physical lines of a file (as std::getline would split them).
struct LineCursor {
  std::string_view text;
  std::size_t position = 0;
  int number = 0;
  /// Receives the `** xpl:` comments; each is taken once, by the cursor that first passes it
  /// (copies of the cursor look ahead and may pass a line again).
  std::vector<PhysicalLine>* directives = nullptr;

  /// The next significant line, skipping comments and blank lines; false at the end.
  bool next(PhysicalLine& out) {
    while (position < text.size()) {
      const std::size_t end = text.find('\n', position);
      const std::size_t stop = end == std::string_view::npos ? text.size() : end;
      const std::string_view line = trim(text.substr(position, stop - position));
      position = end == std::string_view::npos ? text.size() : end + 1;
      ++number;
      if (line.empty()) continue;
      if (line.starts_with("**")) {
        if (directives != nullptr && (directives->empty() || directives->back().number < number))
          if (const auto directive = xpl_directive(line))
            directives->push_back({*directive, number});
        continue;
      }
      out = {line, number};
      return true;
    }
    return false;
  }
};

/// Whether a line can continue a keyword line: a parameter name starts with a letter (a
/// number starts the keyword's data).
bool starts_parameter(std::string_view line) {
  const char c = line.front();
  return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z');
}

/// Number of non-empty comma-separated fields of a data line (element lines hold no quotes).
int filled_fields(std::string_view line) {
  int n = 0;
  bool empty = true;
  for (const char c : line) {
    if (c == ',') {
      n += empty ? 0 : 1;
      empty = true;
    } else if (!is_blank(c)) {
      empty = false;
    }
  }
  return n + (empty ? 0 : 1);
}

/// Fields of one complete data line of an *ELEMENT block (the id and the nodes) for the
/// element types xpl reads, else 0 (continuation by trailing commas only).
int element_line_fields(const DeckKeyword& keyword) {
  if (keyword.name != "ELEMENT") return 0;
  for (const DeckParameter& p : keyword.parameters) {
    if (p.name != "TYPE") continue;
    std::string type(p.value);
    std::transform(type.begin(), type.end(), type.begin(),
                   [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
    if (type == "C3D8R" || type == "C3D8") return 9;
    if (type == "S4R" || type == "S4") return 5;
    if (type == "MASS" || type == "ROTARYI") return 2;
  }
  return 0;
}

}  // namespace

namespace {

/// State shared by a deck and the files it includes.
struct Lexer {
  std::vector<DeckBlock>& blocks;
  DeckStorage& storage;
  InputErrors& errors;
  bool open_block = false;  ///< whether data lines may still be added to blocks.back()
  bool reported_stray_data = false;
  /// The files being read, outermost first: as named in messages, and as compared (their
  /// canonical paths), to tell an *INCLUDE cycle.
  std::vector<std::string> chain_names{};
  std::vector<std::filesystem::path> chain{};
  std::vector<std::string> reported_cycles{};  ///< each cycle is reported once
  int included_files = 0;
  std::uintmax_t included_bytes = 0;

  void read(std::string_view text, const std::string& file_name, int depth);
  void include(const DeckKeyword& keyword, const std::string& file_name, int depth);
  /// Whether `path` is one of the files being read; reports the cycle (once) if so.
  bool cycle(const DeckKeyword& keyword, const std::filesystem::path& path,
             const std::string& name);
};

/// The path a file is compared by: canonical where it exists, else normalised.
std::filesystem::path identity(const std::filesystem::path& path) {
  std::error_code error;
  std::filesystem::path canonical = std::filesystem::weakly_canonical(path, error);
  return error ? path.lexically_normal() : canonical;
}

namespace {

/// The name of a known keyword that `name` spells without (or with other) inner blanks, as
/// CalculiX reads keywords ("*ENDSTEP", "*SOLIDSECTION"), else `name` itself.
std::string canonical_keyword(std::string name) {
  auto squeezed = [](std::string_view text) {
    std::string out;
    for (const char c : text)
      if (c != ' ') out += c;
    return out;
  };
  const std::span<const KeywordSpec> table = keyword_table();
  if (std::any_of(table.begin(), table.end(), [&](const KeywordSpec& s) { return s.name == name; }))
    return name;
  const std::string key = squeezed(name);
  for (const KeywordSpec& spec : table)
    if (spec.name != name && squeezed(spec.name) == key) return std::string(spec.name);
  return name;
}

}  // namespace

DeckKeyword parse_keyword(std::string_view line, const SourceLocation& where, InputErrors& errors) {
  std::vector<std::string_view> fields;
  const bool unterminated = split_fields(line.substr(1), fields);
  DeckKeyword keyword;
  keyword.where = where;
  keyword.name = canonical_keyword(normalize_name(fields.front()));
  if (unterminated)
    errors.add(where, keyword.label(), "unterminated quote", "expected a closing \"");
  for (std::size_t i = 1; i < fields.size(); ++i)
    if (!fields[i].empty()) keyword.parameters.push_back(parse_parameter(fields[i]));
  return keyword;
}

void Lexer::read(std::string_view text, const std::string& file_name, int depth) {
  const std::uint32_t file = storage.add_file(file_name);
  std::vector<PhysicalLine> directives;
  LineCursor cursor{text};
  cursor.directives = &directives;
  // An *INCLUDE is read in the middle of this file: its directives go before the later ones.
  std::size_t kept = 0;
  const auto keep_directives = [&] {
    for (; kept < directives.size(); ++kept)
      storage.directives.push_back(
          {std::string(directives[kept].text), {file_name, directives[kept].number}});
  };
  PhysicalLine current;
  std::string joined_text;
  while (cursor.next(current)) {
    std::string_view joined = current.text;
    const bool is_keyword = joined.front() == '*';
    const bool is_heading = open_block && blocks.back().keyword.name == "HEADING";
    // A line ending with a comma continues on the next line where Abaqus defines it: a keyword
    // line (continued by a line of parameters, which start with a letter; a number starts the
    // keyword's data) and an *ELEMENT data line (continued by its remaining nodes, unless it
    // already holds them all: CalculiX and Abaqus write "1, 1, 2, ..., 8," too). Any other data
    // line ends at its line end: a trailing comma only leaves its last field empty, so that
    // `BS,` then `PS,` of a *CONTACT EXCLUSIONS block stay two self-contact lines.
    const bool continues_data =
        !is_keyword && open_block && blocks.back().keyword.name == "ELEMENT";
    const int complete = continues_data ? element_line_fields(blocks.back().keyword) : 0;
    if ((is_keyword || continues_data) && joined.back() == ',' &&
        (complete == 0 || filled_fields(joined) < complete)) {
      bool joining = false;
      PhysicalLine next;
      for (LineCursor peek = cursor; peek.next(next) && next.text.front() != '*'; peek = cursor) {
        if (is_keyword && !starts_parameter(next.text)) break;
        if (!joining) joined_text.assign(joined);
        joining = true;
        joined_text += next.text;
        cursor = peek;
        if (next.text.back() != ',' || (complete > 0 && filled_fields(joined_text) >= complete))
          break;
      }
      if (joining) joined = is_keyword ? std::string_view(joined_text) : storage.keep(joined_text);
    }
    if (is_keyword) {
      const SourceLocation where{file_name, current.number};
      DeckKeyword keyword = parse_keyword(joined, where, errors);
      if (keyword.name == "INCLUDE") {
        keep_directives();
        include(keyword, file_name, depth);
        continue;
      }
      blocks.push_back({std::move(keyword), DeckData(&storage)});
      open_block = true;
      continue;
    }
    if (!open_block) {
      if (!reported_stray_data)
        errors.add({file_name, current.number}, "", "data line before any keyword",
                   "expected a keyword line starting with *");
      reported_stray_data = true;
      continue;
    }
    if (!is_heading && unterminated_quote(joined))
      errors.add({file_name, current.number}, blocks.back().keyword.label(), "unterminated quote",
                 "expected a closing \"");
    blocks.back().data.push_back({joined, file, current.number});
  }
  keep_directives();
}

void Lexer::include(const DeckKeyword& keyword, const std::string& file_name, int depth) {
  std::string input;
  bool ok = true;
  for (const DeckParameter& p : keyword.parameters) {
    if (p.name == "INPUT" && p.has_value && !p.value.empty()) {
      input = p.value;
    } else {
      errors.add(keyword.where, keyword.label(), "unexpected parameter " + p.name,
                 "accepted parameters: INPUT=file");
      ok = false;
    }
  }
  if (input.empty()) {
    errors.add(keyword.where, keyword.label(), "missing parameter INPUT",
               "expected INPUT=file name relative to the including file");
    return;
  }
  if (!ok) return;
  const std::filesystem::path parent = std::filesystem::path(file_name).parent_path();
  const std::filesystem::path path = (parent / input).lexically_normal();
  if (cycle(keyword, path, path.string())) return;
  if (depth >= MAX_INCLUDE_DEPTH) {
    errors.add(keyword.where, keyword.label(),
               "includes nested deeper than " + std::to_string(MAX_INCLUDE_DEPTH) + " levels",
               "expected at most " + std::to_string(MAX_INCLUDE_DEPTH) + " levels of *INCLUDE");
    return;
  }
  if (++included_files > MAX_INCLUDED_FILES) {
    if (included_files == MAX_INCLUDED_FILES + 1)
      errors.add(keyword.where, keyword.label(),
                 "more than " + std::to_string(MAX_INCLUDED_FILES) + " files included",
                 "expected a deck that includes each file a few times at most");
    return;
  }
  std::string content;
  const DeckFileError refused = read_deck_file(path, content);
  if (!refused.ok()) {
    const std::string where = refused.line > 0 ? ":" + std::to_string(refused.line) : "";
    errors.add(keyword.where, keyword.label(),
               "included file '" + path.string() + "'" + where + " " + refused.problem,
               refused.expected);
    return;
  }
  included_bytes += content.size();
  if (included_bytes > MAX_DECK_BYTES) {
    errors.add(
        keyword.where, keyword.label(),
        "the included files hold more than " + std::to_string(MAX_DECK_BYTES) + " bytes together",
        "expected a deck of at most 2 GiB with its includes");
    return;
  }
  chain.push_back(identity(path));
  chain_names.push_back(path.string());
  read(storage.keep(std::move(content)), path.string(), depth + 1);
  chain.pop_back();
  chain_names.pop_back();
}

bool Lexer::cycle(const DeckKeyword& keyword, const std::filesystem::path& path,
                  const std::string& name) {
  const std::filesystem::path id = identity(path);
  const auto first = std::find(chain.begin(), chain.end(), id);
  if (first == chain.end()) return false;
  // "a.inp includes b.inp, which includes a.inp"
  std::string text;
  for (auto i = static_cast<std::size_t>(first - chain.begin()); i < chain_names.size(); ++i)
    text += chain_names[i] + (text.empty() ? " includes " : ", which includes ");
  text += name;
  if (std::find(reported_cycles.begin(), reported_cycles.end(), text) == reported_cycles.end()) {
    reported_cycles.push_back(text);
    errors.add(keyword.where, keyword.label(), "cycle of includes: " + text,
               "expected no file that includes itself, directly or through other files");
  }
  return true;
}

}  // namespace

std::uint32_t DeckStorage::add_file(std::string name) {
  m_files.push_back(std::move(name));
  return static_cast<std::uint32_t>(m_files.size() - 1);
}

std::string_view DeckStorage::keep(std::string text) {
  m_texts.push_back(std::move(text));
  return m_texts.back();
}

void DeckData::load(std::size_t i, DeckDataLine& line) const {
  const Record& record = m_records[i];
  split_fields(record.text, line.fields);
  line.text = record.text;
  line.file = &m_storage->file(record.file);
  line.line = record.line;
}

DeckParameter parse_parameter(std::string_view field) {
  DeckParameter parameter;
  const std::size_t eq = field.find('=');
  if (eq == std::string_view::npos) {
    parameter.name = normalize_name(field);
  } else {
    parameter.name = normalize_name(field.substr(0, eq));
    parameter.value = unquote(trim(field.substr(eq + 1)));
    parameter.has_value = true;
  }
  return parameter;
}

std::string normalize_name(std::string_view text) {
  std::string out;
  bool pending_blank = false;
  for (char c : trim(text)) {
    if (is_blank(c)) {
      pending_blank = true;
      continue;
    }
    if (pending_blank) out += ' ';
    pending_blank = false;
    out += c;
  }
  return to_upper(out);
}

std::vector<DeckBlock> read_deck_blocks(std::string_view text, const std::string& file_name,
                                        DeckStorage& storage, InputErrors& errors) {
  std::vector<DeckBlock> blocks;
  Lexer lexer{blocks, storage, errors};
  lexer.chain.push_back(identity(file_name));
  lexer.chain_names.push_back(file_name);
  lexer.read(text, file_name, 0);
  return blocks;
}

}  // namespace xpl::io
