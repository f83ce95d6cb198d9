#include "solver/loads/external_loads.hpp"

namespace xpl {

void ExternalLoads::begin_step(const Model& model, int step, const BoundaryState& boundary,
                               const NodalVectors& reference, const std::vector<Real>& mass,
                               const std::vector<PrescribedDof>& prescribed) {
  m_pressures.begin_step(model, step);
  m_gravity.begin_step(model, step, reference, mass);
  collect(model, boundary, prescribed);
}

void ExternalLoads::collect(const Model& model, const BoundaryState& boundary,
                            const std::vector<PrescribedDof>& prescribed) {
  const auto n = static_cast<std::size_t>(model.node_count());
  m_loads.begin_step(model, boundary.loads(), m_pressures, m_gravity);
  // The work of the loads is summed over the free loaded DOFs in the order they were once
  // listed (CLOADs, then pressure nodes, then gravity nodes), so that ALLWK keeps its
  // round-off.
  std::vector<char> is_prescribed(n * 6, 0);
  for (const PrescribedDof& d : prescribed) is_prescribed[d.component * n + d.node] = 1;
  std::vector<char> is_loaded(n * 3, 0);
  std::vector<Index> order;
  for (const LoadedDof& l : boundary.loads()) {
    is_loaded[l.component * n + l.node] = 1;
    order.push_back(static_cast<Index>(l.component * n + l.node));
  }
  for (const std::vector<Index>* nodes : {&m_pressures.nodes(), &m_gravity.nodes()})
    for (Index node : *nodes)
      for (int c = 0; c < 3; ++c)
        if (!is_loaded[c * n + node]) {
          is_loaded[c * n + node] = 1;
          order.push_back(static_cast<Index>(c * n + node));
        }
  m_free_load_dofs.clear();
  m_free_load_mask.assign(m_loads.empty() ? 0 : n, 0);
  for (Index at : order)
    if (!is_prescribed[at]) {
      m_free_load_dofs.push_back(at);
      m_free_load_mask[at % n] |= static_cast<std::uint8_t>(1u << (at / n));
    }
  m_free_load_nodes.clear();
  for (Index i = 0; i < static_cast<Index>(m_free_load_mask.size()); ++i)
    if (m_free_load_mask[i] != 0) m_free_load_nodes.push_back(i);
  if (!m_free_load_dofs.empty() && m_work_force.rows() == 0) {
    m_work_force = NodalVectors::Zero(model.node_count(), 3);
    m_work_velocity = NodalVectors::Zero(model.node_count(), 3);
  }
  // Forces of loads the step no longer has must not stay behind.
  if (m_force.rows() > 0) m_force.setZero();
}

void ExternalLoads::apply(const Model& model, const BoundaryState& boundary, Real step_time,
                          Real total_time) {
  if (m_loads.empty()) return;
  m_loads.set_time(model, boundary, step_time, total_time);
  m_due = true;
  if (m_force.rows() == 0) m_force = NodalVectors::Zero(model.node_count(), 3);
}

void ExternalLoads::evaluate(Index first, Index last, const NodalVectors& position,
                             const Real* velocity_half, Real dt_prev,
                             NodalVectors& previous_force) {
  // The loads of the nodes, and the work of those on free DOFs over the increment just taken
  // (trapezoidal rule, exact for constant forces), before v(n−½) moves on.
  const Index n = position.rows();
  Real* fe = m_force.data();
  Real* f_before = previous_force.data();
  Real* mean_force = m_work_force.data();
  Real* v_before = m_work_velocity.data();
  const bool free_loads = !m_free_load_dofs.empty();
  for (Index i = first; i < last; ++i) {
    if (!m_loads.loaded(i)) continue;
    Real f[3];
    m_loads.force_at(i, position, f);
    for (int c = 0; c < 3; ++c) {
      const Index at = c * n + i;
      fe[at] = f[c];
      if (!free_loads || !(m_free_load_mask[i] >> c & 1u)) continue;
      mean_force[at] = 0.5 * (f_before[at] + f[c]) * dt_prev;
      v_before[at] = velocity_half[at];
      f_before[at] = f[c];
    }
  }
}

void ExternalLoads::add_work(Real& work) {
  if (m_due)
    for (Index at : m_free_load_dofs)
      work = multiply_add(m_work_force.data()[at], m_work_velocity.data()[at], work);
  m_due = false;
  m_evaluated = false;
}

void ExternalLoads::share_positions(const NodeRowShare& share, NodalVectors& position) const {
  if (m_due && !m_pressures.empty()) share(m_pressures.nodes(), {&position});
}

void ExternalLoads::share_work(const NodeRowShare& share) {
  if (m_due && !m_free_load_dofs.empty())
    share(m_free_load_nodes, {&m_work_force, &m_work_velocity});
}

}  // namespace xpl
