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
#include "elements/material/plasticity.hpp"
#include "elements/material/radial_return_lanes.hpp"
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

/// A set of C3D8R elements and their state (stress, hourglass forces).
class Hex8rBlock : public HexBlock {
 public:
  static constexpr const char* NAME = "C3D8R";
  /// What the setup message says after the element and colour counts.
  static constexpr const char* SETUP_NOTE = " (race-free parallel assembly)";
  /// `element_index`: model index of each element; `connectivity`: 8 node indices per
  /// element (Abaqus order, same order as element_index); `materials`: one per element.
  /// `layout`: as HexBatches' (null: coloured and packed here).
  Hex8rBlock(std::vector<Index> element_index, const std::vector<Index>& connectivity,
             const std::vector<HexMaterial>& materials, Index node_count,
             const BatchLayout* layout = nullptr);

  /// One internal-force evaluation at the end of an increment.
  /// `position` x_{n+1} and `velocity_half` v_{n+1/2} (n_nodes × 3); `dt` = t_{n+1} − t_n
  /// (0 at the start of the analysis). The strain increment is taken on the mid-increment
  /// geometry (exactly zero for rigid rotations), forces on x_{n+1}. Adds the internal
  /// forces into `force` (n_nodes × 3, N) and updates the element state.
  /// The block alone is split into omp_get_max_threads() parts (one parallel region).
  void internal_forces(const NodalVectors& position, const NodalVectors& velocity_half, Real dt,
                       Real bulk_linear, Real bulk_quadratic, NodalVectors& force,
                       HexStepTotals& totals);

  /// \name The pieces of internal_forces() for a pass over several blocks (ElementSet; the
  /// partition's in HexBlock).
  /// Part `part` of the force pass (same arguments as internal_forces()): its batches of every
  /// colour, forces at boundary nodes into the exchange buffer, the rest into `force`.
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
  static constexpr int BATCH_TOTALS = 4 + 3;
  void pack_batch_totals(Index b, Real* out) const {
    for (int k = 0; k < 4; ++k) out[k] = m_batch_energy[b * 4 + k];
    m_batches.pack_limit(b, out + 4);
  }
  void unpack_batch_totals(Index b, const Real* in) {
    for (int k = 0; k < 4; ++k) m_batch_energy[b * 4 + k] = in[k];
    m_batches.unpack_limit(b, in + 4);
  }

  /// Writes stress (row e·6.., S11 S22 S33 S12 S13 S23) and current volume of every element
  /// of the block at its model index into model-sized arrays.
  void gather_output(std::vector<Real>& stress, std::vector<Real>& volume) const;
  void gather_output(const OutputArrays& out) const { gather_output(out.stress, out.volume); }

  /// Sets the stress of every element of the block from model-sized rows (n_elements × 6,
  /// row e·6.., S11 S22 S33 S12 S13 S23, global axes, Pa): the inverse of gather_output's
  /// stress part, for a run that starts from an imported state. Rows of elements outside the
  /// block are not read. The accumulated hourglass forces are left as they are (see
  /// set_hourglass_state), and so is the volume that gather_output reports (set by the next
  /// internal-force pass).
  void set_stress(std::span<const Real> stress);
  /// The element kinds' form (element_kind.hpp): a solid reads the `middle` rows.
  void set_stress(const NodalVectors& /*position*/, std::span<const Real> middle,
                  std::span<const Real> /*bottom*/, std::span<const Real> /*top*/) {
    set_stress(middle);
  }

  /// Writes the hourglass state of every block element at its model index into model-sized
  /// rows (n_elements × HOURGLASS_STATE_WIDTH, lane_state.hpp): the stiffness form's
  /// accumulated resultants (4 modes × 3 global components, N; zero under the viscous form),
  /// or the enhanced form's ENHANCED_STATE values (nine hourglass stresses in the element's
  /// frame, Pa, and the ξηζ resultant there, N; hex8r_enhanced.hpp).
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
  /// model's highest frequency: the uniform-gradient part (λ, 2μ) and the stiffness or
  /// enhanced hourglass term as internal_forces() applies them, from a stress-free state (no
  /// geometric stiffness; the viscous hourglass form and bulk viscosity are damping, not
  /// stiffness). `u` (m) and `y` (N) are n_nodes × 3; no element state changes. K u is the
  /// derivative of the internal force along u. Race-free and independent of the thread count.
  void add_stiffness_product(const NodalVectors& position, const NodalVectors& u,
                             NodalVectors& y) const;

 private:
  static constexpr int W = simd::W;
  // Per-lane constants: the shared ones (HexBatches::Constant), then the hourglass control's.
  enum Constant {
    LAMBDA = HexBatches::LAMBDA,
    TWO_MU = HexBatches::TWO_MU,
    DENSITY = HexBatches::DENSITY,
    WAVE_SPEED = HexBatches::WAVE_SPEED,
    DT_FACTOR = HexBatches::DT_FACTOR,
    HG_STIFFNESS = HexBatches::N_SHARED,
    HG_VISCOSITY,
    HG_MU,      ///< κμ of the enhanced form (0 in lanes of the other forms), Pa
    HG_LAMBDA,  ///< κλ̄ = κ 2μλ/(λ + 2μ) of the enhanced form, Pa
    N_CONST
  };
  /// Which hourglass families the lanes of a batch use (one code path per batch).
  enum class HourglassPath : unsigned char { FlanaganBelytschko, Enhanced, Mixed };

  template <bool PLASTIC, HourglassPath PATH>
  void compute_batch(Index batch, const Real* px, const Real* py, const Real* pz, const Real* vx,
                     const Real* vy, const Real* vz, Real dt, Real b1, Real b2, Real* fx, Real* fy,
                     Real* fz);
  /// J2 return of the trial stresses `sn` (6 × W) of a batch with plastic lanes over the
  /// increment `dt` from the stresses `start`: scales the deviatoric part of yielding lanes
  /// onto the yield surface, updates PEEQ, its rate and the yield stress, and returns the
  /// plastic work ½(σ_n + σ_{n+1}) : Δεᵖ per lane (Pa; 0 in lanes that stay elastic;
  /// return_work()). One SIMD yield test; the batch return within table segments, the scalar
  /// return only where that does not apply.
  simd::Vec plastic_return(Index batch, const simd::Vec start[6], simd::Vec sn[6], Real dt);
  /// Copies the plastic laws and the plastic state arrays (constructor).
  void setup_plasticity(const std::vector<HexMaterial>& materials);
  template <HourglassPath PATH>
  void stiffness_batch(Index batch, const Real* px, const Real* py, const Real* pz, const Real* ux,
                       const Real* uy, const Real* uz, Real* yx, Real* yy, Real* yz) const;

  // State, batch b lane l:
  std::vector<Real> m_stress;  ///< [b][6][W]
  /// [b][12][W] hourglass state: stiffness form Q_α (4 modes × 3, N), enhanced form its
  /// frame stresses and ξηζ resultant (hex8r_enhanced.hpp)
  std::vector<Real> m_hourglass;
  std::vector<HourglassPath> m_batch_path;  ///< [b]
  std::vector<Real> m_volume;               ///< [b][W]
  std::vector<Real> m_viscous_before;       ///< [b][W] bulk-viscosity pressure of the last call
  // Plasticity (all empty when no element is plastic):
  std::vector<Plasticity> m_laws;              ///< the distinct laws of the block's materials
  std::vector<int> m_lane_law;                 ///< [b][W] index into m_laws, or -1 (elastic lane)
  std::vector<unsigned char> m_batch_plastic;  ///< [b] 1 if any lane of the batch is plastic
  RadialReturnLanes m_points;                  ///< [b][W] ε̄ᵖ, yield stress and table segment
  std::vector<Real> m_peeq_rate;               ///< [b][W] Δε̄ᵖ/dt of the last increment, 1/s
  // Per-batch energies, reduced serially in batch order (deterministic).
  std::vector<Real> m_batch_energy;  ///< [b][4]: strain, hourglass, viscous, plastic
};

}  // namespace xpl::elements
