#include "io/results_h5.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace xpl::io {

namespace {

#ifndef XPL_VERSION
#define XPL_VERSION "unknown"
#endif

/// A nodal field as a row-major (n_nodes × 3) buffer, the HDF5 layout.
std::vector<double> row_major(const NodalVectors& field) {
  std::vector<double> out(static_cast<std::size_t>(field.rows()) * 3);
  for (Eigen::Index i = 0; i < field.rows(); ++i) {
    for (int c = 0; c < 3; ++c) out[static_cast<std::size_t>(i) * 3 + c] = field(i, c);
  }
  return out;
}

void check_rows(const NodalVectors& field, Index n_nodes, const char* name) {
  if (field.rows() != n_nodes) {
    throw std::invalid_argument(std::string("write_frame: state field ") + name + " has " +
                                std::to_string(field.rows()) + " rows; the model has " +
                                std::to_string(n_nodes) + " nodes");
  }
}

void write_nodal(hid_t group, const char* name, const NodalVectors& field, Index n_nodes) {
  check_rows(field, n_nodes, name);
  h5::write_real(group, name, row_major(field), {static_cast<hsize_t>(n_nodes), 3});
}

/// Deck ids of the members of a set.
std::vector<std::int64_t> member_ids(const NamedSet& set, const std::vector<ExternalId>& ids) {
  std::vector<std::int64_t> out;
  out.reserve(set.members.size());
  for (Index m : set.members) out.push_back(ids.at(static_cast<std::size_t>(m)));
  return out;
}

/// A set name as an HDF5 link name ('/' would make it a path).
std::string link_name(std::string name) {
  for (char& c : name) {
    if (c == '/') c = '_';
  }
  return name;
}

void write_sets(hid_t mesh, const char* group_name, const std::vector<NamedSet>& sets,
                const std::vector<ExternalId>& ids) {
  const h5::Handle group = h5::require_group(mesh, group_name);
  for (const NamedSet& set : sets) {
    const std::vector<std::int64_t> members = member_ids(set, ids);
    h5::write_int64(group.get(), link_name(set.name), members, {members.size()});
  }
}

}  // namespace

const char* element_type_name(ElementType type) {
  switch (type) {
    case ElementType::C3D8R:
      return "C3D8R";
  }
  return "UNKNOWN";
}

Real von_mises(const Real* s) {
  const Real d1 = s[0] - s[1], d2 = s[1] - s[2], d3 = s[2] - s[0];
  const Real shear = s[3] * s[3] + s[4] * s[4] + s[5] * s[5];
  return std::sqrt(0.5 * (d1 * d1 + d2 * d2 + d3 * d3) + 3.0 * shear);
}

ResultsH5::ResultsH5(const std::filesystem::path& path, const std::string& job)
    : m_path(path.string()) {
  h5::silence_errors();
  const h5::Handle access{h5::check_id(H5Pcreate(H5P_FILE_ACCESS), "cannot create properties"),
                          H5Pclose};
  // The 1.8 format stores attributes larger than 64 KiB (node_ids of wide history series).
  h5::check(H5Pset_libver_bounds(access.get(), H5F_LIBVER_V18, H5F_LIBVER_LATEST),
            "cannot set the file format");
  m_file =
      h5::Handle{h5::check_id(H5Fcreate(m_path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, access.get()),
                              "cannot create " + m_path),
                 H5Fclose};
  h5::set_string_attribute(m_file.get(), "xpl_version", XPL_VERSION);
  h5::set_string_attribute(m_file.get(), "job", job);
  h5::set_string_attribute(m_file.get(), "heading", "");
  h5::set_string_attribute(m_file.get(), "status", "running");
  h5::set_string_attribute(m_file.get(), "error", "");
  flush();
}

void ResultsH5::write_mesh(const Model& model) {
  const hid_t file = m_file.get();
  h5::set_string_attribute(file, "heading", model.heading);
  const h5::Handle mesh = h5::require_group(file, "mesh");
  const auto n_nodes = static_cast<hsize_t>(model.node_count());
  if (model.coordinates.rows() != model.node_count()) {
    throw std::invalid_argument("model coordinates do not match the number of nodes");
  }
  h5::write_int64(mesh.get(), "node_ids", model.node_ids, {n_nodes});
  h5::write_real(mesh.get(), "coordinates", row_major(model.coordinates), {n_nodes, 3});
  h5::write_int64(mesh.get(), "element_ids", model.element_ids, {model.element_ids.size()});

  for (ElementType type : {ElementType::C3D8R}) {
    const auto corners = static_cast<std::size_t>(nodes_per_element(type));
    std::vector<std::int64_t> ids, connectivity;
    for (Index e = 0; e < model.element_count(); ++e) {
      if (model.element_types[static_cast<std::size_t>(e)] != type) continue;
      ids.push_back(model.element_ids[static_cast<std::size_t>(e)]);
      const Index* nodes = model.nodes_of(e);
      connectivity.insert(connectivity.end(), nodes, nodes + corners);
    }
    if (ids.empty()) continue;
    const h5::Handle group = h5::require_group(mesh.get(), element_type_name(type));
    h5::write_int64(group.get(), "element_ids", ids, {ids.size()});
    h5::write_int64(group.get(), "connectivity", connectivity, {ids.size(), corners});
  }
  write_sets(mesh.get(), "node_sets", model.node_sets, model.node_ids);
  write_sets(mesh.get(), "element_sets", model.element_sets, model.element_ids);
  flush();
}

void ResultsH5::begin_step(int step) {
  m_history.end();
  m_step = step;
}

void ResultsH5::declare_history(const std::vector<HistorySeries>& series) {
  if (m_history.active()) {
    throw std::logic_error("declare_history called twice in step " + std::to_string(m_step + 1));
  }
  m_history.begin(m_file.get(), m_step + 1, series);
  flush();
}

void ResultsH5::append_history(Real time, std::span<const Real> values) {
  if (m_history.append(time, values)) flush();
}

std::string ResultsH5::write_frame(const Model& model, const State& state,
                                   const FrameRequest& what) {
  m_history.write_pending();
  char name[16];
  std::snprintf(name, sizeof name, "%06d", m_frames);
  const h5::Handle group = h5::require_group(m_file.get(), std::string("frames/") + name);
  const hid_t g = group.get();
  h5::set_real_attribute(g, "time", state.time);
  h5::set_real_attribute(g, "step_time", state.step_time);
  h5::set_int64_attribute(g, "step", state.step + 1);
  const auto step_index = static_cast<std::size_t>(state.step);
  h5::set_string_attribute(g, "step_name",
                           step_index < model.steps.size() ? model.steps[step_index].name : "");
  h5::set_int64_attribute(g, "increment", state.increment);

  const Index n_nodes = model.node_count();
  const auto n_elements = static_cast<std::size_t>(model.element_count());
  if (what.displacement) {
    check_rows(state.reference, n_nodes, "reference");
    write_nodal(g, "U", state.position - state.reference, n_nodes);
  }
  if (what.velocity) write_nodal(g, "V", state.velocity, n_nodes);
  if (what.acceleration) write_nodal(g, "A", state.acceleration, n_nodes);
  if (what.reaction) write_nodal(g, "RF", state.reaction, n_nodes);
  if (what.stress) {
    if (state.stress.size() != n_elements * 6) {
      throw std::invalid_argument("write_frame: state.stress has " +
                                  std::to_string(state.stress.size()) + " values; expected " +
                                  std::to_string(n_elements * 6));
    }
    h5::write_real(g, "S", state.stress, {n_elements, 6});
    std::vector<double> mises(n_elements);
    for (std::size_t e = 0; e < n_elements; ++e) mises[e] = von_mises(&state.stress[e * 6]);
    h5::write_real(g, "MISES", mises, {n_elements});
  }
  if (what.volume) {
    if (state.volume.size() != n_elements) {
      throw std::invalid_argument("write_frame: state.volume has " +
                                  std::to_string(state.volume.size()) + " values; expected " +
                                  std::to_string(n_elements));
    }
    h5::write_real(g, "EVOL", state.volume, {n_elements});
  }
  ++m_frames;
  flush();
  return name;
}

void ResultsH5::finish(const std::string& status, const std::string& error) {
  m_history.end();
  h5::set_string_attribute(m_file.get(), "status", status);
  h5::set_string_attribute(m_file.get(), "error", error);
  flush();
}

void ResultsH5::flush() {
  h5::check(H5Fflush(m_file.get(), H5F_SCOPE_GLOBAL), "cannot flush " + m_path);
}

}  // namespace xpl::io
