#pragma once
/// \file Reports of the initial-overclosure pass (SPEC C11): the .msg listing (DETAIL), the
/// .sta summary (always) and the tables of the results file.

#include <string>

#include "contact/initial_overclosure.hpp"
#include "solver/model.hpp"
#include "solver/output_sink.hpp"

namespace xpl {

/// What the solver measured around the pass: the stable increment on the mesh as read and on
/// the adjusted one (0 when nothing moved).
struct AdjustmentEffect {
  Real dt_before = 0.0;
  Real dt_after = 0.0;
};

/// Writes the reports of `report` for step `step` (zero-based) of `model`; `engine` names the
/// faces and surfaces. DETAIL (`diagnostics.overclosure_detail`) lists every adjusted node,
/// offset, ignored node and crossed edge in the .msg file; both levels write the summary line
/// to the .sta file and the tables /overclosure/step_N/{adjusted, offsets, ignored, crossed}.
void report_overclosures(const contact::OverclosureReport& report,
                         const contact::ContactEngine& engine, const Model& model, int step,
                         const Diagnostics& diagnostics, const AdjustmentEffect& effect,
                         OutputSink& sink);

/// Abaqus name of contact face `face` of element kind `kind` ("S3", "SPOS").
std::string face_label(contact::ElementKind kind, int face);

}  // namespace xpl
