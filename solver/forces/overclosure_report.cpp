#include "solver/forces/overclosure_report.hpp"

#include <cstdint>
#include <string>

#include "solver/forces/report_text.hpp"

namespace xpl {

using report::FACE_CODES;
using report::Names;
using report::real_text;
using report::vector_text;

namespace {

/// Writes the pass's records as tables of the results file.
class Tables {
 public:
  Tables(const contact::ContactEngine& engine, const Model& model, int step)
      : m_engine(engine),
        m_model(model),
        m_prefix("overclosure/step_" + std::to_string(step + 1)) {}

  ResultTable table(const std::string& name, Index rows, const std::string& description) const {
    ResultTable t;
    t.path = m_prefix + "/" + name;
    t.rows = rows;
    t.description = description;
    std::string names;
    const contact::ContactDomain& domain = m_engine.domain();
    for (Index k = 0; k < domain.surface_count(); ++k)
      names += (k > 0 ? "," : "") + domain.surface_name(k);
    t.attributes.emplace_back("surface_names", names);
    return t;
  }
  /// Appends the master element id and face code of contact face f to two columns.
  void add_face(Index f, TableColumn& element, TableColumn& face) const {
    const contact::ContactFace& cf = m_engine.domain().faces()[f];
    element.ids.push_back(m_model.element_ids[cf.element]);
    face.ids.push_back(report::face_code(cf));
  }
  std::int64_t node_id(Index node) const { return m_model.node_ids[node]; }

 private:
  const contact::ContactEngine& m_engine;
  const Model& m_model;
  std::string m_prefix;
};

/// The .msg lines of the adjusted, offset and ignored nodes (DETAIL), or the count of the
/// ignored ones (SUMMARY).
void message_overclosed_nodes(const contact::OverclosureReport& report, const Names& names,
                              const Diagnostics& diagnostics, OutputSink& sink,
                              const std::function<bool(Index, Index)>& tie_joined) {
  if (diagnostics.overclosure_detail) {
    for (const contact::AdjustedNode& a : report.adjusted)
      sink.message(Severity::Info,
                   "initial overclosure: " + names.node(a.node) + " (slave surface " +
                       names.surface(a.slave_surface) + ") adjusted by " + real_text(a.distance) +
                       " m along " + vector_text(a.direction) + "; it penetrated " +
                       names.face(a.face) + " (master surface " + names.surface(a.master_surface) +
                       ") by " + real_text(a.penetration) + " m");
    for (const contact::OffsetNode& o : report.offsets)
      sink.message(Severity::Info, "initial overclosure: " + names.node(o.node) +
                                       " (slave surface " + names.surface(o.slave_surface) +
                                       ") keeps a temporary contact offset d0 = " +
                                       real_text(o.offset) + " m against " + names.face(o.face) +
                                       " (reason: " + contact::offset_reason_name(o.reason) +
                                       "); no force until it penetrates further, and d0 "
                                       "shrinks as the surfaces separate");
    for (const contact::IgnoredNode& g : report.ignored)
      sink.message(Severity::Warning,
                   "initial overclosure: " + names.node(g.node) + " (slave surface " +
                       names.surface(g.slave_surface) + ") penetrates " + names.face(g.face) +
                       " by " + real_text(g.depth) + " m, deeper than the automatic limit " +
                       real_text(g.limit) + " m (15 % of the facet size): not adjusted; " +
                       (tie_joined && tie_joined(g.node, g.face)
                            ? "a *TIE joins it to this face, which keeps them together: the "
                              "penalty cannot push it out, its force and the face's reaction "
                              "act on the tied pair. To keep contact off the tied pair, "
                              "exclude it (*CONTACT EXCLUSIONS)"
                            : "the penalty will push it out from the first increment. Fix the "
                              "mesh or use *CONTACT CLEARANCE"));
  } else if (!report.ignored.empty()) {
    sink.message(Severity::Warning,
                 std::to_string(report.ignored.size()) +
                     " slave node(s) penetrate deeper than the automatic limit and are not "
                     "adjusted (CONTACT INITIAL OVERCLOSURE=SUMMARY: see the results file, "
                     "/overclosure, for the list)");
  }
}

/// The warnings of crossed surfaces (C5: at both levels, they point at modelling errors), the
/// note on node-based surfaces and the elements the pass refused to distort.
void message_crossed_and_refused(const contact::OverclosureReport& report, const Names& names,
                                 const contact::ContactDomain& domain, const Model& model,
                                 const Diagnostics& diagnostics, OutputSink& sink) {
  constexpr std::size_t MAX_CROSSED_LISTED = 100;
  for (std::size_t k = 0; k < report.crossed.size() && k < MAX_CROSSED_LISTED; ++k) {
    const contact::CrossedEdge& c = report.crossed[k];
    sink.message(Severity::Warning,
                 "crossed surfaces: slave nodes " + std::to_string(model.node_ids[c.node_a]) +
                     " and " + std::to_string(model.node_ids[c.node_b]) +
                     " (joined by a facet edge) lie on opposite sides of " + names.face(c.face) +
                     "; contact may hold them on the wrong sides");
  }
  if (report.crossed.size() > MAX_CROSSED_LISTED)
    sink.message(Severity::Warning, std::to_string(report.crossed.size()) +
                                        " facet edges cross a master surface; the first " +
                                        std::to_string(MAX_CROSSED_LISTED) + " are listed above");
  // Node-based surfaces have no facet edges, so nothing tells which side they came from (C5).
  if (diagnostics.detect_crossed_surfaces && domain.point_count() > 0)
    sink.message(Severity::Info,
                 "crossed surfaces: " + std::to_string(domain.point_count()) +
                     " slave node(s) of node-based surfaces are not checked (a node-based surface "
                     "has no facet edges to tell which side of a master surface it came from)");
  for (Index e : report.refused_elements)
    sink.message(Severity::Warning,
                 "initial overclosure: moving the nodes of element " +
                     std::to_string(model.element_ids[e]) +
                     " would invert it or halve a corner volume: not adjusted, its nodes keep "
                     "offsets (reason: distortion)");
}

/// The summary of the pass (.sta and .msg) and, when nodes moved, what that did to the
/// elements.
void message_overclosure_summary(const contact::OverclosureReport& report, const Model& model,
                                 int step, const Diagnostics& diagnostics,
                                 const AdjustmentEffect& effect, OutputSink& sink) {
  const std::string step_name = model.steps[step].name;
  std::string summary = "initial overclosures, step " + std::to_string(step + 1) + " (" +
                        step_name + "): largest " + real_text(report.max_overclosure) + " m; " +
                        std::to_string(report.adjusted.size()) + " node(s) adjusted, " +
                        std::to_string(report.offsets.size()) + " offset(s), " +
                        std::to_string(report.ignored.size()) + " ignored, " +
                        std::to_string(report.crossed.size()) + " crossed edge(s)";
  summary += diagnostics.detect_crossed_surfaces
                 ? " (crossed-surface check " + real_text(report.crossed_seconds) + " s)"
                 : " (crossed-surface check off)";
  summary += "; pass " + real_text(report.seconds) + " s";
  sink.status_note(summary);
  sink.message(Severity::Info, summary);
  if (!report.adjusted.empty())
    sink.message(Severity::Info, "adjusted elements: smallest scaled corner Jacobian " +
                                     real_text(report.quality_before) + " before, " +
                                     real_text(report.quality_after) + " after; stable increment " +
                                     real_text(effect.dt_before) + " s before, " +
                                     real_text(effect.dt_after) + " s after (" +
                                     std::to_string(report.passes) + " adjustment pass(es))");
}

/// overclosure/step_N/adjusted: the slave nodes the pass moved.
void write_adjusted_table(const contact::OverclosureReport& report, const Tables& tables,
                          OutputSink& sink) {
  ResultTable t = tables.table("adjusted", static_cast<Index>(report.adjusted.size()),
                               "slave nodes moved onto the master surface (strain free)");
  TableColumn node = report::ids("node", "deck id of the slave node");
  TableColumn element = report::ids("master_element", "deck id of the master element");
  TableColumn face = report::ids("master_face", FACE_CODES);
  TableColumn slave = report::ids("slave_surface", "index into attribute surface_names");
  TableColumn penetration = report::reals("penetration", "m, as read");
  TableColumn distance = report::reals("distance", "m, length of the move");
  TableColumn direction = report::reals("direction", "unit vector of the move", 3);
  for (const contact::AdjustedNode& a : report.adjusted) {
    node.ids.push_back(tables.node_id(a.node));
    tables.add_face(a.face, element, face);
    slave.ids.push_back(a.slave_surface);
    penetration.values.push_back(a.penetration);
    distance.values.push_back(a.distance);
    for (int d = 0; d < 3; ++d) direction.values.push_back(a.direction[d]);
  }
  t.columns = {node, element, face, slave, penetration, distance, direction};
  sink.write_table(t);
}

/// overclosure/step_N/offsets: the temporary contact offsets.
void write_offsets_table(const contact::OverclosureReport& report, const Tables& tables,
                         OutputSink& sink) {
  ResultTable t = tables.table("offsets", static_cast<Index>(report.offsets.size()),
                               "temporary contact offsets d0 (unresolved penetrations)");
  TableColumn node = report::ids("node", "deck id of the slave node");
  TableColumn element = report::ids("master_element", "deck id of the master element");
  TableColumn face = report::ids("master_face", FACE_CODES);
  TableColumn slave = report::ids("slave_surface", "index into attribute surface_names");
  TableColumn offset = report::reals("offset", "d0, m");
  TableColumn reason = report::ids(
      "reason",
      "0 BC, 1 rigid, 2 pinched, 3 distortion, 4 conflict, 5 later step, 6 import, 7 tie");
  for (const contact::OffsetNode& o : report.offsets) {
    node.ids.push_back(tables.node_id(o.node));
    tables.add_face(o.face, element, face);
    slave.ids.push_back(o.slave_surface);
    offset.values.push_back(o.offset);
    reason.ids.push_back(static_cast<std::int64_t>(o.reason));
  }
  t.columns = {node, element, face, slave, offset, reason};
  sink.write_table(t);
}

/// overclosure/step_N/ignored: the penetrations too deep to adjust.
void write_ignored_table(const contact::OverclosureReport& report, const Tables& tables,
                         OutputSink& sink) {
  ResultTable t = tables.table("ignored", static_cast<Index>(report.ignored.size()),
                               "penetrations deeper than the automatic limit (not adjusted)");
  TableColumn node = report::ids("node", "deck id of the slave node");
  TableColumn element = report::ids("master_element", "deck id of the master element");
  TableColumn face = report::ids("master_face", FACE_CODES);
  TableColumn depth = report::reals("depth", "m");
  TableColumn limit = report::reals("limit", "m");
  for (const contact::IgnoredNode& g : report.ignored) {
    node.ids.push_back(tables.node_id(g.node));
    tables.add_face(g.face, element, face);
    depth.values.push_back(g.depth);
    limit.values.push_back(g.limit);
  }
  t.columns = {node, element, face, depth, limit};
  sink.write_table(t);
}

/// overclosure/step_N/crossed: the slave facet edges that cross a master face.
void write_crossed_table(const contact::OverclosureReport& report, const Tables& tables,
                         OutputSink& sink) {
  ResultTable t = tables.table("crossed", static_cast<Index>(report.crossed.size()),
                               "slave facet edges whose nodes lie on opposite sides of a "
                               "master face");
  TableColumn a = report::ids("node_a", "deck id");
  TableColumn b = report::ids("node_b", "deck id");
  TableColumn element = report::ids("master_element", "deck id of the master element");
  TableColumn face = report::ids("master_face", FACE_CODES);
  for (const contact::CrossedEdge& c : report.crossed) {
    a.ids.push_back(tables.node_id(c.node_a));
    b.ids.push_back(tables.node_id(c.node_b));
    tables.add_face(c.face, element, face);
  }
  t.columns = {a, b, element, face};
  sink.write_table(t);
}

}  // namespace

std::string face_label(contact::ElementKind kind, int face) {
  if (kind == contact::ElementKind::Shell) return face == contact::SHELL_SPOS ? "SPOS" : "SNEG";
  std::string label(1, 'S');  // (not "S" + …: GCC 12 warns falsely on that, -Wrestrict)
  label += std::to_string(face + 1);
  return label;
}

void report_overclosures(const contact::OverclosureReport& report,
                         const contact::ContactEngine& engine, const Model& model, int step,
                         const Diagnostics& diagnostics, const AdjustmentEffect& effect,
                         OutputSink& sink,
                         const std::function<bool(Index node, Index face)>& tie_joined) {
  const Names names(engine.domain(), model);
  message_overclosed_nodes(report, names, diagnostics, sink, tie_joined);
  message_crossed_and_refused(report, names, engine.domain(), model, diagnostics, sink);
  message_overclosure_summary(report, model, step, diagnostics, effect, sink);

  const Tables tables(engine, model, step);
  write_adjusted_table(report, tables, sink);
  write_offsets_table(report, tables, sink);
  write_ignored_table(report, tables, sink);
  write_crossed_table(report, tables, sink);
}

}  // namespace xpl
