// Writes a small result set to a fixed directory for check_results.py (h5py + meshio). Hidden
// ([.]) so that only the ctest fixture runs it, before the Python check.

#include <catch2/catch.hpp>

#include "io/result_files.hpp"
#include "results/results_fixture.hpp"

using namespace xpl;
using namespace xpl::test;

TEST_CASE("results: write the result files read by check_results.py", "[.][io][results][python]") {
  const Model model = tiny_model();
  const std::filesystem::path directory = XPL_RESULTS_PYTHON_DIR;
  std::filesystem::remove_all(directory);
  io::ResultFiles files(directory, "tiny", {.progress = false});
  files.begin_run(model);
  files.begin_step(model, 0);
  files.declare_history({{"energy/ALLKE", 1, {}}, {"node/FIXED/U3", 4, {1000, 1021, 1042, 1063}}});
  for (int frame = 0; frame < 4; ++frame) {
    // The last frame has no stress: a frame lists only the fields it has.
    files.write_frame(model, tiny_state(model, frame), {true, true, true, true, frame < 3, true});
    for (int r = 0; r < 300; ++r) {
      const std::vector<Real> row{r * 0.5, 1.0, 2.0, 3.0, 4.0 + r};
      files.append_history(1e-4 * frame + 1e-7 * r, row);
    }
  }
  files.end_run(RunStatus::Completed, "", PhaseTimers{}, 1.0);
  CHECK(std::filesystem::exists(directory / "tiny.xdmf"));
  CHECK(std::filesystem::exists(directory / "tiny.h5"));
}
