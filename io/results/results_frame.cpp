#include "io/results/results_frame.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "io/results/results_mesh.hpp"
#include "solver/output/output_variables.hpp"

namespace xpl::io {

namespace {

void check_rows(const NodalVectors& field, Index n_nodes, const char* name) {
  if (field.rows() != n_nodes) {
    throw std::invalid_argument(std::string("write_frame: state field ") + name + " has " +
                                std::to_string(field.rows()) + " rows; the model has " +
                                std::to_string(n_nodes) + " nodes");
  }
}

void check_size(const std::vector<Real>& values, std::size_t expected, const char* name) {
  if (values.size() != expected) {
    throw std::invalid_argument(std::string("write_frame: frame field ") + name + " has " +
                                std::to_string(values.size()) + " values; expected " +
                                std::to_string(expected));
  }
}

/// The sizes of the element fields and the nodal fields of the state (check_frame).
void check_fields(const State& state, const FrameFields& fields, const FrameRequest& what,
                  Index n_nodes, std::size_t n_elements, bool shells, bool plastic_shells) {
  if (what.displacement) {
    check_rows(state.reference, n_nodes, "reference");
    check_rows(state.position, n_nodes, "position");
  }
  if (what.velocity) check_rows(state.velocity, n_nodes, "V");
  if (what.acceleration) check_rows(state.acceleration, n_nodes, "A");
  if (what.reaction) check_rows(state.reaction, n_nodes, "RF");
  if (what.stress) {
    check_size(fields.stress, n_elements * 6, "stress");
  }
  if (what.volume) check_size(fields.volume, n_elements, "volume");
  if (what.plastic_strain) check_size(fields.peeq, n_elements, "peeq");
  if (what.plastic_strain && plastic_shells) {
    check_size(fields.peeq_bottom, n_elements, "peeq_bottom");
    check_size(fields.peeq_middle, n_elements, "peeq_middle");
    check_size(fields.peeq_top, n_elements, "peeq_top");
  }
  if (!shells) return;
  if (what.displacement) check_rows(state.rotation, n_nodes, "UR");
  if (what.velocity) check_rows(state.angular_velocity, n_nodes, "VR");
  if (what.reaction) check_rows(state.reaction_moment, n_nodes, "RM");
  if (what.stress) {
    check_size(fields.stress_bottom, n_elements * 6, "stress_bottom");
    check_size(fields.stress_top, n_elements * 6, "stress_top");
    check_rows(state.position, n_nodes, "position");  // the global-axis copies
  }
  if (what.thickness) check_size(fields.thickness, n_elements, "thickness");
}

void check_contact(const FrameFields& fields, const FrameRequest& what, Index n_nodes) {
  const auto n = static_cast<std::size_t>(n_nodes);
  if (what.contact_stress) {
    check_size(fields.contact_pressure, n, "contact_pressure");
    check_rows(fields.contact_shear, n_nodes, "CSHEAR");
  }
  if (what.contact_status) check_size(fields.contact_status, n, "contact_status");
  if (what.contact_force) {
    check_rows(fields.contact_normal_force, n_nodes, "CNORMF");
    check_rows(fields.contact_shear_force, n_nodes, "CSHEARF");
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
std::vector<double> mises_max(const Model& model, const FrameFields& fields) {
  std::vector<double> out = mises_rows(fields.stress);
  for (std::size_t e = 0; e < out.size(); ++e) {
    if (!is_shell(model.element_types[e])) continue;
    out[e] = std::max(
        {out[e], von_mises(&fields.stress_bottom[e * 6]), von_mises(&fields.stress_top[e * 6])});
  }
  return out;
}

/// Writes the frame dataset of `v` from the state and the frame fields.
void write_variable(hid_t group, const OutputVariable& v, const Model& model, const State& state,
                    const FrameFields& fields) {
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
      return write_values(group, v, fields.stress);
    case OutputId::EVOL:
      return write_values(group, v, fields.volume);
    case OutputId::MISES:
      return write_values(group, v, mises_rows(fields.stress));
    case OutputId::MISES_SNEG:
      return write_values(group, v, mises_rows(fields.stress_bottom));
    case OutputId::MISES_SPOS:
      return write_values(group, v, mises_rows(fields.stress_top));
    case OutputId::MISES_MAX:
      return write_values(group, v, mises_max(model, fields));
    case OutputId::STH:
      return write_values(group, v, fields.thickness);
    case OutputId::PEEQ:
      return write_values(group, v, fields.peeq);
    case OutputId::S_SNEG:
      return write_values(group, v, fields.stress_bottom);
    case OutputId::S_SPOS:
      return write_values(group, v, fields.stress_top);
    case OutputId::PEEQ_SNEG:
      return write_values(group, v, fields.peeq_bottom);
    case OutputId::PEEQ_SMID:
      return write_values(group, v, fields.peeq_middle);
    case OutputId::PEEQ_SPOS:
      return write_values(group, v, fields.peeq_top);
    case OutputId::CPRESS:
      return write_values(group, v, fields.contact_pressure);
    case OutputId::CSHEAR:
      return write_nodal(group, v, fields.contact_shear);
    case OutputId::CSTATUS:
      return write_values(group, v, fields.contact_status);
    case OutputId::CNORMF:
      return write_nodal(group, v, fields.contact_normal_force);
    case OutputId::CSHEARF:
      return write_nodal(group, v, fields.contact_shear_force);
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

/// Writes /xdmf/NNNNNN (`path`): the tensors the XDMF file shows, in VTK order, in global axes
/// (S, S_SNEG, S_SPOS) and, on shell models, the shells' local-axes ones (S_LOCAL, ...; NaN
/// rows for solids). The datasets of /frames/NNNNNN keep the Abaqus order; the copies live
/// outside the frame group so that a frame holds datasets only, as before. Each copy is made
/// (global_axis_rows at `position`) and written in turn in one buffer, so that a frame holds
/// one n_elements × 6 array more than its fields, not six.
void write_xdmf_tensors(hid_t file, const std::string& path, const Model& model,
                        const NodalVectors& position, const FrameFields& fields) {
  const h5::Handle group = h5::require_group(file, path);
  const bool shells = model.has_shells();
  const auto n = static_cast<std::size_t>(model.element_count());
  struct Tensor {
    const char* name;
    const std::vector<Real>* rows;  ///< Abaqus order, local axes on shells
  };
  const Tensor tensors[] = {
      {"S", &fields.stress}, {"S_SNEG", &fields.stress_bottom}, {"S_SPOS", &fields.stress_top}};
  const std::string global_names = "XX,YY,ZZ,XY,YZ,XZ";
  std::vector<double> copy;
  for (const Tensor& t : tensors) {
    if (!shells && t.rows != &fields.stress) continue;
    const std::string name = t.name;
    global_axis_rows(model, position, *t.rows, copy);
    h5::write_real(group.get(), name, copy, {n, 6});
    describe(group.get(), name, global_names, "Pa",
             "copy of " + name + " for the XDMF file: global axes, VTK order");
    if (!shells) continue;
    copy.assign(n * 6, std::nan(""));
    for (std::size_t e = 0; e < n; ++e)
      if (is_shell(model.element_types[e])) to_vtk(&(*t.rows)[e * 6], &copy[e * 6]);
    h5::write_real(group.get(), name + "_LOCAL", copy, {n, 6});
    describe(group.get(), name + "_LOCAL", "11,22,33,12,23,13", "Pa",
             "copy of " + name +
                 " for the XDMF file: shells only (NaN rows for solids), local shell axes, VTK "
                 "order");
  }
}

}  // namespace

Real von_mises(const Real* s) {
  const Real d1 = s[0] - s[1], d2 = s[1] - s[2], d3 = s[2] - s[0];
  const Real shear = s[3] * s[3] + s[4] * s[4] + s[5] * s[5];
  return std::sqrt(0.5 * (d1 * d1 + d2 * d2 + d3 * d3) + 3.0 * shear);
}

void check_frame(const Model& model, const State& state, const FrameFields& fields,
                 const FrameRequest& what) {
  // A scan of one byte per element: negligible next to the fields of a frame.
  const auto n_elements = static_cast<std::size_t>(model.element_count());
  check_fields(state, fields, what, model.node_count(), n_elements, model.has_shells(),
               model.has_plastic_shells());
  check_contact(fields, what, model.node_count());
}

void write_frame_datasets(hid_t file, hid_t g, const std::string& name, const Model& model,
                          const State& state, const FrameFields& fields, const FrameRequest& what,
                          const ModelUnits& units) {
  for (const OutputVariable* v : frame_variables(what, output_scope(model))) {
    write_variable(g, *v, model, state, fields);
    describe(g, std::string(v->name), component_list(*v), units.label(v->unit), v->description);
  }
  if (what.stress) write_xdmf_tensors(file, "xdmf/" + name, model, state.position, fields);
  if (what.stress && !fields.hourglass_state.empty()) {
    // Not an output variable (not in the XDMF): the elements' internal hourglass state, for
    // --import (io/result_tools/import_state.hpp).
    const auto n_elements = static_cast<std::size_t>(model.element_count());
    const auto width = static_cast<std::size_t>(FrameFields::HOURGLASS_WIDTH);
    check_size(fields.hourglass_state, n_elements * width, "hourglass_state");
    h5::write_real(g, "HGSTATE", fields.hourglass_state, {n_elements, width});
  }
}

}  // namespace xpl::io
