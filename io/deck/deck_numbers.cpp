#include "io/deck/deck_numbers.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <string>

namespace xpl::io {

namespace {

bool is_digit(char c) {
  return c >= '0' && c <= '9';
}

}  // namespace

std::optional<Real> parse_real(std::string_view text) {
  // Validate the grammar first: from_chars alone would accept "inf", "nan" and hex forms.
  // The normalized copy (no '+', exponent letter 'e') is at most as long as the text: a
  // buffer on the stack for the usual short fields, a string for long ones.
  const std::size_t n = text.size();
  char small[64];
  std::string large;
  char* normalized = small;
  if (n > sizeof small) {
    large.resize(n);
    normalized = large.data();
  }
  std::size_t length = 0;
  std::size_t i = 0;
  if (i < n && (text[i] == '+' || text[i] == '-')) {
    if (text[i] == '-') normalized[length++] = '-';
    ++i;
  }
  std::size_t mantissa_digits = 0;
  for (; i < n && is_digit(text[i]); ++i, ++mantissa_digits) normalized[length++] = text[i];
  if (i < n && text[i] == '.') {
    normalized[length++] = text[i++];
    for (; i < n && is_digit(text[i]); ++i, ++mantissa_digits) normalized[length++] = text[i];
  }
  if (mantissa_digits == 0) return std::nullopt;
  if (i < n && (text[i] == 'e' || text[i] == 'E' || text[i] == 'd' || text[i] == 'D')) {
    normalized[length++] = 'e';
    ++i;
    if (i < n && (text[i] == '+' || text[i] == '-')) normalized[length++] = text[i++];
    std::size_t exponent_digits = 0;
    for (; i < n && is_digit(text[i]); ++i, ++exponent_digits) normalized[length++] = text[i];
    if (exponent_digits == 0) return std::nullopt;
  }
  if (i != n) return std::nullopt;
  Real value = 0.0;
  const char* end = normalized + length;
  const auto [ptr, ec] = std::from_chars(normalized, end, value);
  if (ec != std::errc() || ptr != end || !std::isfinite(value)) return std::nullopt;
  return value;
}

std::optional<long long> parse_integer(std::string_view text) {
  std::size_t start = 0;
  if (!text.empty() && text[0] == '+') start = 1;
  if (start >= text.size()) return std::nullopt;
  long long value = 0;
  const char* begin = text.data() + start;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(begin, end, value);
  if (ec != std::errc() || ptr == begin) return std::nullopt;
  if (ptr == end) return value;
  // An integral float as some exporters write ids ("12.", "12.0"): a point and zeros only.
  if (*ptr != '.') return std::nullopt;
  for (const char* c = ptr + 1; c != end; ++c)
    if (*c != '0') return std::nullopt;
  return value;
}

bool looks_numeric(std::string_view text) {
  if (text.empty()) return false;
  const char c = text[0];
  return is_digit(c) || c == '+' || c == '-' || c == '.';
}

}  // namespace xpl::io
