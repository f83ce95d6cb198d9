#pragma once
/// \file The external loads of the nodal update (CLOAD, pressure, gravity; S2): the step's
/// loads gathered per node (nodal_loads.hpp), their forces evaluated node by node in the
/// nodal pass, and their work on the DOFs that are not prescribed.

#include <cstdint>
#include <functional>
#include <vector>

#include "common/types.hpp"
#include "solver/loads/boundary_state.hpp"
#include "solver/loads/gravity_loads.hpp"
#include "solver/loads/nodal_loads.hpp"
#include "solver/loads/pressure_loads.hpp"
#include "solver/model/model.hpp"

namespace xpl {

/// The external forces of a step and the work they do.
class ExternalLoads {
 public:
  /// Takes in the loads of `step`: the CLOADs of `boundary` (begin_step() of it ran), the
  /// step's pressures and gravity (on `reference`, n_nodes × 3, m, with the nodal masses
  /// `mass`, kg); the loaded DOFs outside `prescribed` are those whose work is counted here.
  /// Forces of loads the step no longer has are cleared.
  void begin_step(const Model& model, int step, const BoundaryState& boundary,
                  const NodalVectors& reference, const std::vector<Real>& mass,
                  const std::vector<PrescribedDof>& prescribed);
  /// Whether the step has loaded DOFs that are not prescribed.
  bool has_free_loads() const { return !m_free_load_dofs.empty(); }
  /// The forces at step time `step_time` / total time `total_time` (amplitudes of
  /// `boundary`) are due: the next nodal pass evaluates them node by node (the positions must
  /// not change in between); nothing when the step has no loads.
  void apply(const Model& model, const BoundaryState& boundary, Real step_time, Real total_time);
  /// Whether apply() made the loads due and the nodal pass has yet to evaluate them.
  bool pending() const { return m_due && !m_evaluated; }
  /// The external forces (n_nodes × 3, N), non-zero only on loaded DOFs; null until a step
  /// has had loads (P2: no array for a model without loads).
  const NodalVectors* force() const { return m_force.rows() > 0 ? &m_force : nullptr; }
  NodalVectors* force() { return m_force.rows() > 0 ? &m_force : nullptr; }

  /// The loads of nodes [first, last) on `position` (n_nodes × 3, m) into force(), and the
  /// work of those on free DOFs over the increment dt_prev just taken (trapezoidal rule with
  /// `previous_force`, n_nodes × 3, N, which takes the new forces; exact for constant forces)
  /// with their velocity v(n−½) from `velocity_half` (n_nodes × 3, column-major), to be
  /// summed by add_work().
  void evaluate(Index first, Index last, const NodalVectors& position, const Real* velocity_half,
                Real dt_prev, NodalVectors& previous_force);
  /// Every node's loads were evaluated before the nodal pass (ties gather the slaves'); the
  /// pass leaves them.
  void set_evaluated() { m_evaluated = true; }
  /// Adds the work of the loads on free DOFs over the last increment to `work` (J), summed
  /// in the order the DOFs were once listed (CLOADs, pressure nodes, gravity nodes) so that
  /// ALLWK keeps its round-off; then the loads are no longer due.
  void add_work(Real& work);

  /// Distributed runs: `share(nodes, rows)` puts into `rows` (n_nodes × 3) the run's values
  /// at `nodes`, from the ranks that integrate them (collective).
  using NodeRowShare =
      std::function<void(const std::vector<Index>& nodes, const std::vector<NodalVectors*>& rows)>;
  /// The positions the loads read (the corners of the loaded faces) into `position` before
  /// they are evaluated, when they are due.
  void share_positions(const NodeRowShare& share, NodalVectors& position) const;
  /// The work terms of the free loaded DOFs (written by evaluate() on the ranks that
  /// integrate them) onto every rank before add_work(), when the loads are due.
  void share_work(const NodeRowShare& share);

 private:
  /// Loaded DOFs: CLOADs and the three components of every node under pressure or gravity;
  /// the free ones are those that are not prescribed.
  void collect(const Model& model, const BoundaryState& boundary,
               const std::vector<PrescribedDof>& prescribed);

  PressureLoads m_pressures;
  GravityLoads m_gravity;
  NodalLoads m_loads;        ///< the step's loads per node
  bool m_due = false;        ///< apply() has set the time of the next update's loads
  bool m_evaluated = false;  ///< evaluate() ran before the nodal pass (ties)
  NodalVectors m_force;      ///< force(); allocated only when a step has loads (P2)
  /// Loaded DOFs that are not prescribed, as c · n_nodes + node, in the order their work is
  /// summed (CLOADs, pressure nodes, gravity nodes).
  std::vector<Index> m_free_load_dofs;
  std::vector<Index> m_free_load_nodes;        ///< the nodes of m_free_load_dofs, ascending
  std::vector<std::uint8_t> m_free_load_mask;  ///< per node: bit c set if DOF c is in the list
  /// The work of the loads on free DOFs over the last increment is Σ mean_force · v_before
  /// over m_free_load_dofs: ½(f_{n-1} + f_n) Δt (N s) and v(n−½) (m/s), n_nodes × 3, written
  /// by the nodal pass, summed after it in the list's order.
  NodalVectors m_work_force, m_work_velocity;
};

}  // namespace xpl
