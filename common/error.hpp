#pragma once
/// \file Error types: input errors (collected, all reported together) and physics failures.

#include <stdexcept>
#include <string>
#include <vector>

#include "common/types.hpp"

namespace xpl {

/// Where something came from in an input deck: file name as given and 1-based line.
struct SourceLocation {
  std::string file;
  int line = 0;
};

/// `text` with its control characters (bytes below 0x20 except tab and newline, and DEL)
/// written as `\xHH`: deck text echoed in a message cannot move the terminal's cursor or
/// change its colours.
std::string escape_control(const std::string& text);

/// Collects every input error of a deck so that all of them are reported at once.
/// Each message reads `file:LINE: *KEYWORD: what is wrong; what is expected`.
class InputErrors {
 public:
  /// Records one error. `keyword` is given with its star ("*NODE"); `expected` may be empty.
  void add(const SourceLocation& where, const std::string& keyword, const std::string& problem,
           const std::string& expected);
  /// Records a message that has no deck location (e.g. a missing file).
  void add_plain(const std::string& message);
  bool empty() const { return m_messages.empty(); }
  std::size_t size() const { return m_messages.size(); }
  const std::vector<std::string>& messages() const { return m_messages; }
  /// All messages joined by newlines.
  std::string joined() const;
  /// Throws InputError carrying every message, if there is any.
  void throw_if_any() const;

 private:
  std::vector<std::string> m_messages;
};

/// Thrown when a deck has errors; what() lists all of them, one per line.
class InputError : public std::runtime_error {
 public:
  explicit InputError(std::vector<std::string> messages);
  const std::vector<std::string>& messages() const { return m_messages; }

 private:
  std::vector<std::string> m_messages;
};

/// A physics failure during time stepping (NaN, instability, inverted element, dt collapse).
class SolverError : public std::runtime_error {
 public:
  /// `element_id` is the deck id of the offending element, or 0 when no element is known.
  SolverError(const std::string& what, ExternalId element_id, long increment, Real time);
  ExternalId element_id() const { return m_element_id; }
  long increment() const { return m_increment; }
  Real time() const { return m_time; }

 private:
  ExternalId m_element_id;
  long m_increment;
  Real m_time;
};

}  // namespace xpl
