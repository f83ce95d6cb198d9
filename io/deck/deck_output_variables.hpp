#pragma once
/// \file Output variable names the deck reader knows, shared by the Abaqus (*NODE OUTPUT & co.)
/// and CalculiX (*NODE FILE & co.) output keywords.

#include <algorithm>
#include <array>
#include <string>
#include <string_view>
#include <vector>

namespace xpl::io {

/// Field node variables. UR, VR, RM: rotation, angular velocity and reaction moment of shell
/// nodes.
inline constexpr std::array<std::string_view, 7> FIELD_NODE_VARIABLES = {"U",  "V",  "A", "RF",
                                                                         "UR", "VR", "RM"};
/// What VARIABLE=PRESELECT writes (on shell models the writer adds UR, VR, RM to U, V, RF).
inline constexpr std::array<std::string_view, 4> PRESELECT_NODE_VARIABLES = {"U", "V", "A", "RF"};
/// Field element variables. STH: the current shell thickness.
inline constexpr std::array<std::string_view, 4> ELEMENT_VARIABLES = {"S", "EVOL", "MISES", "STH"};
/// Whole-model energies. ALLFD: frictional dissipation; ALLPW: work of the contact penalties
/// (both zero without contact).
inline constexpr std::array<std::string_view, 9> ENERGY_VARIABLES = {
    "ALLKE", "ALLSE", "ALLAE", "ALLIE", "ALLVD", "ALLWK", "ALLFD", "ALLPW", "ETOTAL"};
/// Contact field variables: contact stress (pressure, shear), status, force.
inline constexpr std::array<std::string_view, 3> CONTACT_VARIABLES = {"CSTRESS", "CSTATUS",
                                                                      "CFORCE"};

template <std::size_t N>
bool contains(const std::array<std::string_view, N>& list, const std::string& name) {
  return std::find(list.begin(), list.end(), name) != list.end();
}

/// "U, V, A" for messages.
template <std::size_t N>
std::string joined(const std::array<std::string_view, N>& list) {
  std::string text;
  for (std::string_view name : list) {
    if (!text.empty()) text += ", ";
    text += name;
  }
  return text;
}

inline void add_unique(std::vector<std::string>& list, const std::string& name) {
  if (std::find(list.begin(), list.end(), name) == list.end()) list.push_back(name);
}

/// History node variables: components U1..RF3, UR1..RM3; U, V, A, RF, UR, VR, RM stand for
/// their three components. False if `name` is none of these.
inline bool add_history_node_variable(std::vector<std::string>& list, const std::string& name) {
  if (contains(FIELD_NODE_VARIABLES, name)) {
    for (char c : {'1', '2', '3'}) add_unique(list, name + c);
    return true;
  }
  if (name.size() >= 2 && (name.back() >= '1' && name.back() <= '3') &&
      contains(FIELD_NODE_VARIABLES, name.substr(0, name.size() - 1))) {
    add_unique(list, name);
    return true;
  }
  return false;
}

}  // namespace xpl::io
