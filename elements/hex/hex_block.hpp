#pragma once
/// \file What the C3D8R and C3D8 blocks share around their kernels (hex8r.*, hex8.*): the
/// batched layout (HexBatches) and the element-kind members that only forward to it or need
/// no more than the element's corners and material (elements/element_kind.hpp): size and
/// colours, the partition of the force pass, the lumped mass ρV₀/8, the stable increment at
/// rest. A block derives from HexBlock and adds its state and kernels.

#include <cmath>
#include <span>
#include <utility>
#include <vector>

#include "common/types.hpp"
#include "elements/element_kind.hpp"
#include "elements/hex/hex8_geometry.hpp"
#include "elements/hex/hex_batches.hpp"

namespace xpl::elements {

/// Lumped mass share ρV/8 of each node of a hex of density `density` (kg/m³) and corner
/// coordinates x, y, z (m, Abaqus order), kg.
inline Real hex_node_mass(Real density, const Real x[8], const Real y[8], const Real z[8]) {
  return density * hex8_volume(x, y, z) / 8.0;
}

/// Dilatational wave speed c_d = √((λ + 2μ)/ρ) of a hex material, m/s.
inline Real hex_wave_speed(const HexMaterial& m) {
  const Real mu = m.young / (2.0 * (1.0 + m.poisson));
  const Real lambda = m.young * m.poisson / ((1.0 + m.poisson) * (1.0 - 2.0 * m.poisson));
  return std::sqrt((lambda + 2.0 * mu) / m.density);
}

/// The members both hex kinds share (see the file comment).
class HexBlock {
 public:
  using Properties = HexMaterial;
  using Totals = HexStepTotals;
  static constexpr int NODES = 8;

  /// Number of elements.
  Index size() const { return m_batches.size(); }
  /// Number of colours.
  int color_count() const { return m_batches.color_count(); }
  /// Model index of block element i.
  Index element_index(Index i) const { return m_batches.element_index(i); }

  /// Adds ρ V₀ / 8 to each node of each element (reference coordinates n_nodes × 3, m).
  void add_lumped_mass(const NodalVectors& reference, std::vector<Real>& mass) const {
    m_batches.add_lumped_mass(reference, mass);
  }
  /// As above; hexes have no rotary inertia.
  void add_lumped_mass(const NodalVectors& reference, std::vector<Real>& mass,
                       std::vector<Real>& /*rotary_inertia*/) const {
    m_batches.add_lumped_mass(reference, mass);
  }

  /// \name The pieces of the force pass over several blocks (ElementSet, thread_partition.hpp).
  /// Marks the nodes each of `parts` parts touches (mark_part_nodes()).
  void mark_nodes(int parts, std::vector<Index>& node_part) const {
    m_batches.mark_nodes(parts, node_part);
  }
  /// Takes the partition into `parts` parts whose boundary nodes (over every block of the
  /// pass) are `boundary`.
  void set_partition(int parts, const BoundaryNodes& boundary) {
    m_batches.set_partition(parts, boundary);
  }
  /// Number of parts of the partition held (0: none yet).
  int parts() const { return m_batches.parts(); }
  /// The phase of each batch (in_phase(); empty: every batch of phase 0).
  void set_batch_phases(std::vector<unsigned char> phase) {
    m_batches.set_batch_phases(std::move(phase));
  }
  /// Adds the exchanged corner forces of boundary node k (rank), `node`, into `force`.
  void add_boundary_forces(Index k, Index node, NodalVectors& force) const {
    m_batches.add_boundary_forces(k, node, force);
  }
  void add_boundary_forces(Index k, Index node, const ForcePass& pass) const {
    m_batches.add_boundary_forces(k, node, pass.force);
  }

  /// \name Distributed runs (solver/distributed_run.hpp): the layout, the corner slots of the
  /// boundary nodes and their values ([slot][EXCHANGE_WIDTH]).
  static constexpr int EXCHANGE_WIDTH = 3;
  Index batch_count() const { return m_batches.batch_count(); }
  const std::vector<Index>& lane_owners() const { return m_batches.lane_owners(); }
  const std::vector<Index>& color_batches() const { return m_batches.color_batches(); }
  const CornerExchange& corner_exchange() const { return m_batches.corner_exchange(); }
  const std::vector<Real>& exchange_values() const { return m_batches.exchange_values(); }

  /// Mass share per node ρV₀/8 of one element of material `m` with corners `corners` (8, m).
  static Real node_mass(const HexMaterial& m, const V3<Real>* corners) {
    Real x[8], y[8], z[8];
    split_corners(corners, x, y, z);
    return hex_node_mass(m.density, x, y, z);
  }
  /// Stable increment at rest (s) of one element of material `m` with corners `corners`
  /// (8, m) under the linear bulk viscosity `bulk_linear` (damping ξ = b1): the kernels'
  /// estimate poisson_dt_factor(ν) (L_e/c_d)(√(1+ξ²) − ξ), L_e = V / A_max.
  static Real stable_increment(const HexMaterial& m, const V3<Real>* corners, Real bulk_linear) {
    Real x[8], y[8], z[8];
    split_corners(corners, x, y, z);
    V3<Real> modes[8], g[8];
    Real volume = 0.0;
    to_modes(x, y, z, modes);
    volume_gradient(modes, g, volume);
    const Real length = volume / std::sqrt(max_face_area_squared(modes));
    const Real xi = bulk_linear;
    return poisson_dt_factor(m.poisson) * (length / hex_wave_speed(m)) *
           (std::sqrt(1.0 + xi * xi) - xi);
  }

 protected:
  HexBlock(std::vector<Index> element_index, const std::vector<Index>& connectivity,
           const std::vector<HexMaterial>& materials, Index node_count, int n_constants,
           const BatchLayout* layout)
      : m_batches(std::move(element_index), connectivity, materials, node_count, n_constants,
                  layout) {}

  HexBatches m_batches;  ///< layout, constants, increment limits and partition

 private:
  static void split_corners(const V3<Real>* corners, Real x[8], Real y[8], Real z[8]) {
    for (int a = 0; a < 8; ++a) {
      x[a] = corners[a].x;
      y[a] = corners[a].y;
      z[a] = corners[a].z;
    }
  }
};

}  // namespace xpl::elements
