// ResultFiles: a tiny model driven through a whole run, then read back with the HDF5 C API.

#include <catch2/catch.hpp>

#include "io/results/result_files.hpp"
#include "io/results/results_h5.hpp"
#include "results/results_fixture.hpp"

using namespace xpl;
using namespace xpl::test;

namespace {

constexpr int N_ROWS = 1000;
constexpr int N_FIXED = 4;  // members of node set FIXED

/// History row r: ALLKE = r / 2, RF1 of column c = r + c / 4.
std::vector<Real> history_row(int r) {
  std::vector<Real> row{0.5 * r};
  for (int c = 0; c < N_FIXED; ++c) row.push_back(r + 0.25 * c);
  return row;
}

std::vector<HistorySeries> history_series(const Model& model) {
  std::vector<ExternalId> fixed;
  for (Index n : model.node_sets[0].members) fixed.push_back(model.node_ids[n]);
  return {{"energy/ALLKE", 1, {}, "", ""}, {"node/FIXED/RF1", N_FIXED, fixed, "RF1", "N"}};
}

FrameRequest everything() {
  return {true, true, true, true, true, true};
}

/// begin_run, begin_step, declare_history, `frames` frames with N_ROWS history rows between,
/// status lines and a warning; the caller ends the run.
void drive(io::ResultFiles& files, const Model& model, int frames) {
  files.begin_run(model);
  files.begin_step(model, 0);
  files.declare_history(history_series(model));
  const int rows_per_frame = N_ROWS / std::max(frames - 1, 1);
  int row = 0;
  for (int f = 0; f < frames; ++f) {
    const TestFrame state = tiny_state(model, f);
    write_frame(files, model, state, everything());
    for (int r = 0; f + 1 < frames && r < rows_per_frame; ++r, ++row) {
      files.append_history(1e-7 * row, history_row(row));
    }
    StatusLine line;
    line.increment = state.increment;
    line.total_time = state.time;
    line.step_time = state.step_time;
    line.dt = 1e-5;
    line.critical_element = 42;
    line.energies.kinetic = 1.5 * f;
    files.status(line);
  }
  files.message(Severity::Warning, "element 42 is badly shaped");
  files.message(Severity::Note, "hourglass control RELAX STIFFNESS runs as STIFFNESS");
}

}  // namespace

TEST_CASE("results: a completed run writes the documented HDF5 layout", "[io][results]") {
  const Model model = tiny_model();
  const ScratchDirectory scratch("completed");
  const auto directory = scratch.path() / "nested" / "out";
  io::ResultFiles files(directory, "job", {.progress = false});
  drive(files, model, 3);
  PhaseTimers timers;
  timers.add(Phase::InternalForce, 1.25);
  files.end_run(RunStatus::Completed, "", timers, 3.5e6);

  REQUIRE(files.h5_path() == directory / "job.h5");
  const auto file = open_h5(files.h5_path());
  const hid_t f = file.get();
  CHECK(string_attribute(f, "/", "status") == "completed");
  CHECK(string_attribute(f, "/", "error").empty());
  CHECK(string_attribute(f, "/", "job") == "job");
  CHECK(string_attribute(f, "/", "heading") == "two hexes");
  CHECK(string_attribute(f, "/", "xpl_version") == XPL_VERSION);

  SECTION("mesh") {
    CHECK(read<std::int64_t>(f, "/mesh/node_ids") ==
          std::vector<std::int64_t>(model.node_ids.begin(), model.node_ids.end()));
    REQUIRE(shape(f, "/mesh/coordinates") == std::vector<hsize_t>{12, 3});
    const auto xyz = read<double>(f, "/mesh/coordinates");
    CHECK(xyz[3 * 5 + 0] == model.coordinates(5, 0));  // row-major on disk
    CHECK(xyz[3 * 11 + 2] == model.coordinates(11, 2));
    CHECK(read<std::int64_t>(f, "/mesh/element_ids") == std::vector<std::int64_t>{11, 42});
    CHECK(read<std::int64_t>(f, "/mesh/C3D8R/element_ids") == std::vector<std::int64_t>{11, 42});
    REQUIRE(shape(f, "/mesh/C3D8R/connectivity") == std::vector<hsize_t>{2, 8});
    const auto connectivity = read<std::int64_t>(f, "/mesh/C3D8R/connectivity");
    CHECK(std::vector<std::int64_t>(connectivity.begin() + 8, connectivity.end()) ==
          std::vector<std::int64_t>{1, 2, 5, 4, 7, 8, 11, 10});
    CHECK(read<std::int64_t>(f, "/mesh/node_sets/FIXED") ==
          std::vector<std::int64_t>{node_id(0), node_id(3), node_id(6), node_id(9)});
    CHECK(read<std::int64_t>(f, "/mesh/element_sets/ALL") == std::vector<std::int64_t>{11, 42});
  }

  SECTION("frames") {
    CHECK(exists(f, "/frames/000002"));
    CHECK_FALSE(exists(f, "/frames/000003"));
    for (int frame = 0; frame < 3; ++frame) {
      const std::string group = "/frames/00000" + std::to_string(frame);
      const TestFrame expected = tiny_state(model, frame);
      CHECK(numeric_attribute<double>(f, group, "time")[0] == expected.time);
      CHECK(numeric_attribute<double>(f, group, "step_time")[0] == expected.step_time);
      CHECK(numeric_attribute<std::int64_t>(f, group, "step")[0] == 1);
      CHECK(numeric_attribute<std::int64_t>(f, group, "increment")[0] == 10 * frame);
      CHECK(string_attribute(f, group, "step_name") == "LOAD");
      for (const char* name : {"U", "V", "A", "RF"}) {
        CHECK(shape(f, group + "/" + name) == std::vector<hsize_t>{12, 3});
      }
      const auto u = read<double>(f, group + "/U");
      const auto v = read<double>(f, group + "/V");
      for (Index n = 0; n < 12; ++n) {
        for (int c = 0; c < 3; ++c) {
          const std::size_t at = static_cast<std::size_t>(n) * 3 + c;
          CHECK(u[at] == Approx(expected.displacement(n, c)).margin(1e-15));  // x − X round-off
          CHECK(v[at] == expected.velocity(n, c));
        }
      }
      REQUIRE(shape(f, group + "/S") == std::vector<hsize_t>{2, 6});
      CHECK(read<double>(f, group + "/S") == expected.stress);
      const auto mises = read<double>(f, group + "/MISES");
      REQUIRE(mises.size() == 2);
      CHECK(mises[1] == Approx(io::von_mises(&expected.stress[6])).epsilon(1e-14));
      CHECK(read<double>(f, group + "/EVOL") == expected.volume);
    }
  }

  SECTION("history") {
    REQUIRE(shape(f, "/history/step_1/time") == std::vector<hsize_t>{N_ROWS});
    REQUIRE(shape(f, "/history/step_1/energy/ALLKE") == std::vector<hsize_t>{N_ROWS});
    REQUIRE(shape(f, "/history/step_1/node/FIXED/RF1") == std::vector<hsize_t>{N_ROWS, N_FIXED});
    const auto time = read<double>(f, "/history/step_1/time");
    const auto ke = read<double>(f, "/history/step_1/energy/ALLKE");
    const auto rf = read<double>(f, "/history/step_1/node/FIXED/RF1");
    for (int r = 0; r < N_ROWS; ++r) {
      const auto row = history_row(r);
      REQUIRE(time[r] == 1e-7 * r);
      REQUIRE(ke[r] == row[0]);
      for (int c = 0; c < N_FIXED; ++c) REQUIRE(rf[r * N_FIXED + c] == row[1 + c]);
    }
    CHECK(numeric_attribute<std::int64_t>(f, "/history/step_1/node/FIXED/RF1", "node_ids") ==
          std::vector<std::int64_t>{node_id(0), node_id(3), node_id(6), node_id(9)});
  }

  SECTION("xdmf, sta and msg") {
    const std::string xdmf = slurp(files.xdmf_path());
    CHECK(count(xdmf, "GridType=\"Uniform\"") == 3);
    CHECK(count(xdmf, "CollectionType=\"Temporal\"") == 1);
    CHECK(count(xdmf, "job.h5:/mesh/C3D8R/connectivity") == 3);
    CHECK(count(xdmf, "job.h5:/frames/000002/U") == 1);
    CHECK(count(xdmf, "AttributeType=\"Tensor6\"") == 3);

    const std::string sta = slurp(files.sta_path());
    CHECK(count(sta, "JOB  job") == 1);
    CHECK(count(sta, "  1.0000E-05           42") == 3);  // one status line per frame
    CHECK(count(sta, "THE ANALYSIS HAS COMPLETED SUCCESSFULLY") == 1);
    CHECK(count(sta, "3.5000E+06") == 1);

    const std::string msg = slurp(files.msg_path());
    CHECK(count(msg, "***WARNING: element 42 is badly shaped") == 1);
    CHECK(count(msg, "***NOTE: hourglass control") == 1);
    CHECK(count(msg, "internal force") == 1);
    CHECK(count(msg, "internal force              1.250 s") == 1);
    CHECK(count(msg, "total                       1.250 s") == 1);
    CHECK(count(msg, "nodes                                12") == 1);
  }
}

TEST_CASE("results: a failed run stores the error and stays readable", "[io][results]") {
  const Model model = tiny_model();
  const ScratchDirectory scratch("failed");
  const auto directory = scratch.path();
  io::ResultFiles files(directory, "crash", {.progress = false});
  drive(files, model, 2);
  files.end_run(RunStatus::Failed, "NaN at increment 7, element 12", PhaseTimers{}, 0.0);

  const auto file = open_h5(files.h5_path());
  CHECK(string_attribute(file.get(), "/", "status") == "failed");
  CHECK(string_attribute(file.get(), "/", "error") == "NaN at increment 7, element 12");
  CHECK(exists(file.get(), "/frames/000001/U"));
  CHECK_FALSE(exists(file.get(), "/frames/000002"));
  CHECK(count(slurp(files.xdmf_path()), "GridType=\"Uniform\"") == 2);
  const std::string sta = slurp(files.sta_path());
  CHECK(count(sta, "THE ANALYSIS HAS NOT BEEN COMPLETED") == 1);
  CHECK(count(sta, "NaN at increment 7, element 12") == 1);
  CHECK(count(slurp(files.msg_path()), "***ERROR: NaN at increment 7, element 12") == 1);
}

TEST_CASE("results: the status is 'running' until end_run, the file readable between frames",
          "[io][results]") {
  const Model model = tiny_model();
  const ScratchDirectory scratch("running");
  const auto directory = scratch.path();
  io::ResultFiles files(directory, "live", {.progress = false});
  files.begin_run(model);
  files.begin_step(model, 0);
  write_frame(files, model, tiny_state(model, 0), {.displacement = true});
  // JOB.h5 is closed between writes (issue 19): it can be opened as it is, mid-run. (Closed
  // again before the next write: in one process HDF5 refuses to reopen for writing a file
  // that is open read-only.)
  {
    const auto file = open_h5(files.h5_path());
    CHECK(string_attribute(file.get(), "/", "status") == "running");
    CHECK(shape(file.get(), "/frames/000000/U") == std::vector<hsize_t>{12, 3});
    CHECK_FALSE(exists(file.get(), "/frames/000000/V"));
  }
  write_frame(files, model, tiny_state(model, 1), {.velocity = true});
  {
    const auto file = open_h5(files.h5_path());
    CHECK(string_attribute(file.get(), "/", "status") == "running");
    CHECK(shape(file.get(), "/frames/000001/V") == std::vector<hsize_t>{12, 3});
  }
  files.end_run(RunStatus::Checked, "", PhaseTimers{}, 0.0);
  const auto file = open_h5(files.h5_path());
  CHECK(string_attribute(file.get(), "/", "status") == "checked");
  CHECK(count(slurp(files.sta_path()), "DATA CHECK COMPLETED") == 1);
}
