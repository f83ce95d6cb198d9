#pragma once
/// \file What the C3D8R and C3D8 blocks share around their kernels (hex8r.*, hex8.*), written
/// once as the CRTP base HexBlock<Derived, POINTS, ENERGIES>: the batched layout (HexBatches),
/// the element-kind members (elements/element_kind.hpp) that only forward to it or need no
/// more than the element's corners and material (size and colours, the partition of the force
/// pass, the lumped mass ρV₀/8, the stable increment at rest), and the scaffolding around the
/// batch kernels: the force pass and the stiffness product over the batches, the stress,
/// volume and plastic state per stress point with their output and import, the per-batch
/// energies and their reduction. A kind derives from HexBlock and writes only what differs:
/// its batch kernels, its own state (hourglass, point volumes) and how it averages its points.

#include <array>
#include <cmath>
#include <iterator>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "common/types.hpp"
#include "elements/element_kind.hpp"
#include "elements/hex/hex8_geometry.hpp"
#include "elements/hex/hex_batches.hpp"
#include "elements/material/plasticity.hpp"
#include "elements/material/radial_return_lanes.hpp"
#include "elements/parallel/kernel_inline.hpp"
#include "elements/parallel/simd.hpp"

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

/// The columns of the nodal arrays a batch kernel reads and adds into (n_nodes values each):
/// positions, a rate (v_{n+1/2}, m/s, of a force pass; the displacement u, m, of a stiffness
/// product) and what the kernel adds into (forces, N, or K u).
struct NodalColumns {
  const Real* x[3];
  const Real* v[3];
  Real* f[3];
};

/// The columns of `x`, `v` and `f` (n_nodes × 3, column-major).
inline NodalColumns nodal_columns(const NodalVectors& x, const NodalVectors& v, NodalVectors& f) {
  const Index n = static_cast<Index>(x.rows());
  const Real* px = x.data();
  const Real* pv = v.data();
  Real* pf = f.data();
  return {{px, px + n, px + 2 * n}, {pv, pv + n, pv + 2 * n}, {pf, pf + n, pf + 2 * n}};
}

/// The members both hex kinds share (see the file comment), written once for a kind `Derived`
/// (CRTP) with `POINTS` stress points per element (8 Gauss points, or the one point of C3D8R)
/// and `ENERGIES` energy increments per batch. Derived provides, besides its constructor and
/// state:
///   - `template <bool PLASTIC> batch_forces(batch, NodalColumns, dt, b1, b2)`: the force
///     kernel of one batch, which ends with record_batch();
///   - `stiffness_batch(batch, NodalColumns) const`: y += K u of one batch;
///   - `stress(i)`: the element stress of block element i (6 values, Pa) for output, and
///     `plastic_strain(i)`: its PEEQ;
///   - `ENERGY_TOTALS`: the fields of HexStepTotals its ENERGIES increments add into, in order.
template <class Derived, int POINTS, int ENERGIES>
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

  /// One internal-force evaluation of the block alone: `position` x_{n+1} and `velocity_half`
  /// v_{n+1/2} (n_nodes × 3), `dt` = t_{n+1} − t_n (0 at the start of the analysis). Strain
  /// rates on the mid-increment geometry (exactly zero for rigid rotations), forces on x_{n+1},
  /// added into `force` (n_nodes × 3, N); the element state is updated and the energies and
  /// increment limit added to `totals`. The block is split into omp_get_max_threads() parts
  /// (one parallel region).
  void internal_forces(const NodalVectors& position, const NodalVectors& velocity_half, Real dt,
                       Real bulk_linear, Real bulk_quadratic, NodalVectors& force,
                       HexStepTotals& totals) {
    m_batches.own_pass(force, [&](int p) {
      forces_of_part(p, position, velocity_half, dt, bulk_linear, bulk_quadratic, force);
    });
    add_totals(totals);
  }

  /// \name The pieces of internal_forces() for a pass over several blocks (ElementSet,
  /// thread_partition.hpp).
  /// Part `part` of the force pass (same arguments as internal_forces()): its batches of every
  /// colour, forces at boundary nodes into the exchange buffer, the rest into `force`; only
  /// the batches of phase `phase` when it is ≥ 0 (set_batch_phases(), in_phase()).
  void forces_of_part(int part, const NodalVectors& position, const NodalVectors& velocity_half,
                      Real dt, Real bulk_linear, Real bulk_quadratic, NodalVectors& force,
                      int phase = -1) {
    const NodalColumns columns = nodal_columns(position, velocity_half, force);
    m_batches.for_part_batches(part, m_batch_plastic, phase, [&](Index b, auto plastic) {
      derived().template batch_forces<decltype(plastic)::value>(b, columns, dt, bulk_linear,
                                                                bulk_quadratic);
    });
  }
  void forces_of_part(int part, const ForcePass& p) {
    forces_of_part(part, p.position, p.velocity_half, p.dt, p.bulk_linear, p.bulk_quadratic,
                   p.force, p.phase);
  }
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
  /// Adds the energies and the increment limit of the last pass to `totals`; each energy sums
  /// its batches in batch order (independent of the thread count).
  void add_totals(HexStepTotals& totals) const {
    constexpr auto& fields = Derived::ENERGY_TOTALS;
    static_assert(std::size(fields) == ENERGIES);
    for (Index b = 0; b < m_batches.batch_count(); ++b)
      for (int k = 0; k < ENERGIES; ++k) totals.*fields[k] += m_batch_energy[b * ENERGIES + k];
    m_batches.merge_limits(totals);
  }

  /// \name Distributed runs (solver/distributed_run.hpp): the layout, the corner slots of the
  /// boundary nodes and their values ([slot][EXCHANGE_WIDTH]), and the totals of batch b as
  /// BATCH_TOTALS values (its energies, then its limit) and back.
  static constexpr int EXCHANGE_WIDTH = 3;
  static constexpr int BATCH_TOTALS = ENERGIES + 3;
  Index batch_count() const { return m_batches.batch_count(); }
  const std::vector<Index>& lane_owners() const { return m_batches.lane_owners(); }
  const std::vector<Index>& color_batches() const { return m_batches.color_batches(); }
  const CornerExchange& corner_exchange() const { return m_batches.corner_exchange(); }
  const std::vector<Real>& exchange_values() const { return m_batches.exchange_values(); }
  void pack_batch_totals(Index b, Real* out) const {
    for (int k = 0; k < ENERGIES; ++k) out[k] = m_batch_energy[b * ENERGIES + k];
    m_batches.pack_limit(b, out + ENERGIES);
  }
  void unpack_batch_totals(Index b, const Real* in) {
    for (int k = 0; k < ENERGIES; ++k) m_batch_energy[b * ENERGIES + k] = in[k];
    m_batches.unpack_limit(b, in + ENERGIES);
  }

  /// Writes the element stress (row e·6.., S11 S22 S33 S12 S13 S23, Derived::stress()) and
  /// current volume of every element of the block at its model index into model-sized arrays;
  /// an empty array is left alone (the output driver asks for one field at a time).
  void gather_output(std::vector<Real>& stress, std::vector<Real>& volume) const {
    for (Index i = 0; i < size(); ++i) {
      const Index e = m_batches.element_index(i);
      if (!stress.empty()) {
        const std::array<Real, 6> s = derived().stress(i);
        for (int c = 0; c < 6; ++c) stress[e * 6 + c] = s[c];
      }
      const Index b = m_batches.slot(i) / W, l = m_batches.slot(i) % W;
      if (!volume.empty()) volume[e] = m_volume[b * W + l];
    }
  }
  void gather_output(const OutputArrays& out) const { gather_output(out.stress, out.volume); }

  /// Sets the stress of every stress point of every element of the block from model-sized rows
  /// (n_elements × 6, row e·6.., S11 S22 S33 S12 S13 S23, global axes, Pa): an imported state
  /// has one stress per element, so the points start equal. Rows of elements outside the
  /// block are not read; the rest of the state (volumes, hourglass state) is left as it is.
  void set_stress(std::span<const Real> stress) {
    m_batches.check_model_rows(stress.size(), 6,
                               (std::string(Derived::NAME) + " set_stress").c_str());
    for (Index b = 0; b < m_batches.batch_count(); ++b)
      for (int l = 0; l < W; ++l) {
        // Padding lanes compute a copy of lane 0 of their batch: they take its stress as well.
        const auto e =
            static_cast<std::size_t>(m_batches.element_index(m_batches.lane_element(b, l)));
        for (int q = 0; q < POINTS; ++q)
          for (int c = 0; c < 6; ++c)
            m_stress[((static_cast<std::size_t>(b) * POINTS + q) * 6 + c) * W + l] =
                stress[e * 6 + c];
      }
  }
  /// The element kinds' form (element_kind.hpp): a solid reads the `middle` rows.
  void set_stress(const NodalVectors& /*position*/, std::span<const Real> middle,
                  std::span<const Real> /*bottom*/, std::span<const Real> /*top*/) {
    set_stress(middle);
  }
  /// Stress of stress point q (0..POINTS-1; Gauss points ξ fastest, then η, ζ) of block
  /// element i (constructor order), Pa, for tests.
  std::array<Real, 6> point_stress(Index i, int q) const {
    const Index b = m_batches.slot(i) / W, l = m_batches.slot(i) % W;
    std::array<Real, 6> s{};
    for (int c = 0; c < 6; ++c)
      s[c] = m_stress[((static_cast<std::size_t>(b) * POINTS + q) * 6 + c) * W + l];
    return s;
  }

  /// Whether any element of the block is plastic (else no plastic state exists, P2).
  bool has_plasticity() const { return !m_laws.empty(); }
  /// Writes PEEQ (-) of every element of the block (Derived::plastic_strain()) at its model
  /// index into a model-sized array (n_elements); elastic elements write 0 (the caller's array
  /// holds zeros for them).
  void gather_plastic_strain(std::vector<Real>& peeq) const {
    if (m_laws.empty()) return;
    for (Index i = 0; i < size(); ++i)
      peeq[m_batches.element_index(i)] = derived().plastic_strain(i);
  }
  /// Sets PEEQ of every stress point of the plastic elements of the block from a model-sized
  /// array (n_elements, -, ≥ 0), for a run that starts from an imported state. Rows of elastic
  /// elements and of elements outside the block are not read.
  void set_plastic_strain(std::span<const Real> peeq) {
    if (m_laws.empty()) return;
    m_batches.for_imported_peeq(
        peeq, m_lane_law, (std::string(Derived::NAME) + " set_plastic_strain").c_str(),
        [&](Index b, int l, int law, Real value) {
          for (int q = 0; q < POINTS; ++q)
            m_points.reset((static_cast<std::size_t>(b) * POINTS + q) * W + l,
                           m_laws[static_cast<std::size_t>(law)], value);
        });
  }

  /// Linear stiffness product y += K u of the block at `position` (n_nodes × 3, m) from a
  /// stress-free state, for the model's highest frequency (solver/increment/global_increment.*):
  /// Derived::stiffness_batch() says what K holds. `u` (m) and `y` (N) are n_nodes × 3; no
  /// element state changes. Race-free and independent of the thread count.
  void add_stiffness_product(const NodalVectors& position, const NodalVectors& u,
                             NodalVectors& y) const {
    const NodalColumns columns = nodal_columns(position, u, y);
    // Colour by colour: the lanes and batches of a colour share no node.
    m_batches.for_color_batches(ParallelSite::HexStiffness,
                                [&](Index b) { derived().stiffness_batch(b, columns); });
  }
  /// The same over the batches b with `selected[b]` nonzero only (a distributed run's share,
  /// solver/forces/element_set.cpp): each node's terms from them in the same order.
  void add_stiffness_product(const NodalVectors& position, const NodalVectors& u, NodalVectors& y,
                             const std::vector<char>& selected) const {
    const NodalColumns columns = nodal_columns(position, u, y);
    m_batches.for_color_batches(ParallelSite::HexStiffness, [&](Index b) {
      if (selected[b] != 0) derived().stiffness_batch(b, columns);
    });
  }

  /// Adds ρ V₀ / 8 to each node of each element (reference coordinates n_nodes × 3, m).
  void add_lumped_mass(const NodalVectors& reference, std::vector<Real>& mass) const {
    m_batches.add_lumped_mass(reference, mass);
  }
  /// As above; hexes have no rotary inertia.
  void add_lumped_mass(const NodalVectors& reference, std::vector<Real>& mass,
                       std::vector<Real>& /*rotary_inertia*/) const {
    m_batches.add_lumped_mass(reference, mass);
  }
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
  static constexpr int W = simd::W;
  /// The per-lane constants both kinds hold (HexBatches::Constant); a kind's own follow from
  /// N_SHARED.
  enum SharedConstant {
    LAMBDA = HexBatches::LAMBDA,
    TWO_MU = HexBatches::TWO_MU,
    DENSITY = HexBatches::DENSITY,
    WAVE_SPEED = HexBatches::WAVE_SPEED,
    DT_FACTOR = HexBatches::DT_FACTOR,
    N_SHARED = HexBatches::N_SHARED
  };

  /// Lays out the batches (`n_constants` per-lane constants; the arguments as the kinds'
  /// constructors), zero state, and the plastic laws and state of the plastic lanes.
  HexBlock(std::vector<Index> element_index, const std::vector<Index>& connectivity,
           const std::vector<HexMaterial>& materials, Index node_count, int n_constants,
           const BatchLayout* layout)
      : m_batches(std::move(element_index), connectivity, materials, node_count, n_constants,
                  layout) {
    const auto nb = static_cast<std::size_t>(m_batches.batch_count());
    m_stress.assign(nb * POINTS * 6 * W, 0.0);
    m_volume.assign(nb * W, 0.0);
    m_viscous_before.assign(nb * W, 0.0);
    m_batch_energy.assign(nb * ENERGIES, 0.0);
    HexBatches::PlasticLanes lanes = m_batches.plastic_lanes(materials);
    if (lanes.laws.empty()) return;  // P2: an elastic block holds no plastic state
    m_laws = std::move(lanes.laws);
    m_lane_law = std::move(lanes.lane_law);
    m_batch_plastic = std::move(lanes.batch_plastic);
    const std::size_t n = m_lane_law.size();
    m_points = RadialReturnLanes(n * POINTS);
    for (std::size_t k = 0; k < n; ++k) {
      if (m_lane_law[k] < 0) continue;
      const std::size_t b = k / W, l = k % W;
      for (int q = 0; q < POINTS; ++q)
        m_points.reset((b * POINTS + q) * W + l, m_laws[static_cast<std::size_t>(m_lane_law[k])],
                       0.0);
    }
  }

  /// The end of a batch kernel: stores the sums over the real lanes of the energy increments
  /// `increments` (per lane, in the order of Derived::ENERGY_TOTALS) and the batch's increment
  /// limit (HexBatches::record_limit()).
  XPL_KERNEL_INLINE void record_batch(Index batch, const simd::Vec (&increments)[ENERGIES],
                                      const simd::Vec& dt_e, const bool ok[W]) {
    Real sum[ENERGIES] = {};
    for (int l = 0; l < W; ++l) {
      if (m_batches.lane_owner(batch, l) == NO_INDEX) continue;
      for (int k = 0; k < ENERGIES; ++k) sum[k] += increments[k][l];
    }
    for (int k = 0; k < ENERGIES; ++k) m_batch_energy[batch * ENERGIES + k] = sum[k];
    m_batches.record_limit(batch, dt_e, ok);
  }

  HexBatches m_batches;  ///< layout, constants, increment limits and partition
  // State, batch b lane l:
  std::vector<Real> m_stress;          ///< [b][point POINTS][6][W], Pa
  std::vector<Real> m_volume;          ///< [b][W] at x_{n+1}, m³
  std::vector<Real> m_viscous_before;  ///< [b][W] bulk-viscosity pressure of the last call
  // Plasticity (all empty when no element is plastic):
  std::vector<Plasticity> m_laws;              ///< the distinct laws of the block's materials
  std::vector<int> m_lane_law;                 ///< [b][W] index into m_laws, or -1 (elastic lane)
  std::vector<unsigned char> m_batch_plastic;  ///< [b] 1 if any lane of the batch is plastic
  RadialReturnLanes m_points;  ///< [b][point POINTS][W] ε̄ᵖ, yield stress and table segment
  /// [b][ENERGIES] energy increments of the last pass, reduced serially in batch order
  std::vector<Real> m_batch_energy;

 private:
  Derived& derived() { return static_cast<Derived&>(*this); }
  const Derived& derived() const { return static_cast<const Derived&>(*this); }
  static void split_corners(const V3<Real>* corners, Real x[8], Real y[8], Real z[8]) {
    for (int a = 0; a < 8; ++a) {
      x[a] = corners[a].x;
      y[a] = corners[a].y;
      z[a] = corners[a].z;
    }
  }
};

}  // namespace xpl::elements
