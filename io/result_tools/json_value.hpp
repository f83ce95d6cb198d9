#pragma once
/// \file A small JSON value tree and its text form: the run summary (JOB.summary.json) and
/// the reports of `xpl compare --json` are built as one tree, written as JSON text and, for the
/// summary, flattened into HDF5 attributes.

#include <cstdint>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace xpl::io {

/// A JSON value: null, bool, integer, number, string, array or object (keys in insertion
/// order, so that the text is stable and reads in a sensible order).
class JsonValue {
 public:
  using Array = std::vector<JsonValue>;
  using Object = std::vector<std::pair<std::string, JsonValue>>;

  JsonValue() = default;  ///< null
  JsonValue(bool value) : m_value(value) {}
  JsonValue(int value) : m_value(static_cast<std::int64_t>(value)) {}
  JsonValue(long value) : m_value(static_cast<std::int64_t>(value)) {}
  JsonValue(long long value) : m_value(static_cast<std::int64_t>(value)) {}
  JsonValue(double value) : m_value(value) {}
  JsonValue(const char* value) : m_value(std::string(value)) {}
  JsonValue(std::string value) : m_value(std::move(value)) {}
  JsonValue(Array value) : m_value(std::move(value)) {}
  JsonValue(Object value) : m_value(std::move(value)) {}

  /// An empty object, to fill with set().
  static JsonValue object() { return JsonValue(Object{}); }
  /// An empty array, to fill with push().
  static JsonValue array() { return JsonValue(Array{}); }

  /// Adds (or replaces) `key` of an object; returns the value stored.
  JsonValue& set(const std::string& key, JsonValue value);
  /// Appends to an array; returns the value stored.
  JsonValue& push(JsonValue value);

  bool is_null() const { return std::holds_alternative<std::monostate>(m_value); }
  const bool* as_bool() const { return std::get_if<bool>(&m_value); }
  const std::int64_t* as_int() const { return std::get_if<std::int64_t>(&m_value); }
  const double* as_double() const { return std::get_if<double>(&m_value); }
  const std::string* as_string() const { return std::get_if<std::string>(&m_value); }
  const Array* as_array() const { return std::get_if<Array>(&m_value); }
  const Object* as_object() const { return std::get_if<Object>(&m_value); }

  /// JSON text, indented by `indent` spaces per level (0: one line). Numbers are written
  /// with 17 significant digits (they read back bitwise); non-finite numbers become null.
  std::string text(int indent = 2) const;

 private:
  void write(std::string& out, int indent, int depth) const;
  std::variant<std::monostate, bool, std::int64_t, double, std::string, Array, Object> m_value;
};

/// `text` as a JSON string literal, quotes included.
std::string json_quoted(const std::string& text);

}  // namespace xpl::io
