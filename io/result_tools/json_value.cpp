#include "io/result_tools/json_value.hpp"

#include <cmath>
#include <cstdio>

namespace xpl::io {

JsonValue& JsonValue::set(const std::string& key, JsonValue value) {
  if (is_null()) m_value = Object{};
  auto& members = std::get<Object>(m_value);
  for (auto& [name, member] : members)
    if (name == key) return member = std::move(value);
  members.emplace_back(key, std::move(value));
  return members.back().second;
}

JsonValue& JsonValue::push(JsonValue value) {
  if (is_null()) m_value = Array{};
  auto& items = std::get<Array>(m_value);
  items.push_back(std::move(value));
  return items.back();
}

std::string json_quoted(const std::string& text) {
  std::string out = "\"";
  for (const char c : text) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\r':
        out += "\\r";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char escaped[8];
          std::snprintf(escaped, sizeof escaped, "\\u%04x", static_cast<unsigned>(c));
          out += escaped;
        } else {
          out += c;  // UTF-8 bytes pass through unchanged
        }
    }
  }
  return out + "\"";
}

std::string JsonValue::text(int indent) const {
  std::string out;
  write(out, indent, 0);
  if (indent > 0) out += "\n";
  return out;
}

void JsonValue::write(std::string& out, int indent, int depth) const {
  const auto newline = [&](int level) {
    if (indent <= 0) return;
    out += "\n";
    out.append(static_cast<std::size_t>(indent * level), ' ');
  };
  if (is_null()) {
    out += "null";
  } else if (const bool* b = as_bool()) {
    out += *b ? "true" : "false";
  } else if (const std::int64_t* i = as_int()) {
    out += std::to_string(*i);
  } else if (const double* d = as_double()) {
    if (!std::isfinite(*d)) {
      out += "null";
    } else {
      char number[32];
      std::snprintf(number, sizeof number, "%.17g", *d);
      out += number;
    }
  } else if (const std::string* s = as_string()) {
    out += json_quoted(*s);
  } else if (const Array* a = as_array()) {
    out += "[";
    for (std::size_t k = 0; k < a->size(); ++k) {
      out += k > 0 ? "," : "";
      newline(depth + 1);
      (*a)[k].write(out, indent, depth + 1);
    }
    if (!a->empty()) newline(depth);
    out += "]";
  } else if (const Object* o = as_object()) {
    out += "{";
    for (std::size_t k = 0; k < o->size(); ++k) {
      out += k > 0 ? "," : "";
      newline(depth + 1);
      out += json_quoted((*o)[k].first) + (indent > 0 ? ": " : ":");
      (*o)[k].second.write(out, indent, depth + 1);
    }
    if (!o->empty()) newline(depth);
    out += "}";
  }
}

}  // namespace xpl::io
