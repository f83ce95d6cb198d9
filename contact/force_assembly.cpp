#include "contact/force_assembly.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>

namespace xpl::contact {

ForceAssembly::ForceAssembly(Index n_slave, Index n_pairs) {
  const auto n = static_cast<std::size_t>(n_slave);
  m_force.assign(3 * n, 0.0);
  m_previous_force.assign(3 * n, 0.0);
  m_pair_normal.assign(static_cast<std::size_t>(n_pairs), 0.0);
  m_pair_friction.assign(m_pair_normal.size(), 0.0);
  m_marked.assign(n, 0);
}

void ForceAssembly::assemble(const SlaveNodes& slaves, const std::vector<ContactFace>& faces,
                             std::span<const Index> slots, const SpringSet& first,
                             const SpringSet& second, const NodalVectors& velocity_half,
                             std::span<const Real> slot_velocity, Real dt,
                             NodalVectors& force_internal, ContactTotals& totals) {
  m_previous_force.swap(m_force);
  m_previous_forced.swap(m_forced);
  // The array of two increments ago is non-zero at its own list only.
  for (const Index s : m_forced)
    for (int d = 0; d < 3; ++d) m_force[3 * s + d] = 0.0;
  m_forced.clear();
  std::fill(m_pair_normal.begin(), m_pair_normal.end(), 0.0);
  std::fill(m_pair_friction.begin(), m_pair_friction.end(), 0.0);
  for (const Index s : slots) add_spring(slaves, faces, first, s, force_internal, totals);
  for (const Index s : slots)
    if (second.touch[s].face != NO_INDEX)
      add_spring(slaves, faces, second, s, force_internal, totals);
  for (const Index s : m_forced) m_marked[s] = 0;
  std::sort(m_forced.begin(), m_forced.end());
  if (dt > 0.0) add_work(slaves, velocity_half, slot_velocity, dt, totals.work);
}

void ForceAssembly::add_spring(const SlaveNodes& slaves, const std::vector<ContactFace>& faces,
                               const SpringSet& set, Index s, NodalVectors& force_internal,
                               ContactTotals& totals) {
  const SlaveTouch& t = set.touch[s];
  if (t.face == NO_INDEX) return;
  const Vec3 f(set.slave_force[3 * s], set.slave_force[3 * s + 1], set.slave_force[3 * s + 2]);
  if (f.dot(f) == 0.0) return;
  const Index node = slaves.nodes()[s];
  mark(s);
  for (int d = 0; d < 3; ++d) {
    m_force[3 * s + d] += f[d];
    force_internal(node, d) -= f[d];
  }
  const ContactFace& face = faces[t.face];
  for (int a = 0; a < 4; ++a) {
    const Index corner = face.nodes[a];
    const Index cs = slaves.slot(corner);
    mark(cs);
    for (int d = 0; d < 3; ++d) {
      const Real share = t.shape[a] * f[d];
      m_force[3 * cs + d] -= share;
      force_internal(corner, d) += share;
    }
  }
  ++totals.closed;
  if (t.pair != NO_INDEX) {
    m_pair_normal[t.pair] += set.normal_force[s];
    const Vec3& ft = set.constraints[s].tangential_force;
    m_pair_friction[t.pair] += std::sqrt(ft.dot(ft));
  }
  totals.friction_dissipation += set.dissipation[s];
}

void ForceAssembly::add_work(const SlaveNodes& slaves, const NodalVectors& velocity_half,
                             std::span<const Real> slot_velocity, Real dt, Real& work) {
  m_worked.clear();
  std::set_union(m_forced.begin(), m_forced.end(), m_previous_forced.begin(),
                 m_previous_forced.end(), std::back_inserter(m_worked));
  for (const Index s : m_worked) {
    const Real* now = &m_force[3 * s];
    const Real* before = &m_previous_force[3 * s];
    if (now[0] == 0.0 && now[1] == 0.0 && now[2] == 0.0 && before[0] == 0.0 && before[1] == 0.0 &&
        before[2] == 0.0)
      continue;
    const Index node = slaves.nodes()[s];
    for (int d = 0; d < 3; ++d) {
      const Real v = slot_velocity.empty() ? velocity_half(node, d) : slot_velocity[3 * s + d];
      work += 0.5 * (now[d] + before[d]) * v * dt;
    }
  }
}

}  // namespace xpl::contact
