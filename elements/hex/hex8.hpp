#pragma once
/// \file C3D8: fully integrated 8-node hexahedron, selectively reduced (mean dilatation,
/// "B-bar"): the deviatoric strain rate and stress live at the 2×2×2 Gauss points, the
/// volumetric strain rate is the element's mean dilatation (1/V) dV/dt, so that the element does
/// not lock as ν → 0.5. Jaumann-rate linear elasticity (optionally J2 plasticity with a radial
/// return per integration point), bulk viscosity on the mean dilatation, no hourglass control
/// (full integration has no spurious zero-energy modes).
///
/// Forces in mode space (hex8_geometry.hpp): with the Jacobian columns c_ξ, c_η, c_ζ at a
/// Gauss point and its cofactor columns n_ξ = c_η×c_ζ, n_η = c_ζ×c_ξ, n_ζ = c_ξ×c_η,
/// det J · J⁻ᵀ ∇_ξ N_I = ⅛ Σ_k Λ_kI Σ_a n_a ∂m_k/∂ξ_a (m_k the k-th monomial), so
///   F_k = ⅛ ( Σ_q s_q Σ_a n_a,q ∂m_k/∂ξ_a(q) + p̄ g_k ),   f_I = Σ_k Λ_kI F_k,
/// with s_q the stress deviator at point q, p̄ = (1/V) Σ_q det J_q · tr(σ_q)/3 the volume-averaged
/// mean stress (plus bulk viscosity) and g_k the exact volume gradient; no division by det J.
/// Layout, colouring, partition and determinism as Hex8rBlock (hex_batches.hpp).

#include <array>
#include <span>
#include <vector>

#include "common/types.hpp"
#include "elements/hex/hex_block.hpp"
#include "elements/material/plasticity.hpp"
#include "elements/material/radial_return_lanes.hpp"
#include "elements/parallel/simd.hpp"

namespace xpl::elements {

/// Number of integration points of a C3D8 element (2×2×2 Gauss).
inline constexpr int HEX8_POINTS = 8;

/// A set of C3D8 elements and their state (stress and PEEQ per integration point).
class Hex8Block : public HexBlock {
 public:
  static constexpr const char* NAME = "C3D8";
  static constexpr const char* SETUP_NOTE =
      "; 2x2x2 points, mean dilatation (selectively reduced), no hourglass control";
  /// `element_index`: model index of each element; `connectivity`: 8 node indices per element
  /// (Abaqus order); `materials`: one per element (the hourglass fields are not used).
  /// `layout`: as HexBatches' (null: coloured and packed here).
  Hex8Block(std::vector<Index> element_index, const std::vector<Index>& connectivity,
            const std::vector<HexMaterial>& materials, Index node_count,
            const BatchLayout* layout = nullptr);

  /// One internal-force evaluation, as Hex8rBlock::internal_forces: `position` x_{n+1} and
  /// `velocity_half` v_{n+1/2} (n_nodes × 3), `dt` (0 at the start); strain rates on the
  /// mid-increment geometry, forces on x_{n+1}, added into `force` (n_nodes × 3, N). The
  /// hourglass energy of the totals stays 0. The block alone is split into
  /// omp_get_max_threads() parts (one parallel region).
  void internal_forces(const NodalVectors& position, const NodalVectors& velocity_half, Real dt,
                       Real bulk_linear, Real bulk_quadratic, NodalVectors& force,
                       HexStepTotals& totals);

  /// \name The pieces of internal_forces() for a pass over several blocks (as Hex8rBlock's).
  void forces_of_part(int part, const NodalVectors& position, const NodalVectors& velocity_half,
                      Real dt, Real bulk_linear, Real bulk_quadratic, NodalVectors& force);
  void forces_of_part(int part, const ForcePass& p) {
    forces_of_part(part, p.position, p.velocity_half, p.dt, p.bulk_linear, p.bulk_quadratic,
                   p.force);
  }
  /// Adds the energies and the increment limit of the last pass to `totals`, in batch order.
  void add_totals(HexStepTotals& totals) const;
  /// \name Distributed runs (solver/distributed_run.hpp): the totals of batch b as
  /// BATCH_TOTALS values (its energies, then its limit), and back.
  static constexpr int BATCH_TOTALS = 3 + 3;
  void pack_batch_totals(Index b, Real* out) const {
    for (int k = 0; k < 3; ++k) out[k] = m_batch_energy[b * 3 + k];
    m_batches.pack_limit(b, out + 3);
  }
  void unpack_batch_totals(Index b, const Real* in) {
    for (int k = 0; k < 3; ++k) m_batch_energy[b * 3 + k] = in[k];
    m_batches.unpack_limit(b, in + 3);
  }

  /// Writes the element stress (row e·6.., S11 S22 S33 S12 S13 S23: the volume average of the
  /// integration points) and current volume of every element at its model index; an empty
  /// array is left alone.
  void gather_output(std::vector<Real>& stress, std::vector<Real>& volume) const;
  void gather_output(const OutputArrays& out) const { gather_output(out.stress, out.volume); }
  /// Sets the stress of every integration point of every element from model-sized rows
  /// (n_elements × 6, Pa): an imported state has one stress per element, so the points start
  /// equal.
  void set_stress(std::span<const Real> stress);
  /// The element kinds' form (element_kind.hpp): a solid reads the `middle` rows.
  void set_stress(const NodalVectors& /*position*/, std::span<const Real> middle,
                  std::span<const Real> /*bottom*/, std::span<const Real> /*top*/) {
    set_stress(middle);
  }

  /// Volume-averaged stress of block element i (constructor order), for tests.
  std::array<Real, 6> stress(Index i) const;
  /// Stress of integration point q (0..7, ξ fastest, then η, ζ) of block element i, for tests.
  std::array<Real, 6> point_stress(Index i, int q) const;

  /// Whether any element of the block is plastic (else no plastic state exists, P2).
  bool has_plasticity() const { return !m_laws.empty(); }
  /// Writes PEEQ (-) of every element at its model index into a model-sized array: the volume
  /// average of its integration points; elastic elements write 0.
  void gather_plastic_strain(std::vector<Real>& peeq) const;
  /// Sets PEEQ of every integration point of the plastic elements from a model-sized array
  /// (n_elements, -, ≥ 0), for a run that starts from an imported state.
  void set_plastic_strain(std::span<const Real> peeq);
  /// Volume-averaged PEEQ (-) of block element i, for tests.
  Real plastic_strain(Index i) const;

  /// Linear stiffness product y += K u at `position` (n_nodes × 3, m) from a stress-free state
  /// (the selectively reduced K of the element: mean dilatation times the bulk modulus, the
  /// deviatoric part at the Gauss points), for the model's highest frequency
  /// (solver/increment/global_increment.*). `u` (m) and `y` (N) are n_nodes × 3. Race-free,
  /// independent of the thread count.
  void add_stiffness_product(const NodalVectors& position, const NodalVectors& u,
                             NodalVectors& y) const;

 private:
  static constexpr int W = simd::W;
  enum Constant {
    LAMBDA = HexBatches::LAMBDA,
    TWO_MU = HexBatches::TWO_MU,
    DENSITY = HexBatches::DENSITY,
    WAVE_SPEED = HexBatches::WAVE_SPEED,
    DT_FACTOR = HexBatches::DT_FACTOR,
    N_CONST = HexBatches::N_SHARED
  };

  template <bool PLASTIC>
  void compute_batch(Index batch, const Real* px, const Real* py, const Real* pz, const Real* vx,
                     const Real* vy, const Real* vz, Real dt, Real b1, Real b2, Real* fx, Real* fy,
                     Real* fz);
  void stiffness_batch(Index batch, const Real* px, const Real* py, const Real* pz, const Real* ux,
                       const Real* uy, const Real* uz, Real* yx, Real* yy, Real* yz) const;
  /// J2 return of the trial stress `sn` (6 × W) of integration point q of a batch, whose
  /// increment started from `start`; returns the plastic work ½(σ_n + σ_{n+1}) : Δεᵖ per lane
  /// (Pa; 0 where elastic; return_work()).
  simd::Vec plastic_return(Index batch, int q, const simd::Vec start[6], simd::Vec sn[6], Real dt);
  void setup_plasticity(const std::vector<HexMaterial>& materials);

  // State, batch b lane l:
  std::vector<Real> m_stress;          ///< [b][point 8][6][W]
  std::vector<Real> m_point_volume;    ///< [b][point 8][W] det J at x_{n+1} (weight 1), m^3
  std::vector<Real> m_volume;          ///< [b][W]
  std::vector<Real> m_viscous_before;  ///< [b][W] bulk-viscosity pressure of the last call
  // Plasticity (all empty when no element is plastic):
  std::vector<Plasticity> m_laws;
  std::vector<int> m_lane_law;                 ///< [b][W] index into m_laws, or -1
  std::vector<unsigned char> m_batch_plastic;  ///< [b] 1 if any lane of the batch is plastic
  RadialReturnLanes m_points;  ///< [b][point 8][W] ε̄ᵖ, yield stress and table segment
  // Per-batch energies, reduced serially in batch order (deterministic).
  std::vector<Real> m_batch_energy;  ///< [b][3]: strain, viscous, plastic
};

}  // namespace xpl::elements
