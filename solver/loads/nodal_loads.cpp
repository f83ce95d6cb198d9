#include "solver/loads/nodal_loads.hpp"

#include <algorithm>
#include <stdexcept>

namespace xpl {

Index NodalLoads::slot_of(Index amplitude) {
  const auto it = std::find(m_amplitudes.begin(), m_amplitudes.end(), amplitude);
  if (it != m_amplitudes.end()) return static_cast<Index>(it - m_amplitudes.begin());
  m_amplitudes.push_back(amplitude);
  return static_cast<Index>(m_amplitudes.size() - 1);
}

void NodalLoads::begin_step(const Model& model, const std::vector<LoadedDof>& cloads,
                            const PressureLoads& pressures, const GravityLoads& gravity) {
  m_pressures = &pressures;
  m_gravity_loads = &gravity;
  m_cloads.clear();
  m_gravity.clear();
  m_face_slot.clear();
  m_term_slot.clear();
  m_amplitudes.clear();
  m_entries.clear();
  m_start.clear();
  const auto n = static_cast<std::size_t>(model.node_count());
  const std::vector<PressureLoads::Face>& faces = pressures.faces();
  const std::vector<GravityLoads::Term>& terms = gravity.terms();
  if (cloads.empty() && faces.empty() && terms.empty()) return;
  if (faces.size() > INDEX_MASK || cloads.size() > INDEX_MASK)
    throw std::length_error("NodalLoads: too many loads for 30-bit entry indices");

  for (const LoadedDof& l : cloads)
    m_cloads.push_back({l.component, slot_of(l.amplitude), l.value});
  for (const PressureLoads::Face& f : faces) m_face_slot.push_back(slot_of(f.amplitude));
  for (const GravityLoads::Term& t : terms) m_term_slot.push_back(slot_of(t.amplitude));

  // Counting sort by node, each kind appended in its own order: per node the CLOADs, then the
  // faces in face order, then the gravity terms in term order.
  std::vector<std::uint32_t> count(n + 1, 0);
  for (const LoadedDof& l : cloads) ++count[l.node + 1];
  for (const PressureLoads::Face& f : faces)
    for (Index node : f.nodes) ++count[node + 1];
  for (const GravityLoads::Term& t : terms)
    for (Index node : t.nodes) ++count[node + 1];
  for (std::size_t i = 0; i < n; ++i) count[i + 1] += count[i];
  m_start = count;
  m_entries.resize(count[n]);
  std::vector<std::uint32_t> next(count.begin(), count.end() - 1);
  for (std::size_t k = 0; k < cloads.size(); ++k)
    m_entries[next[cloads[k].node]++] = CLOAD << KIND_SHIFT | static_cast<std::uint32_t>(k);
  for (std::size_t k = 0; k < faces.size(); ++k)
    for (Index node : faces[k].nodes)
      m_entries[next[node]++] = FACE << KIND_SHIFT | static_cast<std::uint32_t>(k);
  for (std::size_t t = 0; t < terms.size(); ++t)
    for (std::size_t k = 0; k < terms[t].nodes.size(); ++k) {
      if (m_gravity.size() >= INDEX_MASK)
        throw std::length_error("NodalLoads: too many gravity loads for 30-bit entry indices");
      m_entries[next[terms[t].nodes[k]]++] =
          GRAVITY << KIND_SHIFT | static_cast<std::uint32_t>(m_gravity.size());
      m_gravity.push_back({static_cast<Index>(t), terms[t].mass[k]});
    }
  m_factors.assign(m_amplitudes.size(), 0.0);
}

void NodalLoads::set_time(const Model& model, const BoundaryState& amplitudes, Real step_time,
                          Real total_time) {
  for (std::size_t s = 0; s < m_amplitudes.size(); ++s)
    m_factors[s] = amplitudes.factor(model, m_amplitudes[s], step_time, total_time);
}

void NodalLoads::force_at(Index i, const NodalVectors& position, Real f[3]) const {
  f[0] = f[1] = f[2] = 0.0;
  for (std::uint32_t e = m_start[i]; e < m_start[i + 1]; ++e) {
    const std::uint32_t k = m_entries[e] & INDEX_MASK;
    switch (m_entries[e] >> KIND_SHIFT) {
      case CLOAD: {
        const Cload& l = m_cloads[k];
        f[l.component] = multiply_add(l.value, m_factors[l.slot], f[l.component]);
        break;
      }
      case FACE: {
        const PressureLoads::Face& face = m_pressures->faces()[k];
        const Real p = face.sign * face.value * m_factors[m_face_slot[k]];
        if (p == 0.0) break;
        const Real* x = position.data();
        const Index n = static_cast<Index>(position.rows());
        Real a[3], b[3];  // the diagonals d13 and d24
        for (int c = 0; c < 3; ++c) {
          a[c] = x[c * n + face.nodes[2]] - x[c * n + face.nodes[0]];
          b[c] = x[c * n + face.nodes[3]] - x[c * n + face.nodes[1]];
        }
        // s (a × b) with one fused product per component, added to the first two components
        // once rounded and fused into the third: the roundings of the loop over faces this
        // replaces, as it was compiled (the results stay the same to the bit).
        const Real s = 0.125 * p;
        const Real cx = multiply_add(a[1], b[2], -(a[2] * b[1]));
        const Real cy = multiply_add(a[2], b[0], -(a[0] * b[2]));
        const Real cz = multiply_add(a[0], b[1], -(a[1] * b[0]));
        f[0] += s * cx;
        f[1] += s * cy;
        f[2] = multiply_add(s, cz, f[2]);
        break;
      }
      default: {
        const Gravity& g = m_gravity[k];
        const GravityLoads::Term& t = m_gravity_loads->terms()[g.term];
        const Real factor = m_factors[m_term_slot[g.term]];
        for (int c = 0; c < 3; ++c) f[c] = multiply_add(factor * g.mass, t.acceleration[c], f[c]);
        break;
      }
    }
  }
}

}  // namespace xpl
