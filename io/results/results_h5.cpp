#include "io/results/results_h5.hpp"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <system_error>
#include <thread>

#include "elements/lane_state.hpp"
#include "elements/shell/quad_shell_geometry.hpp"
#include "io/results/results_mesh.hpp"
#include "solver/output_variables.hpp"

namespace xpl::io {

namespace {

#ifndef XPL_VERSION
#define XPL_VERSION "unknown"
#endif

void check_rows(const NodalVectors& field, Index n_nodes, const char* name) {
  if (field.rows() != n_nodes) {
    throw std::invalid_argument(std::string("write_frame: state field ") + name + " has " +
                                std::to_string(field.rows()) + " rows; the model has " +
                                std::to_string(n_nodes) + " nodes");
  }
}

void check_size(const std::vector<Real>& values, std::size_t expected, const char* name) {
  if (values.size() != expected) {
    throw std::invalid_argument(std::string("write_frame: state.") + name + " has " +
                                std::to_string(values.size()) + " values; expected " +
                                std::to_string(expected));
  }
}

/// Throws std::invalid_argument, before anything is written, if a field the frame needs does
/// not have the size of the model.
void check_frame(const State& state, const FrameRequest& what, Index n_nodes,
                 std::size_t n_elements, bool shells, bool plastic_shells) {
  if (what.displacement) {
    check_rows(state.reference, n_nodes, "reference");
    check_rows(state.position, n_nodes, "position");
  }
  if (what.velocity) check_rows(state.velocity, n_nodes, "V");
  if (what.acceleration) check_rows(state.acceleration, n_nodes, "A");
  if (what.reaction) check_rows(state.reaction, n_nodes, "RF");
  if (what.stress) check_size(state.stress, n_elements * 6, "stress");
  if (what.volume) check_size(state.volume, n_elements, "volume");
  if (what.plastic_strain) check_size(state.peeq, n_elements, "peeq");
  if (what.plastic_strain && plastic_shells) {
    check_size(state.peeq_bottom, n_elements, "peeq_bottom");
    check_size(state.peeq_middle, n_elements, "peeq_middle");
    check_size(state.peeq_top, n_elements, "peeq_top");
  }
  if (!shells) return;
  if (what.displacement) check_rows(state.rotation, n_nodes, "UR");
  if (what.velocity) check_rows(state.angular_velocity, n_nodes, "VR");
  if (what.reaction) check_rows(state.reaction_moment, n_nodes, "RM");
  if (what.stress) {
    check_size(state.stress_bottom, n_elements * 6, "stress_bottom");
    check_size(state.stress_top, n_elements * 6, "stress_top");
  }
  if (what.thickness) check_size(state.thickness, n_elements, "thickness");
}

void check_contact(const State& state, const FrameRequest& what, Index n_nodes) {
  const auto n = static_cast<std::size_t>(n_nodes);
  if (what.contact_stress) {
    check_size(state.contact_pressure, n, "contact_pressure");
    check_rows(state.contact_shear, n_nodes, "CSHEAR");
  }
  if (what.contact_status) check_size(state.contact_status, n, "contact_status");
  if (what.contact_force) {
    check_rows(state.contact_normal_force, n_nodes, "CNORMF");
    check_rows(state.contact_shear_force, n_nodes, "CSHEARF");
  }
}

/// Writes the values of `v` (rows × v.width, row-major; width 1: one-dimensional).
void write_values(hid_t group, const OutputVariable& v, const std::vector<Real>& values) {
  const auto width = static_cast<std::size_t>(v.width);
  std::vector<hsize_t> dims{values.size() / width};
  if (width > 1) dims.push_back(width);
  h5::write_real(group, std::string(v.name), values, dims);
}

void write_nodal(hid_t group, const OutputVariable& v, const NodalVectors& field) {
  write_values(group, v, row_major(field));
}

/// Von Mises stress of every stress row of `stress` (rows of 6; NaN rows give NaN).
std::vector<double> mises_rows(const std::vector<Real>& stress) {
  std::vector<double> mises(stress.size() / 6);
  for (std::size_t e = 0; e < mises.size(); ++e) mises[e] = von_mises(&stress[e * 6]);
  return mises;
}

/// Largest von Mises stress through the thickness: of S_SNEG, S and S_SPOS on shells, of S on
/// solids (whose S_SNEG and S_SPOS rows are NaN).
std::vector<double> mises_max(const Model& model, const State& state) {
  std::vector<double> out = mises_rows(state.stress);
  for (std::size_t e = 0; e < out.size(); ++e) {
    if (!is_shell(model.element_types[e])) continue;
    out[e] = std::max(
        {out[e], von_mises(&state.stress_bottom[e * 6]), von_mises(&state.stress_top[e * 6])});
  }
  return out;
}

/// Writes the frame dataset of `v` from the state.
void write_variable(hid_t group, const OutputVariable& v, const Model& model, const State& state) {
  switch (v.id) {
    case OutputId::U:
      return write_nodal(group, v, state.position - state.reference);
    case OutputId::V:
      return write_nodal(group, v, state.velocity);
    case OutputId::A:
      return write_nodal(group, v, state.acceleration);
    case OutputId::RF:
      return write_nodal(group, v, state.reaction);
    case OutputId::UR:
      return write_nodal(group, v, state.rotation);
    case OutputId::VR:
      return write_nodal(group, v, state.angular_velocity);
    case OutputId::RM:
      return write_nodal(group, v, state.reaction_moment);
    case OutputId::S:
      return write_values(group, v, state.stress);
    case OutputId::EVOL:
      return write_values(group, v, state.volume);
    case OutputId::MISES:
      return write_values(group, v, mises_rows(state.stress));
    case OutputId::MISES_SNEG:
      return write_values(group, v, mises_rows(state.stress_bottom));
    case OutputId::MISES_SPOS:
      return write_values(group, v, mises_rows(state.stress_top));
    case OutputId::MISES_MAX:
      return write_values(group, v, mises_max(model, state));
    case OutputId::STH:
      return write_values(group, v, state.thickness);
    case OutputId::PEEQ:
      return write_values(group, v, state.peeq);
    case OutputId::S_SNEG:
      return write_values(group, v, state.stress_bottom);
    case OutputId::S_SPOS:
      return write_values(group, v, state.stress_top);
    case OutputId::PEEQ_SNEG:
      return write_values(group, v, state.peeq_bottom);
    case OutputId::PEEQ_SMID:
      return write_values(group, v, state.peeq_middle);
    case OutputId::PEEQ_SPOS:
      return write_values(group, v, state.peeq_top);
    case OutputId::CPRESS:
      return write_values(group, v, state.contact_pressure);
    case OutputId::CSHEAR:
      return write_nodal(group, v, state.contact_shear);
    case OutputId::CSTATUS:
      return write_values(group, v, state.contact_status);
    case OutputId::CNORMF:
      return write_nodal(group, v, state.contact_normal_force);
    case OutputId::CSHEARF:
      return write_nodal(group, v, state.contact_shear_force);
    case OutputId::CFN:
    case OutputId::CFS:
      break;
  }
  throw std::logic_error("write_frame: " + std::string(v.name) + " is not field output");
}

/// Comma-separated component names of `v` ("S11,S22,S33,S12,S13,S23").
std::string component_list(const OutputVariable& v) {
  std::string out;
  for (int c = 0; c < v.width; ++c) {
    if (c > 0) out += ",";
    out += v.components[static_cast<std::size_t>(c)];
  }
  return out;
}

/// Describes dataset `name` of `group`: its components, unit and meaning (attributes only).
void describe(hid_t group, const std::string& name, const std::string& components,
              std::string_view unit, std::string_view description) {
  const h5::Handle data{
      h5::check_id(H5Dopen2(group, name.c_str(), H5P_DEFAULT), "cannot open " + name), H5Dclose};
  h5::set_string_attribute(data.get(), "components", components);
  h5::set_string_attribute(data.get(), "units", std::string(unit));
  h5::set_string_attribute(data.get(), "description", std::string(description));
}

/// Component order of the XDMF copies of a tensor: VTK's Tensor6 (XX YY ZZ XY YZ XZ), i.e.
/// the Abaqus rows S11 S22 S33 S12 S23 S13.
constexpr int VTK_ORDER[6] = {0, 1, 2, 3, 5, 4};

/// One stress row (Abaqus order) in VTK order.
void to_vtk(const Real* abaqus, Real* vtk) {
  for (int c = 0; c < 6; ++c) vtk[c] = abaqus[VTK_ORDER[c]];
}

/// The stress row `local` (Abaqus order, axes e1 e2 e3) in global axes (Abaqus order):
/// σ_ij = Σ_ab E_ai σ_ab E_bj with E the rows e1, e2, e3.
void to_global(const elements::QuadFrame<Real>& f, const Real* local, Real* global) {
  const Real E[3][3] = {
      {f.e1.x, f.e1.y, f.e1.z}, {f.e2.x, f.e2.y, f.e2.z}, {f.e3.x, f.e3.y, f.e3.z}};
  const Real L[3][3] = {{local[0], local[3], local[4]},
                        {local[3], local[1], local[5]},
                        {local[4], local[5], local[2]}};
  Real G[3][3] = {};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) G[i][j] += E[a][i] * L[a][b] * E[b][j];
  const Real out[6] = {G[0][0], G[1][1], G[2][2], G[0][1], G[0][2], G[1][2]};
  std::copy(out, out + 6, global);
}

/// Writes /xdmf/NNNNNN (`path`): the tensors the XDMF file shows, in VTK order, in global axes
/// (S, S_SNEG, S_SPOS) and, on shell models, the shells' local-axes ones (S_LOCAL, ...; NaN
/// rows for solids). The datasets of /frames/NNNNNN keep the Abaqus order; the copies live
/// outside the frame group so that a frame holds datasets only, as before.
void write_xdmf_tensors(hid_t file, const std::string& path, const Model& model,
                        const State& state) {
  const h5::Handle group = h5::require_group(file, path);
  const bool shells = model.has_shells();
  const auto n = static_cast<std::size_t>(model.element_count());
  struct Tensor {
    const char* name;
    const std::vector<Real>* rows;
  };
  const Tensor tensors[] = {
      {"S", &state.stress}, {"S_SNEG", &state.stress_bottom}, {"S_SPOS", &state.stress_top}};
  const std::string global_names = "XX,YY,ZZ,XY,YZ,XZ";
  for (const Tensor& t : tensors) {
    if (!shells && t.rows != &state.stress) continue;
    std::vector<double> global(n * 6), local;
    if (shells) local.assign(n * 6, std::nan(""));
    for (std::size_t e = 0; e < n; ++e) {
      const Real* row = &(*t.rows)[e * 6];
      const auto type = model.element_types[e];
      if (!is_shell(type)) {
        to_vtk(row, &global[e * 6]);
        continue;
      }
      const Index* nodes = model.nodes_of(static_cast<Index>(e));
      elements::V3<Real> p[4];
      for (int k = 0; k < 4; ++k)
        p[k] = {state.position(nodes[k], 0), state.position(nodes[k], 1),
                state.position(nodes[k], 2)};
      Real rotated[6];
      to_global(elements::quad_frame(p), row, rotated);
      to_vtk(rotated, &global[e * 6]);
      to_vtk(row, &local[e * 6]);
    }
    const std::string name = t.name;
    h5::write_real(group.get(), name, global, {n, 6});
    describe(group.get(), name, global_names, "Pa",
             "copy of " + name + " for the XDMF file: global axes, VTK order");
    if (!shells) continue;
    h5::write_real(group.get(), name + "_LOCAL", local, {n, 6});
    describe(group.get(), name + "_LOCAL", "11,22,33,12,23,13", "Pa",
             "copy of " + name +
                 " for the XDMF file: shells only (NaN rows for solids), local shell axes, VTK "
                 "order");
  }
}

/// Writes the status attributes of the open `file`.
void write_status(hid_t file, const std::string& status, const std::string& error,
                  std::optional<double> time_reached) {
  h5::set_string_attribute(file, "status", status);
  h5::set_string_attribute(file, "error", error);
  if (time_reached) h5::set_real_attribute(file, "time_reached", *time_reached);
}

}  // namespace

Real von_mises(const Real* s) {
  const Real d1 = s[0] - s[1], d2 = s[1] - s[2], d3 = s[2] - s[0];
  const Real shear = s[3] * s[3] + s[4] * s[4] + s[5] * s[5];
  return std::sqrt(0.5 * (d1 * d1 + d2 * d2 + d3 * d3) + 3.0 * shear);
}

ResultsH5::ResultsH5(const std::filesystem::path& path, const std::string& job)
    : m_path(path.string()) {
  h5::silence_errors();
  m_access =
      h5::Handle{h5::check_id(H5Pcreate(H5P_FILE_ACCESS), "cannot create properties"), H5Pclose};
  // The 1.8 format stores attributes larger than 64 KiB (node_ids of wide history series). It
  // also has no "open for writing" flag in the superblock, which would make a file whose
  // writer was killed unreadable until h5clear.
  h5::check(H5Pset_libver_bounds(m_access.get(), H5F_LIBVER_V18, H5F_LIBVER_LATEST),
            "cannot set the file format");
  // Closing the file closes every object still open in it: no handle kept by mistake can
  // keep the file, and its lock, open between writes.
  h5::check(H5Pset_fclose_degree(m_access.get(), H5F_CLOSE_STRONG), "cannot set the close mode");
  // A reader (ParaView, h5py) may still hold the previous run's file open: unlink it rather
  // than truncate it, so that the new run does not wait for the reader's lock and the reader
  // keeps the old, complete file. JOB.lck (job_lock.hpp) keeps one run per job and directory.
  std::error_code ignored;
  std::filesystem::remove(path, ignored);
  h5::Handle file{
      h5::check_id(H5Fcreate(m_path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, m_access.get()),
                   "cannot create " + m_path),
      H5Fclose};
  h5::set_string_attribute(file.get(), "xpl_version", XPL_VERSION);
  h5::set_string_attribute(file.get(), "job", job);
  h5::set_string_attribute(file.get(), "heading", "");
  h5::set_string_attribute(file.get(), "status", "running");
  h5::set_string_attribute(file.get(), "error", "");
  h5::check(H5Fclose(file.release()), "cannot close " + m_path);
}

void ResultsH5::with_file(const std::function<void(hid_t)>& write) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  const auto waited = [&start] {
    return std::chrono::duration<double>(Clock::now() - start).count();
  };
  hid_t id = -1;
  for (int attempt = 0;; ++attempt) {
    id = H5Fopen(m_path.c_str(), H5F_ACC_RDWR, m_access.get());
    if (id >= 0) break;
    // HDF5's lock: a reader has the file open; wait for it. Anything else fails now.
    if (!h5::lock_refused()) h5::fail("cannot open " + m_path + " for writing");
    if (waited() > LOCK_WAIT) {
      h5::fail("cannot open " + m_path + " for writing: another process kept it open for " +
               std::to_string(static_cast<int>(LOCK_WAIT)) +
               " s (readers must close it between reads)");
    }
    H5Eclear2(H5E_DEFAULT);
    std::this_thread::sleep_for(std::chrono::milliseconds(std::min(1 << std::min(attempt, 6), 50)));
  }
  h5::Handle file{id, H5Fclose};
  if (const double seconds = waited(); seconds > LOCK_NOTICE && m_wait_notice) {
    char duration[32];
    std::snprintf(duration, sizeof duration, "%.1f s", seconds);
    m_wait_notice("the run waited " + std::string(duration) +
                  " for another process (a reader) to close " + m_path);
  }
  write(id);
  h5::check(H5Fflush(id, H5F_SCOPE_GLOBAL), "cannot flush " + m_path);
  h5::check(H5Fclose(file.release()), "cannot close " + m_path);
}

XdmfMesh ResultsH5::write_mesh(const Model& model) {
  XdmfMesh mesh;
  m_units = model.units;
  with_file([&](hid_t file) {
    h5::set_string_attribute(file, "heading", model.heading);
    // The numbers are the deck's; these say in which units (common/units.hpp).
    h5::set_string_attribute(file, "unit_system", m_units.system_name());
    h5::set_string_attribute(file, "units",
                             m_units.explanation.empty() ? m_units.summary() : m_units.explanation);
    mesh = write_mesh_group(file, model);
    const h5::Handle coordinates{h5::check_id(H5Dopen2(file, "mesh/coordinates", H5P_DEFAULT),
                                              "cannot open /mesh/coordinates"),
                                 H5Dclose};
    h5::set_string_attribute(coordinates.get(), "units", m_units.label("m"));
  });
  return mesh;
}

void ResultsH5::begin_step(int step) {
  if (m_history.pending()) with_file([&](hid_t file) { m_history.write_pending(file); });
  m_history.end();
  m_step = step;
}

void ResultsH5::declare_history(const std::vector<HistorySeries>& series) {
  if (m_history.active()) {
    throw std::logic_error("declare_history called twice in step " + std::to_string(m_step + 1));
  }
  with_file([&](hid_t file) { m_history.begin(file, m_step + 1, series, m_units); });
}

void ResultsH5::append_history(Real time, std::span<const Real> values) {
  if (m_history.append(time, values)) with_file([&](hid_t file) { m_history.write_pending(file); });
}

std::string ResultsH5::write_frame(const Model& model, const State& state,
                                   const FrameRequest& what) {
  // A scan of one byte per element: negligible next to the fields of a frame.
  const bool shells = model.has_shells();
  const auto n_elements = static_cast<std::size_t>(model.element_count());
  check_frame(state, what, model.node_count(), n_elements, shells, model.has_plastic_shells());
  check_contact(state, what, model.node_count());
  char name[16];
  std::snprintf(name, sizeof name, "%06d", m_frames);
  with_file([&](hid_t file) {
    // The history rows up to the frame go with it: a reader sees both up to the same time.
    m_history.write_pending(file);
    const h5::Handle group = h5::require_group(file, std::string("frames/") + name);
    const hid_t g = group.get();
    h5::set_real_attribute(g, "time", state.time);
    h5::set_real_attribute(g, "step_time", state.step_time);
    h5::set_int64_attribute(g, "step", state.step + 1);
    const auto step_index = static_cast<std::size_t>(state.step);
    h5::set_string_attribute(g, "step_name",
                             step_index < model.steps.size() ? model.steps[step_index].name : "");
    h5::set_int64_attribute(g, "increment", state.increment);

    for (const OutputVariable* v : frame_variables(what, output_scope(model))) {
      write_variable(g, *v, model, state);
      describe(g, std::string(v->name), component_list(*v), m_units.label(v->unit), v->description);
    }
    if (what.stress) write_xdmf_tensors(file, std::string("xdmf/") + name, model, state);
    if (what.stress && !state.hourglass_state.empty()) {
      // Not an output variable (not in the XDMF): the elements' internal hourglass state, for
      // --import (io/results/import_state.hpp).
      const auto width = static_cast<std::size_t>(elements::HOURGLASS_STATE_WIDTH);
      check_size(state.hourglass_state, n_elements * width, "hourglass_state");
      h5::write_real(g, "HGSTATE", state.hourglass_state, {n_elements, width});
    }
  });
  ++m_frames;
  return name;
}

std::string ResultsH5::with_length_unit(const std::string& text) const {
  const std::string length = m_units.label("m");
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const bool alone =
        text[i] == 'm' && (i == 0 || !std::isalnum(static_cast<unsigned char>(text[i - 1]))) &&
        (i + 1 == text.size() || !std::isalnum(static_cast<unsigned char>(text[i + 1])));
    out += alone ? length : std::string(1, text[i]);
  }
  return out;
}

void ResultsH5::write_table(const ResultTable& table) {
  with_file([&](hid_t file) {
    const h5::Handle group = h5::require_group(file, table.path);
    if (!table.description.empty())
      h5::set_string_attribute(group.get(), "description", table.description);
    h5::set_int64_attribute(group.get(), "rows", table.rows);
    for (const auto& [name, value] : table.attributes)
      h5::set_string_attribute(group.get(), name, value);
    for (const TableColumn& c : table.columns) {
      const std::vector<hsize_t> dims = c.width == 1
                                            ? std::vector<hsize_t>{static_cast<hsize_t>(table.rows)}
                                            : std::vector<hsize_t>{static_cast<hsize_t>(table.rows),
                                                                   static_cast<hsize_t>(c.width)};
      if (c.integer)
        h5::write_int64(group.get(), c.name, c.ids, dims);
      else
        h5::write_real(group.get(), c.name, c.values, dims);
      if (!c.description.empty()) {
        const h5::Handle data =
            h5::Handle(h5::check_id(H5Dopen2(group.get(), c.name.c_str(), H5P_DEFAULT),
                                    "cannot open " + c.name),
                       H5Dclose);
        // The solver describes lengths in m (SI): in the model's units instead.
        h5::set_string_attribute(data.get(), "description",
                                 c.integer ? c.description : with_length_unit(c.description));
      }
    }
  });
}

void ResultsH5::finish(const std::string& status, const std::string& error,
                       std::optional<double> time_reached) {
  // The last history rows and the status in one write: a reader that sees "completed" sees
  // the whole history.
  with_file([&](hid_t file) {
    m_history.write_pending(file);
    write_status(file, status, error, time_reached);
  });
  m_history.end();
}

void ResultsH5::record_status(const std::string& status, const std::string& error,
                              std::optional<double> time_reached) {
  with_file([&](hid_t file) { write_status(file, status, error, time_reached); });
}

void ResultsH5::write_summary(const JsonValue& summary) {
  with_file([&](hid_t file) {
    const h5::Handle group = h5::require_group(file, "summary");
    const auto write = [&](const auto& self, const JsonValue& value,
                           const std::string& key) -> void {
      if (const auto* members = value.as_object()) {
        for (const auto& [name, member] : *members)
          self(self, member, key.empty() ? name : key + "." + name);
      } else if (const bool* b = value.as_bool()) {
        h5::set_int64_attribute(group.get(), key, *b ? 1 : 0);
      } else if (const std::int64_t* i = value.as_int()) {
        h5::set_int64_attribute(group.get(), key, *i);
      } else if (const double* d = value.as_double()) {
        h5::set_real_attribute(group.get(), key, *d);
      } else if (const std::string* s = value.as_string()) {
        h5::set_string_attribute(group.get(), key, *s);
      } else if (value.is_null()) {
        h5::set_real_attribute(group.get(), key, std::nan(""));
      }
      // Arrays: the summary has none.
    };
    write(write, summary, "");
  });
}

}  // namespace xpl::io
