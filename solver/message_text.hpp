#pragma once
/// \file How the solver's parts write numbers into .msg/.sta texts.

#include <sstream>
#include <string>

#include "common/types.hpp"

namespace xpl {

/// `v` with four significant digits ("0.0001234", "1.5e+07"), as every solver message
/// prints lengths, angles, energies and increments.
inline std::string format_real(Real v) {
  std::ostringstream out;
  out.precision(4);
  out << v;
  return out.str();
}

}  // namespace xpl
