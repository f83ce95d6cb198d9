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
  // Element fields from a source are checked as the writer takes them (element_rows).
  const bool held = fields.source == nullptr;
  if (what.stress && held) check_size(fields.stress, n_elements * 6, "stress");
  if (what.volume && held) check_size(fields.volume, n_elements, "volume");
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
  if (what.stress && held) {
    check_size(fields.stress_bottom, n_elements * 6, "stress_bottom");
    check_size(fields.stress_top, n_elements * 6, "stress_top");
  }
  if (what.stress) check_rows(state.position, n_nodes, "position");  // the global-axis copies
  if (what.thickness && held) check_size(fields.thickness, n_elements, "thickness");
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

/// Which rows of a dataset are rows of nodes or of elements (FrameRows).
enum class RowsOf { Nodes, Elements };

/// Writes the datasets of a frame: whole, or, when the ranks of a distributed run write the
/// file together, each rank its rows (FrameRows) where they belong.
class RowWriter {
 public:
  explicit RowWriter(const FrameRows& rows) : m_collective(rows.collective) {
    for (const auto& [first, count] : rows.nodes)
      m_nodes.emplace_back(static_cast<hsize_t>(first), static_cast<hsize_t>(count));
    for (const auto& [first, count] : rows.elements)
      m_elements.emplace_back(static_cast<hsize_t>(first), static_cast<hsize_t>(count));
  }
  void write(hid_t group, const std::string& name, const std::vector<Real>& values,
             const std::vector<hsize_t>& dims, RowsOf rows) const {
    if (!m_collective) return h5::write_real(group, name, values, dims);
    h5::write_real_rows(group, name, values, dims, rows == RowsOf::Nodes ? m_nodes : m_elements);
  }

 private:
  bool m_collective;
  h5::RowRuns m_nodes, m_elements;
};

/// Writes the values of `v` (rows × v.width, row-major; width 1: one-dimensional).
void write_values(const RowWriter& out, hid_t group, const OutputVariable& v,
                  const std::vector<Real>& values, RowsOf rows) {
  const auto width = static_cast<std::size_t>(v.width);
  std::vector<hsize_t> dims{values.size() / width};
  if (width > 1) dims.push_back(width);
  out.write(group, std::string(v.name), values, dims, rows);
}

void write_nodal(const RowWriter& out, hid_t group, const OutputVariable& v,
                 const NodalVectors& field) {
  write_values(out, group, v, row_major(field), RowsOf::Nodes);
}

/// Von Mises stress of every stress row of `stress` (rows of 6; NaN rows give NaN).
std::vector<double> mises_rows(const std::vector<Real>& stress) {
  std::vector<double> mises(stress.size() / 6);
  for (std::size_t e = 0; e < mises.size(); ++e) mises[e] = von_mises(&stress[e * 6]);
  return mises;
}

/// The rows of element field `field` of the frame (`name` for the error), `width` values per
/// element: held by `fields` or pulled from its source into `buffer`.
const std::vector<Real>& element_rows(const Model& model, const FrameFields& fields,
                                      ElementField field, std::size_t width, const char* name,
                                      std::vector<Real>& buffer) {
  const std::vector<Real>& rows = fields.element_rows(field, buffer);
  check_size(rows, static_cast<std::size_t>(model.element_count()) * width, name);
  return rows;
}

/// Writes the frame dataset of `v` from the state and the frame fields.
void write_variable(const RowWriter& out, hid_t group, const OutputVariable& v, const Model& model,
                    const State& state, const FrameFields& fields) {
  switch (v.id) {
    case OutputId::U:
      return write_nodal(out, group, v, state.position - state.reference);
    case OutputId::V:
      return write_nodal(out, group, v, state.velocity);
    case OutputId::A:
      return write_nodal(out, group, v, state.acceleration);
    case OutputId::RF:
      return write_nodal(out, group, v, state.reaction);
    case OutputId::UR:
      return write_nodal(out, group, v, state.rotation);
    case OutputId::VR:
      return write_nodal(out, group, v, state.angular_velocity);
    case OutputId::RM:
      return write_nodal(out, group, v, state.reaction_moment);
    case OutputId::EVOL: {
      std::vector<Real> buffer;
      return write_values(out, group, v,
                          element_rows(model, fields, ElementField::Volume, 1, "volume", buffer),
                          RowsOf::Elements);
    }
    case OutputId::STH: {
      std::vector<Real> buffer;
      return write_values(
          out, group, v,
          element_rows(model, fields, ElementField::Thickness, 1, "thickness", buffer),
          RowsOf::Elements);
    }
    case OutputId::PEEQ:
      return write_values(out, group, v, fields.peeq, RowsOf::Elements);
    case OutputId::S:
    case OutputId::MISES:
    case OutputId::S_SNEG:
    case OutputId::S_SPOS:
    case OutputId::MISES_SNEG:
    case OutputId::MISES_SPOS:
    case OutputId::MISES_MAX:
      break;  // write_stresses
    case OutputId::PEEQ_SNEG:
      return write_values(out, group, v, fields.peeq_bottom, RowsOf::Elements);
    case OutputId::PEEQ_SMID:
      return write_values(out, group, v, fields.peeq_middle, RowsOf::Elements);
    case OutputId::PEEQ_SPOS:
      return write_values(out, group, v, fields.peeq_top, RowsOf::Elements);
    case OutputId::CPRESS:
      return write_values(out, group, v, fields.contact_pressure, RowsOf::Nodes);
    case OutputId::CSHEAR:
      return write_nodal(out, group, v, fields.contact_shear);
    case OutputId::CSTATUS:
      return write_values(out, group, v, fields.contact_status, RowsOf::Nodes);
    case OutputId::CNORMF:
      return write_nodal(out, group, v, fields.contact_normal_force);
    case OutputId::CSHEARF:
      return write_nodal(out, group, v, fields.contact_shear_force);
    case OutputId::CFN:
    case OutputId::CFS:
      break;
  }
  throw std::logic_error("write_frame: " + std::string(v.name) +
                         " is not field output written alone");
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

/// Whether stress output variable `id` is one the frame writes (it is in `variables`).
bool written(const std::vector<const OutputVariable*>& variables, OutputId id) {
  return std::any_of(variables.begin(), variables.end(),
                     [id](const OutputVariable* v) { return v->id == id; });
}

/// Writes `v` (`values`) into `group` and describes it.
void write_described(const RowWriter& out, hid_t group, const OutputVariable& v,
                     const std::vector<Real>& values, const ModelUnits& units) {
  write_values(out, group, v, values, RowsOf::Elements);
  describe(group, std::string(v.name), component_list(v), units.label(v.unit), v.description);
}

/// Writes the stress datasets among `variables` into the frame group `g` (S, MISES, and on
/// shell models S_SNEG, S_SPOS, MISES_SNEG, MISES_SPOS, MISES_MAX) and /xdmf/NNNNNN (`path`):
/// the tensors the XDMF file shows, in VTK order, in global axes (S, S_SNEG, S_SPOS) and, on
/// shell models, the shells' local-axes ones (S_LOCAL, ...; NaN rows for solids). The datasets
/// of /frames/NNNNNN keep the Abaqus order; the copies live outside the frame group so that a
/// frame holds datasets only, as before. Tensor by tensor: each is taken once
/// (element_rows, pulled from the elements in a one-process run) and written with its von
/// Mises stress and its XDMF copies (global_axis_rows at `position`, one buffer) before the
/// next, so that a frame holds one tensor, one copy and MISES_MAX at a time.
void write_stresses(const RowWriter& out, hid_t file, hid_t g, const std::string& path,
                    const Model& model, const NodalVectors& position, const FrameFields& fields,
                    const std::vector<const OutputVariable*>& variables, const ModelUnits& units) {
  const h5::Handle group = h5::require_group(file, path);
  const bool shells = model.has_shells();
  const auto n = static_cast<std::size_t>(model.element_count());
  struct Tensor {
    ElementField field;
    OutputId rows, mises;
    const char* field_name;  ///< the FrameFields member, for the size check
  };
  const Tensor tensors[] = {
      {ElementField::Stress, OutputId::S, OutputId::MISES, "stress"},
      {ElementField::StressBottom, OutputId::S_SNEG, OutputId::MISES_SNEG, "stress_bottom"},
      {ElementField::StressTop, OutputId::S_SPOS, OutputId::MISES_SPOS, "stress_top"}};
  const std::string global_names = "XX,YY,ZZ,XY,YZ,XZ";
  const bool maximum = written(variables, OutputId::MISES_MAX);
  // Largest von Mises stress through the thickness: of S, S_SNEG and S_SPOS on shells (in
  // that order, as std::max of the three), of S on solids (whose S_SNEG and S_SPOS are NaN).
  std::vector<double> mises_max;
  std::vector<Real> buffer, copy;
  for (const Tensor& t : tensors) {
    if (!shells && t.field != ElementField::Stress) continue;
    const std::vector<Real>& rows = element_rows(model, fields, t.field, 6, t.field_name, buffer);
    if (written(variables, t.rows)) write_described(out, g, output_variable(t.rows), rows, units);
    if (written(variables, t.mises) || maximum) {
      std::vector<double> mises = mises_rows(rows);
      if (written(variables, t.mises))
        write_described(out, g, output_variable(t.mises), mises, units);
      if (maximum && t.field == ElementField::Stress) {
        mises_max = std::move(mises);
      } else if (maximum) {
        for (std::size_t e = 0; e < n; ++e)
          if (is_shell(model.element_types[e])) mises_max[e] = std::max(mises_max[e], mises[e]);
      }
    }
    const std::string name(output_variable(t.rows).name);
    global_axis_rows(model, position, rows, copy);
    out.write(group.get(), name, copy, {n, 6}, RowsOf::Elements);
    describe(group.get(), name, global_names, "Pa",
             "copy of " + name + " for the XDMF file: global axes, VTK order");
    if (!shells) continue;
    copy.assign(n * 6, std::nan(""));
    for (std::size_t e = 0; e < n; ++e)
      if (is_shell(model.element_types[e])) to_vtk(&rows[e * 6], &copy[e * 6]);
    out.write(group.get(), name + "_LOCAL", copy, {n, 6}, RowsOf::Elements);
    describe(group.get(), name + "_LOCAL", "11,22,33,12,23,13", "Pa",
             "copy of " + name +
                 " for the XDMF file: shells only (NaN rows for solids), local shell axes, VTK "
                 "order");
  }
  if (maximum) write_described(out, g, output_variable(OutputId::MISES_MAX), mises_max, units);
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
  const std::vector<const OutputVariable*> variables = frame_variables(what, output_scope(model));
  const RowWriter out(fields.rows);
  for (const OutputVariable* v : variables) {
    if (v->frame == &FrameRequest::stress) continue;  // write_stresses
    write_variable(out, g, *v, model, state, fields);
    describe(g, std::string(v->name), component_list(*v), units.label(v->unit), v->description);
  }
  if (what.stress)
    write_stresses(out, file, g, "xdmf/" + name, model, state.position, fields, variables, units);
  std::vector<Real> buffer;
  if (what.stress) {
    const std::vector<Real>& hourglass = fields.element_rows(ElementField::HourglassState, buffer);
    if (!hourglass.empty()) {
      // Not an output variable (not in the XDMF): the elements' internal hourglass state, for
      // --import (io/result_tools/import_state.hpp).
      const auto n_elements = static_cast<std::size_t>(model.element_count());
      const auto width = static_cast<std::size_t>(FrameFields::HOURGLASS_WIDTH);
      check_size(hourglass, n_elements * width, "hourglass_state");
      out.write(g, "HGSTATE", hourglass, {n_elements, width}, RowsOf::Elements);
    }
  }
}

}  // namespace xpl::io
