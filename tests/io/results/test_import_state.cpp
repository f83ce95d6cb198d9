// read_imported_state (--import): result files written by ResultFiles are read back onto the
// model, in the model's row order; a file of another mesh, a missing file or a last frame
// without U or V is refused with one "FILE: --import: ...; expected ..." message.

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "io/result_tools/import_state.hpp"
#include "io/results/result_files.hpp"
#include "results/shell_fixture.hpp"

using namespace xpl;
using namespace xpl::test;

namespace {

/// Writes a run of `model` with frames 0 .. n−1 (state of `make_state`), frame i with
/// `request(i)`, and returns the path of the .h5 file.
template <class MakeState, class Request>
std::filesystem::path write_run(const std::filesystem::path& directory, const Model& model,
                                int frames, MakeState make_state, Request request,
                                RunStatus status = RunStatus::Completed) {
  io::ResultFiles files(directory, "prev", {.progress = false});
  files.begin_run(model);
  files.begin_step(model, 0);
  for (int frame = 0; frame < frames; ++frame) {
    write_frame(files, model, make_state(model, frame), request(frame));
  }
  files.end_run(status, "", PhaseTimers{}, 0.0);
  return files.h5_path();
}

std::filesystem::path write_tiny_run(const std::filesystem::path& directory, int frames = 3) {
  return write_run(directory, tiny_model(), frames, tiny_state, [](int) { return all_fields(); });
}

/// The message of the InputError that read_imported_state throws, or "no error".
std::string import_error(const std::filesystem::path& h5, const Model& model) {
  try {
    io::read_imported_state(h5, model);
  } catch (const InputError& error) {
    REQUIRE(error.messages().size() == 1);
    return error.messages().front();
  }
  return "no error";
}

/// tiny_model() with its nodes and elements in reverse order (same ids, coordinates, mesh).
Model reversed_tiny_model() {
  const Model original = tiny_model();
  Model model = original;
  const Index n_nodes = original.node_count();
  const auto reversed = [&](Index n) { return n_nodes - 1 - n; };
  for (Index n = 0; n < n_nodes; ++n) {
    model.node_ids[static_cast<std::size_t>(reversed(n))] =
        original.node_ids[static_cast<std::size_t>(n)];
    model.coordinates.row(reversed(n)) = original.coordinates.row(n);
  }
  model.element_ids = {original.element_ids[1], original.element_ids[0]};
  model.element_nodes.clear();
  for (Index e : {1, 0}) {
    for (int a = 0; a < 8; ++a) model.element_nodes.push_back(reversed(original.nodes_of(e)[a]));
  }
  return model;
}

}  // namespace

TEST_CASE("import: the last frame of a hex result file", "[io][results][import]") {
  const ScratchDirectory scratch("import_hex");
  const Model model = tiny_model();
  const auto h5 = write_tiny_run(scratch.path());
  const io::ImportedState imported = io::read_imported_state(h5, model);
  const TestFrame last = tiny_state(model, 2);

  CHECK(imported.source == h5.string());
  CHECK(imported.time == last.time);
  CHECK(imported.increment == 20);
  REQUIRE(imported.displacement.rows() == 12);
  REQUIRE(imported.velocity.rows() == 12);
  for (Index n = 0; n < 12; ++n) {
    for (int c = 0; c < 3; ++c) {
      CHECK(imported.displacement(n, c) == last.position(n, c) - last.reference(n, c));
      CHECK(imported.velocity(n, c) == last.velocity(n, c));
    }
  }
  CHECK(imported.rotation.rows() == 0);  // a hex-only file has no UR/VR
  CHECK(imported.angular_velocity.rows() == 0);
  CHECK(imported.stress == last.stress);
  CHECK(imported.stress_bottom.empty());
  CHECK(imported.stress_top.empty());
  CHECK(imported.hourglass_state == last.hourglass_state);
  CHECK(imported.notes.empty());
}

TEST_CASE("import: rows are mapped by deck id onto the model's order", "[io][results][import]") {
  const ScratchDirectory scratch("import_order");
  const auto h5 = write_tiny_run(scratch.path());
  const Model model = reversed_tiny_model();
  const io::ImportedState imported = io::read_imported_state(h5, model);
  const TestFrame last = tiny_state(tiny_model(), 2);
  for (Index n = 0; n < 12; ++n) {
    for (int c = 0; c < 3; ++c) {
      CHECK(imported.displacement(11 - n, c) == last.position(n, c) - last.reference(n, c));
      CHECK(imported.velocity(11 - n, c) == last.velocity(n, c));
    }
  }
  REQUIRE(imported.stress.size() == 12);
  CHECK(std::equal(imported.stress.begin(), imported.stress.begin() + 6, last.stress.begin() + 6));
  CHECK(std::equal(imported.stress.begin() + 6, imported.stress.end(), last.stress.begin()));
}

TEST_CASE("import: shell fields, and notes on what the last frame lacks",
          "[io][results][import][shell]") {
  const ScratchDirectory scratch("import_shell");
  const Model model = mixed_model();

  SECTION("every field") {
    const auto h5 =
        write_run(scratch.path(), model, 2, mixed_state, [](int) { return all_fields(); });
    const io::ImportedState imported = io::read_imported_state(h5, model);
    const TestFrame last = mixed_state(model, 1);
    REQUIRE(imported.rotation.rows() == 12);
    REQUIRE(imported.angular_velocity.rows() == 12);
    CHECK(imported.rotation == last.rotation);
    CHECK(imported.angular_velocity == last.angular_velocity);
    CHECK(imported.stress == last.stress);
    CHECK(same_values(imported.stress_bottom, last.stress_bottom));  // NaN rows of the hex
    CHECK(same_values(imported.stress_top, last.stress_top));
    CHECK(imported.hourglass_state == last.hourglass_state);
    CHECK(same_values(imported.shell_thickness, last.thickness));
    CHECK(imported.notes.empty());
  }

  SECTION("a last frame with U and V only") {
    const auto h5 = write_run(scratch.path(), model, 2, mixed_state, [](int frame) {
      return frame == 0 ? all_fields() : FrameRequest{.displacement = true, .velocity = true};
    });
    const io::ImportedState imported = io::read_imported_state(h5, model);
    // U and V on a shell model come with UR and VR; the stresses of frame 0 are not used.
    CHECK(imported.rotation == mixed_state(model, 1).rotation);
    CHECK(imported.stress.empty());
    CHECK(imported.stress_bottom.empty());
    REQUIRE(imported.notes.size() == 1);
    CHECK(imported.notes[0] == "no S in the last frame: the elements start unstressed");
  }

  SECTION("a failed run") {
    const auto h5 = write_run(
        scratch.path(), model, 2, mixed_state, [](int) { return all_fields(); }, RunStatus::Failed);
    const io::ImportedState imported = io::read_imported_state(h5, model);
    REQUIRE(imported.notes.size() == 1);
    CHECK(imported.notes[0] ==
          "the earlier run's status is 'failed', not 'completed': its last frame is imported "
          "as it is");
  }
}

TEST_CASE("import: coordinates within the tolerance are accepted and U follows the model's",
          "[io][results][import]") {
  const ScratchDirectory scratch("import_tolerance");
  const auto h5 = write_tiny_run(scratch.path());
  Model model = tiny_model();
  // Model size: the diagonal of 1 × 0.25 × 0.125 m, ~1.04 m; tolerance ~1.04e-9 m.
  model.coordinates(5, 1) += 5e-10;
  const io::ImportedState imported = io::read_imported_state(h5, model);
  const TestFrame last = tiny_state(tiny_model(), 2);
  // The current position is the file's: X_model + U = X_file + U_file (to the round-off of
  // a few additions of values ~0.25 m, 1e-16 m each).
  CHECK(model.coordinates(5, 1) + imported.displacement(5, 1) ==
        Approx(last.position(5, 1)).margin(1e-15));
  CHECK(imported.displacement(5, 1) ==
        Approx(last.position(5, 1) - last.reference(5, 1) - 5e-10).margin(1e-15));
}

TEST_CASE("import: a file of another mesh is refused, naming the first mismatch",
          "[io][results][import][errors]") {
  const ScratchDirectory scratch("import_mismatch");
  const auto h5 = write_tiny_run(scratch.path());
  const std::string file = h5.string() + ": --import: ";
  const std::string same_mesh =
      "; expected the result file of a run on the same mesh (the same node and element ids, "
      "element types, connectivity and reference coordinates)";
  Model model = tiny_model();

  SECTION("a node id the file does not have") {
    model.node_ids[3] = 99999;
    CHECK(import_error(h5, model) ==
          file + "node 99999 of the model is not in the file (/mesh/node_ids)" + same_mesh);
  }
  SECTION("a node fewer in the model") {
    // Node 11 (id 1077) dropped: the model's nodes are all in the file, the file has one more.
    model.node_ids.pop_back();
    model.coordinates.conservativeResize(11, 3);
    CHECK(import_error(h5, model) ==
          file + "node 1077 of the file (/mesh/node_ids) is not in the model" + same_mesh);
  }
  SECTION("different coordinates") {
    model.coordinates(5, 1) += 1e-6;  // node 5 is (1, 0.25, 0), id 1035
    CHECK(import_error(h5, model) ==
          file +
              "node 1035 is at (1, 0.250001, 0) in the model but at (1, 0.25, 0) in the file "
              "(/mesh/coordinates)" +
              same_mesh + "; coordinates may differ by 1.04e-09 m (1e-9 of the model size)");
  }
  SECTION("an element id the file does not have") {
    model.element_ids[1] = 43;
    CHECK(import_error(h5, model) ==
          file + "element 43 of the model is not in the file (/mesh/element_ids)" + same_mesh);
  }
  SECTION("different connectivity") {
    std::swap(model.element_nodes[8], model.element_nodes[9]);  // element 42: nodes 1 and 2
    CHECK(import_error(h5, model) ==
          file +
              "element 42 has nodes 1007, 1014, 1035, 1028, 1049, 1056, 1077, 1070 in the file but "
              "1014, 1007, 1035, 1028, 1049, 1056, 1077, 1070 in the model" +
              same_mesh);
  }
}

TEST_CASE("import: an element of another type is refused", "[io][results][import][errors]") {
  const ScratchDirectory scratch("import_type");
  const Model written = mixed_model(false);  // two shells, S4R 7 and 42
  const auto h5 =
      write_run(scratch.path(), written, 1, mixed_state, [](int) { return all_fields(); });
  Model model = written;
  model.element_types[1] = ElementType::C3D8R;
  CHECK(import_error(h5, model) ==
        h5.string() +
            ": --import: element 42 is S4R in the file but C3D8R in the model; expected the "
            "result file of a run on the same mesh (the same node and element ids, element "
            "types, connectivity and reference coordinates)");
}

TEST_CASE("import: missing files, other files and incomplete frames are refused",
          "[io][results][import][errors]") {
  const ScratchDirectory scratch("import_errors");
  const Model model = tiny_model();
  const std::string xpl_file = "; expected the .h5 result file of an earlier xpl run";

  SECTION("no file") {
    const auto h5 = scratch.path() / "nothing.h5";
    CHECK(import_error(h5, model) ==
          h5.string() + ": --import: the file does not exist" + xpl_file);
  }
  SECTION("a directory") {
    std::filesystem::create_directories(scratch.path());
    CHECK(import_error(scratch.path(), model) ==
          scratch.path().string() + ": --import: not a file" + xpl_file);
  }
  SECTION("not HDF5") {
    const auto xdmf = write_tiny_run(scratch.path()).replace_extension(".xdmf");
    CHECK(import_error(xdmf, model) ==
          xdmf.string() + ": --import: not an HDF5 file" + xpl_file + " (JOB.h5, not JOB.xdmf)");
  }
  SECTION("no frames") {
    const auto h5 = write_tiny_run(scratch.path(), 0);
    CHECK(import_error(h5, model) ==
          h5.string() +
              ": --import: the file has no frames (/frames); expected a result file with at "
              "least one field output frame");
  }
  SECTION("no V in the last frame") {
    const auto h5 = write_run(scratch.path(), model, 3, tiny_state, [](int frame) {
      return frame < 2 ? all_fields() : FrameRequest{.displacement = true};
    });
    CHECK(import_error(h5, model) ==
          h5.string() +
              ": --import: the last frame (/frames/000002, t = 0.0002 s) has no V; expected a "
              "last frame with U and V (*NODE OUTPUT U, V in the earlier run's field output)");
  }
  SECTION("no U in the last frame") {
    const auto h5 = write_run(scratch.path(), model, 2, tiny_state, [](int frame) {
      return frame < 1 ? all_fields() : FrameRequest{.velocity = true};
    });
    CHECK(import_error(h5, model) ==
          h5.string() +
              ": --import: the last frame (/frames/000001, t = 0.0001 s) has no U; expected a "
              "last frame with U and V (*NODE OUTPUT U, V in the earlier run's field output)");
  }
  SECTION("a non-finite velocity") {
    const auto h5 = write_run(
        scratch.path(), model, 1,
        [](const Model& m, int frame) {
          TestFrame state = tiny_state(m, frame);
          state.velocity(4, 2) = std::numeric_limits<Real>::infinity();
          return state;
        },
        [](int) { return all_fields(); });
    CHECK(import_error(h5, model) ==
          h5.string() +
              ": --import: /frames/000000/V is not finite at node 1028; expected the state of a "
              "run that did not go unstable");
  }
}
