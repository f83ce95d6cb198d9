// ResultFiles: failures become exceptions with a clear message; odd but legal inputs work.

#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>

#include "io/results/result_files.hpp"
#include "io/results/results_h5.hpp"
#include "results/results_fixture.hpp"

using namespace xpl;
using namespace xpl::test;

TEST_CASE("results: von Mises stress of simple states", "[io][results]") {
  const Real uniaxial[6] = {250.0, 0, 0, 0, 0, 0};
  CHECK(io::von_mises(uniaxial) == Approx(250.0).epsilon(1e-14));
  const Real shear[6] = {0, 0, 0, 0, 10.0, 0};
  CHECK(io::von_mises(shear) == Approx(10.0 * std::sqrt(3.0)).epsilon(1e-14));
  const Real hydrostatic[6] = {-7.0, -7.0, -7.0, 0, 0, 0};
  CHECK(io::von_mises(hydrostatic) == Approx(0.0).margin(1e-12));
}

TEST_CASE("results: an unusable output directory is reported", "[io][results]") {
  const ScratchDirectory scratch("blocked");
  const auto directory = scratch.path();
  std::filesystem::create_directories(directory);
  std::ofstream(directory / "file") << "not a directory";
  CHECK_THROWS(io::ResultFiles(directory / "file", "job"));
}

TEST_CASE("results: HDF5 failures become exceptions that name the object", "[io][results]") {
  const Model model = tiny_model();
  const ScratchDirectory scratch("duplicate");
  io::ResultFiles files(scratch.path(), "job", {.progress = false});
  files.begin_run(model);
  files.begin_step(model, 0);
  const std::vector<HistorySeries> twice{{"energy/ALLKE", 1, {}, "", ""},
                                         {"energy/ALLKE", 1, {}, "", ""}};
  try {
    files.declare_history(twice);
    FAIL("a duplicate series was accepted");
  } catch (const io::h5::Error& error) {
    const std::string what = error.what();
    CHECK(what.rfind("HDF5: cannot create dataset history/step_1/energy/ALLKE", 0) == 0);
  }
}

TEST_CASE("results: history rows that do not match the declaration are rejected", "[io][results]") {
  const Model model = tiny_model();
  const ScratchDirectory scratch("mismatch");
  io::ResultFiles files(scratch.path(), "job", {.progress = false});
  files.begin_run(model);
  files.begin_step(model, 0);
  CHECK_THROWS_AS(files.declare_history({{"/absolute", 1, {}, "", ""}}), std::invalid_argument);
  files.begin_step(model, 1);
  files.declare_history({{"energy/ALLKE", 1, {}, "", ""}});
  const std::vector<Real> two{1.0, 2.0};
  CHECK_THROWS_AS(files.append_history(0.0, two), std::invalid_argument);
  CHECK_THROWS_AS(files.declare_history({}), std::logic_error);
}

TEST_CASE("results: wide history series, several steps and an overwritten file", "[io][results]") {
  const Model model = tiny_model();
  const ScratchDirectory scratch("wide");
  const auto directory = scratch.path();
  constexpr Index WIDTH = 10000;  // node_ids attribute of 80 kB: needs dense attribute storage
  for (int run = 0; run < 2; ++run) {
    io::ResultFiles files(directory, "job", {.progress = false});
    files.begin_run(model);
    for (int step = 0; step < 2; ++step) {
      files.begin_step(model, step);
      HistorySeries wide{"node/ALL/U1", WIDTH, {}, "", ""};
      for (Index i = 0; i < WIDTH; ++i) wide.node_ids.push_back(5 * i + 1);
      files.declare_history({wide});
      std::vector<Real> row(WIDTH);
      for (int r = 0; r < 3 + step + run; ++r) {
        row[WIDTH - 1] = r + 100.0 * step;
        files.append_history(r, row);
      }
    }
    if (run == 0) write_frame(files, model, tiny_state(model, 0), {.volume = true});
    files.end_run(RunStatus::Completed, "", PhaseTimers{}, 0.0);
  }
  const auto file = open_h5(directory / "job.h5");
  const hid_t f = file.get();
  CHECK_FALSE(exists(f, "/frames/000000"));  // the second run replaced the first file
  REQUIRE(shape(f, "/history/step_1/node/ALL/U1") == std::vector<hsize_t>{4, WIDTH});
  REQUIRE(shape(f, "/history/step_2/node/ALL/U1") == std::vector<hsize_t>{5, WIDTH});
  const auto u1 = read<double>(f, "/history/step_2/node/ALL/U1");
  CHECK(u1[4 * WIDTH + WIDTH - 1] == 104.0);
  const auto ids = numeric_attribute<std::int64_t>(f, "/history/step_2/node/ALL/U1", "node_ids");
  REQUIRE(ids.size() == WIDTH);
  CHECK(ids.back() == 5 * (WIDTH - 1) + 1);
}

TEST_CASE("results: a sink destroyed without end_run marks the file failed", "[io][results]") {
  const Model model = tiny_model();
  const ScratchDirectory scratch("abandoned");
  const auto directory = scratch.path();
  {
    io::ResultFiles files(directory, "job", {.progress = false});
    files.begin_run(model);
    files.begin_step(model, 0);
    files.declare_history({{"energy/ALLKE", 1, {}, "", ""}});
    const Real value = 3.0;
    files.append_history(0.5, {&value, 1});
  }
  const auto file = open_h5(directory / "job.h5");
  CHECK(string_attribute(file.get(), "/", "status") == "failed");
  CHECK(string_attribute(file.get(), "/", "error") == "the run ended without end_run");
  CHECK(read<double>(file.get(), "/history/step_1/energy/ALLKE") == std::vector<double>{3.0});
}
