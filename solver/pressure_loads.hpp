#pragma once
/// \file Pressures on element faces (`*DLOAD` P/Pn, `*DSLOAD`), active per step and applied
/// on the current geometry (follower loads) as consistent nodal forces of a bilinear face.

#include <map>
#include <utility>
#include <vector>

#include "common/types.hpp"
#include "solver/boundary_state.hpp"
#include "solver/model.hpp"

namespace xpl {

/// The pressure faces in force during one step.
class PressureLoads {
 public:
  /// Applies the changes of `step` (a later entry for the same face replaces an earlier one;
  /// `pressures_reset` clears the earlier steps' pressures).
  void begin_step(const Model& model, int step);

  bool empty() const { return m_faces.empty(); }
  /// Nodes that carry pressure forces (sorted, unique).
  const std::vector<Index>& nodes() const { return m_nodes; }

  /// Adds the nodal forces of every active pressure on the configuration `position`
  /// (n_nodes × 3) to `force` (n_nodes × 3). On a bilinear face the consistent force of a
  /// uniform pressure p is p·(½ d13 × d24)/4 at each corner, exact for warped faces too.
  void add_forces(const Model& model, const BoundaryState& amplitudes, const NodalVectors& position,
                  Real step_time, Real total_time, NodalVectors& force) const;

 private:
  struct Face {
    Index nodes[4];
    Real sign;  ///< +1: the pressure pushes along d13 × d24, −1: against it
    Real value;
    Index amplitude;
  };
  std::map<std::pair<Index, int>, PressureLoad> m_active;  ///< by (element, face)
  std::vector<Face> m_faces;
  std::vector<Index> m_nodes;
};

}  // namespace xpl
