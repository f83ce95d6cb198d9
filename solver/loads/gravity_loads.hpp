#pragma once
/// \file Gravity (`*DLOAD` GRAV) active per step: a body force m·g on each node, with the
/// lumped mass of the loaded elements (the whole nodal mass when no element set is given).

#include <map>
#include <vector>

#include "common/types.hpp"
#include "solver/loads/boundary_state.hpp"
#include "solver/model/model.hpp"

namespace xpl {

/// The gravity loads in force during one step.
class GravityLoads {
 public:
  /// Applies the changes of `step` (keyed by element set; `gravity_reset` — OP=NEW on *DLOAD —
  /// clears the earlier steps' gravity). `nodal_mass` (n_nodes) is the lumped mass used for
  /// whole-model gravity; element sets use their elements' own lumped mass.
  void begin_step(const Model& model, int step, const NodalVectors& reference,
                  const std::vector<Real>& nodal_mass);

  bool empty() const { return m_terms.empty(); }
  /// Nodes that carry gravity forces (sorted, unique).
  const std::vector<Index>& nodes() const { return m_nodes; }

  /// One *DLOAD GRAV in force: the force on node nodes[k] is the amplitude times
  /// mass[k] · acceleration.
  struct Term {
    std::vector<Index> nodes;
    std::vector<Real> mass;  ///< per node, kg
    Real acceleration[3];    ///< g · direction, m/s^2
    Index amplitude;
  };
  /// The terms in force, in element-set order.
  const std::vector<Term>& terms() const { return m_terms; }

 private:
  std::map<Index, GravityLoad> m_active;
  std::vector<Term> m_terms;
  std::vector<Index> m_nodes;
};

}  // namespace xpl
