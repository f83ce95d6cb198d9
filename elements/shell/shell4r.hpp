#pragma once
/// \file S4R: 4-node Belytschko–Tsay-type shell with one in-plane integration point.
///
/// Corotational local frame per element (see quad_shell_geometry.hpp); Mindlin kinematics
/// with nodal translations and rotations; membrane + bending integrated through the
/// thickness (Simpson's rule), plane-stress linear elasticity; transverse shear with the
/// shear correction factor 5/6. Hourglass control (ShellHourglass): by default the two
/// in-plane patterns take the Flanagan–Belytschko stiffness form and the bending and
/// transverse-shear patterns a physical stabilisation that stores no energy under constant
/// curvature or twist (shell4r_hourglass.hpp); the older stiffness form of all five patterns
/// (two in-plane, one transverse, two rotational) is kept as an option. Warped elements are
/// evaluated on their projected plane, with each node joined to its projection by a rigid link of
/// length z_h Γ_I along the normal (velocities projected, forces and moments transferred
/// back), so rigid rotations of warped elements stay strain and hourglass free.
///
/// Plastic materials: plane-stress J2 at every section point (shell_plasticity.hpp), the
/// thickness following the elastic plane-stress strain and the plastic incompressibility;
/// the transverse shear stays elastic (as in Belytschko–Tsay codes). Blocks without plastic
/// material carry no plastic state and run the elastic kernel alone.
///
/// Rotary inertia is lumped and scaled only as far as the stable increment needs: each node
/// gets (m_e/4)·r² from each element, r² = max(t²/12, c_ν L²) with L the element's
/// stable-increment length (√2 A / longer diagonal) and c_ν = SHELL_ROTARY_MARGIN /
/// (4 (2(1+ν)/(κ_s(1−ν)) − 1)): the smallest value for which the fastest transverse-shear
/// mode of the element (a tilt of the normal against a rotation, ω² = κ_s G (4/L² + 1/r²)/ρ)
/// stays below the membrane breathing mode ω² = 4 c² (1+ν)/L² that sets the increment.
/// Thick elements (t²/12 above it) keep their physical inertia. Skewed and tapered quads get
/// r² times shell_rotary_shape_factor() (shell4r_increment.hpp; 1 on rectangles). (Before issue 21
/// the scale was A/8 on every element, which added ~19 % to the polar inertia of a strip 4 elements
/// wide and made its torsion frequency low.)
///
/// Elements are coloured and batched like the C3D8R block: race-free, deterministic.

#include <array>
#include <limits>
#include <span>
#include <vector>

#include "common/types.hpp"
#include "elements/element_kind.hpp"
#include "elements/increment_limit.hpp"
#include "elements/lane_state.hpp"
#include "elements/material/shell_plasticity.hpp"
#include "elements/parallel/element_coloring.hpp"
#include "elements/parallel/simd.hpp"
#include "elements/parallel/thread_partition.hpp"
#include "elements/shared_blocks.hpp"

namespace xpl::elements {

/// Default hourglass stiffness coefficient of the shell (times the user's scale factor).
/// In-plane: C = κ E t A (B·B)/4; rotational: κ (E t³/12) A (B·B)/4; transverse:
/// κ (E t³/12)(B·B). On a square the in-plane value is about 20 % of what full integration
/// would give to the same pattern.
inline constexpr Real SHELL_HOURGLASS_STIFFNESS = 0.05;
/// Transverse shear correction factor.
inline constexpr Real SHELL_SHEAR_FACTOR = 5.0 / 6.0;
/// Safety factor on the smallest rotary inertia scale c_ν (see the file comment).
inline constexpr Real SHELL_ROTARY_MARGIN = 1.25;
/// Factor on ω² of the tilt-mode bound κ_s G (4/L² + 12/t²)/ρ that limits the increment of
/// ROTARY INERTIA=EXACT elements: the bound is exact on a square, and distorted elements
/// reach 2.3 % above it in ω (tests/elements/test_shell4r_hourglass.cpp).
inline constexpr Real SHELL_EXACT_ROTARY_MARGIN = 1.1;

/// Plastic sections of the physical form (issue 32 item 5): the hourglass resultants advance
/// with the section's current tangent, measured at its section points, instead of the elastic
/// moduli. Bending increments keep at least this fraction of the elastic stiffness, a lower
/// bound for stability: at 0.15 or less a corner element of the crash tube's first fold folds
/// over; 0.175 to 1 complete, ALLAE rising with it (benchmarks/RESULTS.md, "floor sweep").
inline constexpr Real SHELL_HOURGLASS_TANGENT_FLOOR = 0.2;
/// Plastic sections of the physical form: the in-plane hourglass resultants relax with the
/// membrane return and their linear resultant field stays within this multiple of the
/// section's flow resultant σ_f t (hourglass_field_norm(), shell4r_hourglass.hpp).
inline constexpr Real SHELL_HOURGLASS_PLASTIC_BOUND = 1.5;

/// Hourglass control of the S4R bending and transverse-shear patterns.
enum class ShellHourglass {
  /// Physical stabilisation (default): the exactly integrated energy of the linear
  /// curvature and (assumed-strain) transverse-shear parts the one-point rule misses, zero
  /// for constant curvature and twist (shell4r_hourglass.hpp). Scaled by hourglass_scale.
  Physical,
  /// The older Flanagan–Belytschko stiffness form on the transverse and rotational patterns
  /// with the coefficient SHELL_HOURGLASS_STIFFNESS (resists part of a twist field).
  Stiffness,
};
/// A corner of an S4R whose angle exceeds 180° by more than asin(SHELL_FOLD_LIMIT) = 30°
/// (scaled Jacobian below −SHELL_FOLD_LIMIT, quad_corner_jacobians()) has its node pushed
/// across the diagonal of its neighbours: the element is folded over, and the run fails
/// naming it; a corner concave or straight in the reference configuration (the reader accepts
/// one concave corner) is left out. Not at 180°, as C3D8R's HEX_FOLD_LIMIT: a quad crushed to
/// a sliver has corners near 0° and 180° that the least motion turns either way.
inline constexpr Real SHELL_FOLD_LIMIT = 0.5;
/// Largest number of through-thickness integration points.
inline constexpr int SHELL_MAX_POINTS = 15;

template <class T>
struct QuadFrame;
template <class T>
struct EdgeShear;
struct ShellPlaneRates;
struct ShellSectionResultants;
namespace shell4r_kernel {
template <int N>
struct HourglassAdvance;
struct ShearForces;
}  // namespace shell4r_kernel

/// Material and section constants of one shell element.
struct ShellProperties {
  Real density = 0.0;          ///< kg/m^3
  Real young = 0.0;            ///< Pa
  Real poisson = 0.0;          ///< -
  Real thickness = 0.0;        ///< initial thickness, m
  int integration_points = 5;  ///< through the thickness (Simpson, odd), 1 = membrane only
  Real offset = 0.0;           ///< reference surface above the mid-surface / thickness
  Real hourglass_scale = 1.0;  ///< scales the hourglass control (both forms)
  /// J2 plasticity of the material, or nullptr for an elastic one. Not owned: read (and
  /// copied, once per distinct law) by the block's constructor only.
  const Plasticity* plastic = nullptr;
  /// Form of the bending and transverse-shear hourglass control.
  ShellHourglass hourglass = ShellHourglass::Physical;
  /// Physical form on a plastic material: the hourglass resultants follow the section's
  /// plastic state (SHELL_HOURGLASS_TANGENT_FLOOR, SHELL_HOURGLASS_PLASTIC_BOUND; the default);
  /// false keeps them elastic (issue 21's form, `*SECTION CONTROLS, PLASTIC HOURGLASS=ELASTIC`).
  bool plastic_hourglass = true;
  /// Rotary inertia t²/12 per unit mass (ROTARY INERTIA=EXACT), with the stable increment
  /// of the element's fastest transverse-shear mode, instead of the scaled default.
  bool rotary_exact = false;
};

/// Rotary inertia per unit translational mass (m²) of a shell element of thickness t,
/// stable-increment length L (m) and Poisson's ratio ν (see the file comment); `exact`:
/// t²/12 (ROTARY INERTIA=EXACT).
Real shell_rotary_radius2(Real thickness, Real length, Real poisson, bool exact = false);

/// What one shell internal-force pass reports (sums over the block in a fixed order).
struct ShellStepTotals : IncrementLimit {
  Real strain_energy_increment = 0.0;     ///< ΔALLSE, J
  Real hourglass_energy_increment = 0.0;  ///< ΔALLAE, J
  /// ΔALLPD, J: Σ over section points of weight · ½(σ_n + σ_{n+1}) : Δεᵖ · mid-increment
  /// volume. The strain energy increment above is the recoverable part (total work minus
  /// this), the elastic energy of the stress state.
  Real plastic_energy_increment = 0.0;
};

/// Section output of one shell element.
struct ShellSectionOutput {
  /// S11 S22 S33 S12 S13 S23 at the bottom, middle and top section points, in the Abaqus
  /// default local axes (1 = projection of global x, or of global z when x is normal).
  std::array<std::array<Real, 6>, 3> stress{};
  Real thickness = 0.0;  ///< current thickness, m
  /// Equivalent plastic strain PEEQ (-) at the bottom, middle and top section points
  /// (0 for an elastic element).
  std::array<Real, 3> peeq{};
  Real peeq_max = 0.0;  ///< largest PEEQ over all section points, -
};

/// Speed of the one-point quad's breathing mode, √(E/ρ(1−ν²)) · √(1+ν) (ν < 0 taken as 0),
/// m/s: the stable increment is √2 A / (longer diagonal) over it.
Real shell_wave_speed(const ShellProperties& p);

/// A set of S4R elements and their state (an element kind, element_kind.hpp).
class Shell4rBlock {
 public:
  static constexpr const char* NAME = "S4R";
  static constexpr const char* SETUP_NOTE =
      "; rotary inertia scaled to (m/4)·max(t²/12, c_nu L²) per node so that the membrane "
      "wave sets the stable increment";
  static constexpr int NODES = 4;
  static constexpr bool ROTATIONS = true;  ///< its nodes have rotational DOFs
  using Properties = ShellProperties;
  using Totals = ShellStepTotals;

  /// `element_index`: model index per element; `connectivity`: 4 node indices per element;
  /// `properties`: one per element.
  Shell4rBlock(std::vector<Index> element_index, const std::vector<Index>& connectivity,
               const std::vector<ShellProperties>& properties, Index node_count,
               const BatchLayout* layout = nullptr);

  Index size() const { return static_cast<Index>(m_element_index.size()); }
  int color_count() const { return static_cast<int>(m_color_batches.size()) - 1; }
  /// Model index of block element i.
  Index element_index(Index i) const { return m_element_index[i]; }

  /// Mass share per node ρ t A/4 (kg) of one element with properties `p` and corners
  /// `corners` (4, m; A the area of their quad_frame()).
  static Real node_mass(const ShellProperties& p, const V3<Real>* corners);
  /// Stable increment (s) of one element at rest with properties `p` and corners `corners`
  /// (4, m), as the force pass estimates it: √2 A / (longer diagonal) / shell_wave_speed()
  /// (the membrane estimate; the bulk viscosity does not enter, nor the tilt-mode limit of
  /// ROTARY INERTIA=EXACT).
  static Real stable_increment(const ShellProperties& p, const V3<Real>* corners, Real bulk_linear);

  /// Adds the lumped translational mass ρ t A/4 and the scaled rotary inertia to the nodes.
  void add_lumped_mass(const NodalVectors& reference, std::vector<Real>& mass,
                       std::vector<Real>& rotary_inertia) const;

  /// Notes the corners of each element that are concave or straight in `reference`
  /// (n_nodes × 3, m): the reader accepts one concave corner, so the fold check of the force
  /// pass (SHELL_FOLD_LIMIT) leaves those corners out. Until called, every corner is checked.
  void note_reference_corners(const NodalVectors& reference);

  /// Thickness of each node: the area-weighted mean initial thickness of the shells around
  /// it (n_nodes; 0 for nodes on no shell), for contact.
  std::vector<Real> node_thickness(const NodalVectors& reference, Index node_count) const;

  /// Warp angle (degrees) of block element i in the given configuration.
  Real warp_angle(const NodalVectors& position, Index i) const;

  /// One internal-force evaluation at the end of an increment: positions x_{n+1}, velocities
  /// v_{n+1/2}, angular velocities ω_{n+1/2} (n_nodes × 3 each), dt = t_{n+1} − t_n. Strain
  /// increments are taken on the mid-increment geometry, forces on x_{n+1}. Adds forces and
  /// moments into `force` and `moment` (n_nodes × 3).
  /// The block alone is split into omp_get_max_threads() parts (thread_partition.hpp).
  void internal_forces(const NodalVectors& position, const NodalVectors& velocity_half,
                       const NodalVectors& angular_velocity_half, Real dt, NodalVectors& force,
                       NodalVectors& moment, ShellStepTotals& totals);

  /// \name The pieces of internal_forces() for a pass over several blocks (ElementSet); as
  /// those of Hex8rBlock.
  void mark_nodes(int parts, std::vector<Index>& node_part) const;
  void set_partition(int parts, const BoundaryNodes& boundary);
  int parts() const { return m_parts; }
  void set_batch_phases(std::vector<unsigned char> phase) { m_batch_phase = std::move(phase); }
  void forces_of_part(int part, const NodalVectors& position, const NodalVectors& velocity_half,
                      const NodalVectors& angular_velocity_half, Real dt, NodalVectors& force,
                      NodalVectors& moment, int phase = -1);
  /// Adds the exchanged corner forces and moments of boundary node k (rank), `node`.
  void add_boundary_forces(Index k, Index node, NodalVectors& force, NodalVectors& moment) const {
    const Index n = static_cast<Index>(force.rows());
    Real* f = force.data() + node;
    Real* m = moment.data() + node;
    for (Index s = m_exchange.first(k); s < m_exchange.first(k + 1); ++s) {
      const Real* e = &m_exchange_force[6 * static_cast<std::size_t>(s)];
      f[0] += e[0];
      f[n] += e[1];
      f[2 * n] += e[2];
      m[0] += e[3];
      m[n] += e[4];
      m[2 * n] += e[5];
    }
  }
  void forces_of_part(int part, const ForcePass& p) {
    forces_of_part(part, p.position, p.velocity_half, p.angular_velocity_half, p.dt, p.force,
                   p.moment, p.phase);
  }
  void add_boundary_forces(Index k, Index node, const ForcePass& p) const {
    add_boundary_forces(k, node, p.force, p.moment);
  }
  void add_totals(ShellStepTotals& totals) const;
  /// \name Distributed runs (solver/distributed_run.hpp): the totals of batch b as
  /// BATCH_TOTALS values (its energies, then its limit), and back.
  static constexpr int BATCH_TOTALS = 6;
  void pack_batch_totals(Index b, Real* out) const {
    for (int k = 0; k < 3; ++k) out[k] = m_batch_energy[b * 3 + k];
    out[3] = m_batch_dt[b];
    out[4] = static_cast<Real>(m_batch_critical[b]);
    out[5] = static_cast<Real>(m_batch_failed[b]);
  }
  void unpack_batch_totals(Index b, const Real* in) {
    for (int k = 0; k < 3; ++k) m_batch_energy[b * 3 + k] = in[k];
    m_batch_dt[b] = in[3];
    m_batch_critical[b] = static_cast<Index>(in[4]);
    m_batch_failed[b] = static_cast<Index>(in[5]);
  }
  /// The layout, the corner slots of the boundary nodes and their values ([slot][6]: force,
  /// moment).
  static constexpr int EXCHANGE_WIDTH = 6;
  Index batch_count() const { return m_color_batches.back(); }
  const std::vector<Index>& lane_owners() const { return m_lane_owner; }
  const std::vector<Index>& color_batches() const { return m_color_batches; }
  const CornerExchange& corner_exchange() const { return m_exchange; }
  const std::vector<Real>& exchange_values() const { return m_exchange_force; }

  /// Section output of block element i in the configuration `position`.
  ShellSectionOutput section_output(const NodalVectors& position, Index i) const;

  /// Writes middle/bottom/top stresses (rows e·6.., Abaqus order) and thickness of every block
  /// element at its model index into model-sized arrays; an empty array is left alone.
  void gather_output(const NodalVectors& position, std::vector<Real>& stress,
                     std::vector<Real>& bottom, std::vector<Real>& top,
                     std::vector<Real>& thickness) const;
  void gather_output(const OutputArrays& out) const {
    gather_output(out.position, out.stress, out.stress_bottom, out.stress_top, out.thickness);
  }

  /// Sets the stresses of every block element from model-sized rows (n_elements × 6, row
  /// e·6.., S11 S22 S33 S12 S13 S23, Pa) at the middle, bottom (SNEG) and top (SPOS) section
  /// points, given in the output local axes of gather_output in the configuration `position`
  /// (n_nodes × 3, m): the inverse of gather_output's stresses, for a run that starts from an
  /// imported state. Rows of elements outside the block are not read.
  ///
  /// In-plane stresses (S11 S22 S12) are rotated into the element's corotational frame at
  /// `position` and interpolated linearly in ζ between the bottom and middle values (ζ ≤ 0)
  /// and between the middle and top values (ζ ≥ 0), ζ ∈ [−1, 1] being the through-thickness
  /// coordinate of an integration point: exact for membrane + bending (stresses linear
  /// through the thickness, the only distribution an elastic section holds), and the three
  /// section points, which are integration points (ζ = −1, 0, 1), get exactly the given
  /// values. A membrane-only element (one point) takes the middle values. The transverse
  /// shear is one value per element, constant through the thickness (κ G γ as the element
  /// computes it): it is taken from S13 S23 of the middle rows; S33 and the transverse shear
  /// of the bottom and top rows are not read (gather_output writes S33 = 0 and the same
  /// shear at all three points). Thickness and hourglass resultants are left as they are
  /// (set_thickness, set_hourglass_state).
  void set_output_stress(const NodalVectors& position, std::span<const Real> middle,
                         std::span<const Real> bottom, std::span<const Real> top);
  /// set_output_stress() under the element kinds' name (element_kind.hpp).
  void set_stress(const NodalVectors& position, std::span<const Real> middle,
                  std::span<const Real> bottom, std::span<const Real> top) {
    set_output_stress(position, middle, bottom, top);
  }

  /// Writes the hourglass resultants of every block element at its model index into
  /// model-sized rows (n_elements × HOURGLASS_STATE_WIDTH, lane_state.hpp): the N_HOURGLASS
  /// values below, in the element's corotational frame (N, N·m), the remaining columns 0.
  void gather_hourglass_state(std::vector<Real>& rows) const;
  /// The inverse of gather_hourglass_state, for a run that starts from an imported state in
  /// the same configuration (the corotational frame follows from the nodes).
  void set_hourglass_state(std::span<const Real> rows);
  /// Sets the current thickness of every block element from a model-sized array (STH,
  /// n_elements, m, > 0), for a run that starts from an imported state.
  void set_thickness(std::span<const Real> thickness);

  /// Whether any element of the block is plastic (else no plastic state exists, P2).
  bool has_plasticity() const { return !m_plastic.empty(); }
  /// Writes the largest PEEQ (-) through the thickness of every block element at its model
  /// index into a model-sized array (n_elements); elastic elements write 0.
  void gather_plastic_strain(std::vector<Real>& peeq) const;
  /// Writes the PEEQ (-) of the bottom (SNEG), middle and top (SPOS) section points of every
  /// block element at its model index into model-sized arrays (n_elements each).
  void gather_section_plastic_strain(std::vector<Real>& bottom, std::vector<Real>& middle,
                                     std::vector<Real>& top) const;
  /// Sets the PEEQ of the plastic elements from model-sized arrays (n_elements each, -, ≥ 0)
  /// at the middle, bottom and top section points (an imported state): interpolated linearly
  /// in ζ between them as set_output_stress does for the stresses. Exact at the three section
  /// points; points between them get the interpolated value (a result file does not hold the
  /// others). Elastic elements and rows outside the block are not read.
  void set_plastic_strain(std::span<const Real> middle, std::span<const Real> bottom,
                          std::span<const Real> top);
  /// PEEQ (-) and its rate over the last increment (1/s) of section point k (0 = bottom) of
  /// block element i, for tests.
  Real plastic_strain(Index i, int k) const;

 private:
  static constexpr int W = simd::W;
  enum Constant {
    Q11 = 0,     ///< E / (1 − ν²)
    Q12,         ///< ν E / (1 − ν²)
    SHEAR,       ///< G
    SHEAR_T,     ///< κ_s G (transverse)
    NU_RATIO,    ///< ν / (1 − ν): thickness strain per unit in-plane dilatation
    DT_SPEED,    ///< √(E/ρ(1−ν²)) · √(1+ν): the one-point quad's breathing-mode speed
    HG_MODULUS,  ///< κ E (in-plane patterns, both forms)
    HG_OLD,      ///< κ E on the transverse/rotational patterns (stiffness form), else 0
    HG_PHYS,     ///< hourglass scale of the physical form, else 0
    PHYS_ON,     ///< 1 on physical-form lanes, else 0
    POISSON,     ///< ν
    OFFSET,      ///< reference surface above the mid-surface / thickness
    DENSITY,
    THICKNESS0,  ///< initial thickness
    ROT_SPEED2,  ///< κ_s G / ρ on ROTARY INERTIA=EXACT lanes, else 0 (no rotational limit)
    ROT_EXACT,   ///< 1 on ROTARY INERTIA=EXACT lanes, else 0
    HG_PLASTIC,  ///< 1 on physical-form lanes whose hourglass follows the plastic state, else 0
    N_CONST
  };
  /// Hourglass resultants: in-plane x, y; stiffness form: transverse, rotational x, y;
  /// physical form: shear Q_ξ, Q_η, bending M_1, M_2 (conjugate to q = Σ γ_I β_I / 4).
  static constexpr int N_HOURGLASS = 9;
  /// Forms present in a batch (bits of m_batch_forms).
  static constexpr unsigned char FORM_OLD = 1, FORM_PHYS = 2;

  template <bool PLASTIC>
  void compute_batch(Index batch, const Real* const p[3], const Real* const v[3],
                     const Real* const w[3], Real dt, Real* const f[3], Real* const m[3]);
  /// The pieces of compute_batch (shell4r.cpp, shell4r_kernel.hpp), inlined into it: the
  /// through-thickness integration of batch b with its plasticity and thickness update, the
  /// physical hourglass, and the stable increment, fold check, scatter and per-batch
  /// reductions.
  ///
  /// section_resultants: plane stress, the thickness follows the in-plane dilatation of the
  /// reference surface, ε̇_zz = −ν/(1−ν)(d_xx + d_yy + z_ref(κ_xx + κ_yy)). It is advanced
  /// before the resultants: the strain increments see the mid-increment thickness (as the rates
  /// see the mid-increment geometry) and the resultants at t_{n+1} the end thickness, so N and M
  /// are functions of the state at t_{n+1}. Resultants taken with the thickness of t_n lag the
  /// stresses by one increment; in compressed walls (tr N < 0) that lag does negative work on
  /// every membrane vibration, ∝ ν/(1−ν)·|σ|/E·ωΔt per cycle, and a crushed tube gains energy
  /// until it fails.
  template <bool PLASTIC>
  [[gnu::always_inline]] inline ShellSectionResultants section_resultants(
      std::size_t b, Real dt, const ShellPlaneRates& rates);
  /// The physical form's transverse-shear and bending hourglass of batch b (lanes with
  /// PHYS_ON; shell4r_hourglass.hpp): advances resultants 5..8 in `hg` from the edge shears
  /// `edge` and the rotation patterns' rates `rate_tx`, `rate_ty` on the mid geometry `fm`
  /// (bending stiffness following the section's tangent on lanes with `plastic_on`), and puts
  /// into `shear` the part of the shear resultants of `sr` that acts through the one-point shear
  /// and the edge shears' nodal forces on x_{n+1} (`fe`, corners `x`).
  template <bool PLASTIC>
  [[gnu::always_inline]] inline void physical_hourglass(
      std::size_t b, const QuadFrame<simd::Vec>& fm, const QuadFrame<simd::Vec>& fe,
      const V3<simd::Vec> x[4], const EdgeShear<simd::Vec>& edge, simd::Vec rate_tx,
      simd::Vec rate_ty, const ShellSectionResultants& sr, simd::Vec plastic_on,
      shell4r_kernel::HourglassAdvance<N_HOURGLASS>& hg, shell4r_kernel::ShearForces& shear);
  template <bool PLASTIC>
  [[gnu::always_inline]] inline void finish_batch(Index batch, const QuadFrame<simd::Vec>& fe,
                                                  simd::Vec mid_area, simd::Vec work,
                                                  simd::Vec plastic_work, simd::Vec hg_work,
                                                  const V3<simd::Vec> fn[4],
                                                  const V3<simd::Vec> mn[4], Real* const f[3],
                                                  Real* const m[3]);
  void own_partition(int parts, Index node_count);
  std::size_t slot_of(Index i) const { return static_cast<std::size_t>(m_slot[i]); }
  /// Number of through-thickness points of the element in batch b, lane l.
  int points_of(std::size_t b, std::size_t l) const;

  std::vector<Index> m_element_index;
  int m_points = 1;             ///< integration points of the block (max over elements)
  bool m_rotary_exact = false;  ///< any element with ROTARY INERTIA=EXACT
  // Batched (AoSoA) data, batch b lane l.
  std::vector<Index> m_conn;        ///< [b][4][W]
  std::vector<Index> m_lane_owner;  ///< [b][W]
  // Read-only after construction and alike in most batches: each distinct batch block once
  // (208 bytes per element on a block of one section, issue 38).
  SharedBlocks<Real> m_const;                ///< [b][N_CONST][W]
  SharedBlocks<Real> m_zeta;                 ///< [b][m_points][W] point position in [−1, 1]
  SharedBlocks<Real> m_weight;               ///< [b][m_points][W] weight, Σ = 1 (0: unused point)
  std::vector<Real> m_thickness;             ///< [b][W] current thickness
  std::vector<Real> m_stress;                ///< [b][m_points][3][W] σxx σyy σxy, local frame
  std::vector<Real> m_shear;                 ///< [b][2][W] τxz τyz
  std::vector<Real> m_hourglass;             ///< [b][N_HOURGLASS][W]
  std::vector<Index> m_slot;                 ///< block element -> b*W + l
  std::vector<Index> m_color_batches;        ///< batches of colour c: [c], [c+1]
  std::vector<unsigned char> m_batch_forms;  ///< [b]: FORM_OLD | FORM_PHYS of its lanes
  /// [b][W]: bit k set where corner k is not checked for a fold (concave or straight in the
  /// reference configuration: note_reference_corners())
  std::vector<unsigned char> m_fold_exempt;
  ShellPlasticState m_plastic;       ///< section-point plasticity (empty when elastic)
  std::vector<Real> m_batch_energy;  ///< [b][3]: strain, hourglass, plastic
  std::vector<Real> m_batch_dt;
  std::vector<Index> m_batch_critical;
  std::vector<Index> m_batch_failed;
  // Partition of the force pass (thread_partition.hpp).
  int m_parts = 0;
  std::vector<unsigned char> m_batch_phase;  ///< [b] (in_phase()), or empty
  bool m_own_partition = false;
  CornerExchange m_exchange;
  std::vector<Real> m_exchange_force;   ///< [slot][6]: force N, moment N·m
  std::vector<Index> m_boundary_nodes;  ///< of the partition of the block alone
};

}  // namespace xpl::elements
