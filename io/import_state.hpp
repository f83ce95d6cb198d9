#pragma once
/// \file `xpl run DECK --import prev.h5`: the state of the last frame of an earlier xpl result
/// file (layout in README.md), checked against the model's mesh and mapped onto its internal
/// indices, so that a run can start where the earlier one stopped.

#include <filesystem>
#include <string>
#include <vector>

#include "solver/model.hpp"

namespace xpl::io {

/// The state of the last frame of an earlier xpl result file, mapped onto `model`'s internal
/// indices (row i is node or element i of the model, whatever the row order of the file).
struct ImportedState {
  std::string source;  ///< the file path, as given
  Real time = 0.0;     ///< total time of the frame, s
  long increment = 0;  ///< total increment count of the frame
  /// U (n_nodes × 3) relative to the model's reference coordinates, m: the file's current
  /// positions minus the model's coordinates (which match the file's within the tolerance).
  NodalVectors displacement;
  NodalVectors velocity;          ///< V (n_nodes × 3), m/s
  NodalVectors rotation;          ///< UR (n_nodes × 3), rad; 0 rows when the frame has none
  NodalVectors angular_velocity;  ///< VR (n_nodes × 3), rad/s; 0 rows when the frame has none
  /// S (n_elements × 6, row-major, S11 S22 S33 S12 S13 S23), Pa; solids in global axes,
  /// shells at the middle section point in the output local axes. Empty when the frame has
  /// no S.
  std::vector<Real> stress;
  /// S_SNEG / S_SPOS (n_elements × 6), Pa: shell bottom / top section points, NaN rows for
  /// solids. Empty when the frame has none.
  std::vector<Real> stress_bottom, stress_top;
  /// What was missing or assumed, one sentence each, for the .msg file.
  std::vector<std::string> notes;
};

/// Reads the last frame (the highest /frames/NNNNNN) of the xpl result file `h5`, opened
/// read-only. The file's mesh must be the model's: the same node ids and element ids (in any
/// order: rows are mapped by deck id), the same element types and connectivity, and the same
/// reference coordinates within 1e-9 of the model size (its bounding-box diagonal). The frame
/// must hold U and V; UR, VR, S, S_SNEG and S_SPOS are read when present. Values must be
/// finite (S_SNEG/S_SPOS rows of solids are NaN by design and not checked). Every problem
/// throws InputError with one message `FILE: --import: what is wrong; what is expected`.
ImportedState read_imported_state(const std::filesystem::path& h5, const Model& model);

}  // namespace xpl::io
