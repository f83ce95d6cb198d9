#include "solver/loads/boundary_state.hpp"

#include <algorithm>
#include <map>
#include <utility>

namespace xpl {

void BoundaryState::begin_step(const Model& model, int step, const NodalVectors& displacement,
                               const NodalVectors& velocity, const NodalVectors& rotation,
                               const NodalVectors& angular_velocity) {
  const bool rotations = rotation.rows() > 0;
  const Step& s = model.steps[step];
  m_ramp = s.ramp_amplitude;
  m_period = s.time_period;
  m_rotational = false;

  // Boundary conditions: keyed by (node, component) so later entries replace earlier ones.
  std::map<std::pair<Index, int>, PrescribedDof> bcs;
  if (!s.boundaries_reset)
    for (const PrescribedDof& d : m_prescribed) bcs[{d.node, d.component}] = d;
  for (const BoundaryCondition& bc : s.boundaries) {
    for (int dof = bc.first_dof; dof <= bc.last_dof; ++dof) {
      if (dof > 3 && !rotations) {
        m_rotational = true;
        continue;
      }
      PrescribedDof d;
      d.node = bc.node;
      d.component = dof - 1;
      d.type = bc.type;
      d.value = bc.value;
      d.amplitude = bc.amplitude;
      bcs[{d.node, d.component}] = d;
    }
  }
  m_prescribed.clear();
  for (auto& [key, d] : bcs) {
    const bool turn = d.component >= 3;
    const int c = turn ? d.component - 3 : d.component;
    if (d.type == BoundaryType::Displacement)
      d.start_value = turn ? rotation(d.node, c) : displacement(d.node, c);
    else
      d.start_value = turn ? angular_velocity(d.node, c) : velocity(d.node, c);
    m_prescribed.push_back(d);
  }

  std::map<std::pair<Index, int>, LoadedDof> loads;
  if (!s.loads_reset)
    for (const LoadedDof& l : m_loads) loads[{l.node, l.component}] = l;
  for (const ConcentratedLoad& cl : s.loads) {
    LoadedDof l;
    l.node = cl.node;
    l.component = cl.dof - 1;
    l.value = cl.value;
    l.amplitude = cl.amplitude;
    loads[{l.node, l.component}] = l;
  }
  m_loads.clear();
  for (const auto& [key, l] : loads) m_loads.push_back(l);
}

Real BoundaryState::factor(const Model& model, Index amplitude, Real step_time,
                           Real total_time) const {
  if (amplitude != NO_INDEX) {
    const Amplitude& a = model.amplitudes[amplitude];
    return a.evaluate(a.total_time ? total_time : step_time);
  }
  if (!m_ramp || m_period <= 0.0) return 1.0;
  return std::clamp(step_time / m_period, 0.0, 1.0);
}

Real BoundaryState::target(const Model& model, const PrescribedDof& dof, Real step_time,
                           Real total_time) const {
  if (dof.amplitude != NO_INDEX)
    return dof.value * factor(model, dof.amplitude, step_time, total_time);
  // Default amplitude: STEP jumps to the value, RAMP goes from the step's start value.
  const Real f = factor(model, NO_INDEX, step_time, total_time);
  return dof.start_value + (dof.value - dof.start_value) * f;
}

}  // namespace xpl
