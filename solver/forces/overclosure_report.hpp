#pragma once
/// \file Reports of the initial-overclosure pass (SPEC C11): the .msg listing (DETAIL), the
/// .sta summary (always) and the tables of the results file.

#include <functional>
#include <string>

#include "contact/contact_clearance.hpp"
#include "contact/initial_overclosure.hpp"
#include "solver/model/model.hpp"
#include "solver/output/output_sink.hpp"

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
/// `tie_joined(node, face)`: a *TIE joins the node to a corner of the face (a slave and a
/// master corner it is bound to); such an ignored node is reported as held by its tie.
void report_overclosures(const contact::OverclosureReport& report,
                         const contact::ContactEngine& engine, const Model& model, int step,
                         const Diagnostics& diagnostics, const AdjustmentEffect& effect,
                         OutputSink& sink,
                         const std::function<bool(Index node, Index face)>& tie_joined = {});

/// Names of one clearance view for the reports: the clearance and the slave and master
/// surfaces.
struct ClearanceViewNames {
  std::string clearance, slave, master;
  bool initialization = false;  ///< `*CONTACT INITIALIZATION DATA` (SPEC C14)
  bool interference = false;    ///< an interference fit (C15)
  Real step_fraction = 1.0;     ///< its STEP FRACTION
};

/// Writes the reports of the clearance pass of step `step` (SPEC C7–C11): with DETAIL one .msg
/// line per node (clearance name, surfaces, gap as read, the move or the permanent offset) and
/// per skipped node; at both levels a summary line (.sta and .msg) and the tables
/// /overclosure/step_N/{clearances, clearance_skipped}.
void report_clearances(const contact::ClearanceReport& report,
                       const std::vector<ClearanceViewNames>& views,
                       const contact::ContactEngine& engine, const Model& model, int step,
                       const Diagnostics& diagnostics, OutputSink& sink);

/// Abaqus name of contact face `face` of element kind `kind` ("S3", "SPOS").
std::string face_label(contact::ElementKind kind, int face);

}  // namespace xpl
