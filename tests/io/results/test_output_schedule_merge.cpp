// OutputSchedule with a variable requested twice in a step (issue 15, item 2): written once,
// at the finer interval, with a note; and output intervals far below the increment.

#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "results/results_fixture.hpp"
#include "solver/output/output_schedule.hpp"

using namespace xpl;
using namespace xpl::test;

namespace {

OutputRequest request(OutputRequest::Kind kind, Real interval, int line) {
  OutputRequest r;
  r.kind = kind;
  r.time_interval = interval;
  r.where = {"deck.inp", line};
  return r;
}

std::vector<std::string> paths(const OutputSchedule& schedule) {
  std::vector<std::string> out;
  for (const HistorySeries& s : schedule.series()) out.push_back(s.path);
  return out;
}

bool mentions(const std::vector<std::string>& notes, const std::string& text) {
  for (const std::string& note : notes)
    if (note.find(text) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST_CASE("output schedule: history asked twice is declared once, with a note",
          "[io][results][merge]") {
  Model model = tiny_model();
  // PRESELECT (every energy) plus *ENERGY OUTPUT, ALLKE of another request, and one node set
  // in two requests.
  OutputRequest preselect = request(OutputRequest::Kind::History, 1e-4, 10);
  preselect.energy = true;
  preselect.node_set = 0;
  preselect.node_variables = {"RF1"};
  OutputRequest energy = request(OutputRequest::Kind::History, 2e-5, 20);
  energy.energy = true;
  energy.energy_variables = {"ALLKE"};
  energy.node_set = 0;
  energy.node_variables = {"RF1", "U2"};
  model.steps[0].outputs = {preselect, energy};
  OutputSchedule schedule;
  schedule.begin_step(model, 0);

  const std::vector<std::string> declared = paths(schedule);
  for (const std::string& path : declared)
    CHECK(std::count(declared.begin(), declared.end(), path) == 1);
  CHECK(std::count(declared.begin(), declared.end(), "energy/ALLKE") == 1);
  CHECK(std::count(declared.begin(), declared.end(), "node/FIXED/U2") == 1);
  // The row holds every declared column once: 8 energies (no contact), RF1 and U2 of 4 nodes.
  CHECK(declared.size() == 10);
  State state;
  state.reference = state.position = NodalVectors::Zero(12, 3);
  state.reaction = NodalVectors::Zero(12, 3);
  std::vector<Real> row;
  schedule.history_row(state, row);
  CHECK(row.size() == 8 + 2 * 4);

  const std::vector<std::string> notes = schedule.take_notes();
  REQUIRE(notes.size() == 1);  // one per pair of keywords, naming every repeated series
  CHECK(mentions(notes, "deck.inp:20 asks again for ALLKE, FIXED/RF1"));
  CHECK(mentions(notes, "already requested at deck.inp:10"));
  CHECK(schedule.take_notes().empty());

  // Rows fall due at the finer interval (2e-5 s), not only at the coarser one.
  CHECK(schedule.history_due(2e-5, false));
  CHECK_FALSE(schedule.history_due(3e-5, false));
  CHECK(schedule.history_due(4e-5, false));
}

TEST_CASE("output schedule: a field variable in two requests is written at the finer interval",
          "[io][results][merge]") {
  Model model = tiny_model();
  OutputRequest coarse = request(OutputRequest::Kind::Field, 1e-4, 10);
  coarse.node_variables = {"U", "V"};
  coarse.element_variables = {"S"};
  OutputRequest fine = request(OutputRequest::Kind::Field, 2e-5, 20);
  fine.node_variables = {"U"};
  model.steps[0].outputs = {coarse, fine};
  OutputSchedule schedule;
  schedule.begin_step(model, 0);

  const std::vector<std::string> notes = schedule.take_notes();
  REQUIRE(notes.size() == 1);
  CHECK(mentions(notes,
                 "deck.inp:10 (every 0.0001 s) asks again for U (also requested at "
                 "deck.inp:20, every 2e-05 s): written once, at the finer interval"));
  // U at every 2e-5 s; V and S with the coarse request only.
  const FrameRequest at_fine = schedule.field_due(2e-5, false);
  CHECK(at_fine.displacement);
  CHECK_FALSE(at_fine.velocity);
  CHECK_FALSE(at_fine.stress);
  for (int k = 2; k <= 4; ++k) CHECK(schedule.field_due(k * 2e-5, false).displacement);
  const FrameRequest at_coarse = schedule.field_due(1e-4, false);
  CHECK(at_coarse.displacement);
  CHECK(at_coarse.velocity);
  CHECK(at_coarse.stress);
  const FrameRequest all = schedule.field_all();
  CHECK((all.displacement && all.velocity && all.stress));
}

TEST_CASE("output schedule: an interval far below the increment fires once per increment",
          "[io][results][merge]") {
  Model model = tiny_model();
  OutputRequest tiny = request(OutputRequest::Kind::Field, 1e-20, 10);
  tiny.node_variables = {"U"};
  model.steps[0].outputs = {tiny};
  OutputSchedule schedule;
  schedule.begin_step(model, 0);
  schedule.note_short_intervals(1e-7);
  const std::vector<std::string> notes = schedule.take_notes();
  REQUIRE(notes.size() == 1);
  CHECK(mentions(notes,
                 "deck.inp:10: the output interval 1e-20 s is shorter than the stable "
                 "increment 1e-07 s; output is written once per increment"));
  // Each increment fires once; the next due time lands past the current time at once (a
  // loop stepping by 1e-20 s would take 1e13 turns to reach 1e-7 s).
  for (int increment = 1; increment <= 5; ++increment)
    CHECK(schedule.field_due(increment * 1e-7, false).displacement);
  // A request at a sane interval gets no note.
  model.steps[0].outputs[0].time_interval = 1e-5;
  schedule.begin_step(model, 0);
  schedule.note_short_intervals(1e-7);
  CHECK(schedule.take_notes().empty());
}
