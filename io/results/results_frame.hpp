#pragma once
/// \file The datasets of one field frame of JOB.h5: /frames/NNNNNN (one dataset per output
/// variable, with its components, units and description) and /xdmf/NNNNNN (the tensors in
/// VTK order for the XDMF file), from the state and the frame fields. ResultsH5::write_frame
/// opens the file and the group; layout in docs/user/results.md.

#include <string>

#include "common/units.hpp"
#include "io/result_tools/h5_handles.hpp"
#include "solver/model/model.hpp"
#include "solver/model/state.hpp"
#include "solver/output/frame_fields.hpp"
#include "solver/output/output_sink.hpp"

namespace xpl::io {

/// Von Mises stress of one stress row (S11 S22 S33 S12 S13 S23), Pa.
Real von_mises(const Real* s);

/// Throws std::invalid_argument, before anything is written, if a field the frame `what`
/// needs does not have the size of the model.
void check_frame(const Model& model, const State& state, const FrameFields& fields,
                 const FrameRequest& what);

/// Writes the datasets of `what` into the frame group `g` (/frames/`name`) and the XDMF
/// copies of the tensors into /xdmf/`name` of the open `file`; `units` label them.
void write_frame_datasets(hid_t file, hid_t g, const std::string& name, const Model& model,
                          const State& state, const FrameFields& fields, const FrameRequest& what,
                          const ModelUnits& units);

}  // namespace xpl::io
