#include "solver/loads/pressure_loads.hpp"

#include <algorithm>

namespace xpl {

void PressureLoads::begin_step(const Model& model, int step) {
  const Step& s = model.steps[step];
  if (s.pressures_reset) m_active.clear();
  if (!s.pressures.empty()) {
    // The earlier steps' faces, then this step's in deck order; a stable sort by face keeps
    // that order among equal faces, so the last of each run is the entry in force (a later
    // line for the same face replaces an earlier one).
    m_active.reserve(m_active.size() + s.pressures.size());
    for (const PressureLoad& p : s.pressures)
      m_active.push_back({{p.face.element, p.face.face}, {p.face, p.value, p.amplitude}});
    std::stable_sort(m_active.begin(), m_active.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    std::size_t kept = 0;
    for (std::size_t i = 0; i < m_active.size(); ++i) {
      if (i + 1 < m_active.size() && m_active[i + 1].first == m_active[i].first) continue;
      m_active[kept++] = m_active[i];
    }
    m_active.resize(kept);
    m_active.shrink_to_fit();
  }
  m_faces.clear();
  m_nodes.clear();
  for (const auto& [key, p] : m_active) {
    const Index e = p.face.element;
    const Index* en = model.nodes_of(e);
    Face f;
    if (is_shell(model.element_types[e])) {
      for (int a = 0; a < 4; ++a) f.nodes[a] = en[a];
      // Positive pressure pushes against the face's outward normal: SPOS faces +n, so the
      // load acts along −n; SNEG faces −n, so it acts along +n.
      f.sign = p.face.face == SHELL_FACE_POS ? -1.0 : 1.0;
    } else {
      for (int a = 0; a < 4; ++a) f.nodes[a] = en[HEX_FACE_NODES[p.face.face][a]];
      f.sign = 1.0;  // the corner cycle's normal points into the element
    }
    f.value = p.value;
    f.amplitude = p.amplitude;
    m_faces.push_back(f);
    m_nodes.insert(m_nodes.end(), f.nodes, f.nodes + 4);
  }
  std::sort(m_nodes.begin(), m_nodes.end());
  m_nodes.erase(std::unique(m_nodes.begin(), m_nodes.end()), m_nodes.end());
}

}  // namespace xpl
