#include "common/units.hpp"

#include <algorithm>
#include <cctype>

namespace xpl {

namespace {

bool same_name(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::toupper(static_cast<unsigned char>(x)) ==
                  std::toupper(static_cast<unsigned char>(y));
         });
}

/// Replaces each word of `si_unit` (a run of letters) by `word(token)`.
template <class Word>
std::string map_words(std::string_view si_unit, Word word) {
  std::string out;
  std::size_t i = 0;
  while (i < si_unit.size()) {
    if (!std::isalpha(static_cast<unsigned char>(si_unit[i]))) {
      out += si_unit[i++];
      continue;
    }
    std::size_t j = i;
    while (j < si_unit.size() && std::isalpha(static_cast<unsigned char>(si_unit[j]))) ++j;
    out += word(si_unit.substr(i, j - i));
    i = j;
  }
  return out;
}

}  // namespace

const UnitSystem* find_unit_system(std::string_view name) {
  for (const UnitSystem& s : UNIT_SYSTEMS)
    if (same_name(s.name, name)) return &s;
  return nullptr;
}

std::string unit_system_names() {
  std::string text;
  for (const UnitSystem& s : UNIT_SYSTEMS) text += (text.empty() ? "" : ", ") + std::string(s.name);
  return text;
}

std::string unit_in(std::string_view si_unit, const UnitSystem& system) {
  return map_words(si_unit, [&](std::string_view token) -> std::string {
    if (token == "m") return std::string(system.length);
    if (token == "kg") return std::string(system.mass);
    if (token == "s") return std::string(system.time);
    if (token == "N") return std::string(system.force);
    if (token == "Pa") return std::string(system.stress);
    if (token == "J") return std::string(system.energy);
    return std::string(token);
  });
}

std::string dimension_of(std::string_view si_unit) {
  return map_words(si_unit, [](std::string_view token) -> std::string {
    if (token == "m") return "[length]";
    if (token == "kg") return "[mass]";
    if (token == "s") return "[time]";
    if (token == "N") return "[force]";
    if (token == "Pa") return "[stress]";
    if (token == "J") return "[energy]";
    return std::string(token);
  });
}

std::string ModelUnits::label(std::string_view si_unit) const {
  return dimensions_only ? dimension_of(si_unit) : unit_in(si_unit, labels());
}

std::string ModelUnits::system_name() const {
  if (stated != nullptr) return std::string(stated->name);
  return dimensions_only ? "unstated" : "SI (assumed)";
}

std::string ModelUnits::summary() const {
  if (dimensions_only)
    return "consistent units as given in the deck (not stated, and not SI): labels name the "
           "dimension only ([length], [mass], [time], [force], [stress], [energy])";
  const UnitSystem& s = labels();
  std::string text = "length " + std::string(s.length) + ", mass " + std::string(s.mass) +
                     ", time " + std::string(s.time) + ", force " + std::string(s.force) +
                     ", stress " + std::string(s.stress) + ", energy " + std::string(s.energy);
  if (stated == nullptr)
    text = "consistent units as given in the deck (not stated; SI assumed for the labels: " + text +
           ")";
  return text;
}

}  // namespace xpl
