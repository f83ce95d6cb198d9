#pragma once
/// \file Boundary conditions and loads active in a step, flattened to one entry per
/// prescribed or loaded translational DOF.

#include <vector>

#include "common/types.hpp"
#include "solver/model/model.hpp"

namespace xpl {

/// One prescribed DOF.
struct PrescribedDof {
  Index node = NO_INDEX;
  int component = 0;  ///< 0..2 translations, 3..5 rotations
  BoundaryType type = BoundaryType::Displacement;
  Real value = 0.0;            ///< target displacement or velocity
  Real start_value = 0.0;      ///< displacement or velocity at the start of the step
  Index amplitude = NO_INDEX;  ///< NO_INDEX: the step's default (STEP or RAMP)
};

/// One loaded translational DOF.
struct LoadedDof {
  Index node = NO_INDEX;
  int component = 0;
  Real value = 0.0;
  Index amplitude = NO_INDEX;
};

/// The BCs and loads in force during one step, with the rules of Abaqus propagation
/// (kept from earlier steps unless OP=NEW; a later entry for the same DOF replaces it).
class BoundaryState {
 public:
  /// Applies the changes of `step` to the active set. `displacement` and `velocity` of the
  /// current state give the start values of ramped BCs; `rotation` and `angular_velocity`
  /// those of rotational DOFs, which are kept only when these arrays exist (shell models).
  void begin_step(const Model& model, int step, const NodalVectors& displacement,
                  const NodalVectors& velocity, const NodalVectors& rotation,
                  const NodalVectors& angular_velocity);

  const std::vector<PrescribedDof>& prescribed() const { return m_prescribed; }
  const std::vector<LoadedDof>& loads() const { return m_loads; }
  /// Whether any BC of the step names rotational DOFs (4..6) that were dropped because the
  /// model has no rotations.
  bool has_rotational_dofs() const { return m_rotational; }

  /// Amplitude factor at step time `step_time` / total time `total_time`.
  Real factor(const Model& model, Index amplitude, Real step_time, Real total_time) const;
  /// Prescribed displacement or velocity of entry `dof` at the given time.
  Real target(const Model& model, const PrescribedDof& dof, Real step_time, Real total_time) const;

 private:
  std::vector<PrescribedDof> m_prescribed;
  std::vector<LoadedDof> m_loads;
  bool m_rotational = false;
  bool m_ramp = false;
  Real m_period = 0.0;
};

}  // namespace xpl
