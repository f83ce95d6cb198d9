#include "io/deck_lines.hpp"

#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "solver/model.hpp"

namespace xpl::io {

namespace {

/// Deeper nesting is almost certainly a file including itself.
constexpr int MAX_INCLUDE_DEPTH = 16;

bool is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v';
}

std::string trim(const std::string& text) {
  std::size_t begin = 0, end = text.size();
  while (begin < end && is_blank(text[begin])) ++begin;
  while (end > begin && is_blank(text[end - 1])) --end;
  return text.substr(begin, end - begin);
}

/// Removes one pair of surrounding double quotes.
std::string unquote(const std::string& text) {
  if (text.size() >= 2 && text.front() == '"' && text.back() == '"')
    return text.substr(1, text.size() - 2);
  return text;
}

/// Splits at commas outside double quotes; fields trimmed and unquoted. A single trailing
/// empty field (the line ended with a comma) is dropped.
std::vector<std::string> split_fields(const std::string& line, bool& unterminated_quote) {
  std::vector<std::string> fields;
  std::string current;
  bool quoted = false;
  for (char c : line) {
    if (c == '"') quoted = !quoted;
    if (c == ',' && !quoted) {
      fields.push_back(unquote(trim(current)));
      current.clear();
    } else {
      current += c;
    }
  }
  unterminated_quote = quoted;
  fields.push_back(unquote(trim(current)));
  if (fields.size() > 1 && fields.back().empty()) fields.pop_back();
  return fields;
}

/// Physical lines of a file with their 1-based numbers, comments and blank lines removed.
struct PhysicalLine {
  std::string text;
  int number = 0;
};

std::vector<PhysicalLine> significant_lines(const std::string& text) {
  std::vector<PhysicalLine> lines;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    std::string t = trim(line);
    if (t.empty() || t.rfind("**", 0) == 0) continue;
    lines.push_back({std::move(t), number});
  }
  return lines;
}

/// State shared by a deck and the files it includes.
struct Lexer {
  std::vector<DeckBlock>& blocks;
  InputErrors& errors;
  bool open_block = false;  ///< whether data lines may still be added to blocks.back()
  bool reported_stray_data = false;

  void read(const std::string& text, const std::string& file_name, int depth);
  void include(const DeckKeyword& keyword, const std::string& file_name, int depth);
};

DeckKeyword parse_keyword(const std::string& line, const SourceLocation& where,
                          InputErrors& errors) {
  bool unterminated = false;
  std::vector<std::string> fields = split_fields(line.substr(1), unterminated);
  DeckKeyword keyword;
  keyword.where = where;
  keyword.name = normalize_name(fields.front());
  if (unterminated)
    errors.add(where, keyword.label(), "unterminated quote", "expected a closing \"");
  for (std::size_t i = 1; i < fields.size(); ++i) {
    const std::string& field = fields[i];
    if (field.empty()) continue;
    DeckParameter parameter;
    const std::size_t eq = field.find('=');
    if (eq == std::string::npos) {
      parameter.name = normalize_name(field);
    } else {
      parameter.name = normalize_name(field.substr(0, eq));
      parameter.value = unquote(trim(field.substr(eq + 1)));
      parameter.has_value = true;
    }
    keyword.parameters.push_back(std::move(parameter));
  }
  return keyword;
}

void Lexer::read(const std::string& text, const std::string& file_name, int depth) {
  const std::vector<PhysicalLine> lines = significant_lines(text);
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const SourceLocation where{file_name, lines[i].number};
    std::string joined = lines[i].text;
    const bool is_keyword = joined.front() == '*';
    const bool is_heading = open_block && blocks.back().keyword.name == "HEADING";
    // A line ending with a comma continues on the next line, unless that is a keyword line.
    while (!(is_heading && !is_keyword) && joined.back() == ',' && i + 1 < lines.size() &&
           lines[i + 1].text.front() != '*') {
      joined += lines[++i].text;
    }
    if (is_keyword) {
      DeckKeyword keyword = parse_keyword(joined, where, errors);
      if (keyword.name == "INCLUDE") {
        include(keyword, file_name, depth);
        continue;
      }
      blocks.push_back({std::move(keyword), {}});
      open_block = true;
      continue;
    }
    if (!open_block) {
      if (!reported_stray_data)
        errors.add(where, "", "data line before any keyword",
                   "expected a keyword line starting with *");
      reported_stray_data = true;
      continue;
    }
    DeckDataLine data;
    bool unterminated = false;
    data.fields = split_fields(joined, unterminated);
    data.text = joined;
    data.where = where;
    if (unterminated && !is_heading)
      errors.add(where, blocks.back().keyword.label(), "unterminated quote",
                 "expected a closing \"");
    blocks.back().data.push_back(std::move(data));
  }
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
  if (depth >= MAX_INCLUDE_DEPTH) {
    errors.add(keyword.where, keyword.label(),
               "includes nested deeper than " + std::to_string(MAX_INCLUDE_DEPTH) + " levels",
               "expected no file that includes itself");
    return;
  }
  const std::filesystem::path parent = std::filesystem::path(file_name).parent_path();
  const std::filesystem::path path = (parent / input).lexically_normal();
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    errors.add(keyword.where, keyword.label(), "cannot open included file '" + path.string() + "'",
               "expected an existing file, relative to the including file");
    return;
  }
  std::ostringstream content;
  content << in.rdbuf();
  read(content.str(), path.string(), depth + 1);
}

}  // namespace

std::string normalize_name(const std::string& text) {
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

std::vector<DeckBlock> read_deck_blocks(const std::string& text, const std::string& file_name,
                                        InputErrors& errors) {
  std::vector<DeckBlock> blocks;
  Lexer lexer{blocks, errors};
  lexer.read(text, file_name, 0);
  return blocks;
}

}  // namespace xpl::io
