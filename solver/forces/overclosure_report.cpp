#include "solver/forces/overclosure_report.hpp"

#include <algorithm>
#include <cstdio>

namespace xpl {

namespace {

/// Face codes of the tables: hex S1..S6 = 1..6, shell SPOS = 7, SNEG = 8.
constexpr const char* FACE_CODES = "1..6: S1..S6 of a C3D8R; 7: SPOS, 8: SNEG of an S4R";

std::string real_text(Real v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.4e", v);
  return buffer;
}

std::string vector_text(const contact::Vec3& v) {
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, "(%.4f, %.4f, %.4f)", v[0], v[1], v[2]);
  return buffer;
}

std::int64_t face_code(const contact::ContactFace& face) {
  if (!face.shell) return face.face + 1;
  return face.face == contact::SHELL_SPOS ? 7 : 8;
}

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
  static TableColumn ids(const std::string& name, const std::string& description) {
    TableColumn c;
    c.name = name;
    c.integer = true;
    c.description = description;
    return c;
  }
  static TableColumn reals(const std::string& name, const std::string& description,
                           Index width = 1) {
    TableColumn c;
    c.name = name;
    c.width = width;
    c.description = description;
    return c;
  }
  /// Appends the master element id and face code of contact face f to two columns.
  void add_face(Index f, TableColumn& element, TableColumn& face) const {
    const contact::ContactFace& cf = m_engine.domain().faces()[f];
    element.ids.push_back(m_model.element_ids[cf.element]);
    face.ids.push_back(face_code(cf));
  }
  std::int64_t node_id(Index node) const { return m_model.node_ids[node]; }

 private:
  const contact::ContactEngine& m_engine;
  const Model& m_model;
  std::string m_prefix;
};

std::string surface_text(const contact::ContactDomain& domain, Index surface) {
  return surface == NO_INDEX ? std::string("?") : domain.surface_name(surface);
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
                         OutputSink& sink) {
  const contact::ContactDomain& domain = engine.domain();
  const std::string step_name = model.steps[step].name;
  auto face_text = [&](Index f) {
    const contact::ContactFace& cf = domain.faces()[f];
    return "face " +
           face_label(cf.shell ? contact::ElementKind::Shell : contact::ElementKind::Hex, cf.face) +
           " of element " + std::to_string(model.element_ids[cf.element]);
  };
  auto node_text = [&](Index node) { return "node " + std::to_string(model.node_ids[node]); };

  if (diagnostics.overclosure_detail) {
    for (const contact::AdjustedNode& a : report.adjusted)
      sink.message(Severity::Info, "initial overclosure: " + node_text(a.node) +
                                       " (slave surface " + surface_text(domain, a.slave_surface) +
                                       ") adjusted by " + real_text(a.distance) + " m along " +
                                       vector_text(a.direction) + "; it penetrated " +
                                       face_text(a.face) + " (master surface " +
                                       surface_text(domain, a.master_surface) + ") by " +
                                       real_text(a.penetration) + " m");
    for (const contact::OffsetNode& o : report.offsets)
      sink.message(Severity::Info, "initial overclosure: " + node_text(o.node) +
                                       " (slave surface " + surface_text(domain, o.slave_surface) +
                                       ") keeps a temporary contact offset d0 = " +
                                       real_text(o.offset) + " m against " + face_text(o.face) +
                                       " (reason: " + contact::offset_reason_name(o.reason) +
                                       "); no force until it penetrates further, and d0 "
                                       "shrinks as the surfaces separate");
    for (const contact::IgnoredNode& g : report.ignored)
      sink.message(Severity::Warning,
                   "initial overclosure: " + node_text(g.node) + " (slave surface " +
                       surface_text(domain, g.slave_surface) + ") penetrates " + face_text(g.face) +
                       " by " + real_text(g.depth) + " m, deeper than the automatic limit " +
                       real_text(g.limit) +
                       " m (15 % of the facet size): not adjusted; the penalty will push it "
                       "out from the first increment. Fix the mesh or use *CONTACT CLEARANCE");
  } else if (!report.ignored.empty()) {
    sink.message(Severity::Warning,
                 std::to_string(report.ignored.size()) +
                     " slave node(s) penetrate deeper than the automatic limit and are not "
                     "adjusted (CONTACT INITIAL OVERCLOSURE=SUMMARY: see the results file, "
                     "/overclosure, for the list)");
  }
  // Crossed surfaces are warnings at both levels (C5): they point at modelling errors.
  constexpr std::size_t MAX_CROSSED_LISTED = 100;
  for (std::size_t k = 0; k < report.crossed.size() && k < MAX_CROSSED_LISTED; ++k) {
    const contact::CrossedEdge& c = report.crossed[k];
    sink.message(Severity::Warning,
                 "crossed surfaces: slave nodes " + std::to_string(model.node_ids[c.node_a]) +
                     " and " + std::to_string(model.node_ids[c.node_b]) +
                     " (joined by a facet edge) lie on opposite sides of " + face_text(c.face) +
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

  // Tables.
  Tables tables(engine, model, step);
  {
    ResultTable t = tables.table("adjusted", static_cast<Index>(report.adjusted.size()),
                                 "slave nodes moved onto the master surface (strain free)");
    TableColumn node = Tables::ids("node", "deck id of the slave node");
    TableColumn element = Tables::ids("master_element", "deck id of the master element");
    TableColumn face = Tables::ids("master_face", FACE_CODES);
    TableColumn slave = Tables::ids("slave_surface", "index into attribute surface_names");
    TableColumn penetration = Tables::reals("penetration", "m, as read");
    TableColumn distance = Tables::reals("distance", "m, length of the move");
    TableColumn direction = Tables::reals("direction", "unit vector of the move", 3);
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
  {
    ResultTable t = tables.table("offsets", static_cast<Index>(report.offsets.size()),
                                 "temporary contact offsets d0 (unresolved penetrations)");
    TableColumn node = Tables::ids("node", "deck id of the slave node");
    TableColumn element = Tables::ids("master_element", "deck id of the master element");
    TableColumn face = Tables::ids("master_face", FACE_CODES);
    TableColumn slave = Tables::ids("slave_surface", "index into attribute surface_names");
    TableColumn offset = Tables::reals("offset", "d0, m");
    TableColumn reason = Tables::ids(
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
  {
    ResultTable t = tables.table("ignored", static_cast<Index>(report.ignored.size()),
                                 "penetrations deeper than the automatic limit (not adjusted)");
    TableColumn node = Tables::ids("node", "deck id of the slave node");
    TableColumn element = Tables::ids("master_element", "deck id of the master element");
    TableColumn face = Tables::ids("master_face", FACE_CODES);
    TableColumn depth = Tables::reals("depth", "m");
    TableColumn limit = Tables::reals("limit", "m");
    for (const contact::IgnoredNode& g : report.ignored) {
      node.ids.push_back(tables.node_id(g.node));
      tables.add_face(g.face, element, face);
      depth.values.push_back(g.depth);
      limit.values.push_back(g.limit);
    }
    t.columns = {node, element, face, depth, limit};
    sink.write_table(t);
  }
  {
    ResultTable t = tables.table("crossed", static_cast<Index>(report.crossed.size()),
                                 "slave facet edges whose nodes lie on opposite sides of a "
                                 "master face");
    TableColumn a = Tables::ids("node_a", "deck id");
    TableColumn b = Tables::ids("node_b", "deck id");
    TableColumn element = Tables::ids("master_element", "deck id of the master element");
    TableColumn face = Tables::ids("master_face", FACE_CODES);
    for (const contact::CrossedEdge& c : report.crossed) {
      a.ids.push_back(tables.node_id(c.node_a));
      b.ids.push_back(tables.node_id(c.node_b));
      tables.add_face(c.face, element, face);
    }
    t.columns = {a, b, element, face};
    sink.write_table(t);
  }
}

void report_clearances(const contact::ClearanceReport& report,
                       const std::vector<ClearanceViewNames>& views,
                       const contact::ContactEngine& engine, const Model& model, int step,
                       const Diagnostics& diagnostics, OutputSink& sink) {
  const contact::ContactDomain& domain = engine.domain();
  auto face_text = [&](Index f) {
    const contact::ContactFace& cf = domain.faces()[f];
    return "face " +
           face_label(cf.shell ? contact::ElementKind::Shell : contact::ElementKind::Hex, cf.face) +
           " of element " + std::to_string(model.element_ids[cf.element]);
  };
  auto view_text = [&](Index v) {
    return std::string(views[v].initialization ? "contact initialization " : "contact clearance ") +
           views[v].clearance + ": node ";
  };
  std::size_t adjusted = 0, offsets = 0, interference = 0;
  Real largest_interference = 0.0;
  for (const contact::ClearedNode& c : report.nodes) {
    adjusted += c.distance > 0.0 ? 1 : 0;
    offsets += c.offset != 0.0 ? 1 : 0;
    interference += c.interference > 0.0 ? 1 : 0;
    largest_interference = std::max(largest_interference, c.interference);
    if (!diagnostics.overclosure_detail) continue;
    std::string text = view_text(c.view) + std::to_string(model.node_ids[c.node]) +
                       " (slave surface " + views[c.view].slave + ", master surface " +
                       views[c.view].master + ", " + face_text(c.face) + "): gap " +
                       real_text(c.gap_before) + " m as read";
    if (!views[c.view].interference) text += ", clearance " + real_text(c.clearance) + " m";
    if (c.interference > 0.0)
      text += "; interference fit: overclosure " + real_text(c.interference) +
              " m resolved by the penalty over the first " +
              real_text(views[c.view].step_fraction * model.steps[step].time_period) +
              " s of the step (offset ramped to zero)";
    if (c.distance > 0.0)
      text += "; adjusted by " + real_text(c.distance) + " m along " + vector_text(c.direction);
    if (c.offset != 0.0)
      text += "; permanent contact offset d0 = " + real_text(c.offset) + " m" +
              (c.distance > 0.0 || c.reason != contact::OffsetReason::Conflict
                   ? std::string(" (reason: ") + contact::offset_reason_name(c.reason) + ")"
                   : std::string());
    sink.message(Severity::Info, text);
  }
  for (const contact::SkippedNode& k : report.skipped)
    if (diagnostics.overclosure_detail)
      sink.message(Severity::Note, view_text(k.view) + std::to_string(model.node_ids[k.node]) +
                                       " (slave surface " + views[k.view].slave +
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
  const std::string summary =
      "contact clearances, step " + std::to_string(step + 1) + " (" + model.steps[step].name +
      "): " + std::to_string(report.nodes.size()) + " slave node(s) in search zones, " +
      std::to_string(adjusted) + " adjusted, " + std::to_string(offsets) +
      " permanent offset(s), " + std::to_string(report.skipped.size()) + " skipped (" +
      std::to_string(report.passes) + " adjustment pass(es), smallest scaled corner Jacobian " +
      real_text(report.quality_before) + " before, " + real_text(report.quality_after) +
      " after); pass " + real_text(report.seconds) + " s";
  sink.status_note(summary);
  sink.message(Severity::Info, summary);
  if (interference > 0) {
    std::string names;
    for (std::size_t v = 0; v < views.size(); ++v)
      if (views[v].interference && names.find(views[v].clearance) == std::string::npos)
        names += (names.empty() ? "" : ", ") + views[v].clearance;
    const std::string fits =
        "interference fits, step " + std::to_string(step + 1) + " (" + model.steps[step].name +
        "): " + std::to_string(interference) + " overclosure(s) of slave nodes (largest " +
        real_text(largest_interference) + " m) are resolved by the penalty as their offsets ramp " +
        "to zero over the step fraction (" + names +
        "); the automatic strain-free pass leaves them alone, and the ramp's energy is booked "
        "in ALLWK and ALLPW (SPEC C15)";
    sink.status_note(fits);
    sink.message(Severity::Info, fits);
  }

  const std::string prefix = "overclosure/step_" + std::to_string(step + 1) + "/";
  auto table = [&](const std::string& name, Index rows, const std::string& description) {
    ResultTable t;
    t.path = prefix + name;
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
  };
  {
    ResultTable t = table("clearances", static_cast<Index>(report.nodes.size()),
                          "slave nodes given a contact clearance (C7-C10)");
    TableColumn node = Tables::ids("node", "deck id of the slave node");
    TableColumn view = Tables::ids("view",
                                   "index into the attributes view_clearance, "
                                   "view_slave_surface, view_master_surface");
    TableColumn element =
        Tables::ids("master_element", "deck id of the nearest master element as read");
    TableColumn face = Tables::ids("master_face", FACE_CODES);
    TableColumn clearance = Tables::reals("clearance", "m, positive above the master surface");
    TableColumn gap = Tables::reals("gap_before", "m, as read (negative: below the surface)");
    TableColumn distance = Tables::reals("distance", "m, length of the move");
    TableColumn direction = Tables::reals("direction", "unit vector of the move", 3);
    TableColumn offset = Tables::reals("offset", "permanent contact offset d0, m (0: none)");
    for (const contact::ClearedNode& c : report.nodes) {
      node.ids.push_back(model.node_ids[c.node]);
      view.ids.push_back(c.view);
      const contact::ContactFace& cf = domain.faces()[c.face];
      element.ids.push_back(model.element_ids[cf.element]);
      face.ids.push_back(face_code(cf));
      clearance.values.push_back(c.clearance);
      gap.values.push_back(c.gap_before);
      distance.values.push_back(c.distance);
      for (int d = 0; d < 3; ++d) direction.values.push_back(c.direction[d]);
      offset.values.push_back(c.offset);
    }
    t.columns = {node, view, element, face, clearance, gap, distance, direction, offset};
    sink.write_table(t);
  }
  {
    ResultTable t = table("clearance_skipped", static_cast<Index>(report.skipped.size()),
                          "slave nodes in a search zone that got no clearance");
    TableColumn node = Tables::ids("node", "deck id of the slave node");
    TableColumn view = Tables::ids("view", "index into the attribute view_clearance");
    TableColumn why =
        Tables::ids("reason",
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
}

}  // namespace xpl
