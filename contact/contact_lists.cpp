// The lists ContactEngine's search (contact_search.cpp) walks: the broad-phase refresh, with
// each slot's candidates sifted by the rules that do not depend on positions, and the view of
// a slave node that the admissibility test reads.
#include <algorithm>
#include <span>
#include <vector>

#include "contact/contact_engine.hpp"

namespace xpl::contact {

ContactEngine::SlaveView ContactEngine::slave_view(Index s, const NodalVectors& position,
                                                   std::span<const Real> node_thickness,
                                                   bool all_faces) const {
  const std::vector<ContactFace>& faces = m_domain.faces();
  SlaveView v;
  v.slot = s;
  const Index node = m_domain.slaves().nodes()[s];
  v.node = node;
  v.point = node_point(position, node);
  v.normal = m_domain.slaves().normal(s);
  v.double_sided = m_domain.slave_double_sided(s);
  v.free_edge = m_domain.slave_on_free_edge(s);
  v.point_node = m_domain.slave_point(s);
  v.half_t = v.double_sided ? 0.5 * node_thickness_of(node_thickness, node) : 0.0;
  v.listed = !all_faces;
  if (v.double_sided && all_faces) {
    // The nodes of its own elements, once per node rather than once per candidate face.
    for (Index g : m_domain.slaves().faces_of(s))
      for (Index a : faces[g].nodes) {
        if (v.own_count < 0) break;
        bool seen = false;
        for (int k = 0; k < v.own_count; ++k) seen = seen || v.own[k] == a;
        if (seen) continue;
        if (v.own_count == static_cast<int>(v.own.size()))
          v.own_count = -1;  // more than fit: admissible() walks the faces instead
        else
          v.own[v.own_count++] = a;
      }
  }
  const ContactConstraint& before = m_constraints[s];
  if (before.offset_permanent) v.allowance = std::max(before.offset, 0.0);
  // Side memory: a node pressed onto one side of a shell last increment may not be taken by
  // the other side of that shell, however deep it has gone (no pass-through).
  if (before.status == ContactStatus::Closed && before.master_face >= 0 &&
      faces[before.master_face].shell)
    v.held = &faces[before.master_face];
  if (m_updated && before.status == ContactStatus::Closed && before.master_face >= 0 &&
      !faces[before.master_face].shell)
    v.continuing = before.master_face;
  return v;
}

bool ContactEngine::never_admissible(const SlaveView& v, Index f) const {
  const std::vector<ContactFace>& faces = m_domain.faces();
  // A face of the node's own hex (file comment).
  if (faces[f].behind(v.node)) return true;
  // A shell face next to the shell node's own elements continues its own shell (file comment).
  if (v.double_sided && faces[f].shell) {
    bool own = false;
    if (v.own_count >= 0) {
      for (Index b : faces[f].nodes)
        for (int k = 0; k < v.own_count; ++k) own = own || v.own[k] == b;
    } else {
      for (Index g : m_domain.slaves().faces_of(v.slot))
        for (Index a : faces[g].nodes)
          for (Index b : faces[f].nodes) own = own || a == b;
    }
    if (own) return true;
  }
  Index pair = NO_INDEX;
  return m_domain.weight(v.slot, f, pair) == 0.0;
}

void ContactEngine::widen_search(Real extra) {
  if (!(extra > 0.0)) return;
  m_broad = BroadPhase(m_broad.margin() + extra, m_broad.rebuild_motion());
}

bool ContactEngine::refresh_broad_phase(const NodalVectors& position,
                                        std::span<const Real> node_thickness, Real* step_sq) {
  SlaveNodes& slaves = m_domain.slaves();
  // A shared pass scans only this process's slots; a whole one (probe(), the step's
  // overclosure passes) needs every slot's candidates, so it does not reuse such a build.
  const bool whole_needed = !m_shared_pass && m_broad_owned_only;
  // A decision the processes took together (decide_rebuild()) holds for this update() alone.
  const bool decided = m_rebuild_decision >= 0 && m_shared_pass && m_broad.build_count() > 0;
  // The step motion (sleeping slots) comes from the same walk as the rebuild motion.
  const bool due = decided              ? m_rebuild_decision != 0
                   : step_sq == nullptr ? m_broad.needs_rebuild(position)
                   : m_broad.build_count() == 0
                       ? true
                       : m_broad.exceeds_rebuild_motion(m_broad.motions_sq(position, {}, *step_sq));
  m_rebuild_decision = -1;
  if (!due && !whole_needed) return false;
  m_broad_owned_only = m_shared_pass;
  m_broad.build(m_domain.faces(), slaves.nodes(), position, node_thickness, m_domain.face_depths(),
                m_shared_pass ? std::span<const char>(m_owned) : std::span<const char>(),
                m_shared_pass ? m_faces_held : std::span<const char>());
  const Index n_slave = slaves.size();
  m_active_slot.assign(static_cast<std::size_t>(n_slave), 0);
  m_active_face.assign(m_domain.faces().size(), 0);
  m_try_skip = false;
  for (Index f = 0; f < static_cast<Index>(m_domain.faces().size()) && !m_try_skip; ++f) {
    const ContactFace& face = m_domain.faces()[f];
    Real depth = m_domain.face_depth(f);
    if (face.shell) {
      Real t = 0.0;
      for (Index c : face.nodes) t += node_thickness_of(node_thickness, c);
      depth = DEPTH_LIMIT_FRACTION * 0.25 * t;
    }
    m_try_skip = depth < m_broad.margin();
  }
  // Each slot's candidates less the faces never_admissible() rejects (topology and pairs,
  // fixed for the step): the search's lists.
  m_listed_offset.assign(static_cast<std::size_t>(n_slave) + 1, 0);
  m_listed.clear();
  m_listed_slots.clear();
  for (Index s = 0; s < n_slave; ++s) {
    const std::span<const Index> candidates = m_broad.candidates(s);
    if (!candidates.empty() && owned(s)) {  // another process searches the others
      const SlaveView view = slave_view(s, position, node_thickness);
      for (Index f : candidates)
        if (!never_admissible(view, f)) m_listed.push_back(f);
    }
    m_listed_offset[s + 1] = static_cast<Index>(m_listed.size());
    if (m_listed_offset[s + 1] > m_listed_offset[s]) m_listed_slots.push_back(s);
  }
  for (Index s = 0; s < n_slave; ++s)
    if (!m_broad.candidates(s).empty()) m_active_slot[s] = 1;
  // The other processes' slots with candidates, so that every process updates the same node
  // areas (the output's contact pressures read them) and every slot's faces.
  if (m_shared_pass) share_active_slots();
  for (Index s = 0; s < n_slave; ++s) {
    if (m_active_slot[s] == 0) continue;
    for (Index f : slaves.faces_of(s)) m_active_face[f] = 1;
  }
  return true;
}

void ContactEngine::build_shared_broad_phase(const NodalVectors& position,
                                             std::span<const Real> node_thickness,
                                             std::span<const char> faces_held) {
  m_shared_pass = true;
  m_rebuild_decision = 1;
  m_faces_held = faces_held;
  refresh_broad_phase(position, node_thickness);
  m_faces_held = {};
  m_shared_pass = false;
  m_built_ahead = true;
}

bool ContactEngine::probe(const NodalVectors& position, std::span<const Real> node_thickness) {
  const bool rebuild = refresh_broad_phase(position, node_thickness);
  m_visit_all = true;  // the search below writes every slot
  build_visits();
  m_domain.slaves().update_areas(m_domain.faces(), position);
  search(position, node_thickness);
  return rebuild;
}

}  // namespace xpl::contact
