#pragma once
/// \file The one table of output variables: per variable its name, where it lives, its
/// components, unit, the models that have it, and how a deck requests it; and the one list of
/// whole-model energies. The deck reader looks names up here, the output schedule turns
/// requests into FrameRequest flags and history columns with it, and the HDF5 and XDMF writers
/// take dataset names, shapes and order from it.

#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "common/types.hpp"
#include "solver/model/state.hpp"
#include "solver/output/output_sink.hpp"

namespace xpl {

/// Every output variable, in the order of OUTPUT_VARIABLES.
// clang-format off
enum class OutputId {
  U, V, A, RF, UR, VR, RM,                  // node
  S, EVOL, MISES, STH, PEEQ, S_SNEG, S_SPOS, // element
  PEEQ_SNEG, PEEQ_SMID, PEEQ_SPOS,          // element, plastic shells
  CPRESS, CSHEAR, CSTATUS, CNORMF, CSHEARF, // node, contact
  CFN, CFS,                                 // contact pair
  MISES_SNEG, MISES_SPOS, MISES_MAX         // element, shell surfaces (with S)
};
// clang-format on

/// Where the values of a variable live.
enum class OutputLocation {
  Node,         ///< one row per node (the rows of /mesh/node_ids)
  Element,      ///< one row per element (the rows of /mesh/element_ids)
  WholeModel,   ///< one value for the model (the energies, ENERGIES)
  ContactPair,  ///< one value per contact pair (history of steps with contact)
};

/// The models that have a variable.
enum class OutputModels {
  All,     ///< every model
  Shells,  ///< models with shells only: left out of the frames of other models
  /// Models with a plastic material only (PEEQ, ALLPD): left out of elastic models (P2).
  Plastic,
  /// Models with shells and a plastic material (the shells' per-section-point PEEQ).
  PlasticShells,
  /// Contact output: zero away from contact; the contact energies and pair forces are left
  /// out of models without contact.
  Contact,
};

/// The deck keyword that requests a variable.
enum class OutputKeyword {
  None,     ///< not requested by name (written with another variable, or always)
  Node,     ///< *NODE OUTPUT (field and history), *NODE FILE, *NODE PRINT
  Element,  ///< *ELEMENT OUTPUT (field), *EL FILE
  Contact,  ///< *CONTACT OUTPUT (field)
};

/// History value of component `c` (0..2) of node `i` in `state`.
using NodeValue = Real (*)(const State& state, Index i, int c);

/// One output variable (one dataset of a frame, or one history column group).
struct OutputVariable {
  OutputId id;
  std::string_view name;  ///< dataset and XDMF attribute name ("U", "S_SNEG")
  OutputLocation location;
  int width;  ///< values per node/element/pair: 1 scalar, 3 vector, 6 symmetric tensor
  std::array<std::string_view, 6> components;  ///< the first `width` are the component names
  std::string_view unit;                       ///< SI unit ("" for codes)
  OutputModels models;
  OutputKeyword keyword;     ///< the keyword that requests it
  std::string_view request;  ///< the name that requests it there ("CSTRESS" for CPRESS)
  bool preselect;            ///< part of *OUTPUT, FIELD, VARIABLE=PRESELECT
  /// The flag of a field frame that writes it (nullptr: not field output). The variables of
  /// one flag are written together: U with UR, S with MISES, S_SNEG and S_SPOS, PEEQ with
  /// PEEQ_SNEG, PEEQ_SMID and PEEQ_SPOS.
  bool FrameRequest::*frame;
  NodeValue node_value;  ///< node history value (nullptr: no node history)
  std::string_view description;
};

/// Component names of a symmetric tensor (Abaqus order), shared by S, S_SNEG and S_SPOS.
inline constexpr std::array<std::string_view, 6> STRESS_COMPONENTS = {"S11", "S22", "S33",
                                                                      "S12", "S13", "S23"};

/// Node history accessors of the table: component `c` of node `i`.
namespace node_values {
Real displacement(const State& s, Index i, int c);
Real velocity(const State& s, Index i, int c);
Real acceleration(const State& s, Index i, int c);
Real reaction(const State& s, Index i, int c);
Real rotation(const State& s, Index i, int c);
Real angular_velocity(const State& s, Index i, int c);
Real reaction_moment(const State& s, Index i, int c);
}  // namespace node_values

/// Every output variable. The rows of a keyword are in the order the deck reader lists them
/// in messages; a frame writes its datasets flag by flag (FRAME_FLAGS), in table order within
/// a flag (frame_variables()).
// clang-format off
inline constexpr std::array<OutputVariable, 27> OUTPUT_VARIABLES = {{
    // id, name, location, width, components, unit, models, keyword, request, preselect,
    // frame flag, node history value, description
    {OutputId::U, "U", OutputLocation::Node, 3, {"U1", "U2", "U3"}, "m", OutputModels::All,
     OutputKeyword::Node, "U", true, &FrameRequest::displacement, node_values::displacement,
     "displacement u = x - X"},
    {OutputId::V, "V", OutputLocation::Node, 3, {"V1", "V2", "V3"}, "m/s", OutputModels::All,
     OutputKeyword::Node, "V", true, &FrameRequest::velocity, node_values::velocity,
     "velocity"},
    {OutputId::A, "A", OutputLocation::Node, 3, {"A1", "A2", "A3"}, "m/s^2", OutputModels::All,
     OutputKeyword::Node, "A", true, &FrameRequest::acceleration, node_values::acceleration,
     "acceleration"},
    {OutputId::RF, "RF", OutputLocation::Node, 3, {"RF1", "RF2", "RF3"}, "N", OutputModels::All,
     OutputKeyword::Node, "RF", true, &FrameRequest::reaction, node_values::reaction,
     "reaction force at prescribed DOFs"},
    {OutputId::UR, "UR", OutputLocation::Node, 3, {"UR1", "UR2", "UR3"}, "rad",
     OutputModels::Shells, OutputKeyword::Node, "UR", false, &FrameRequest::displacement,
     node_values::rotation,
     "rotation vector"},
    {OutputId::VR, "VR", OutputLocation::Node, 3, {"VR1", "VR2", "VR3"}, "rad/s",
     OutputModels::Shells, OutputKeyword::Node, "VR", false, &FrameRequest::velocity,
     node_values::angular_velocity,
     "angular velocity"},
    {OutputId::RM, "RM", OutputLocation::Node, 3, {"RM1", "RM2", "RM3"}, "N m",
     OutputModels::Shells, OutputKeyword::Node, "RM", false, &FrameRequest::reaction,
     node_values::reaction_moment,
     "reaction moment at prescribed rotational DOFs"},
    {OutputId::S, "S", OutputLocation::Element, 6, STRESS_COMPONENTS, "Pa", OutputModels::All,
     OutputKeyword::Element, "S", true, &FrameRequest::stress, nullptr,
     "Cauchy stress; shells: middle section point, local shell axes"},
    {OutputId::EVOL, "EVOL", OutputLocation::Element, 1, {"EVOL"}, "m^3", OutputModels::All,
     OutputKeyword::Element, "EVOL", false, &FrameRequest::volume, nullptr,
     "current element volume"},
    {OutputId::MISES, "MISES", OutputLocation::Element, 1, {"MISES"}, "Pa", OutputModels::All,
     OutputKeyword::Element, "MISES", false, &FrameRequest::stress, nullptr,
     "von Mises stress of S"},
    {OutputId::STH, "STH", OutputLocation::Element, 1, {"STH"}, "m", OutputModels::Shells,
     OutputKeyword::Element, "STH", false, &FrameRequest::thickness, nullptr,
     "current shell thickness; NaN for solids"},
    {OutputId::PEEQ, "PEEQ", OutputLocation::Element, 1, {"PEEQ"}, "", OutputModels::Plastic,
     OutputKeyword::Element, "PEEQ", true, &FrameRequest::plastic_strain, nullptr,
     "equivalent plastic strain; 0 for elastic elements; shells: largest section point"},
    {OutputId::S_SNEG, "S_SNEG", OutputLocation::Element, 6, STRESS_COMPONENTS, "Pa",
     OutputModels::Shells, OutputKeyword::Element, "S", false, &FrameRequest::stress, nullptr,
     "shell stress at the bottom section point; NaN for solids"},
    {OutputId::S_SPOS, "S_SPOS", OutputLocation::Element, 6, STRESS_COMPONENTS, "Pa",
     OutputModels::Shells, OutputKeyword::Element, "S", false, &FrameRequest::stress, nullptr,
     "shell stress at the top section point; NaN for solids"},
    {OutputId::PEEQ_SNEG, "PEEQ_SNEG", OutputLocation::Element, 1, {"PEEQ_SNEG"}, "",
     OutputModels::PlasticShells, OutputKeyword::Element, "PEEQ", false,
     &FrameRequest::plastic_strain, nullptr,
     "shell PEEQ at the bottom section point; NaN for solids"},
    {OutputId::PEEQ_SMID, "PEEQ_SMID", OutputLocation::Element, 1, {"PEEQ_SMID"}, "",
     OutputModels::PlasticShells, OutputKeyword::Element, "PEEQ", false,
     &FrameRequest::plastic_strain, nullptr,
     "shell PEEQ at the middle section point (what --import needs besides SNEG and SPOS); "
     "NaN for solids"},
    {OutputId::PEEQ_SPOS, "PEEQ_SPOS", OutputLocation::Element, 1, {"PEEQ_SPOS"}, "",
     OutputModels::PlasticShells, OutputKeyword::Element, "PEEQ", false,
     &FrameRequest::plastic_strain, nullptr,
     "shell PEEQ at the top section point; NaN for solids"},
    {OutputId::CPRESS, "CPRESS", OutputLocation::Node, 1, {"CPRESS"}, "Pa", OutputModels::Contact,
     OutputKeyword::Contact, "CSTRESS", false, &FrameRequest::contact_stress, nullptr,
     "contact pressure"},
    {OutputId::CSHEAR, "CSHEAR", OutputLocation::Node, 3, {"CSHEAR1", "CSHEAR2", "CSHEAR3"}, "Pa",
     OutputModels::Contact, OutputKeyword::Contact, "CSTRESS", false, &FrameRequest::contact_stress,
     nullptr,
     "frictional stress vector"},
    {OutputId::CSTATUS, "CSTATUS", OutputLocation::Node, 1, {"CSTATUS"}, "", OutputModels::Contact,
     OutputKeyword::Contact, "CSTATUS", false, &FrameRequest::contact_status, nullptr,
     "contact status: 0 open, 1 slipping, 2 sticking"},
    {OutputId::CNORMF, "CNORMF", OutputLocation::Node, 3, {"CNORMF1", "CNORMF2", "CNORMF3"}, "N",
     OutputModels::Contact, OutputKeyword::Contact, "CFORCE", false, &FrameRequest::contact_force,
     nullptr,
     "normal part of the nodal contact force"},
    {OutputId::CSHEARF, "CSHEARF", OutputLocation::Node, 3, {"CSHEARF1", "CSHEARF2", "CSHEARF3"},
     "N", OutputModels::Contact, OutputKeyword::Contact, "CFORCE", false,
     &FrameRequest::contact_force, nullptr,
     "tangential part of the nodal contact force"},
    {OutputId::CFN, "CFN", OutputLocation::ContactPair, 1, {"CFN"}, "N", OutputModels::Contact,
     OutputKeyword::None, "", false, nullptr, nullptr,
     "total normal contact force of a pair (history of every contact step)"},
    {OutputId::CFS, "CFS", OutputLocation::ContactPair, 1, {"CFS"}, "N", OutputModels::Contact,
     OutputKeyword::None, "", false, nullptr, nullptr,
     "total frictional force of a pair (history of every contact step)"},
    {OutputId::MISES_SNEG, "MISES_SNEG", OutputLocation::Element, 1, {"MISES_SNEG"}, "Pa",
     OutputModels::Shells, OutputKeyword::None, "", false, &FrameRequest::stress, nullptr,
     "von Mises stress of S_SNEG (shell bottom surface); NaN for solids"},
    {OutputId::MISES_SPOS, "MISES_SPOS", OutputLocation::Element, 1, {"MISES_SPOS"}, "Pa",
     OutputModels::Shells, OutputKeyword::None, "", false, &FrameRequest::stress, nullptr,
     "von Mises stress of S_SPOS (shell top surface); NaN for solids"},
    {OutputId::MISES_MAX, "MISES_MAX", OutputLocation::Element, 1, {"MISES_MAX"}, "Pa",
     OutputModels::Shells, OutputKeyword::None, "", false, &FrameRequest::stress, nullptr,
     "largest von Mises stress through the thickness (shells: of S_SNEG, S, S_SPOS; solids: "
     "MISES): the field to colour a shell model by"},
}};
// clang-format on

/// The row of `id`.
constexpr const OutputVariable& output_variable(OutputId id) {
  return OUTPUT_VARIABLES[static_cast<std::size_t>(id)];
}

/// The flags of a field frame, in the order their variables are written.
inline constexpr std::array<bool FrameRequest::*, 11> FRAME_FLAGS = {
    &FrameRequest::displacement,   &FrameRequest::velocity,       &FrameRequest::acceleration,
    &FrameRequest::reaction,       &FrameRequest::stress,         &FrameRequest::volume,
    &FrameRequest::thickness,      &FrameRequest::plastic_strain, &FrameRequest::contact_stress,
    &FrameRequest::contact_status, &FrameRequest::contact_force};

/// What a model has that decides which variables its frames write (OutputModels).
struct OutputScope {
  bool shells = false;          ///< the model has shells (Model::has_shells)
  bool plastic = false;         ///< the model has a plastic material (Model::has_plasticity)
  bool plastic_shells = false;  ///< a shell section of the model has a plastic material
};

/// The scope of `model`.
OutputScope output_scope(const Model& model);

/// Whether a frame of a model of scope `scope` writes `v`.
constexpr bool written_on(const OutputVariable& v, OutputScope scope) {
  return (v.models != OutputModels::Shells || scope.shells) &&
         (v.models != OutputModels::Plastic || scope.plastic) &&
         (v.models != OutputModels::PlasticShells || scope.plastic_shells);
}

/// Whether `flag` writes anything on a model of scope `scope` (STH: not without shells;
/// PEEQ: not without plasticity; U: always, with or without UR).
bool frame_flag_written(bool FrameRequest::*flag, OutputScope scope);

/// The datasets a frame `what` holds on a model of scope `scope`, in the order they are
/// written.
std::vector<const OutputVariable*> frame_variables(const FrameRequest& what, OutputScope scope);

/// A history node request parsed: the variable and the component asked for.
struct NodeHistoryRequest {
  const OutputVariable* variable = nullptr;  ///< nullptr: not a node history variable
  int component = -1;                        ///< 0..width-1, or -1 for all components
};
/// Parses a history node variable: "U" (all components), "U2" (one), "UR1"...
NodeHistoryRequest parse_node_history(std::string_view name);

/// Appends the history series of contact pair `pair` (CFN, CFS: "contact/PAIR/CFN", ...), in
/// table order, as every step with contact declares them.
void append_contact_pair_series(std::vector<HistorySeries>& series, const std::string& pair);

/// One whole-model energy (location OutputLocation::WholeModel), J.
struct EnergyVariable {
  std::string_view name;  ///< Abaqus name ("ALLKE")
  std::string_view unit;
  OutputModels models;  ///< All, Contact (left out without contact) or Plastic (without plasticity)
  Real (*value)(const Energies& e);
  std::string_view description;
};

/// The whole-model energies (*ENERGY OUTPUT): the terms of the balance, then the balance.
/// The history lists them in energy_history_order().
inline constexpr std::array<EnergyVariable, 11> ENERGIES = {{
    {"ALLKE", "J", OutputModels::All, [](const Energies& e) { return e.kinetic; },
     "kinetic energy"},
    {"ALLKD", "J", OutputModels::All, [](const Energies& e) { return e.kinetic_defect; },
     "kinetic energy of central differences beyond ALLKE"},
    {"ALLSE", "J", OutputModels::All, [](const Energies& e) { return e.strain; },
     "recoverable strain energy"},
    {"ALLPD", "J", OutputModels::Plastic, [](const Energies& e) { return e.plastic; },
     "plastic dissipation"},
    {"ALLAE", "J", OutputModels::All, [](const Energies& e) { return e.artificial; },
     "hourglass energy"},
    {"ALLIE", "J", OutputModels::All, [](const Energies& e) { return e.internal(); },
     "internal energy ALLSE + ALLPD + ALLAE"},
    {"ALLVD", "J", OutputModels::All, [](const Energies& e) { return e.viscous; },
     "bulk-viscosity dissipation"},
    {"ALLWK", "J", OutputModels::All, [](const Energies& e) { return e.external_work; },
     "work of loads and of reactions at prescribed DOFs"},
    {"ALLFD", "J", OutputModels::Contact, [](const Energies& e) { return e.friction; },
     "frictional dissipation"},
    {"ALLPW", "J", OutputModels::Contact, [](const Energies& e) { return e.contact; },
     "energy of the contact penalties"},
    {"ETOTAL", "J", OutputModels::All, [](const Energies& e) { return e.total(); },
     "energy balance ALLKE + ALLKD + ALLIE + ALLVD + ALLFD + ALLPW - ALLWK"},
}};

/// Indices into ENERGIES in history order: the energies of every model, then the contact
/// ones (so that the history of a model without contact keeps its layout).
const std::vector<int>& energy_history_order();

namespace detail {

/// Whether `keyword` (its PRESELECT if `preselect_only`) requests `v`.
constexpr bool accepts(const OutputVariable& v, OutputKeyword keyword, bool preselect_only) {
  return v.keyword == keyword && (v.preselect || !preselect_only);
}

/// Number of distinct names `keyword` accepts (CSTRESS names both CPRESS and CSHEAR).
constexpr std::size_t request_count(OutputKeyword keyword, bool preselect_only) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < OUTPUT_VARIABLES.size(); ++i) {
    if (!accepts(OUTPUT_VARIABLES[i], keyword, preselect_only)) continue;
    bool seen = false;
    for (std::size_t j = 0; j < i; ++j)
      seen = seen || (accepts(OUTPUT_VARIABLES[j], keyword, preselect_only) &&
                      OUTPUT_VARIABLES[j].request == OUTPUT_VARIABLES[i].request);
    if (!seen) ++n;
  }
  return n;
}

}  // namespace detail

/// The names `KEYWORD` accepts (only the PRESELECT ones if `PRESELECT_ONLY`), in table order
/// without repeats.
template <OutputKeyword KEYWORD, bool PRESELECT_ONLY = false>
constexpr auto request_names() {
  std::array<std::string_view, detail::request_count(KEYWORD, PRESELECT_ONLY)> names{};
  std::size_t n = 0;
  for (const OutputVariable& v : OUTPUT_VARIABLES) {
    if (!detail::accepts(v, KEYWORD, PRESELECT_ONLY)) continue;
    bool seen = false;
    for (std::size_t j = 0; j < n; ++j) seen = seen || names[j] == v.request;
    if (!seen) names[n++] = v.request;
  }
  return names;
}

/// The names of ENERGIES, in its order.
constexpr std::array<std::string_view, ENERGIES.size()> energy_names() {
  std::array<std::string_view, ENERGIES.size()> names{};
  for (std::size_t i = 0; i < ENERGIES.size(); ++i) names[i] = ENERGIES[i].name;
  return names;
}

}  // namespace xpl
