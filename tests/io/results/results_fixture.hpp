#pragma once
/// \file A tiny hand-built model and state for the result-file tests, and HDF5 read-back
/// helpers (plain C API, independent of the writer's code paths).

#include <hdf5.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>
#include <type_traits>
#include <vector>

#include "io/result_tools/h5_handles.hpp"
#include "solver/model/model.hpp"
#include "solver/model/state.hpp"
#include "solver/output/frame_fields.hpp"
#include "solver/output/output_sink.hpp"

namespace xpl::test {

/// Nodes of the 3 × 2 × 2 grid of the two-hex model: index n = i + 3 j + 6 k.
inline Index grid_node(int i, int j, int k) {
  return i + 3 * j + 6 * k;
}

/// Sparse deck id of node n.
inline ExternalId node_id(Index n) {
  return 1000 + 7 * static_cast<ExternalId>(n);
}

/// Two C3D8R elements (ids 11 and 42) side by side, 12 nodes with sparse ids, node set FIXED
/// (the x = 0 face), element set ALL, one step LOAD of 1 ms.
inline Model tiny_model() {
  Model model;
  model.heading = "two hexes";
  model.job_name = "tiny";
  model.coordinates.resize(12, 3);
  for (int k = 0; k < 2; ++k) {
    for (int j = 0; j < 2; ++j) {
      for (int i = 0; i < 3; ++i) {
        const Index n = grid_node(i, j, k);
        model.node_ids.push_back(0);
        model.coordinates.row(n) << 0.5 * i, 0.25 * j, 0.125 * k;
      }
    }
  }
  for (Index n = 0; n < 12; ++n) model.node_ids[static_cast<std::size_t>(n)] = node_id(n);
  for (int e = 0; e < 2; ++e) {
    model.element_ids.push_back(e == 0 ? 11 : 42);
    model.element_types.push_back(ElementType::C3D8R);
    for (int k = 0; k < 2; ++k) {
      model.element_nodes.push_back(grid_node(e, 0, k));
      model.element_nodes.push_back(grid_node(e + 1, 0, k));
      model.element_nodes.push_back(grid_node(e + 1, 1, k));
      model.element_nodes.push_back(grid_node(e, 1, k));
    }
    model.element_offsets.push_back(static_cast<Index>(model.element_nodes.size()));
    model.element_section.push_back(0);
    model.add_element_source("fixture.inp", 1);
  }
  Material steel;
  steel.name = "STEEL";
  steel.density = 7800.0;
  steel.young = 210e9;
  steel.poisson = 0.3;
  steel.has_density = steel.has_elastic = true;
  model.materials.push_back(steel);
  model.node_sets.push_back({"FIXED", {0, 3, 6, 9}, {}});
  model.element_sets.push_back({"ALL", {0, 1}, {}});
  Step step;
  step.name = "LOAD";
  step.time_period = 1e-3;
  model.steps.push_back(step);
  model.initial_velocity = NodalVectors::Zero(12, 3);
  return model;
}

/// A frame for the writer: the solution (State) and the output-only fields (FrameFields) of
/// one made-up frame, in one object so that a test reads `frame.position` and `frame.stress`
/// alike.
struct TestFrame : State, FrameFields {};

/// Writes `frame` to `sink` (OutputSink::write_frame of its two parts).
inline void write_frame(OutputSink& sink, const Model& model, const TestFrame& frame,
                        const FrameRequest& what) {
  sink.write_frame(model, frame, frame, what);
}

/// The state of frame `frame`: x = X + u with u_n = (0.01 n, −0.02 n, 0.001 frame),
/// v = 10 u, a = 100 u, RF = −u, S of element e = (1 2 3 4 5 6) × (e + 1) × (frame + 1) (and
/// its XDMF copy as the output driver fills it).
inline TestFrame tiny_state(const Model& model, int frame) {
  TestFrame state;
  state.reference = model.coordinates;
  NodalVectors u(12, 3);
  for (Index n = 0; n < 12; ++n) u.row(n) << 0.01 * n, -0.02 * n, 0.001 * frame;
  state.position = state.reference + u;
  state.velocity = 10.0 * u;
  state.velocity_half = state.velocity;
  state.acceleration = 100.0 * u;
  state.reaction = -u;
  state.mass.assign(12, 1.0);
  for (int e = 0; e < 2; ++e) {
    for (int c = 0; c < 6; ++c) state.stress.push_back((c + 1.0) * (e + 1) * (frame + 1));
    state.volume.push_back(0.015625 * (1.0 + 0.01 * frame));
    // C3D8R hourglass state (HGSTATE), 12 values per element.
    for (int c = 0; c < 12; ++c) state.hourglass_state.push_back(0.5 * (c + 1) - e + frame);
  }
  state.time = 1e-4 * frame;
  state.step_time = state.time;
  state.increment = 10 * frame;
  state.step = 0;
  return state;
}

/// An opened HDF5 file (read-only).
inline io::h5::Handle open_h5(const std::filesystem::path& path) {
  io::h5::silence_errors();
  return {io::h5::check_id(H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), "open"), H5Fclose};
}

/// Whether the link `path` exists (every intermediate group must exist).
inline bool exists(hid_t file, const std::string& path) {
  std::string prefix;
  std::stringstream parts(path);
  for (std::string part; std::getline(parts, part, '/');) {
    if (part.empty()) continue;
    prefix += "/" + part;
    if (H5Lexists(file, prefix.c_str(), H5P_DEFAULT) <= 0) return false;
  }
  return true;
}

/// Shape of the dataset at `path`.
inline std::vector<hsize_t> shape(hid_t file, const std::string& path) {
  const io::h5::Handle dataset{io::h5::check_id(H5Dopen2(file, path.c_str(), H5P_DEFAULT), path),
                               H5Dclose};
  const io::h5::Handle space{io::h5::check_id(H5Dget_space(dataset.get()), path), H5Sclose};
  std::vector<hsize_t> dims(static_cast<std::size_t>(H5Sget_simple_extent_ndims(space.get())));
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  return dims;
}

/// All values of a dataset converted to `T` (double or int64), row-major.
template <typename T>
std::vector<T> read(hid_t file, const std::string& path) {
  const io::h5::Handle dataset{io::h5::check_id(H5Dopen2(file, path.c_str(), H5P_DEFAULT), path),
                               H5Dclose};
  std::size_t count = 1;
  for (hsize_t d : shape(file, path)) count *= d;
  std::vector<T> values(count);
  const hid_t type = std::is_same_v<T, double> ? H5T_NATIVE_DOUBLE : H5T_NATIVE_INT64;
  if (count > 0) {
    io::h5::check(H5Dread(dataset.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), path);
  }
  return values;
}

/// An attribute of the object at `path`: string (variable length), double or int64 values.
inline std::string string_attribute(hid_t file, const std::string& path, const std::string& name) {
  const io::h5::Handle attribute{
      io::h5::check_id(H5Aopen_by_name(file, path.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT),
                       name),
      H5Aclose};
  const io::h5::Handle type{io::h5::check_id(H5Tcopy(H5T_C_S1), name), H5Tclose};
  H5Tset_size(type.get(), H5T_VARIABLE);
  H5Tset_cset(type.get(), H5T_CSET_UTF8);
  char* text = nullptr;
  io::h5::check(H5Aread(attribute.get(), type.get(), static_cast<void*>(&text)), name);
  std::string value = text != nullptr ? text : "";
  H5free_memory(text);
  return value;
}

template <typename T>
std::vector<T> numeric_attribute(hid_t file, const std::string& path, const std::string& name) {
  const io::h5::Handle attribute{
      io::h5::check_id(H5Aopen_by_name(file, path.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT),
                       name),
      H5Aclose};
  const io::h5::Handle space{io::h5::check_id(H5Aget_space(attribute.get()), name), H5Sclose};
  std::vector<T> values(static_cast<std::size_t>(H5Sget_simple_extent_npoints(space.get())));
  const hid_t type = std::is_same_v<T, double> ? H5T_NATIVE_DOUBLE : H5T_NATIVE_INT64;
  io::h5::check(H5Aread(attribute.get(), type, values.data()), name);
  return values;
}

/// Whole text file.
inline std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

/// Number of occurrences of `needle` in `text`.
inline int count(const std::string& text, const std::string& needle) {
  int n = 0;
  for (auto at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) ++n;
  return n;
}

/// A fresh, empty directory below the system temporary directory, removed at the end of
/// the test.
class ScratchDirectory {
 public:
  explicit ScratchDirectory(const std::string& name)
      : m_path(std::filesystem::temp_directory_path() /
               ("xpl_results_" + std::to_string(::getpid()) + "_" + name)) {
    std::filesystem::remove_all(m_path);
  }
  ~ScratchDirectory() {
    std::error_code ignored;
    std::filesystem::remove_all(m_path, ignored);
  }
  ScratchDirectory(const ScratchDirectory&) = delete;
  ScratchDirectory& operator=(const ScratchDirectory&) = delete;
  const std::filesystem::path& path() const { return m_path; }

 private:
  std::filesystem::path m_path;
};

}  // namespace xpl::test
