#pragma once
/// \file `xpl run DECK --import prev.h5`: the state of the last frame of an earlier xpl result
/// file (layout in docs/user/results.md), checked against the model's mesh and mapped onto its
/// internal indices, so that a run can start where the earlier one stopped.

#include <filesystem>
#include <string>
#include <vector>

#include "solver/explicit_solver.hpp"
#include "solver/model/model.hpp"

namespace xpl::io {

/// The state of the last frame of an earlier xpl result file, mapped onto `model`'s internal
/// indices (row i is node or element i of the model, whatever the row order of the file).
struct ImportedState : InitialState {
  // InitialState: source (the file path, as given), U relative to the model's reference
  // coordinates (the file's current positions minus the model's coordinates, which match the
  // file's within the tolerance), V, UR/VR (0 rows when the frame has none), S and the shell
  // S_SNEG/S_SPOS (empty when the frame has none), PEEQ on plastic models (empty when the
  // frame has none), PEEQ_SMID/SNEG/SPOS on models with plastic shells (PEEQ where the frame
  // has PEEQ only, empty when it has neither).
  Real time = 0.0;     ///< total time of the frame, s
  long increment = 0;  ///< total increment count of the frame
  /// What was missing or assumed, one sentence each, for the .msg file.
  std::vector<std::string> notes;
  /// Adds a note. Never inlined: GCC 12 inlining a literal's std::string into
  /// push_back warned -Warray-bounds under the precompiled header (a false positive).
  [[gnu::noinline]] void add_note(std::string text);
};

/// Reads the last frame (the highest /frames/NNNNNN) of the xpl result file `h5`, opened
/// read-only. The file's mesh must be the model's: the same node ids and element ids (in any
/// order: rows are mapped by deck id), the same element types and connectivity, and the same
/// reference coordinates within 1e-9 of the model size (its bounding-box diagonal). The frame
/// must hold U and V; UR, VR, S, S_SNEG, S_SPOS, (plastic models) PEEQ and (plastic shells)
/// PEEQ_SMID, PEEQ_SNEG, PEEQ_SPOS are read when present. Values must be
/// finite (S_SNEG/S_SPOS rows of solids are NaN by design and not checked). Every problem
/// throws InputError with one message `FILE: --import: what is wrong; what is expected`.
ImportedState read_imported_state(const std::filesystem::path& h5, const Model& model);

}  // namespace xpl::io
