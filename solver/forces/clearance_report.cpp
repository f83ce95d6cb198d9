// report_clearances (overclosure_report.hpp): the .msg lines, the .sta summary and the result
// tables of the contact clearances and initialization data (SPEC C7-C10, C14, C15).
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "solver/forces/overclosure_report.hpp"
#include "solver/forces/report_text.hpp"

namespace xpl {

using report::Names;
using report::real_text;

namespace {

/// What the cleared nodes add up to.
struct ClearanceCounts {
  std::size_t adjusted = 0, offsets = 0, interference = 0;
  Real largest_interference = 0.0;
};

/// "contact clearance NAME: node " (or "contact initialization NAME: node "), before a node id.
std::string view_text(const std::vector<ClearanceViewNames>& views, Index v) {
  return std::string(views[v].initialization ? "contact initialization " : "contact clearance ") +
         views[v].clearance + ": node ";
}

/// The .msg line of one cleared node (DETAIL).
std::string cleared_node_text(const contact::ClearedNode& c,
                              const std::vector<ClearanceViewNames>& views, const Names& names,
                              const Model& model, int step) {
  std::string text = view_text(views, c.view) + std::to_string(model.node_ids[c.node]) +
                     " (slave surface " + views[c.view].slave + ", master surface " +
                     views[c.view].master + ", " + names.face(c.face) + "): gap " +
                     real_text(c.gap_before) + " m as read";
  if (!views[c.view].interference) text += ", clearance " + real_text(c.clearance) + " m";
  if (c.interference > 0.0)
    text += "; interference fit: overclosure " + real_text(c.interference) +
            " m resolved by the penalty over the first " +
            real_text(views[c.view].step_fraction * model.steps[step].time_period) +
            " s of the step (offset ramped to zero)";
  if (c.distance > 0.0)
    text +=
        "; adjusted by " + real_text(c.distance) + " m along " + report::vector_text(c.direction);
  if (c.offset != 0.0)
    text += "; permanent contact offset d0 = " + real_text(c.offset) + " m" +
            (c.distance > 0.0 || c.reason != contact::OffsetReason::Conflict
                 ? std::string(" (reason: ") + contact::offset_reason_name(c.reason) + ")"
                 : std::string());
  return text;
}

/// Counts the cleared nodes and, with DETAIL, lists them and the skipped ones in the .msg; warns
/// of master faces outside the contact domain and of the elements the pass refused to distort.
ClearanceCounts message_cleared_nodes(const contact::ClearanceReport& report,
                                      const std::vector<ClearanceViewNames>& views,
                                      const Names& names, const Model& model, int step,
                                      const Diagnostics& diagnostics, OutputSink& sink) {
  ClearanceCounts counts;
  for (const contact::ClearedNode& c : report.nodes) {
    counts.adjusted += c.distance > 0.0 ? 1 : 0;
    counts.offsets += c.offset != 0.0 ? 1 : 0;
    counts.interference += c.interference > 0.0 ? 1 : 0;
    counts.largest_interference = std::max(counts.largest_interference, c.interference);
    if (!diagnostics.overclosure_detail) continue;
    sink.message(Severity::Info, cleared_node_text(c, views, names, model, step));
  }
  for (const contact::SkippedNode& k : report.skipped)
    if (diagnostics.overclosure_detail)
      sink.message(Severity::Note, view_text(views, k.view) +
                                       std::to_string(model.node_ids[k.node]) + " (slave surface " +
                                       views[k.view].slave +
                                       ") is skipped: " + contact::clearance_skip_name(k.why));
  std::vector<char> warned(views.size(), 0);
  for (Index v : report.faces_outside_domain)
    if (!warned[v]) {
      warned[v] = 1;
      sink.message(Severity::Warning,
                   "contact clearance " + views[v].clearance + ": faces of master surface " +
                       views[v].master +
                       " are not in the contact domain of the step (include the surfaces in "
                       "*CONTACT INCLUSIONS); the clearance does not apply to them");
    }
  for (Index e : report.refused_elements)
    sink.message(Severity::Warning,
                 "contact clearance: moving the nodes of element " +
                     std::to_string(model.element_ids[e]) +
                     " would invert it or halve a corner volume: not adjusted, its nodes keep "
                     "permanent offsets (reason: distortion)");
  return counts;
}

/// The summary of the pass and, with interference fits, their note (.sta and .msg).
void message_clearance_summary(const contact::ClearanceReport& report,
                               const std::vector<ClearanceViewNames>& views,
                               const ClearanceCounts& counts, const Model& model, int step,
                               OutputSink& sink) {
  const std::string summary =
      "contact clearances, step " + std::to_string(step + 1) + " (" + model.steps[step].name +
      "): " + std::to_string(report.nodes.size()) + " slave node(s) in search zones, " +
      std::to_string(counts.adjusted) + " adjusted, " + std::to_string(counts.offsets) +
      " permanent offset(s), " + std::to_string(report.skipped.size()) + " skipped (" +
      std::to_string(report.passes) + " adjustment pass(es), smallest scaled corner Jacobian " +
      real_text(report.quality_before) + " before, " + real_text(report.quality_after) +
      " after); pass " + real_text(report.seconds) + " s";
  sink.status_note(summary);
  sink.message(Severity::Info, summary);
  if (counts.interference == 0) return;
  std::string names;
  for (std::size_t v = 0; v < views.size(); ++v)
    if (views[v].interference && names.find(views[v].clearance) == std::string::npos)
      names += (names.empty() ? "" : ", ") + views[v].clearance;
  const std::string fits =
      "interference fits, step " + std::to_string(step + 1) + " (" + model.steps[step].name +
      "): " + std::to_string(counts.interference) + " overclosure(s) of slave nodes (largest " +
      real_text(counts.largest_interference) +
      " m) are resolved by the penalty as their offsets ramp " +
      "to zero over the step fraction (" + names +
      "); the automatic strain-free pass leaves them alone, and the ramp's energy is booked "
      "in ALLWK and ALLPW (SPEC C15)";
  sink.status_note(fits);
  sink.message(Severity::Info, fits);
}

/// An empty table of overclosure/step_N/ with the clearance, slave and master surface of every
/// view as attributes.
ResultTable clearance_table(const std::vector<ClearanceViewNames>& views, int step,
                            const std::string& name, Index rows, const std::string& description) {
  ResultTable t;
  t.path = "overclosure/step_" + std::to_string(step + 1) + "/" + name;
  t.rows = rows;
  t.description = description;
  std::string clearances, slaves, masters;
  for (std::size_t v = 0; v < views.size(); ++v) {
    clearances += (v > 0 ? "," : "") + views[v].clearance;
    slaves += (v > 0 ? "," : "") + views[v].slave;
    masters += (v > 0 ? "," : "") + views[v].master;
  }
  t.attributes = {{"view_clearance", clearances},
                  {"view_slave_surface", slaves},
                  {"view_master_surface", masters}};
  return t;
}

/// overclosure/step_N/clearances: the slave nodes given a clearance.
void write_clearances_table(const contact::ClearanceReport& report,
                            const std::vector<ClearanceViewNames>& views,
                            const contact::ContactDomain& domain, const Model& model, int step,
                            OutputSink& sink) {
  ResultTable t =
      clearance_table(views, step, "clearances", static_cast<Index>(report.nodes.size()),
                      "slave nodes given a contact clearance (C7-C10)");
  TableColumn node = report::ids("node", "deck id of the slave node");
  TableColumn view = report::ids("view",
                                 "index into the attributes view_clearance, "
                                 "view_slave_surface, view_master_surface");
  TableColumn element =
      report::ids("master_element", "deck id of the nearest master element as read");
  TableColumn face = report::ids("master_face", report::FACE_CODES);
  TableColumn clearance = report::reals("clearance", "m, positive above the master surface");
  TableColumn gap = report::reals("gap_before", "m, as read (negative: below the surface)");
  TableColumn distance = report::reals("distance", "m, length of the move");
  TableColumn direction = report::reals("direction", "unit vector of the move", 3);
  TableColumn offset = report::reals("offset", "permanent contact offset d0, m (0: none)");
  for (const contact::ClearedNode& c : report.nodes) {
    node.ids.push_back(model.node_ids[c.node]);
    view.ids.push_back(c.view);
    const contact::ContactFace& cf = domain.faces()[c.face];
    element.ids.push_back(model.element_ids[cf.element]);
    face.ids.push_back(report::face_code(cf));
    clearance.values.push_back(c.clearance);
    gap.values.push_back(c.gap_before);
    distance.values.push_back(c.distance);
    for (int d = 0; d < 3; ++d) direction.values.push_back(c.direction[d]);
    offset.values.push_back(c.offset);
  }
  t.columns = {node, view, element, face, clearance, gap, distance, direction, offset};
  sink.write_table(t);
}

/// overclosure/step_N/clearance_skipped: the slave nodes in a search zone that got none.
void write_skipped_table(const contact::ClearanceReport& report,
                         const std::vector<ClearanceViewNames>& views, const Model& model, int step,
                         OutputSink& sink) {
  ResultTable t =
      clearance_table(views, step, "clearance_skipped", static_cast<Index>(report.skipped.size()),
                      "slave nodes in a search zone that got no clearance");
  TableColumn node = report::ids("node", "deck id of the slave node");
  TableColumn view = report::ids("view", "index into the attribute view_clearance");
  TableColumn why = report::ids("reason",
                                "0 no value, 1 perimeter edge, 2 wrong side, 3 not in the contact "
                                "domain, 4 repeated");
  for (const contact::SkippedNode& k : report.skipped) {
    node.ids.push_back(model.node_ids[k.node]);
    view.ids.push_back(k.view);
    why.ids.push_back(static_cast<std::int64_t>(k.why));
  }
  t.columns = {node, view, why};
  sink.write_table(t);
}

}  // namespace

void report_clearances(const contact::ClearanceReport& report,
                       const std::vector<ClearanceViewNames>& views,
                       const contact::ContactEngine& engine, const Model& model, int step,
                       const Diagnostics& diagnostics, OutputSink& sink) {
  const Names names(engine.domain(), model);
  const ClearanceCounts counts =
      message_cleared_nodes(report, views, names, model, step, diagnostics, sink);
  message_clearance_summary(report, views, counts, model, step, sink);
  write_clearances_table(report, views, engine.domain(), model, step, sink);
  write_skipped_table(report, views, model, step, sink);
}

}  // namespace xpl
