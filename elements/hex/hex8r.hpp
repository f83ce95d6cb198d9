#pragma once
/// \file C3D8R: 8-node hexahedron, one-point (uniform-gradient) integration with hourglass
/// control (the enhanced assumed-strain stabilisation of hex8r_enhanced.hpp, or
/// Flanagan–Belytschko's stiffness or viscous form), Jaumann-rate linear elasticity, bulk
/// viscosity.
///
/// Elements are coloured (no two elements of a colour share a node) and packed into
/// batches of simd::W elements of one colour; a batch is computed as one SIMD value per
/// quantity. Threads take per-thread ranges of every colour (thread_partition.hpp): a batch
/// scatters its forces directly except at the nodes two threads share, which are summed
/// after the pass, so assembly is race-free and every node sums its contributions in colour
/// order whatever the number of threads.

#include <array>
#include <span>
#include <vector>

#include "common/types.hpp"
#include "elements/hex/hex_block.hpp"
#include "elements/lane_state.hpp"
#include "elements/parallel/simd.hpp"

namespace xpl::elements {

/// Default Flanagan–Belytschko coefficients (multiplied by the user's scale factors).
/// Stiffness: Q̇_α = κ_s · 2G · (Σ_I b_I·b_I) / (8V) · q_α, with q_α = γ_α·v and |Γ_α|² = 8;
/// on a cube of side h the hourglass stiffness per node is 3 κ_s G h.
inline constexpr Real HOURGLASS_STIFFNESS = 0.05;
/// Viscous: Q_α = κ_v · ρ c_d A_max / 8 · q_α (≈ 14 % of critical damping on a cube).
inline constexpr Real HOURGLASS_VISCOSITY = 0.1;
/// Enhanced (hex8r_enhanced.hpp): the material's own moduli times the user's scale factor κ,
/// no other coefficient; the hourglass stresses are kept in a frame that follows the element.
/// In a plastic element
/// the hourglass stresses are the linear variation of the stress over the element, which the
/// material bounds as it bounds the stress itself (hex8r_hourglass.hpp):
/// - in a lane that yields they are multiplied by the factor the radial return applied to
///   its deviatoric stress, |dev σ| / |dev σ_trial|: returning the stress of each fibre,
///   σ + Σ, with the centre's flow scales Σ alike to first order. An hourglass mode keeps its
///   elastic stiffness against a sudden motion (no zero-energy mode opens in a flowing
///   element) while a sustained one relaxes as the material flows;
/// - in a lane that yields, the part of the hourglass strain increment along the centre's flow
///   direction N = dev σ/|dev σ| is plastic and loads no hourglass stress ((N:ε) N taken off
///   each plane's strain, its transverse strain included: flow_projected()): the elastic–
///   plastic tangent of J2 flow with a hardening modulus small next to μ, which the points of
///   a fully integrated element apply to the linear part of their strain. The other parts
///   keep the elastic moduli, so a bent hinge (whose hourglass strain is not the centre's
///   flow) keeps its stiffness, while a crushed element's spreading modes, coaxial with its
///   flow, flow with it: plastic steel cubes meeting at 600 m/s (examples/impacts/blocks_600)
///   end with ALLAE 57.7 J = 8.6 % of ALLIE instead of 72.4 J = 10.7 %, and 0.119 mm (RMS
///   over the nodes) from the selectively reduced C3D8's final shape instead of 0.167 mm;
/// - the von Mises value of each plane hourglass stress stays below 3/2 of the flow stress
///   (HOURGLASS_PLASTIC_AMPLITUDE): the linear stress of that amplitude carries the fully
///   plastic moment σ_y t²/4 of a section, so a hinge one element thick bends at M_p, and with
///   n elements through the thickness the section's fully plastic moment is M_p for any n.
/// What either removes is dissipated in ALLAE: the work of the resultants, stored or not, is
/// all artificial energy, and a hinge's bending work carried by the stabilisation is in ALLAE.
/// A corner of a C3D8R whose scaled Jacobian det J / (|J_ξ| |J_η| |J_ζ|) is below −HEX_FOLD_LIMIT
/// (one edge pushed more than 30° through the plane of the other two: corner_fold()) turns the
/// element inside out there, and the run fails naming it, as a C3D8 fails at a Gauss point's
/// Jacobian; the one point alone sees only the mean gradient and would carry on. Not at 0: an
/// element crushed to a pancake (plastic blocks meeting at 2000–3000 m/s, 2 mm cubes spread
/// to 0.01 mm × 30 mm) has nearly coplanar edges at every corner, whose sign the least
/// hourglass motion turns either way (scaled Jacobians down to −0.075 there, corner Jacobians
/// down to −5.5 V/8), yet its one-point response stays sound; a corner node driven through
/// the plane of its three neighbours reaches −0.5 a sixth of an edge past it.
inline constexpr Real HEX_FOLD_LIMIT = 0.5;

class Hex8rBlock;
/// The scaffolding C3D8R shares with C3D8: 1 stress point, 4 energies (strain, hourglass,
/// viscous, plastic).
using Hex8rBase = HexBlock<Hex8rBlock, 1, 4>;

/// A set of C3D8R elements and their state (stress, hourglass forces). The force pass, output
/// and import are HexBlock's; this class adds the hourglass control.
class Hex8rBlock : public Hex8rBase {
 public:
  static constexpr const char* NAME = "C3D8R";
  /// What the setup message says after the element and colour counts.
  static constexpr const char* SETUP_NOTE = " (race-free parallel assembly)";
  /// The totals the batch energies add into, in their order in the batch.
  static constexpr Real HexStepTotals::*ENERGY_TOTALS[] = {
      &HexStepTotals::strain_energy_increment, &HexStepTotals::hourglass_energy_increment,
      &HexStepTotals::viscous_energy_increment, &HexStepTotals::plastic_energy_increment};
  /// `element_index`: model index of each element; `connectivity`: 8 node indices per
  /// element (Abaqus order, same order as element_index); `materials`: one per element.
  /// `layout`: as HexBatches' (null: coloured and packed here).
  Hex8rBlock(std::vector<Index> element_index, const std::vector<Index>& connectivity,
             const std::vector<HexMaterial>& materials, Index node_count,
             const BatchLayout* layout = nullptr);

  /// Writes the hourglass state of every block element at its model index into model-sized
  /// rows (n_elements × HOURGLASS_STATE_WIDTH, lane_state.hpp): the stiffness form's
  /// accumulated resultants (4 modes × 3 global components, N; zero under the viscous form),
  /// or the enhanced form's ENHANCED_STATE values (nine hourglass stresses in the element's
  /// frame, Pa, and the ξηζ resultant there, N; hex8r_enhanced.hpp).
  void gather_hourglass_state(std::vector<Real>& rows) const;
  /// The inverse of gather_hourglass_state, for a run that starts from an imported state.
  void set_hourglass_state(std::span<const Real> rows);

  /// Stress of block element i (constructor order).
  std::array<Real, 6> stress(Index i) const { return point_stress(i, 0); }

  /// Sets PEEQ of the plastic elements (HexBlock::set_plastic_strain()) and zeroes their rate.
  void set_plastic_strain(std::span<const Real> peeq);
  /// PEEQ (-) and its rate over the last increment (1/s) of block element i, for output and
  /// tests.
  Real plastic_strain(Index i) const;
  Real plastic_strain_rate(Index i) const;

 private:
  friend Hex8rBase;
  // Per-lane constants: the shared ones (HexBatches::Constant), then the hourglass control's.
  enum Constant {
    HG_STIFFNESS = N_SHARED,
    HG_VISCOSITY,
    HG_MU,      ///< κμ of the enhanced form (0 in lanes of the other forms), Pa
    HG_LAMBDA,  ///< κλ̄ = κ 2μλ/(λ + 2μ) of the enhanced form, Pa
    N_CONST
  };
  /// Which hourglass families the lanes of a batch use (one code path per batch).
  enum class HourglassPath : unsigned char { FlanaganBelytschko, Enhanced, Mixed };

  /// The force kernel of one batch (HexBlock::forces_of_part()): compute_batch for the
  /// batch's hourglass path.
  template <bool PLASTIC>
  void batch_forces(Index batch, const NodalColumns& c, Real dt, Real b1, Real b2);
  template <bool PLASTIC, HourglassPath PATH>
  void compute_batch(Index batch, const NodalColumns& c, Real dt, Real b1, Real b2);
  /// J2 return of the trial stresses `sn` (6 × W) of a batch with plastic lanes over the
  /// increment `dt` from the stresses `start`: scales the deviatoric part of yielding lanes
  /// onto the yield surface, updates PEEQ, its rate and the yield stress, and returns the
  /// plastic work ½(σ_n + σ_{n+1}) : Δεᵖ per lane (Pa; 0 in lanes that stay elastic;
  /// return_work()). One SIMD yield test; the batch return within table segments, the scalar
  /// return only where that does not apply.
  simd::Vec plastic_return(Index batch, const simd::Vec start[6], simd::Vec sn[6], Real dt);
  /// y += K u of one batch (HexBlock::add_stiffness_product()): the uniform-gradient part
  /// (λ, 2μ) and the stiffness or enhanced hourglass term as the force pass applies them, from
  /// a stress-free state (no geometric stiffness; the viscous hourglass form and bulk viscosity
  /// are damping, not stiffness). K u is the derivative of the internal force along u.
  void stiffness_batch(Index batch, const NodalColumns& c) const;
  template <HourglassPath PATH>
  void stiffness_batch(Index batch, const NodalColumns& c) const;

  /// [b][12][W] hourglass state: stiffness form Q_α (4 modes × 3, N), enhanced form its
  /// frame stresses and ξηζ resultant (hex8r_enhanced.hpp)
  std::vector<Real> m_hourglass;
  std::vector<HourglassPath> m_batch_path;  ///< [b]
  std::vector<Real> m_peeq_rate;  ///< [b][W] Δε̄ᵖ/dt of the last increment, 1/s (plastic only)
};

}  // namespace xpl::elements
