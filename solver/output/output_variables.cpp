#include "solver/output/output_variables.hpp"

namespace xpl {

namespace {

constexpr bool ids_in_order() {
  for (std::size_t i = 0; i < OUTPUT_VARIABLES.size(); ++i)
    if (static_cast<std::size_t>(OUTPUT_VARIABLES[i].id) != i) return false;
  return true;
}
static_assert(ids_in_order(), "OUTPUT_VARIABLES must list the variables in OutputId order");

}  // namespace

namespace node_values {
Real displacement(const State& s, Index i, int c) {
  return s.displacement(i, c);
}
Real velocity(const State& s, Index i, int c) {
  return s.velocity(i, c);
}
Real acceleration(const State& s, Index i, int c) {
  return s.acceleration(i, c);
}
Real reaction(const State& s, Index i, int c) {
  return s.reaction(i, c);
}
Real rotation(const State& s, Index i, int c) {
  return s.rotation(i, c);
}
Real angular_velocity(const State& s, Index i, int c) {
  return s.angular_velocity(i, c);
}
Real reaction_moment(const State& s, Index i, int c) {
  return s.reaction_moment(i, c);
}
}  // namespace node_values

OutputScope output_scope(const Model& model) {
  return {model.has_shells(), model.has_plasticity(), model.has_plastic_shells()};
}

bool frame_flag_written(bool FrameRequest::*flag, OutputScope scope) {
  for (const OutputVariable& v : OUTPUT_VARIABLES)
    if (v.frame == flag && written_on(v, scope)) return true;
  return false;
}

std::vector<const OutputVariable*> frame_variables(const FrameRequest& what, OutputScope scope) {
  std::vector<const OutputVariable*> out;
  for (bool FrameRequest::*flag : FRAME_FLAGS) {
    if (!(what.*flag)) continue;
    for (const OutputVariable& v : OUTPUT_VARIABLES)
      if (v.frame == flag && written_on(v, scope)) out.push_back(&v);
  }
  return out;
}

NodeHistoryRequest parse_node_history(std::string_view name) {
  for (const OutputVariable& v : OUTPUT_VARIABLES) {
    if (v.node_value == nullptr) continue;
    if (v.name == name) return {&v, -1};
    for (int c = 0; c < v.width; ++c)
      if (v.components[static_cast<std::size_t>(c)] == name) return {&v, c};
  }
  return {};
}

void append_contact_pair_series(std::vector<HistorySeries>& series, const std::string& pair) {
  for (const OutputVariable& v : OUTPUT_VARIABLES)
    if (v.location == OutputLocation::ContactPair)
      series.push_back({"contact/" + pair + "/" + std::string(v.name),
                        1,
                        {},
                        std::string(v.name),
                        std::string(v.unit)});
}

const std::vector<int>& energy_history_order() {
  static const std::vector<int> order = [] {
    std::vector<int> out;
    for (const bool contact : {false, true})
      for (std::size_t i = 0; i < ENERGIES.size(); ++i)
        if ((ENERGIES[i].models == OutputModels::Contact) == contact)
          out.push_back(static_cast<int>(i));
    return out;
  }();
  return order;
}

}  // namespace xpl
