// The table of output variables (solver/output/output_variables.hpp): the names the deck reader
// accepts, the order of the datasets in a frame and of the energies in the history. These
// orders are those of the files written before the table existed; a change here changes the
// result files or the deck messages.

#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "solver/output/output_variables.hpp"

using namespace xpl;

namespace {

template <typename List>
std::vector<std::string> strings(const List& list) {
  return {list.begin(), list.end()};
}

std::vector<std::string> frame_names(const FrameRequest& what, bool shells, bool plastic = false,
                                     bool plastic_shells = false) {
  std::vector<std::string> names;
  for (const OutputVariable* v : frame_variables(what, {shells, plastic, plastic_shells}))
    names.emplace_back(v->name);
  return names;
}

FrameRequest everything() {
  FrameRequest what;
  for (bool FrameRequest::*flag : FRAME_FLAGS) what.*flag = true;
  return what;
}

}  // namespace

TEST_CASE("output variables: the names each deck keyword accepts", "[results][variables]") {
  using Names = std::vector<std::string>;
  CHECK(strings(request_names<OutputKeyword::Node>()) ==
        Names{"U", "V", "A", "RF", "UR", "VR", "RM"});
  CHECK(strings(request_names<OutputKeyword::Node, true>()) == Names{"U", "V", "A", "RF"});
  CHECK(strings(request_names<OutputKeyword::Element>()) ==
        Names{"S", "EVOL", "MISES", "STH", "PEEQ"});
  // As Abaqus/Explicit's PRESELECT (PEEQ is written on plastic models only).
  CHECK(strings(request_names<OutputKeyword::Element, true>()) == Names{"S", "PEEQ"});
  CHECK(strings(request_names<OutputKeyword::Contact>()) == Names{"CSTRESS", "CSTATUS", "CFORCE"});
  CHECK(strings(energy_names()) == Names{"ALLKE", "ALLKD", "ALLSE", "ALLPD", "ALLAE", "ALLIE",
                                         "ALLVD", "ALLWK", "ALLFD", "ALLPW", "ETOTAL"});
}

TEST_CASE("output variables: a frame writes its datasets in the order of the files",
          "[results][variables]") {
  using Names = std::vector<std::string>;
  CHECK(frame_names(everything(), true) ==
        Names{"U",    "UR",    "V",      "VR",     "A",          "RF",         "RM",
              "S",    "MISES", "S_SNEG", "S_SPOS", "MISES_SNEG", "MISES_SPOS", "MISES_MAX",
              "EVOL", "STH",   "CPRESS", "CSHEAR", "CSTATUS",    "CNORMF",     "CSHEARF"});
  CHECK(frame_names(everything(), false) == Names{"U", "V", "A", "RF", "S", "MISES", "EVOL",
                                                  "CPRESS", "CSHEAR", "CSTATUS", "CNORMF",
                                                  "CSHEARF"});
  CHECK(frame_names({.reaction = true, .volume = true}, true) == Names{"RF", "RM", "EVOL"});
  CHECK(frame_names({}, true).empty());
  // PEEQ after EVOL and STH, on plastic models only.
  CHECK(frame_names(everything(), false, true) == Names{"U", "V", "A", "RF", "S", "MISES", "EVOL",
                                                        "PEEQ", "CPRESS", "CSHEAR", "CSTATUS",
                                                        "CNORMF", "CSHEARF"});
  // Plastic shells: PEEQ (the largest through the thickness) with its section points; a model
  // with shells whose plastic material is on solids only writes PEEQ alone.
  CHECK(frame_names({.plastic_strain = true}, true, true, true) ==
        Names{"PEEQ", "PEEQ_SNEG", "PEEQ_SMID", "PEEQ_SPOS"});
  CHECK(frame_names({.plastic_strain = true}, true, true, false) == Names{"PEEQ"});
  // A flag whose variables are all shell-only writes nothing without shells, PEEQ nothing
  // without plasticity.
  CHECK_FALSE(frame_flag_written(&FrameRequest::thickness, {false, true}));
  CHECK(frame_flag_written(&FrameRequest::thickness, {true, false}));
  CHECK(frame_flag_written(&FrameRequest::displacement, {}));
  CHECK_FALSE(frame_flag_written(&FrameRequest::plastic_strain, {true, false}));
  CHECK(frame_flag_written(&FrameRequest::plastic_strain, {false, true}));
}

TEST_CASE("output variables: energies in history order, contact ones last",
          "[results][variables]") {
  std::vector<std::string> names;
  for (const int i : energy_history_order()) names.emplace_back(ENERGIES[i].name);
  CHECK(names == std::vector<std::string>{"ALLKE", "ALLKD", "ALLSE", "ALLPD", "ALLAE", "ALLIE",
                                          "ALLVD", "ALLWK", "ETOTAL", "ALLFD", "ALLPW"});
  Energies e;
  e.kinetic = 1.0;
  e.strain = 2.0;
  e.artificial = 4.0;
  e.viscous = 8.0;
  e.external_work = 16.0;
  e.friction = 32.0;
  e.contact = 64.0;
  e.plastic = 128.0;
  e.kinetic_defect = -0.5;
  std::vector<Real> values;
  for (const EnergyVariable& energy : ENERGIES) values.push_back(energy.value(e));
  // ALLIE = ALLSE + ALLPD + ALLAE.
  CHECK(values ==
        std::vector<Real>{1.0, -0.5, 2.0, 128.0, 4.0, 134.0, 8.0, 16.0, 32.0, 64.0, e.total()});
  CHECK(e.total() == 1.0 - 0.5 + 134.0 + 8.0 + 32.0 + 64.0 - 16.0);
}

TEST_CASE("output variables: history node requests", "[results][variables]") {
  const NodeHistoryRequest all = parse_node_history("U");
  REQUIRE(all.variable != nullptr);
  CHECK(all.variable->id == OutputId::U);
  CHECK(all.component == -1);
  const NodeHistoryRequest rf3 = parse_node_history("RF3");
  REQUIRE(rf3.variable != nullptr);
  CHECK(rf3.variable->id == OutputId::RF);
  CHECK(rf3.component == 2);
  const NodeHistoryRequest ur1 = parse_node_history("UR1");
  REQUIRE(ur1.variable != nullptr);
  CHECK(ur1.variable->id == OutputId::UR);
  CHECK(ur1.component == 0);
  CHECK(parse_node_history("U4").variable == nullptr);
  CHECK(parse_node_history("S").variable == nullptr);
  CHECK(parse_node_history("CSHEAR1").variable == nullptr);
  CHECK(output_variable(OutputId::CSHEARF).name == "CSHEARF");
}

TEST_CASE("output variables: the history of a contact pair", "[results][variables]") {
  std::vector<HistorySeries> series{{"energy/ALLKE", 1, {}, "", ""}};
  append_contact_pair_series(series, "ALL_EXTERIOR");
  REQUIRE(series.size() == 3);
  CHECK(series[1].path == "contact/ALL_EXTERIOR/CFN");
  CHECK(series[2].path == "contact/ALL_EXTERIOR/CFS");
  CHECK(series[2].width == 1);
  CHECK(series[2].node_ids.empty());
}
