#pragma once
/// \file Strict number parsing for deck fields: nothing is silently read as zero.

#include <optional>
#include <string_view>

#include "common/types.hpp"

namespace xpl::io {

/// Parses a real number: `1`, `-2.5`, `1.`, `.5`, `1e3`, `1.0E-3`, Fortran `1.0D3`.
/// Returns nothing for anything else (`1.0e`, `abc`, `1,5`, `inf`, `nan`) or on overflow.
std::optional<Real> parse_real(std::string_view text);

/// Parses a (possibly signed) decimal integer that fits in 64 bits; an integral float written
/// with a point and zeros ("12.", "12.0", as some mesh exporters write ids) is that integer.
std::optional<long long> parse_integer(std::string_view text);

/// Whether a field looks like a number (starts with a digit, sign or dot): used to tell
/// node/element ids from set names, which start with a letter.
bool looks_numeric(std::string_view text);

}  // namespace xpl::io
