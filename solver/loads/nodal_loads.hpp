#pragma once
/// \file The external forces of a step (CLOAD, pressure, gravity) gathered per node, so that
/// the nodal update evaluates a node's load where it updates the node: one pass over the
/// nodes, in parallel, with no scatter between threads.

#include <cmath>
#include <cstdint>
#include <vector>

#include "common/types.hpp"
#include "solver/loads/boundary_state.hpp"
#include "solver/loads/gravity_loads.hpp"
#include "solver/loads/pressure_loads.hpp"
#include "solver/model/model.hpp"

namespace xpl {

/// a·b + c rounded as GCC compiles `c += a * b` with contraction on: once (fused) where the
/// target has FMA, twice where it has not. The nodal loads and their work spell their
/// multiply-adds out with it (nodal_loads.cpp is compiled without contraction), so that their
/// values do not hang on how the compiler happens to contract the loop they sit in.
inline Real multiply_add(Real a, Real b, Real c) {
#ifdef __FMA__
  return std::fma(a, b, c);
#else
  return a * b + c;
#endif
}

/// Per-node lists of the loads in force during a step. A node's force is summed in the order
/// the loads were once added to a global array one after the other (its CLOADs, then its
/// pressure faces in face order, then its gravity terms in term order), so every component
/// is the same to the bit whatever the thread count.
class NodalLoads {
 public:
  /// Gathers the loads of the step: `cloads` (one per DOF), the pressure faces and the
  /// gravity terms in force. Keeps references to `pressures` and `gravity`, which must stay
  /// unchanged until the next begin_step().
  void begin_step(const Model& model, const std::vector<LoadedDof>& cloads,
                  const PressureLoads& pressures, const GravityLoads& gravity);

  bool empty() const { return m_entries.empty(); }
  /// Whether node `i` carries any load.
  bool loaded(Index i) const { return m_start[i] != m_start[i + 1]; }

  /// Amplitude factors at step time `step_time` / total time `total_time`, for the forces
  /// that force_at() evaluates next.
  void set_time(const Model& model, const BoundaryState& amplitudes, Real step_time,
                Real total_time);
  /// The external force on node `i` (N, three components into f) on the configuration
  /// `position` (n_nodes × 3, m), at the time of the last set_time(). On a bilinear face
  /// the consistent force of a uniform pressure p is p·(½ d13 × d24)/4 at each corner,
  /// exact for warped faces too.
  void force_at(Index i, const NodalVectors& position, Real f[3]) const;

 private:
  /// Entry kinds, in the top two bits of an entry; the rest is an index into m_cloads, the
  /// pressure faces or m_gravity.
  static constexpr std::uint32_t KIND_SHIFT = 30;
  static constexpr std::uint32_t INDEX_MASK = (1u << KIND_SHIFT) - 1;
  enum Kind : std::uint32_t { CLOAD = 0, FACE = 1, GRAVITY = 2 };
  struct Cload {
    int component;
    Index slot;  ///< amplitude slot
    Real value;  ///< N
  };
  struct Gravity {
    Index term;  ///< into gravity.terms()
    Real mass;   ///< kg
  };
  /// Slot of an amplitude (NO_INDEX: the step's default) in m_factors, added when new.
  Index slot_of(Index amplitude);

  const PressureLoads* m_pressures = nullptr;
  const GravityLoads* m_gravity_loads = nullptr;
  std::vector<std::uint32_t> m_start;    ///< n_nodes + 1 offsets into m_entries
  std::vector<std::uint32_t> m_entries;  ///< kind << KIND_SHIFT | index, per node
  std::vector<Cload> m_cloads;
  std::vector<Gravity> m_gravity;
  std::vector<Index> m_face_slot;   ///< amplitude slot per pressure face
  std::vector<Index> m_term_slot;   ///< amplitude slot per gravity term
  std::vector<Index> m_amplitudes;  ///< amplitude of each slot
  std::vector<Real> m_factors;      ///< factor of each slot at the last set_time()
};

}  // namespace xpl
