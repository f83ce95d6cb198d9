#include "io/result_tools/import_state.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <type_traits>
#include <unordered_map>

#include "io/result_tools/h5_handles.hpp"
#include "io/result_tools/h5_reader.hpp"
#include "solver/output/frame_fields.hpp"

namespace xpl::io {

void ImportedState::add_note(std::string text) {
  notes.push_back(std::move(text));
}

namespace {

using h5::has_link;
using h5::refuse;

/// What every mesh mismatch expects.
const char* const SAME_MESH =
    "expected the result file of a run on the same mesh (the same node and element ids, "
    "element types, connectivity and reference coordinates)";
/// What every defect of the file's structure expects.
const char* const XPL_FILE = "expected the .h5 result file of an earlier xpl run";

/// Relative tolerance on the reference coordinates, times the model size.
constexpr Real COORDINATE_TOLERANCE = 1e-9;

/// Element types a result file can hold, as /mesh/TYPE groups.
constexpr ElementType ELEMENT_TYPES[] = {ElementType::C3D8R, ElementType::C3D8, ElementType::S4R};

std::string format_reals(const Real* values, int count) {
  std::string out = "(";
  for (int i = 0; i < count; ++i) {
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", values[i]);
    out += (i > 0 ? ", " : "") + std::string(text);
  }
  return out + ")";
}

std::string format_ids(const std::vector<ExternalId>& ids) {
  std::string out;
  for (ExternalId id : ids) out += (out.empty() ? "" : ", ") + std::to_string(id);
  return out;
}

/// h5::read_array with this reader's expectation (an earlier xpl run's file).
template <class T>
std::vector<T> read_array(hid_t file, const std::string& path, std::optional<hsize_t> rows,
                          hsize_t width) {
  return h5::read_array<T>(file, path, rows, width, XPL_FILE);
}

template <class T>
T numeric_attribute(hid_t file, const std::string& path, const char* name) {
  return h5::numeric_attribute<T>(file, path, name, XPL_FILE);
}

/// Rows of the file mapped onto model indices, for nodes or elements ("node", "element").
/// Refuses ids that appear twice, model ids missing from the file (first in model order)
/// and file ids missing from the model.
std::vector<Index> map_rows(const std::vector<std::int64_t>& file_ids,
                            const std::vector<ExternalId>& model_ids, const std::string& what,
                            const std::string& path) {
  std::unordered_map<ExternalId, Index> file_row;
  file_row.reserve(file_ids.size());
  for (std::size_t r = 0; r < file_ids.size(); ++r) {
    if (!file_row.emplace(file_ids[r], static_cast<Index>(r)).second) {
      refuse(what + " " + std::to_string(file_ids[r]) + " appears twice in " + path, XPL_FILE);
    }
  }
  std::vector<Index> model_index(file_ids.size(), NO_INDEX);
  for (std::size_t i = 0; i < model_ids.size(); ++i) {
    const auto found = file_row.find(model_ids[i]);
    if (found == file_row.end()) {
      refuse(what + " " + std::to_string(model_ids[i]) + " of the model is not in the file (" +
                 path + ")",
             SAME_MESH);
    }
    model_index[static_cast<std::size_t>(found->second)] = static_cast<Index>(i);
  }
  for (std::size_t r = 0; r < file_ids.size(); ++r) {
    if (model_index[r] == NO_INDEX) {
      refuse(what + " " + std::to_string(file_ids[r]) + " of the file (" + path +
                 ") is not in the model",
             SAME_MESH);
    }
  }
  return model_index;
}

/// Model size for the coordinate tolerance: the bounding-box diagonal (the largest
/// coordinate magnitude for a single point). Plain loops: GCC 12 warns inside its own
/// AVX-512 header on Eigen's vectorised reductions (GCC bug 105593).
Real model_size(const NodalVectors& x) {
  Real diagonal_squared = 0.0, largest = 0.0;
  for (int c = 0; c < 3; ++c) {
    Real low = 0.0, high = 0.0;
    for (Eigen::Index n = 0; n < x.rows(); ++n) {
      low = n == 0 ? x(n, c) : std::min(low, x(n, c));
      high = n == 0 ? x(n, c) : std::max(high, x(n, c));
    }
    diagonal_squared += (high - low) * (high - low);
    largest = std::max({largest, std::abs(low), std::abs(high)});
  }
  return diagonal_squared > 0.0 ? std::sqrt(diagonal_squared) : largest;
}

void check_coordinates(const std::vector<Real>& file_xyz, const std::vector<Index>& node_of_row,
                       const Model& model) {
  const Real size = model_size(model.coordinates);
  const Real tolerance = COORDINATE_TOLERANCE * size;
  // Reported in model order: the first mismatching node of the deck.
  std::vector<std::size_t> row_of(node_of_row.size());
  for (std::size_t r = 0; r < node_of_row.size(); ++r) {
    row_of[static_cast<std::size_t>(node_of_row[r])] = r;
  }
  for (Index n = 0; n < model.node_count(); ++n) {
    const Real* in_file = &file_xyz[row_of[static_cast<std::size_t>(n)] * 3];
    const Real in_model[3] = {model.coordinates(n, 0), model.coordinates(n, 1),
                              model.coordinates(n, 2)};
    for (int c = 0; c < 3; ++c) {
      if (std::abs(in_file[c] - in_model[c]) <= tolerance) continue;
      char limit[64];
      std::snprintf(limit, sizeof limit, "%.3g m", tolerance);
      refuse("node " + std::to_string(model.node_ids[static_cast<std::size_t>(n)]) + " is at " +
                 format_reals(in_model, 3) + " in the model but at " + format_reals(in_file, 3) +
                 " in the file (/mesh/coordinates)",
             std::string(SAME_MESH) + "; coordinates may differ by " + limit +
                 " (1e-9 of the model size)");
    }
  }
}

/// Checks /mesh/TYPE/element_ids and connectivity of every type group against the model.
void check_element_types(hid_t file, const Model& model, const std::vector<std::int64_t>& node_ids,
                         const std::unordered_map<ExternalId, Index>& element_of_id) {
  std::vector<bool> typed(static_cast<std::size_t>(model.element_count()), false);
  for (ElementType type : ELEMENT_TYPES) {
    const std::string group = std::string("/mesh/") + element_type_name(type);
    if (!has_link(file, group)) continue;
    const auto ids = read_array<std::int64_t>(file, group + "/element_ids", std::nullopt, 0);
    const auto corners = static_cast<hsize_t>(nodes_per_element(type));
    const auto connectivity =
        read_array<std::int64_t>(file, group + "/connectivity", ids.size(), corners);
    for (std::size_t j = 0; j < ids.size(); ++j) {
      const auto found = element_of_id.find(ids[j]);
      if (found == element_of_id.end()) {
        refuse(group + "/element_ids lists element " + std::to_string(ids[j]) +
                   ", which is not in /mesh/element_ids",
               XPL_FILE);
      }
      const Index e = found->second;
      const ElementType model_type = model.element_types[static_cast<std::size_t>(e)];
      if (model_type != type) {
        refuse("element " + std::to_string(ids[j]) + " is " + element_type_name(type) +
                   " in the file but " + element_type_name(model_type) + " in the model",
               SAME_MESH);
      }
      typed[static_cast<std::size_t>(e)] = true;
      std::vector<ExternalId> in_file, in_model;
      for (hsize_t a = 0; a < corners; ++a) {
        const std::int64_t row = connectivity[j * corners + a];
        if (row < 0 || static_cast<std::size_t>(row) >= node_ids.size()) {
          refuse(group + "/connectivity of element " + std::to_string(ids[j]) + " names node row " +
                     std::to_string(row) + ", outside /mesh/node_ids",
                 XPL_FILE);
        }
        in_file.push_back(node_ids[static_cast<std::size_t>(row)]);
        in_model.push_back(model.node_ids[static_cast<std::size_t>(model.nodes_of(e)[a])]);
      }
      if (in_file != in_model) {
        refuse("element " + std::to_string(ids[j]) + " has nodes " + format_ids(in_file) +
                   " in the file but " + format_ids(in_model) + " in the model",
               SAME_MESH);
      }
    }
  }
  for (Index e = 0; e < model.element_count(); ++e) {
    if (typed[static_cast<std::size_t>(e)]) continue;
    refuse(
        "element " + std::to_string(model.element_ids[static_cast<std::size_t>(e)]) +
            " has no element type in the file (no /mesh/C3D8R, /mesh/C3D8 or /mesh/S4R lists it)",
        XPL_FILE);
  }
}

/// Name of the last frame: the highest all-digit name below /frames.
std::string last_frame(hid_t file) {
  const char* const no_frames = "expected a result file with at least one field output frame";
  if (!has_link(file, "/frames")) refuse("the file has no frames (/frames)", no_frames);
  std::string best;
  long long best_number = -1;
  for (const std::string& name : h5::group_members(file, "/frames")) {
    if (name.empty() || name.size() > 15 ||
        name.find_first_not_of("0123456789") != std::string::npos) {
      continue;
    }
    const long long number = std::stoll(name);
    if (number > best_number) {
      best_number = number;
      best = name;
    }
  }
  if (best.empty()) refuse("the file has no frames (/frames is empty)", no_frames);
  return best;
}

/// A nodal field of the frame (file rows → model rows); refuses non-finite values.
NodalVectors read_nodal(hid_t file, const std::string& frame, const char* name,
                        const std::vector<Index>& node_of_row, const Model& model) {
  const std::string path = frame + "/" + name;
  const auto values = read_array<Real>(file, path, node_of_row.size(), 3);
  NodalVectors field(model.node_count(), 3);
  for (std::size_t r = 0; r < node_of_row.size(); ++r) {
    const Index n = node_of_row[r];
    for (int c = 0; c < 3; ++c) {
      const Real v = values[r * 3 + c];
      if (!std::isfinite(v)) {
        refuse(path + " is not finite at node " +
                   std::to_string(model.node_ids[static_cast<std::size_t>(n)]),
               "expected the state of a run that did not go unstable");
      }
      field(n, c) = v;
    }
  }
  return field;
}

/// An element field of the frame (n_elements × `width`, file rows → model rows; width 1: a
/// one-dimensional dataset); refuses non-finite values in the rows of the elements
/// `check_row` accepts.
template <class CheckRow>
std::vector<Real> read_cells(hid_t file, const std::string& path,
                             const std::vector<Index>& element_of_row, const Model& model,
                             CheckRow check_row, int width = 6) {
  const auto w = static_cast<std::size_t>(width);
  const auto values = read_array<Real>(file, path, element_of_row.size(), width == 1 ? 0 : w);
  std::vector<Real> field(values.size());
  for (std::size_t r = 0; r < element_of_row.size(); ++r) {
    const auto e = static_cast<std::size_t>(element_of_row[r]);
    for (std::size_t c = 0; c < w; ++c) {
      const Real v = values[r * w + c];
      if (check_row(e) && !std::isfinite(v)) {
        refuse(path + " is not finite at element " + std::to_string(model.element_ids[e]),
               "expected the state of a run that did not go unstable");
      }
      field[e * w + c] = v;
    }
  }
  return field;
}

/// The last frame of a file: its path and which datasets it holds.
struct Frame {
  hid_t file;
  std::string path;
  bool has(const char* name) const { return has_link(file, path + "/" + name); }
};

/// U (as a displacement from the model's reference coordinates), V, UR and VR of the frame.
void read_nodal_state(const Frame& frame, const std::vector<Index>& node_of_row,
                      const std::vector<Real>& file_xyz, const Model& model, ImportedState& state) {
  for (const char* name : {"U", "V"}) {
    if (frame.has(name)) continue;
    char when[48];
    std::snprintf(when, sizeof when, "%.9g s", state.time);
    refuse("the last frame (" + frame.path + ", t = " + when + ") has no " + name,
           "expected a last frame with U and V (*NODE OUTPUT U, V in the earlier run's field "
           "output)");
  }
  const hid_t file = frame.file;
  state.displacement = read_nodal(file, frame.path, "U", node_of_row, model);
  // Current positions of the file, relative to the model's (equal within the tolerance)
  // reference coordinates: x = X_file + U_file = X_model + U.
  for (std::size_t r = 0; r < node_of_row.size(); ++r) {
    const Index n = node_of_row[r];
    for (int c = 0; c < 3; ++c) {
      state.displacement(n, c) += file_xyz[r * 3 + c] - model.coordinates(n, c);
    }
  }
  state.velocity = read_nodal(file, frame.path, "V", node_of_row, model);
  if (frame.has("UR")) state.rotation = read_nodal(file, frame.path, "UR", node_of_row, model);
  if (frame.has("VR")) {
    state.angular_velocity = read_nodal(file, frame.path, "VR", node_of_row, model);
  }
  const bool shells = model.has_shells();
  if (shells && !frame.has("UR")) state.add_note("no UR in the last frame: rotations start at 0");
  if (shells && !frame.has("VR"))
    state.add_note("no VR in the last frame: angular velocities start at 0");
}

/// S, and the shells' S_SNEG and S_SPOS, of the frame.
void read_stresses(const Frame& frame, const std::vector<Index>& element_of_row, const Model& model,
                   ImportedState& state) {
  const auto all_rows = [](std::size_t) { return true; };
  const auto shell_rows = [&](std::size_t e) { return is_shell(model.element_types[e]); };
  if (frame.has("S")) {
    state.stress = read_cells(frame.file, frame.path + "/S", element_of_row, model, all_rows);
  } else if (model.element_count() > 0) {
    state.add_note("no S in the last frame: the elements start unstressed");
  }
  if (frame.has("S_SNEG") && frame.has("S_SPOS")) {
    state.stress_bottom =
        read_cells(frame.file, frame.path + "/S_SNEG", element_of_row, model, shell_rows);
    state.stress_top =
        read_cells(frame.file, frame.path + "/S_SPOS", element_of_row, model, shell_rows);
  } else if (model.has_shells() && frame.has("S")) {
    state.add_note(
        "no S_SNEG/S_SPOS in the last frame: the shells take the middle stress S through the "
        "whole thickness (no bending stress)");
  }
}

/// PEEQ of the frame and the shells' PEEQ per section point (or, from another writer, the
/// largest PEEQ through the whole thickness).
void read_plastic_strains(const Frame& frame, const std::vector<Index>& element_of_row,
                          const Model& model, ImportedState& state) {
  const auto all_rows = [](std::size_t) { return true; };
  const auto shell_rows = [&](std::size_t e) { return is_shell(model.element_types[e]); };
  if (model.has_plasticity()) {
    if (frame.has("PEEQ")) {
      state.peeq = read_cells(frame.file, frame.path + "/PEEQ", element_of_row, model, all_rows, 1);
      for (std::size_t e = 0; e < state.peeq.size(); ++e)
        if (state.peeq[e] < 0.0)
          refuse(
              frame.path + "/PEEQ is negative at element " + std::to_string(model.element_ids[e]),
              "expected equivalent plastic strains >= 0");
    } else {
      state.add_note("no PEEQ in the last frame: the plastic strains start at 0");
    }
  }
  if (!model.has_plastic_shells()) return;
  const char* names[3] = {"PEEQ_SMID", "PEEQ_SNEG", "PEEQ_SPOS"};
  std::vector<Real>* fields[3] = {&state.peeq_middle, &state.peeq_bottom, &state.peeq_top};
  if (frame.has(names[0]) && frame.has(names[1]) && frame.has(names[2])) {
    for (int k = 0; k < 3; ++k) {
      const std::string path = frame.path + "/" + names[k];
      *fields[k] = read_cells(frame.file, path, element_of_row, model, shell_rows, 1);
      for (std::size_t e = 0; e < fields[k]->size(); ++e)
        if (shell_rows(e) && (*fields[k])[e] < 0.0)
          refuse(path + " is negative at element " + std::to_string(model.element_ids[e]),
                 "expected equivalent plastic strains >= 0");
    }
  } else if (!state.peeq.empty()) {
    // A frame of another writer: the largest PEEQ through the thickness, everywhere in it.
    for (std::vector<Real>* field : fields) *field = state.peeq;
    state.add_note(
        "no PEEQ_SNEG/PEEQ_SMID/PEEQ_SPOS in the last frame: the shells take their largest "
        "PEEQ through the whole thickness");
  }
}

/// Hourglass resultants (written with S by xpl since issue 14) and the shells' current
/// thickness: without them a continued run starts with no hourglass resistance and the
/// section thickness.
void read_hourglass_and_thickness(const Frame& frame, const std::vector<Index>& element_of_row,
                                  const Model& model, ImportedState& state) {
  const auto all_rows = [](std::size_t) { return true; };
  const auto shell_rows = [&](std::size_t e) { return is_shell(model.element_types[e]); };
  const bool shells = model.has_shells();
  const bool hourglass_elements =
      std::any_of(model.element_types.begin(), model.element_types.end(),
                  [](ElementType t) { return t == ElementType::C3D8R || t == ElementType::S4R; });
  if (hourglass_elements && frame.has("HGSTATE")) {
    state.hourglass_state = read_cells(frame.file, frame.path + "/HGSTATE", element_of_row, model,
                                       all_rows, FrameFields::HOURGLASS_WIDTH);
  } else if (hourglass_elements && frame.has("S")) {
    state.add_note("no HGSTATE in the last frame: the hourglass forces start at zero");
  }
  if (shells && frame.has("STH")) {
    state.shell_thickness =
        read_cells(frame.file, frame.path + "/STH", element_of_row, model, shell_rows, 1);
    for (std::size_t e = 0; e < state.shell_thickness.size(); ++e)
      if (shell_rows(e) && !(state.shell_thickness[e] > 0.0))
        refuse(
            frame.path + "/STH is not positive at element " + std::to_string(model.element_ids[e]),
            "expected shell thicknesses > 0");
  } else if (shells && frame.has("S")) {
    state.add_note("no STH in the last frame: the shells start at their section thickness");
  }
}

ImportedState read_file(hid_t file, const Model& model) {
  ImportedState state;
  // Mesh: ids, coordinates, element types and connectivity.
  const auto node_ids = read_array<std::int64_t>(file, "/mesh/node_ids", std::nullopt, 0);
  const std::vector<Index> node_of_row =
      map_rows(node_ids, model.node_ids, "node", "/mesh/node_ids");
  const auto file_xyz = read_array<Real>(file, "/mesh/coordinates", node_ids.size(), 3);
  check_coordinates(file_xyz, node_of_row, model);
  const auto element_ids = read_array<std::int64_t>(file, "/mesh/element_ids", std::nullopt, 0);
  const std::vector<Index> element_of_row =
      map_rows(element_ids, model.element_ids, "element", "/mesh/element_ids");
  // The element fields' rows follow /mesh/element_ids: it must agree with the type groups.
  h5::check_element_rows(file, element_ids, XPL_FILE);
  std::unordered_map<ExternalId, Index> element_of_id;
  for (Index e = 0; e < model.element_count(); ++e) {
    element_of_id.emplace(model.element_ids[static_cast<std::size_t>(e)], e);
  }
  check_element_types(file, model, node_ids, element_of_id);

  // The last frame.
  const Frame frame{file, "/frames/" + last_frame(file)};
  state.time = numeric_attribute<double>(file, frame.path, "time");
  state.increment =
      static_cast<long>(numeric_attribute<std::int64_t>(file, frame.path, "increment"));
  read_nodal_state(frame, node_of_row, file_xyz, model, state);
  read_stresses(frame, element_of_row, model, state);
  read_plastic_strains(frame, element_of_row, model, state);
  read_hourglass_and_thickness(frame, element_of_row, model, state);
  const std::string status = h5::string_attribute(file, "/", "status").value_or("");
  if (!status.empty() && status != "completed" && status != "checked")
    state.add_note("the earlier run's status is '" + status +
                   "', not 'completed': its last frame is imported as it is");
  return state;
}

}  // namespace

ImportedState read_imported_state(const std::filesystem::path& h5, const Model& model) {
  const std::string source = h5.string();
  const auto refused = [&](const std::string& problem, const std::string& expected) {
    return InputError({source + ": --import: " + problem + "; " + expected});
  };
  try {
    const h5::Handle file = h5::open_read_only(h5, XPL_FILE);
    ImportedState state = read_file(file.get(), model);
    state.source = source;
    return state;
  } catch (const h5::FormatError& refusal) {
    throw refused(refusal.what(), refusal.expected());
  } catch (const h5::Error& failure) {
    throw refused(failure.what(), XPL_FILE);
  }
}

}  // namespace xpl::io
