#include "solver/loads/pressure_loads.hpp"

#include <algorithm>

namespace xpl {

namespace {

/// Whether a step after `step` adds pressures to those in force at its end (the first later
/// step that resets or gives pressures gives some without resetting).
bool later_step_adds(const Model& model, int step) {
  for (std::size_t k = static_cast<std::size_t>(step) + 1; k < model.steps.size(); ++k) {
    const Step& s = model.steps[k];
    if (s.pressures_reset) return false;
    if (!s.pressures.empty()) return true;
  }
  return false;
}

}  // namespace

void PressureLoads::begin_step(const Model& model, int step) {
  const Step& s = model.steps[step];
  // A step that neither resets nor gives pressures keeps the faces of the one before.
  if (!s.pressures_reset && s.pressures.empty()) return;
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
  m_faces.reserve(m_active.size());
  m_nodes.clear();
  m_nodes.reserve(4 * m_active.size());
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
  m_faces.shrink_to_fit();
  std::sort(m_nodes.begin(), m_nodes.end());
  m_nodes.erase(std::unique(m_nodes.begin(), m_nodes.end()), m_nodes.end());
  m_nodes.shrink_to_fit();
  // The faces are all a step needs; the sorted entries only serve a later step that adds
  // faces to them (issue 38: 24 bytes per loaded face at the run's peak).
  if (!later_step_adds(model, step)) {
    m_active.clear();
    m_active.shrink_to_fit();
  }
}

}  // namespace xpl
