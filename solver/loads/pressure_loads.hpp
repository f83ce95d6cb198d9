#pragma once
/// \file Pressures on element faces (`*DLOAD` P/Pn, `*DSLOAD`), active per step and applied
/// on the current geometry (follower loads) as consistent nodal forces of a bilinear face.

#include <utility>
#include <vector>

#include "common/types.hpp"
#include "solver/loads/boundary_state.hpp"
#include "solver/model/model.hpp"

namespace xpl {

/// The pressure faces in force during one step.
class PressureLoads {
 public:
  /// Applies the changes of `step` (a later entry for the same face replaces an earlier one;
  /// `pressures_reset` clears the earlier steps' pressures). Steps are begun in order.
  void begin_step(const Model& model, int step);

  bool empty() const { return m_faces.empty(); }
  /// Nodes that carry pressure forces (sorted, unique).
  const std::vector<Index>& nodes() const { return m_nodes; }

  /// One loaded face: its corner nodes in the cycle whose d13 × d24 the sign refers to.
  struct Face {
    Index nodes[4];
    Real sign;  ///< +1: the pressure pushes along d13 × d24, −1: against it
    Real value;
    Index amplitude;
  };
  /// The active faces, in (element, face) order.
  const std::vector<Face>& faces() const { return m_faces; }

 private:
  /// What a face keeps from its *DLOAD/*DSLOAD line (no source location: it is not needed
  /// once the deck is read, and the map holds one entry per loaded face).
  struct Active {
    ElementFace face;
    Real value;
    Index amplitude;
  };
  /// The faces in force, sorted by (element, face), one entry each: a sorted array rather
  /// than a map (a map node per loaded face cost ~140 bytes on a 100k-shell plate). Emptied
  /// once no later step adds faces.
  std::vector<std::pair<std::pair<Index, int>, Active>> m_active;
  std::vector<Face> m_faces;
  std::vector<Index> m_nodes;
};

}  // namespace xpl
