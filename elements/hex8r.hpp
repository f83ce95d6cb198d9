#pragma once
/// \file C3D8R: 8-node hexahedron, one-point (uniform-gradient) integration with
/// Flanagan–Belytschko hourglass control, Jaumann-rate linear elasticity, bulk viscosity.
///
/// Elements are coloured (no two elements of a colour share a node) and packed into
/// batches of simd::W elements of one colour; a batch is computed as one SIMD value per
/// quantity. Threads take per-thread ranges of every colour (thread_partition.hpp): a batch
/// scatters its forces directly except at the nodes two threads share, which are summed
/// after the pass, so assembly is race-free and every node sums its contributions in colour
/// order whatever the number of threads.

#include <array>
#include <limits>
#include <span>
#include <vector>

#include "common/types.hpp"
#include "elements/increment_limit.hpp"
#include "elements/lane_state.hpp"
#include "elements/plasticity.hpp"
#include "elements/simd.hpp"
#include "elements/thread_partition.hpp"

namespace xpl::elements {

/// Hourglass control form of a hex element.
enum class HourglassForm { Stiffness, Viscous };

/// Default Flanagan–Belytschko coefficients (multiplied by the user's scale factors).
/// Stiffness: Q̇_α = κ_s · 2G · (Σ_I b_I·b_I) / (8V) · q_α, with q_α = γ_α·v and |Γ_α|² = 8;
/// on a cube of side h the hourglass stiffness per node is 3 κ_s G h.
inline constexpr Real HOURGLASS_STIFFNESS = 0.05;
/// Viscous: Q_α = κ_v · ρ c_d A_max / 8 · q_α (≈ 14 % of critical damping on a cube).
inline constexpr Real HOURGLASS_VISCOSITY = 0.1;

/// Extra factor on the stable increment of nearly incompressible one-point hexes: L_e/c_d is
/// not conservative there (measured limits on regular meshes, in units of L_e/c_d: 1.01 at
/// ν = 0, 0.99 at 0.3, 0.97 at 0.4, 0.90 at 0.45, 0.86 at 0.49; tests/solver/test_stability).
/// 1 up to ν = 0.3, then falling linearly by 0.55 per unit of ν (0.895 at ν = 0.49).
constexpr Real poisson_dt_factor(Real poisson) {
  return poisson <= 0.3 ? 1.0 : 1.0 - 0.55 * (poisson - 0.3);
}

/// Material and control constants of one hex element.
struct HexMaterial {
  Real density = 0.0;  ///< kg/m^3
  Real young = 0.0;    ///< Pa
  Real poisson = 0.0;  ///< -
  HourglassForm hourglass = HourglassForm::Stiffness;
  Real hourglass_scale = 1.0;  ///< scales the coefficient of the chosen form
  /// J2 plasticity of the material, or nullptr for an elastic one. Not owned: read (and
  /// copied, once per distinct law) by the block's constructor only.
  const Plasticity* plastic = nullptr;
};

/// What one internal-force pass reports (sums are over the block, in a fixed order).
struct HexStepTotals : IncrementLimit {
  Real strain_energy_increment = 0.0;     ///< ΔALLSE, J
  Real hourglass_energy_increment = 0.0;  ///< ΔALLAE, J
  Real viscous_energy_increment = 0.0;    ///< ΔALLVD, J
  Real plastic_energy_increment = 0.0;    ///< ΔALLPD, J (σ_y Δε̄ᵖ V at mid-increment)
};

/// A set of C3D8R elements and their state (stress, hourglass forces).
class Hex8rBlock {
 public:
  /// `element_index`: model index of each element; `connectivity`: 8 node indices per
  /// element (Abaqus order, same order as element_index); `materials`: one per element.
  Hex8rBlock(std::vector<Index> element_index, const std::vector<Index>& connectivity,
             const std::vector<HexMaterial>& materials, Index node_count);

  /// Number of elements.
  Index size() const { return static_cast<Index>(m_element_index.size()); }
  /// Number of colours (parallel passes per internal-force evaluation).
  int color_count() const { return static_cast<int>(m_color_batches.size()) - 1; }

  /// Adds ρ V₀ / 8 to each node of each element (reference coordinates n_nodes × 3, m).
  void add_lumped_mass(const NodalVectors& reference, std::vector<Real>& mass) const;

  /// One internal-force evaluation at the end of an increment.
  /// `position` x_{n+1} and `velocity_half` v_{n+1/2} (n_nodes × 3); `dt` = t_{n+1} − t_n
  /// (0 at the start of the analysis). The strain increment is taken on the mid-increment
  /// geometry (exactly zero for rigid rotations), forces on x_{n+1}. Adds the internal
  /// forces into `force` (n_nodes × 3, N) and updates the element state.
  /// The block alone is split into omp_get_max_threads() parts (one parallel region).
  void internal_forces(const NodalVectors& position, const NodalVectors& velocity_half, Real dt,
                       Real bulk_linear, Real bulk_quadratic, NodalVectors& force,
                       HexStepTotals& totals);

  /// \name The pieces of internal_forces() for a pass over several blocks (ElementSet).
  /// Marks the nodes each of `parts` parts touches (mark_part_nodes()).
  void mark_nodes(int parts, std::vector<Index>& node_part) const;
  /// Takes the partition into `parts` parts whose boundary nodes (over every block of the
  /// pass) are `boundary`.
  void set_partition(int parts, const BoundaryNodes& boundary);
  /// Number of parts of the partition held (0: none yet).
  int parts() const { return m_parts; }
  /// Part `part` of the force pass (same arguments as internal_forces()): its batches of every
  /// colour, forces at boundary nodes into the exchange buffer, the rest into `force`.
  void forces_of_part(int part, const NodalVectors& position, const NodalVectors& velocity_half,
                      Real dt, Real bulk_linear, Real bulk_quadratic, NodalVectors& force);
  /// Adds the exchanged corner forces of boundary node k (rank), `node`, into `force`.
  void add_boundary_forces(Index k, Index node, NodalVectors& force) const {
    const Index n = static_cast<Index>(force.rows());
    Real* f = force.data() + node;
    for (Index s = m_exchange.first(k); s < m_exchange.first(k + 1); ++s) {
      f[0] += m_exchange_force[3 * s];
      f[n] += m_exchange_force[3 * s + 1];
      f[2 * n] += m_exchange_force[3 * s + 2];
    }
  }
  /// Adds the energies and the increment limit of the last pass to `totals`, in batch order.
  void add_totals(HexStepTotals& totals) const;

  /// Writes stress (row e·6.., S11 S22 S33 S12 S13 S23) and current volume of every element
  /// of the block at its model index into model-sized arrays.
  void gather_output(std::vector<Real>& stress, std::vector<Real>& volume) const;

  /// Sets the stress of every element of the block from model-sized rows (n_elements × 6,
  /// row e·6.., S11 S22 S33 S12 S13 S23, global axes, Pa): the inverse of gather_output's
  /// stress part, for a run that starts from an imported state. Rows of elements outside the
  /// block are not read. The accumulated hourglass forces are left as they are (see
  /// set_hourglass_state), and so is the volume that gather_output reports (set by the next
  /// internal-force pass).
  void set_stress(std::span<const Real> stress);

  /// Writes the accumulated stiffness-form hourglass forces (4 modes × 3 global components,
  /// N; zero under the viscous form) of every block element at its model index into
  /// model-sized rows (n_elements × HOURGLASS_STATE_WIDTH, lane_state.hpp).
  void gather_hourglass_state(std::vector<Real>& rows) const;
  /// The inverse of gather_hourglass_state, for a run that starts from an imported state.
  void set_hourglass_state(std::span<const Real> rows);

  /// Stress of block element i (constructor order), for tests.
  std::array<Real, 6> stress(Index i) const;

  /// Whether any element of the block is plastic (else no plastic state exists, P2).
  bool has_plasticity() const { return !m_laws.empty(); }
  /// Writes the equivalent plastic strain PEEQ (-) of every element of the block at its model
  /// index into a model-sized array (n_elements); elastic elements write 0.
  void gather_plastic_strain(std::vector<Real>& peeq) const;
  /// Sets PEEQ of the plastic elements of the block from a model-sized array (n_elements, -,
  /// ≥ 0): the inverse of gather_plastic_strain, for a run that starts from an imported
  /// state. Rows of elastic elements and of elements outside the block are not read.
  void set_plastic_strain(std::span<const Real> peeq);
  /// PEEQ (-) and its rate over the last increment (1/s) of block element i, for tests.
  Real plastic_strain(Index i) const;
  Real plastic_strain_rate(Index i) const;

  /// Linear stiffness product y += K u of the block at `position` (n_nodes × 3, m), for the
  /// model's highest frequency: the uniform-gradient part (λ, 2μ) and the stiffness
  /// hourglass term as internal_forces() applies them, from a stress-free state (no geometric
  /// stiffness; the viscous hourglass form and bulk viscosity are damping, not stiffness).
  /// `u` (m) and `y` (N) are n_nodes × 3; no element state changes. K u is the derivative of
  /// the internal force along u. Race-free and independent of the thread count.
  void add_stiffness_product(const NodalVectors& position, const NodalVectors& u,
                             NodalVectors& y) const;

 private:
  static constexpr int W = simd::W;
  enum Constant {
    LAMBDA = 0,
    TWO_MU,
    DENSITY,
    WAVE_SPEED,
    HG_STIFFNESS,
    HG_VISCOSITY,
    DT_FACTOR,
    N_CONST
  };

  template <bool PLASTIC>
  void compute_batch(Index batch, const Real* px, const Real* py, const Real* pz, const Real* vx,
                     const Real* vy, const Real* vz, Real dt, Real b1, Real b2, Real* fx, Real* fy,
                     Real* fz);
  /// Partition of the block alone into `parts` parts, unless it holds that one already.
  void own_partition(int parts, Index node_count);
  /// J2 return of the trial stresses `sn` (6 × W) of a batch with plastic lanes over the
  /// increment `dt`: scales the deviatoric part of yielding lanes onto the yield surface,
  /// updates PEEQ, its rate and the yield stress, and returns σ_y Δε̄ᵖ per lane (Pa; 0 in
  /// lanes that stay elastic). One SIMD yield test; the scalar return only where it fails.
  simd::Vec plastic_return(Index batch, simd::Vec sn[6], Real dt);
  /// Copies the plastic laws and the plastic state arrays (constructor).
  void setup_plasticity(const std::vector<HexMaterial>& materials);
  void stiffness_batch(Index batch, const Real* px, const Real* py, const Real* pz, const Real* ux,
                       const Real* uy, const Real* uz, Real* yx, Real* yy, Real* yz) const;

  std::vector<Index> m_element_index;  ///< model index per block element
  // Batched (AoSoA) data, batch b lane l:
  std::vector<Index> m_conn;           ///< [b][node 8][W]
  std::vector<Index> m_lane_owner;     ///< [b][W] block element, or NO_INDEX for padding lanes
  std::vector<Real> m_const;           ///< [b][N_CONST][W]
  std::vector<Real> m_stress;          ///< [b][6][W]
  std::vector<Real> m_hourglass;       ///< [b][4 modes × 3][W] accumulated stiffness forces
  std::vector<Real> m_volume;          ///< [b][W]
  std::vector<Real> m_viscous_before;  ///< [b][W] bulk-viscosity pressure of the last call
  std::vector<Index> m_slot;           ///< block element -> batch*W + lane
  std::vector<Index> m_color_batches;  ///< batches of colour c: [m_color_batches[c], [c+1])
  // Plasticity (all empty when no element is plastic):
  std::vector<Plasticity> m_laws;              ///< the distinct laws of the block's materials
  std::vector<int> m_lane_law;                 ///< [b][W] index into m_laws, or -1 (elastic lane)
  std::vector<unsigned char> m_batch_plastic;  ///< [b] 1 if any lane of the batch is plastic
  std::vector<Real> m_peeq;                    ///< [b][W] equivalent plastic strain ε̄ᵖ, -
  std::vector<Real> m_peeq_rate;               ///< [b][W] Δε̄ᵖ/dt of the last increment, 1/s
  std::vector<Real> m_yield;  ///< [b][W] σ_y(ε̄ᵖ, 0), Pa; +inf in elastic lanes
  // Per-batch results, reduced serially in batch order (deterministic).
  std::vector<Real> m_batch_energy;  ///< [b][4]: strain, hourglass, viscous, plastic
  std::vector<Real> m_batch_dt;
  std::vector<Index> m_batch_critical;
  std::vector<Index> m_batch_failed;
  // Partition of the force pass (thread_partition.hpp).
  int m_parts = 0;
  bool m_own_partition = false;  ///< built by internal_forces() for the block alone
  CornerExchange m_exchange;
  std::vector<Real> m_exchange_force;   ///< [slot][3], N
  std::vector<Index> m_boundary_nodes;  ///< of the partition of the block alone
};

}  // namespace xpl::elements
