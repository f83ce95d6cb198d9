#include "solver/loads/gravity_loads.hpp"

#include <algorithm>

#include "solver/forces/element_kinds.hpp"

namespace xpl {

void GravityLoads::begin_step(const Model& model, int step, const NodalVectors& reference,
                              const std::vector<Real>& nodal_mass) {
  const Step& s = model.steps[step];
  if (s.gravity_reset) m_active.clear();
  for (const GravityLoad& g : s.gravity) m_active[g.element_set] = g;
  m_terms.clear();
  m_nodes.clear();
  for (const auto& [set, g] : m_active) {
    Term t;
    for (int c = 0; c < 3; ++c) t.acceleration[c] = g.magnitude * g.direction[c];
    t.amplitude = g.amplitude;
    if (set == NO_INDEX) {
      for (Index n = 0; n < model.node_count(); ++n)
        if (nodal_mass[n] > 0.0) {
          t.nodes.push_back(n);
          t.mass.push_back(nodal_mass[n]);
        }
    } else {
      std::map<Index, Real> share;
      for (Index e : model.element_sets[set].members) {
        const Real m = element_node_mass(model, e, reference);
        const Index* nodes = model.nodes_of(e);
        for (int a = 0; a < nodes_per_element(model.element_types[e]); ++a) share[nodes[a]] += m;
      }
      for (const auto& [node, m] : share) {
        t.nodes.push_back(node);
        t.mass.push_back(m);
      }
    }
    m_nodes.insert(m_nodes.end(), t.nodes.begin(), t.nodes.end());
    m_terms.push_back(std::move(t));
  }
  std::sort(m_nodes.begin(), m_nodes.end());
  m_nodes.erase(std::unique(m_nodes.begin(), m_nodes.end()), m_nodes.end());
}

}  // namespace xpl
