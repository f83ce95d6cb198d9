// OutputSchedule with rotational variables: UR/VR/RM/STH field requests and UR1..RM3 history
// on shell models, and what they mean on a model without shells. (The schedule lives in
// solver/; its output is what these result files are written from.)

#include <catch2/catch.hpp>

#include "results/shell_fixture.hpp"
#include "solver/output/output_schedule.hpp"

using namespace xpl;
using namespace xpl::test;

namespace {

OutputRequest field(std::vector<std::string> nodes, std::vector<std::string> elements) {
  OutputRequest r;
  r.kind = OutputRequest::Kind::Field;
  r.node_variables = std::move(nodes);
  r.element_variables = std::move(elements);
  return r;
}

OutputRequest history(Index node_set, std::vector<std::string> nodes) {
  OutputRequest r;
  r.kind = OutputRequest::Kind::History;
  r.node_set = node_set;
  r.node_variables = std::move(nodes);
  return r;
}

std::vector<std::string> paths(const OutputSchedule& schedule) {
  std::vector<std::string> out;
  for (const HistorySeries& s : schedule.series()) out.push_back(s.path);
  return out;
}

}  // namespace

TEST_CASE("output schedule: UR, VR, RM come with U, V, RF and STH asks for the thickness",
          "[io][results][shell]") {
  Model model = mixed_model();
  model.steps[0].outputs = {field({"UR"}, {"STH"}), field({"VR", "RM"}, {})};
  OutputSchedule schedule;
  schedule.begin_step(model, 0);
  const FrameRequest all = schedule.field_all();
  CHECK(all.displacement);
  CHECK(all.velocity);
  CHECK(all.reaction);
  CHECK(all.thickness);
  CHECK_FALSE(all.acceleration);
  CHECK_FALSE(all.stress);
  CHECK(schedule.field_due(1e-3, true).thickness);  // merged like every other field

  SECTION("a model without shells has no thickness to write") {
    Model hexes = tiny_model();
    hexes.steps[0].outputs = {field({}, {"STH"}), field({"UR"}, {})};
    schedule.begin_step(hexes, 0);
    CHECK_FALSE(schedule.field_all().thickness);
    CHECK(schedule.field_all().displacement);
  }
}

TEST_CASE("output schedule: history of rotations reads the rotational state",
          "[io][results][shell]") {
  Model model = mixed_model();
  model.steps[0].outputs = {history(0, {"UR2", "VR", "RM3", "U1"})};
  OutputSchedule schedule;
  schedule.begin_step(model, 0);
  REQUIRE(paths(schedule) == std::vector<std::string>{"node/EDGE/UR2", "node/EDGE/VR1",
                                                      "node/EDGE/VR2", "node/EDGE/VR3",
                                                      "node/EDGE/RM3", "node/EDGE/U1"});
  CHECK(schedule.series()[0].node_ids == std::vector<ExternalId>{node_id(8), node_id(9)});

  const State state = mixed_state(model, 2);
  std::vector<Real> row;
  schedule.history_row(state, row);
  // Two columns (nodes 8 and 9) per series.
  const std::vector<Real> expected{
      state.rotation(8, 1),         state.rotation(9, 1),         state.angular_velocity(8, 0),
      state.angular_velocity(9, 0), state.angular_velocity(8, 1), state.angular_velocity(9, 1),
      state.angular_velocity(8, 2), state.angular_velocity(9, 2), state.reaction_moment(8, 2),
      state.reaction_moment(9, 2),  state.displacement(8, 0),     state.displacement(9, 0)};
  CHECK(row == expected);
  // UR2 of node 8 is 0.2 + 8 in the fixture; one rounding of that sum.
  CHECK(row[0] == Approx(8.2).epsilon(1e-15));
}

TEST_CASE("output schedule: history of rotations on a model without shells is zero",
          "[io][results][shell]") {
  Model model = tiny_model();
  model.steps[0].outputs = {history(0, {"UR", "RM1", "RF1"})};
  OutputSchedule schedule;
  schedule.begin_step(model, 0);
  REQUIRE(paths(schedule) == std::vector<std::string>{"node/FIXED/UR1", "node/FIXED/UR2",
                                                      "node/FIXED/UR3", "node/FIXED/RM1",
                                                      "node/FIXED/RF1"});
  // The state of a hex model has no rotational arrays at all (0 rows): nothing reads them.
  const State state = tiny_state(model, 3);
  REQUIRE(state.rotation.rows() == 0);
  std::vector<Real> row;
  schedule.history_row(state, row);
  REQUIRE(row.size() == 5 * 4);
  for (std::size_t i = 0; i < 16; ++i) CHECK(row[i] == 0.0);
  for (int c = 0; c < 4; ++c)
    CHECK(row[16 + c] == state.reaction(model.node_sets[0].members[c], 0));
}
