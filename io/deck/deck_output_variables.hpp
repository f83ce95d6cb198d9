#pragma once
/// \file Output variable names the deck reader knows, shared by the Abaqus (*NODE OUTPUT & co.)
/// and CalculiX (*NODE FILE & co.) output keywords.

#include <algorithm>
#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "solver/output/output_variables.hpp"

namespace xpl::io {

/// Field node variables (solver/output/output_variables.hpp). UR, VR, RM: rotation, angular
/// velocity and reaction moment of shell nodes.
inline constexpr auto FIELD_NODE_VARIABLES = request_names<OutputKeyword::Node>();
/// What VARIABLE=PRESELECT writes (on shell models the writer adds UR, VR, RM to U, V, RF).
inline constexpr auto PRESELECT_NODE_VARIABLES = request_names<OutputKeyword::Node, true>();
/// ... and its element variables (S).
inline constexpr auto PRESELECT_ELEMENT_VARIABLES = request_names<OutputKeyword::Element, true>();
/// Field element variables. STH: the current shell thickness.
inline constexpr auto ELEMENT_VARIABLES = request_names<OutputKeyword::Element>();
/// Whole-model energies. ALLFD: frictional dissipation; ALLPW: work of the contact penalties
/// (both zero without contact).
inline constexpr auto ENERGY_VARIABLES = energy_names();
/// Contact field variables: contact stress (pressure, shear), status, force.
inline constexpr auto CONTACT_VARIABLES = request_names<OutputKeyword::Contact>();

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
  const NodeHistoryRequest request = parse_node_history(name);
  if (request.variable == nullptr) return false;
  for (int c = 0; c < request.variable->width; ++c)
    if (request.component < 0 || request.component == c)
      add_unique(list, std::string(request.variable->components[static_cast<std::size_t>(c)]));
  return true;
}

}  // namespace xpl::io
