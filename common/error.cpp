#include "common/error.hpp"

#include <algorithm>
#include <sstream>

namespace xpl {

std::string escape_control(const std::string& text) {
  const auto is_control = [](unsigned char c) {
    return (c < 0x20 && c != '\t' && c != '\n') || c == 0x7f;
  };
  if (std::none_of(text.begin(), text.end(),
                   [&](char c) { return is_control(static_cast<unsigned char>(c)); }))
    return text;
  static constexpr char HEX[] = "0123456789abcdef";
  std::string out;
  out.reserve(text.size() + 8);
  for (const char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    if (!is_control(c)) {
      out += ch;
      continue;
    }
    out += "\\x";
    out += HEX[c >> 4];
    out += HEX[c & 0xf];
  }
  return out;
}

void InputErrors::add(const SourceLocation& where, const std::string& keyword,
                      const std::string& problem, const std::string& expected) {
  std::ostringstream out;
  out << where.file << ':' << where.line << ": ";
  if (!keyword.empty()) out << keyword << ": ";
  out << problem;
  if (!expected.empty()) out << "; " << expected;
  m_messages.push_back(escape_control(out.str()));
}

void InputErrors::add_plain(const std::string& message) {
  m_messages.push_back(escape_control(message));
}

std::string InputErrors::joined() const {
  std::string all;
  for (const auto& m : m_messages) {
    if (!all.empty()) all += '\n';
    all += m;
  }
  return all;
}

void InputErrors::throw_if_any() const {
  if (!m_messages.empty()) throw InputError(m_messages);
}

namespace {
std::string join_lines(const std::vector<std::string>& lines) {
  std::string all;
  for (const auto& m : lines) {
    if (!all.empty()) all += '\n';
    all += m;
  }
  return all;
}
}  // namespace

InputError::InputError(std::vector<std::string> messages)
    : std::runtime_error(join_lines(messages)), m_messages(std::move(messages)) {}

SolverError::SolverError(const std::string& what, ExternalId element_id, long increment, Real time)
    : std::runtime_error(what), m_element_id(element_id), m_increment(increment), m_time(time) {}

}  // namespace xpl
