// Writes small result sets to a fixed directory for check_results.py (h5py + meshio): a hex
// model (job tiny) and a hex between two shells (job mixed). Hidden ([.]) so that only the
// ctest fixture runs them, before the Python checks.

#include <catch2/catch.hpp>

#include "io/results/result_files.hpp"
#include "results/shell_fixture.hpp"

using namespace xpl;
using namespace xpl::test;

namespace {

/// Removes the files of an earlier run of `job` (the other job's files stay).
void remove_job(const std::filesystem::path& directory, const std::string& job) {
  for (const char* extension : {".h5", ".xdmf", ".sta", ".msg"}) {
    std::filesystem::remove(directory / (job + extension));
  }
}

}  // namespace

TEST_CASE("results: write the result files read by check_results.py", "[.][io][results][python]") {
  const Model model = tiny_model();
  const std::filesystem::path directory = XPL_RESULTS_PYTHON_DIR;
  remove_job(directory, "tiny");
  io::ResultFiles files(directory, "tiny", {.progress = false});
  files.begin_run(model);
  files.begin_step(model, 0);
  files.declare_history({{"energy/ALLKE", 1, {}, "ALLKE", "J"},
                         {"node/FIXED/U3", 4, {1000, 1021, 1042, 1063}, "U3", "m"}});
  for (int frame = 0; frame < 4; ++frame) {
    // The last frame has no stress: a frame lists only the fields it has.
    write_frame(files, model, tiny_state(model, frame), {true, true, true, true, frame < 3, true});
    for (int r = 0; r < 300; ++r) {
      const std::vector<Real> row{r * 0.5, 1.0, 2.0, 3.0, 4.0 + r};
      files.append_history(1e-4 * frame + 1e-7 * r, row);
    }
  }
  files.end_run(RunStatus::Completed, "", PhaseTimers{}, 1.0);
  CHECK(std::filesystem::exists(directory / "tiny.xdmf"));
  CHECK(std::filesystem::exists(directory / "tiny.h5"));
}

TEST_CASE("results: write the mixed hex + shell result files read by check_results.py",
          "[.][io][results][python]") {
  const Model model = mixed_model();
  const std::filesystem::path directory = XPL_RESULTS_PYTHON_DIR;
  remove_job(directory, "mixed");
  io::ResultFiles files(directory, "mixed", {.progress = false});
  files.begin_run(model);
  files.begin_step(model, 0);
  files.declare_history({{"energy/ALLKE", 1, {}, "ALLKE", "J"}});
  for (int frame = 0; frame < 3; ++frame) {
    // The last frame has no stress and no thickness.
    FrameRequest what = all_fields();
    what.stress = what.thickness = frame < 2;
    write_frame(files, model, mixed_state(model, frame), what);
    const Real kinetic = frame;
    files.append_history(1e-4 * frame, {&kinetic, 1});
  }
  files.end_run(RunStatus::Completed, "", PhaseTimers{}, 1.0);
  CHECK(std::filesystem::exists(directory / "mixed.xdmf"));
  CHECK(std::filesystem::exists(directory / "mixed.h5"));
}
