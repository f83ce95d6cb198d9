// The nodes a distributed run's process reads for the slots it searches (ContactEngine::
// mark_read_nodes, docs/dev/mpi.md "Contact shared out among the ranks"): between two builds
// of the broad phase a slot's search and springs look only at its node, its candidate faces
// and the faces its state already holds (the face it is pressed on, the held shell, the face
// of a release), so these rows are all it needs of the other processes' nodes.
#include "contact/contact_engine.hpp"

namespace xpl::contact {

bool ContactEngine::mark_read_nodes(std::vector<char>& mark) const {
  if (m_user_stiffness) return false;  // every slot's area each increment (update())
  const SlaveNodes& slaves = m_domain.slaves();
  const std::vector<ContactFace>& faces = m_domain.faces();
  const auto corners = [&](Index f) {
    if (f == NO_INDEX) return;
    for (Index a : faces[f].nodes) mark[a] = 1;
  };
  for (Index s = 0; s < slaves.size(); ++s) {
    if (!m_owned.empty() && m_owned[s] == 0) continue;
    const std::span<const Index> candidates = m_broad.candidates(s);
    const bool held = m_constraints[s].master_face != NO_INDEX ||
                      m_second[s].master_face != NO_INDEX || m_touch[s].face != NO_INDEX ||
                      m_second_touch[s].face != NO_INDEX || m_event_face[s] != NO_INDEX;
    if (candidates.empty() && !held) continue;
    mark[slaves.nodes()[s]] = 1;
    for (Index f : candidates) corners(f);
    corners(m_constraints[s].master_face);
    corners(m_second[s].master_face);
    corners(m_touch[s].face);
    corners(m_second_touch[s].face);
    corners(m_event_face[s]);
  }
  return true;
}

}  // namespace xpl::contact
