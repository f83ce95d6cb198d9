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
#include "elements/parallel/simd.hpp"

namespace xpl::elements {

/// Number of integration points of a C3D8 element (2×2×2 Gauss).
inline constexpr int HEX8_POINTS = 8;

class Hex8Block;
/// The scaffolding C3D8 shares with C3D8R: 8 stress points, 3 energies (strain, viscous,
/// plastic).
using Hex8Base = HexBlock<Hex8Block, HEX8_POINTS, 3>;

/// A set of C3D8 elements and their state (stress and PEEQ per integration point). The force
/// pass, output and import are HexBlock's; the hourglass energy of the totals stays 0.
class Hex8Block : public Hex8Base {
 public:
  static constexpr const char* NAME = "C3D8";
  static constexpr const char* SETUP_NOTE =
      "; 2x2x2 points, mean dilatation (selectively reduced), no hourglass control";
  /// The totals the batch energies add into, in their order in the batch.
  static constexpr Real HexStepTotals::*ENERGY_TOTALS[] = {
      &HexStepTotals::strain_energy_increment, &HexStepTotals::viscous_energy_increment,
      &HexStepTotals::plastic_energy_increment};
  /// `element_index`: model index of each element; `connectivity`: 8 node indices per element
  /// (Abaqus order); `materials`: one per element (the hourglass fields are not used).
  /// `layout`: as HexBatches' (null: coloured and packed here).
  Hex8Block(std::vector<Index> element_index, const std::vector<Index>& connectivity,
            const std::vector<HexMaterial>& materials, Index node_count,
            const BatchLayout* layout = nullptr);

  /// Volume-averaged stress of block element i (constructor order): the element stress of
  /// gather_output (a plain mean of the points before the first force pass).
  std::array<Real, 6> stress(Index i) const;
  /// Volume-averaged PEEQ (-) of block element i, for output and tests.
  Real plastic_strain(Index i) const;

 private:
  friend Hex8Base;
  enum Constant { N_CONST = N_SHARED };

  /// The force kernel of one batch (HexBlock::forces_of_part()).
  template <bool PLASTIC>
  void batch_forces(Index batch, const NodalColumns& c, Real dt, Real b1, Real b2) {
    compute_batch<PLASTIC>(batch, c, dt, b1, b2);
  }
  template <bool PLASTIC>
  void compute_batch(Index batch, const NodalColumns& c, Real dt, Real b1, Real b2);
  /// y += K u of one batch: the selectively reduced K of the element (mean dilatation times
  /// the bulk modulus, the deviatoric part at the Gauss points).
  void stiffness_batch(Index batch, const NodalColumns& c) const;
  /// J2 return of the trial stress `sn` (6 × W) of integration point q of a batch, whose
  /// increment started from `start`; returns the plastic work ½(σ_n + σ_{n+1}) : Δεᵖ per lane
  /// (Pa; 0 where elastic; return_work()).
  simd::Vec plastic_return(Index batch, int q, const simd::Vec start[6], simd::Vec sn[6], Real dt);

  std::vector<Real> m_point_volume;  ///< [b][point 8][W] det J at x_{n+1} (weight 1), m^3
};

}  // namespace xpl::elements
