// ResultFiles on shell models: rotations, shell section stresses and thickness in the frames,
// per-type connectivity and the mixed XDMF topology; hex-only files stay as they were.

#include <catch2/catch.hpp>

#include "io/results/result_files.hpp"
#include "results/shell_fixture.hpp"

using namespace xpl;
using namespace xpl::test;

namespace {

using Strings = std::vector<std::string>;
using Ints = std::vector<std::int64_t>;

/// A state field as the row-major values HDF5 should hold.
std::vector<double> rows_of(const NodalVectors& field) {
  std::vector<double> out;
  for (Eigen::Index n = 0; n < field.rows(); ++n) {
    for (int c = 0; c < 3; ++c) out.push_back(field(n, c));
  }
  return out;
}

/// A whole run: frames 0..2 with every field, frame 3 with U only.
void run(io::ResultFiles& files, const Model& model) {
  files.begin_run(model);
  files.begin_step(model, 0);
  for (int frame = 0; frame < 4; ++frame) {
    const FrameRequest what = frame < 3 ? all_fields() : FrameRequest{.displacement = true};
    write_frame(files, model, mixed_state(model, frame), what);
  }
  files.end_run(RunStatus::Completed, "", PhaseTimers{}, 0.0);
}

}  // namespace

TEST_CASE("results: a hex between two shells writes per-type meshes and shell fields",
          "[io][results][shell]") {
  const Model model = mixed_model();
  const ScratchDirectory scratch("mixed");
  io::ResultFiles files(scratch.path(), "job", {.progress = false});
  run(files, model);
  const auto file = open_h5(files.h5_path());
  const hid_t f = file.get();

  SECTION("mesh") {
    CHECK(links(f, "/mesh") == Strings{"C3D8R", "S4R", "coordinates", "element_ids", "element_sets",
                                       "mixed_topology", "node_ids", "node_sets"});
    CHECK(read<std::int64_t>(f, "/mesh/element_ids") == Ints{7, 11, 42});
    CHECK(read<std::int64_t>(f, "/mesh/C3D8R/element_ids") == Ints{11});
    CHECK(read<std::int64_t>(f, "/mesh/C3D8R/element_rows") == Ints{1});
    CHECK(read<std::int64_t>(f, "/mesh/C3D8R/connectivity") == Ints{0, 1, 3, 2, 4, 5, 7, 6});
    CHECK(read<std::int64_t>(f, "/mesh/S4R/element_ids") == Ints{7, 42});
    CHECK(read<std::int64_t>(f, "/mesh/S4R/element_rows") == Ints{0, 2});
    REQUIRE(shape(f, "/mesh/S4R/connectivity") == std::vector<hsize_t>{2, 4});
    CHECK(read<std::int64_t>(f, "/mesh/S4R/connectivity") == Ints{8, 0, 2, 9, 5, 10, 11, 7});
    // XDMF cell codes: 5 quadrilateral, 9 hexahedron; element order, not type order.
    CHECK(read<std::int64_t>(f, "/mesh/mixed_topology") ==
          Ints{5, 8, 0, 2, 9, 9, 0, 1, 3, 2, 4, 5, 7, 6, 5, 5, 10, 11, 7});
  }

  SECTION("frames with every field") {
    for (int frame = 0; frame < 3; ++frame) {
      const std::string group = "/frames/00000" + std::to_string(frame);
      const TestFrame expected = mixed_state(model, frame);
      // Issue 19: the shell surfaces' Mises stresses and the largest through the thickness.
      CHECK(links(f, group) == Strings{"A", "EVOL", "HGSTATE", "MISES", "MISES_MAX", "MISES_SNEG",
                                       "MISES_SPOS", "RF", "RM", "S", "STH", "S_SNEG", "S_SPOS",
                                       "U", "UR", "V", "VR"});
      for (const char* name : {"UR", "VR", "RM"}) {
        CHECK(shape(f, group + "/" + name) == std::vector<hsize_t>{12, 3});
      }
      CHECK(read<double>(f, group + "/UR") == rows_of(expected.rotation));
      CHECK(read<double>(f, group + "/VR") == rows_of(expected.angular_velocity));
      CHECK(read<double>(f, group + "/RM") == rows_of(expected.reaction_moment));
      REQUIRE(shape(f, group + "/S_SNEG") == std::vector<hsize_t>{3, 6});
      REQUIRE(shape(f, group + "/S_SPOS") == std::vector<hsize_t>{3, 6});
      REQUIRE(shape(f, group + "/STH") == std::vector<hsize_t>{3});
      const auto bottom = read<double>(f, group + "/S_SNEG");
      CHECK(same_values(bottom, expected.stress_bottom));
      CHECK(same_values(read<double>(f, group + "/S_SPOS"), expected.stress_top));
      CHECK(same_values(read<double>(f, group + "/STH"), expected.thickness));
      CHECK(std::isnan(bottom[6]));  // the hex row
      CHECK(bottom[12] == -10.0 * 3 * (frame + 1));
      CHECK(read<double>(f, group + "/S") == expected.stress);
    }
  }

  SECTION("a frame with U only also has UR, nothing else") {
    CHECK(links(f, "/frames/000003") == Strings{"U", "UR"});
    CHECK(read<double>(f, "/frames/000003/UR") == rows_of(mixed_state(model, 3).rotation));
  }

  SECTION("xdmf") {
    const std::string xdmf = slurp(files.xdmf_path());
    CHECK(count(xdmf, "<Topology TopologyType=\"Mixed\" NumberOfElements=\"3\">") == 4);
    CHECK(count(xdmf,
                "Dimensions=\"19\" DataType=\"Int\" Precision=\"8\" Format=\"HDF\">"
                "job.h5:/mesh/mixed_topology<") == 4);
    CHECK(count(xdmf, "<Attribute Name=\"UR\" AttributeType=\"Vector\" Center=\"Node\">") == 4);
    CHECK(count(xdmf, "<Attribute Name=\"VR\" AttributeType=\"Vector\" Center=\"Node\">") == 3);
    CHECK(count(xdmf, "<Attribute Name=\"RM\" AttributeType=\"Vector\" Center=\"Node\">") == 3);
    CHECK(count(xdmf, "<Attribute Name=\"S_SNEG\" AttributeType=\"Tensor6\" Center=\"Cell\">") ==
          3);
    CHECK(count(xdmf, "<Attribute Name=\"S_SPOS\" AttributeType=\"Tensor6\" Center=\"Cell\">") ==
          3);
    // Issue 34: one "Scalar" per frame, the field ParaView colours by (MISES_MAX on shell
    // models); the other scalars are plain arrays ("None").
    CHECK(count(xdmf, "<Attribute Name=\"STH\" AttributeType=\"None\" Center=\"Cell\">") == 3);
    CHECK(count(xdmf, "<Attribute Name=\"MISES_MAX\" AttributeType=\"Scalar\" Center=\"Cell\">") ==
          3);
    CHECK(count(xdmf, "AttributeType=\"Scalar\"") == 3);
    CHECK(count(xdmf,
                "Dimensions=\"3 6\" DataType=\"Float\" Precision=\"8\" Format=\"HDF\">"
                "job.h5:/frames/000002/S_SNEG<") == 0);
    // Issue 19: tensors come from their VTK-ordered global-axes copies below /xdmf.
    CHECK(count(xdmf,
                "Dimensions=\"3 6\" DataType=\"Float\" Precision=\"8\" Format=\"HDF\">"
                "job.h5:/xdmf/000002/S_SNEG<") == 1);
    CHECK(count(xdmf, "job.h5:/frames/000003/UR<") == 1);
  }

  SECTION("msg summary") {
    const std::string msg = slurp(files.msg_path());
    CHECK(count(msg, "     C3D8R                               1") == 1);
    CHECK(count(msg, "     S4R                                 2") == 1);
    CHECK(count(msg, "   shell sections                        1") == 1);
  }
}

TEST_CASE("results: a model of shells only has a quadrilateral topology", "[io][results][shell]") {
  const Model model = mixed_model(false);
  const ScratchDirectory scratch("shells");
  io::ResultFiles files(scratch.path(), "job", {.progress = false});
  run(files, model);
  const auto file = open_h5(files.h5_path());
  const hid_t f = file.get();
  CHECK(links(f, "/mesh") ==
        Strings{"S4R", "coordinates", "element_ids", "element_sets", "node_ids", "node_sets"});
  CHECK(links(f, "/mesh/S4R") == Strings{"connectivity", "element_ids"});
  CHECK(read<std::int64_t>(f, "/mesh/S4R/connectivity") == Ints{8, 0, 2, 9, 5, 10, 11, 7});
  CHECK(same_values(read<double>(f, "/frames/000001/STH"), mixed_state(model, 1).thickness));

  const std::string xdmf = slurp(files.xdmf_path());
  CHECK(count(xdmf, "<Topology TopologyType=\"Quadrilateral\" NumberOfElements=\"2\">") == 4);
  CHECK(count(xdmf,
              "Dimensions=\"2 4\" DataType=\"Int\" Precision=\"8\" Format=\"HDF\">"
              "job.h5:/mesh/S4R/connectivity<") == 4);
  CHECK(count(xdmf, "Mixed") == 0);
}

TEST_CASE("results: hex-only models write no shell datasets, even when STH is asked for",
          "[io][results][shell]") {
  const Model model = tiny_model();
  const ScratchDirectory scratch("hex_only");
  io::ResultFiles files(scratch.path(), "job", {.progress = false});
  files.begin_run(model);
  files.begin_step(model, 0);
  write_frame(files, model, tiny_state(model, 0), all_fields());
  files.end_run(RunStatus::Completed, "", PhaseTimers{}, 0.0);

  const auto file = open_h5(files.h5_path());
  const hid_t f = file.get();
  CHECK(links(f, "/mesh") ==
        Strings{"C3D8R", "coordinates", "element_ids", "element_sets", "node_ids", "node_sets"});
  CHECK(links(f, "/mesh/C3D8R") == Strings{"connectivity", "element_ids"});
  CHECK(links(f, "/frames/000000") ==
        Strings{"A", "EVOL", "HGSTATE", "MISES", "RF", "S", "U", "V"});
  const std::string xdmf = slurp(files.xdmf_path());
  CHECK(count(xdmf, "<Topology TopologyType=\"Hexahedron\" NumberOfElements=\"2\">") == 1);
  CHECK(count(xdmf,
              "Dimensions=\"2 8\" DataType=\"Int\" Precision=\"8\" Format=\"HDF\">"
              "job.h5:/mesh/C3D8R/connectivity<") == 1);
  // Issue 19: the 7 fields and the deck ids node_id and element_id; issue 34: besides them,
  // the sets' 0/1 arrays.
  CHECK(count(xdmf, "<Attribute ") - count(xdmf, "<Attribute Name=\"NSET_") -
            count(xdmf, "<Attribute Name=\"ELSET_") ==
        9);
  for (const char* name : {"\"UR\"", "\"VR\"", "\"RM\"", "S_SNEG", "S_SPOS", "STH"}) {
    CHECK(count(xdmf, name) == 0);
  }
}

TEST_CASE("results: shell fields of the wrong size are rejected before anything is written",
          "[io][results][shell]") {
  const Model model = mixed_model();
  const ScratchDirectory scratch("shell_sizes");
  io::ResultFiles files(scratch.path(), "job", {.progress = false});
  files.begin_run(model);
  files.begin_step(model, 0);
  TestFrame state = mixed_state(model, 0);
  state.rotation.resize(0, 3);  // as if the solver had not allocated the rotations
  CHECK_THROWS_WITH(write_frame(files, model, state, {.displacement = true}),
                    "write_frame: state field UR has 0 rows; the model has 12 nodes");
  state = mixed_state(model, 0);
  state.stress_top.pop_back();
  CHECK_THROWS_WITH(write_frame(files, model, state, {.stress = true}),
                    "write_frame: frame field stress_top has 17 values; expected 18");
  state = mixed_state(model, 0);
  state.thickness.clear();
  CHECK_THROWS_WITH(write_frame(files, model, state, {.thickness = true}),
                    "write_frame: frame field thickness has 0 values; expected 3");
  // Nothing of the rejected frames reached the file: the next frame is a complete frame 0.
  write_frame(files, model, mixed_state(model, 0), {.displacement = true});
  files.end_run(RunStatus::Completed, "", PhaseTimers{}, 0.0);
  const auto file = open_h5(files.h5_path());
  CHECK(links(file.get(), "/frames") == Strings{"000000"});
  CHECK(links(file.get(), "/frames/000000") == Strings{"U", "UR"});
}
