#include "common/error.hpp"

#include <sstream>

namespace xpl {

void InputErrors::add(const SourceLocation& where, const std::string& keyword,
                      const std::string& problem, const std::string& expected) {
  std::ostringstream out;
  out << where.file << ':' << where.line << ": ";
  if (!keyword.empty()) out << keyword << ": ";
  out << problem;
  if (!expected.empty()) out << "; " << expected;
  m_messages.push_back(out.str());
}

void InputErrors::add_plain(const std::string& message) {
  m_messages.push_back(message);
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
