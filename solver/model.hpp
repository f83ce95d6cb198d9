#pragma once
/// \file The analysis model as read from a deck: mesh, sets, materials, sections, steps.
///
/// Everything inside xpl works on contiguous internal indices. Deck ids (arbitrary, sparse)
/// are mapped once by `io` and kept here only to be written back to results and messages.

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "common/error.hpp"
#include "common/types.hpp"
#include "common/units.hpp"
#include "elements/material/plasticity.hpp"

namespace xpl {

/// Element formulations known to the solver.
enum class ElementType : std::uint8_t {
  C3D8R,  ///< 8-node hex, one-point integration, hourglass control
  S4R,    ///< 4-node shell, one in-plane point, hourglass control (S4 is read as S4R)
  C3D8,   ///< 8-node hex, 2×2×2 points, selectively reduced (mean dilatation), no hourglass
};

/// Abaqus name of an element type ("C3D8R", "S4R"), as in decks and result files.
constexpr const char* element_type_name(ElementType type) {
  switch (type) {
    case ElementType::C3D8R:
      return "C3D8R";
    case ElementType::S4R:
      return "S4R";
    case ElementType::C3D8:
      return "C3D8";
  }
  return "UNKNOWN";
}

/// Whether elements of a type carry rotational degrees of freedom at their nodes.
constexpr bool is_shell(ElementType type) {
  return type == ElementType::S4R;
}

/// Whether elements of a type are 8-node hexahedra (C3D8R, C3D8): same nodes, faces S1..S6,
/// sections, surfaces and loads; they differ only in their element kernel.
constexpr bool is_hex(ElementType type) {
  return type == ElementType::C3D8R || type == ElementType::C3D8;
}

/// Number of nodes of an element type.
constexpr int nodes_per_element(ElementType type) {
  switch (type) {
    case ElementType::C3D8R:
    case ElementType::C3D8:
      return 8;
    case ElementType::S4R:
      return 4;
  }
  return 0;
}

/// Isotropic linear elastic material with density (consistent units, e.g. SI), optionally
/// J2-plastic with isotropic hardening (`*PLASTIC`, `*RATE DEPENDENT`).
struct Material {
  std::string name;    ///< upper-case name
  Real density = 0.0;  ///< mass density, kg/m^3
  Real young = 0.0;    ///< Young's modulus E, Pa
  Real poisson = 0.0;  ///< Poisson's ratio ν, -1 < ν < 0.5
  bool has_density = false;
  bool has_elastic = false;
  /// `*PLASTIC` (with `*RATE DEPENDENT` folded in); empty for an elastic material, which
  /// then does no plasticity work at all.
  std::optional<elements::Plasticity> plastic;
  SourceLocation plastic_where;  ///< the *PLASTIC line (when plastic)
  SourceLocation where;          ///< the *MATERIAL line
};

/// Hourglass control of reduced-integration elements (`*SECTION CONTROLS, HOURGLASS=`).
enum class HourglassType {
  Stiffness,       ///< Flanagan–Belytschko stiffness form
  Viscous,         ///< Flanagan–Belytschko viscous form
  RelaxStiffness,  ///< Abaqus' integral-viscoelastic form; xpl runs it as Stiffness (noted in .msg)
  /// The physical stabilisations, the default of both elements when HOURGLASS= is not given:
  /// S4R's of the bending and transverse-shear patterns (shell4r_hourglass.hpp), C3D8R's
  /// enhanced assumed-strain form (elements/hex/hex8r_enhanced.hpp).
  Enhanced,
};

/// `*SECTION CONTROLS, NAME=...`.
struct SectionControls {
  std::string name;
  HourglassType hourglass = HourglassType::Enhanced;
  /// Whether HOURGLASS= was given: C3D8R and S4R use their physical forms unless STIFFNESS,
  /// VISCOUS or RELAX STIFFNESS asks for an older one.
  bool hourglass_given = false;
  Real stiffness_scale = 1.0;  ///< multiplies the default hourglass stiffness coefficient
  Real viscous_scale = 1.0;    ///< multiplies the default hourglass viscosity coefficient
  SourceLocation where;
};

/// `*SOLID SECTION, ELSET=, MATERIAL=[, CONTROLS=]`.
struct SolidSection {
  Index element_set = NO_INDEX;  ///< into Model::element_sets
  Index material = NO_INDEX;     ///< into Model::materials
  Index controls = NO_INDEX;     ///< into Model::section_controls, NO_INDEX = defaults
  SourceLocation where;
};

/// `*SHELL SECTION, ELSET=, MATERIAL=[, OFFSET=][, CONTROLS=]` with the data line
/// `thickness[, integration points]` (Simpson's rule through the thickness).
struct ShellSection {
  Index element_set = NO_INDEX;  ///< into Model::element_sets
  Index material = NO_INDEX;     ///< into Model::materials
  Index controls = NO_INDEX;     ///< into Model::section_controls, NO_INDEX = defaults
  Real thickness = 0.0;          ///< initial shell thickness, m (> 0)
  int integration_points = 5;    ///< through the thickness, odd, >= 1
  /// Position of the reference surface (the nodes) measured from the mid-surface, as a
  /// fraction of the thickness along the shell normal: OFFSET=SPOS is 0.5, SNEG is -0.5,
  /// MIDSURFACE (default) is 0.
  Real offset = 0.0;
  /// ROTARY INERTIA=EXACT: the physical rotary inertia t²/12 per unit mass, the element's
  /// stable increment then including its rotational (transverse-shear) mode; ISOTROPIC
  /// (default, false): scaled up where that mode would set the increment (shell4r.hpp).
  bool rotary_exact = false;
  SourceLocation where;
};

/// A named set of nodes or elements (internal indices, sorted, unique).
struct NamedSet {
  std::string name;  ///< upper-case name
  std::vector<Index> members;
  SourceLocation where;
};

/// Corner nodes (0-based, element node order) of the C3D8R faces S1..S6. The right-hand
/// normal of each corner cycle points into the element (Abaqus' face numbering).
inline constexpr int HEX_FACE_NODES[6][4] = {{0, 1, 2, 3}, {4, 7, 6, 5}, {0, 4, 5, 1},
                                             {1, 5, 6, 2}, {2, 6, 7, 3}, {3, 7, 4, 0}};

/// Faces of an S4R element: SNEG (the side opposite the normal n = (x3−x1)×(x4−x2)) and SPOS.
inline constexpr std::uint8_t SHELL_FACE_NEG = 0;
inline constexpr std::uint8_t SHELL_FACE_POS = 1;

/// One face of an element: C3D8R faces S1..S6 are stored as 0..5 (Abaqus numbering:
/// S1 = nodes 1-2-3-4, S2 = 5-8-7-6, S3 = 1-5-6-2, S4 = 2-6-7-3, S5 = 3-7-8-4, S6 = 4-8-5-1);
/// S4R faces are SHELL_FACE_NEG (SNEG) and SHELL_FACE_POS (SPOS).
struct ElementFace {
  Index element = NO_INDEX;
  std::uint8_t face = 0;
};

/// `*SURFACE, TYPE=ELEMENT|NODE, NAME=`.
struct Surface {
  enum class Type { Element, Node };
  std::string name;  ///< upper-case name
  Type type = Type::Element;
  std::vector<ElementFace> faces;  ///< TYPE=ELEMENT
  std::vector<Index> nodes;        ///< TYPE=NODE, ascending, each once
  /// TYPE=NODE: the area (or weight) the data line gives each node (parallel to `nodes`), m²;
  /// NaN where the line gives none (the contact domain then takes its default, SPEC C13).
  std::vector<Real> node_areas;
  SourceLocation where;
};

/// `*AMPLITUDE, NAME=, DEFINITION=TABULAR[, TIME=STEP TIME|TOTAL TIME]`: piecewise linear,
/// held constant before the first and after the last point.
struct Amplitude {
  std::string name;  ///< upper-case name
  std::vector<Real> time;
  std::vector<Real> value;
  bool total_time = false;  ///< false: abscissa is step time (the Abaqus default)
  SourceLocation where;
  /// Value at time t (step or total time, as `total_time` says).
  Real evaluate(Real t) const;
};

/// Whether a boundary condition prescribes displacement or velocity.
enum class BoundaryType { Displacement, Velocity };

/// One prescribed degree-of-freedom range on one node (sets are expanded by io).
/// DOFs use Abaqus numbering 1..6; 4..6 act on the rotations of shell nodes and are ignored
/// (with a .msg note) on nodes that have no rotational DOFs.
struct BoundaryCondition {
  Index node = NO_INDEX;
  int first_dof = 1;
  int last_dof = 1;
  Real value = 0.0;  ///< magnitude (displacement or velocity), times the amplitude
  BoundaryType type = BoundaryType::Displacement;
  Index amplitude = NO_INDEX;  ///< NO_INDEX: the step's default amplitude
  SourceLocation where;
};

/// `*CLOAD`: a concentrated force on one node and DOF (sets expanded by io).
struct ConcentratedLoad {
  Index node = NO_INDEX;
  int dof = 1;       ///< 1..3
  Real value = 0.0;  ///< N, times the amplitude
  Index amplitude = NO_INDEX;
  SourceLocation where;
};

/// A pressure on one element face (`*DLOAD` P / Pn, `*DSLOAD` P on an element-based
/// surface), following the current geometry. Positive pressure pushes against the face's
/// outward normal: into a solid; for a shell, `*DLOAD P` and SPOS push along −n, SNEG along +n.
struct PressureLoad {
  ElementFace face;
  Real value = 0.0;  ///< Pa, times the amplitude
  Index amplitude = NO_INDEX;
  SourceLocation where;
};

/// `*DLOAD` GRAV: a body force ρ·g·direction on the elements of a set (all elements when
/// `element_set` is NO_INDEX), N/kg times the amplitude.
struct GravityLoad {
  Index element_set = NO_INDEX;
  Real magnitude = 0.0;            ///< m/s^2
  Real direction[3] = {0, 0, -1};  ///< unit vector (normalised by io)
  Index amplitude = NO_INDEX;
  SourceLocation where;
};

/// `*SURFACE INTERACTION, NAME=` with `*FRICTION` and `*SURFACE BEHAVIOR`.
struct SurfaceInteraction {
  std::string name;     ///< upper-case name
  Real friction = 0.0;  ///< Coulomb coefficient μ (`*FRICTION`), 0 = frictionless
  /// `*SURFACE BEHAVIOR, PRESSURE-OVERCLOSURE=`: HARD (default) and LINEAR both run as penalty
  /// contact; LINEAR with a slope uses it (pressure per unit overclosure, Pa/m) as the
  /// penalty stiffness per unit area, HARD uses the default penalty.
  bool linear = false;
  Real linear_slope = 0.0;  ///< Pa/m, > 0 when given
  SourceLocation where;
};

/// A pair of surfaces (indices into Model::surfaces). NO_INDEX stands for "all exterior
/// faces" (an empty surface field in the deck); `first == second` is self contact.
struct SurfacePair {
  Index first = NO_INDEX;
  Index second = NO_INDEX;
  SourceLocation where;
};

/// `*DISTRIBUTION, NAME=, LOCATION=NODE`: one scalar per node (SPEC C8: a clearance per slave
/// node). A first data line with a blank node field gives the default of every node not listed.
struct NodalDistribution {
  std::string name;          ///< upper-case name
  std::vector<Real> values;  ///< (n_nodes), NaN where the deck gives no value
  SourceLocation where;
};

/// `*CONTACT CLEARANCE, NAME=, ADJUST=, CLEARANCE=, SEARCH ABOVE=, SEARCH BELOW=` (SPEC C7–C9),
/// or the same written `*CONTACT INITIALIZATION DATA, NAME=, INITIAL CLEARANCE=, ADJUST=, SEARCH
/// ABOVE=, SEARCH BELOW=` (SPEC C14), which may instead ask for an interference fit (C15).
struct ContactClearance {
  std::string name;  ///< upper-case name
  /// Spelled `*CONTACT INITIALIZATION DATA` (its names are apart from `*CONTACT CLEARANCE`'s).
  bool initialization = false;
  /// `INTERFERENCE FIT` (C15): the overclosures of the slave nodes in the search zone become
  /// offsets ramped to zero over `step_fraction` of the first step (the penalty pushes the
  /// surfaces apart); `value` and `distribution` are then unused.
  bool interference = false;
  /// `INTERFERENCE FIT=h`: nodes are first moved (strain free, ADJUST=YES) to an overclosure h,
  /// m; empty: the overclosure as read is the interference.
  std::optional<Real> interference_distance;
  Real step_fraction = 1.0;  ///< `STEP FRACTION=`, in (0, 1]
  /// ADJUST=YES (default): nodes move, strain free, in the first step only; ADJUST=NO:
  /// permanent contact offsets, never ramped away.
  bool adjust = true;
  Real value = 0.0;               ///< CLEARANCE=value, m (default 0) when no distribution
  Index distribution = NO_INDEX;  ///< CLEARANCE=distribution name: into Model::distributions
  /// Search zone above / below the master surface, m; empty: the default of SPEC C9 (a tenth
  /// of the facet size at a solid slave node, the thickness at a shell slave node).
  std::optional<Real> search_above, search_below;
  SourceLocation where;
};

/// The keyword that defined `c`, for messages.
inline const char* clearance_keyword(const ContactClearance& c) {
  return c.initialization ? "*CONTACT INITIALIZATION DATA" : "*CONTACT CLEARANCE";
}
/// The assignment keyword of the spelling (`initialization`: the SPEC C14 one), for messages.
inline const char* assignment_keyword(bool initialization) {
  return initialization ? "*CONTACT INITIALIZATION ASSIGNMENT" : "*CONTACT CLEARANCE ASSIGNMENT";
}

/// A `*CONTACT CLEARANCE ASSIGNMENT` data line: `surf1, surf2, name[, MASTER|SLAVE]`, or a
/// `*CONTACT INITIALIZATION ASSIGNMENT` line with the same fields (SPEC C14).
struct ClearanceAssignment {
  /// Both: the nodes of each surface against the faces of the other (balanced, default);
  /// Master: surf1 is the master, only the nodes of surf2 move; Slave: surf1 is the slave.
  enum class View { Both, Master, Slave };
  Index first = NO_INDEX;      ///< into Model::surfaces (element based, single sided)
  Index second = NO_INDEX;     ///< into Model::surfaces, != first
  Index clearance = NO_INDEX;  ///< into Model::contact_clearances
  View view = View::Both;
  SourceLocation where;
};

/// `*CONTACT` (general contact) in a step, with its sub-options.
struct GeneralContact {
  /// `*CONTACT INCLUSIONS, ALL EXTERIOR`: every exterior solid face and both sides of every
  /// shell, including self contact.
  bool all_exterior = false;
  std::vector<SurfacePair> inclusions;  ///< `*CONTACT INCLUSIONS` data lines
  std::vector<SurfacePair> exclusions;  ///< `*CONTACT EXCLUSIONS` data lines
  /// `*CONTACT PROPERTY ASSIGNMENT`: interaction (into Model::surface_interactions) per
  /// pair; a pair of two NO_INDEX surfaces is the global default.
  std::vector<std::pair<SurfacePair, Index>> properties;
  /// `*CONTACT CONTROLS ASSIGNMENT` penalty scale factor (`*CONTACT CONTROLS, NAME=,
  /// PENALTY SCALE FACTOR=`... or the data-line form), multiplies the default penalty.
  Real penalty_scale = 1.0;
  /// `*CONTACT CLEARANCE ASSIGNMENT` lines of this step only (a later step's *CONTACT starts
  /// without them): they act when the step's contact domain is built new (SPEC C7, C10).
  std::vector<ClearanceAssignment> clearances;
  SourceLocation where;
};

/// `*CONTACT PAIR, INTERACTION=` (CalculiX/Abaqus pairwise contact): slave, master surfaces.
struct ContactPair {
  Index slave = NO_INDEX;   ///< into Model::surfaces
  Index master = NO_INDEX;  ///< into Model::surfaces
  Index interaction = NO_INDEX;
  SourceLocation where;
};

/// `*RIGID BODY, REF NODE=, ELSET=[, PIN NSET=][, TIE NSET=]`: the elements of the set (and
/// the pinned/tied nodes) move with the reference node as one rigid body.
struct RigidBody {
  Index reference_node = NO_INDEX;
  Index element_set = NO_INDEX;  ///< NO_INDEX: none
  Index pin_node_set = NO_INDEX;
  Index tie_node_set = NO_INDEX;
  SourceLocation where;
};

/// `*TIE, NAME=, POSITION TOLERANCE=, ADJUST=YES|NO` with the data line `slave, master`
/// (SPEC S6): every slave node within the tolerance of the master surface is bound to its
/// closest point there (solver/ties.hpp).
struct Tie {
  std::string name;               ///< upper-case name
  Index slave = NO_INDEX;         ///< into Model::surfaces (element or node based)
  Index master = NO_INDEX;        ///< into Model::surfaces (element based)
  std::optional<Real> tolerance;  ///< POSITION TOLERANCE=, m; empty: the default (ties.hpp)
  bool adjust = true;             ///< ADJUST=YES: slave nodes moved onto the master first
  SourceLocation where;
};

/// A point mass (`*ELEMENT, TYPE=MASS` + `*MASS, ELSET=`) or rotary inertia
/// (`TYPE=ROTARYI` + `*ROTARY INERTIA`: I11, I22, I33, I12, I13, I23 in global axes) on a node.
struct PointInertia {
  Index node = NO_INDEX;
  Real mass = 0.0;                       ///< kg
  Real inertia[6] = {0, 0, 0, 0, 0, 0};  ///< kg·m^2
  SourceLocation where;
};

/// `*OUTPUT, FIELD|HISTORY` with the `*NODE OUTPUT`, `*ELEMENT OUTPUT`, `*ENERGY OUTPUT`
/// requests that follow it.
struct OutputRequest {
  enum class Kind { Field, History };
  Kind kind = Kind::Field;
  /// Exactly one of these is positive. Defaults (neither given): field NUMBER INTERVAL=20,
  /// history NUMBER INTERVAL=200 (as Abaqus/Explicit).
  int number_interval = 0;
  Real time_interval = 0.0;
  /// Node variables, upper case: field U V A RF UR VR RM; history also components U1..RF3,
  /// UR1..RM3. As in Abaqus, U/V/RF on shell models also write UR/VR/RM.
  std::vector<std::string> node_variables;
  Index node_set = NO_INDEX;  ///< NO_INDEX: all nodes (field) / none (history)
  /// Element variables, upper case: S, EVOL, MISES, STH (shell thickness), ...
  std::vector<std::string> element_variables;
  Index element_set = NO_INDEX;
  /// Whole-model energies (history): ALLKE ALLSE ALLAE ALLIE ALLVD ALLWK ETOTAL, and with
  /// contact ALLFD (frictional dissipation) and ALLPW (work of contact penalties); `energy`
  /// with an empty list means all of them.
  bool energy = false;
  std::vector<std::string> energy_variables;
  /// Contact variables (`*CONTACT OUTPUT`, field), upper case: CSTRESS (contact pressure and
  /// shear stress), CSTATUS, CFORCE; over the whole contact domain.
  std::vector<std::string> contact_variables;
  SourceLocation where;
};

/// `*DIAGNOSTICS`: how much the initial-overclosure pass reports (SPEC C5, C11).
struct Diagnostics {
  /// `CONTACT INITIAL OVERCLOSURE=DETAIL` (default): every adjusted node and every offset in
  /// the .msg file; SUMMARY: only the counts and the largest overclosure, in the .sta file.
  bool overclosure_detail = true;
  /// `DETECT CROSSED SURFACES=ON` (default): warn about slave facet edges that cross a master
  /// surface at the start of a contact step.
  bool detect_crossed_surfaces = true;
  SourceLocation where;
};

/// `*FIXED MASS SCALING, FACTOR=, DT=, TYPE=, ELSET=` (SPEC S4): the masses of the elements of a
/// set (all deformable elements without ELSET=) scaled once, at the start of the analysis (xpl
/// accepts it in the first step only), FACTOR first, then DT.
struct FixedMassScaling {
  /// How DT= scales: BelowMin brings every element whose stable increment is below DT up to it
  /// (factor (DT/Δt_e)²); Uniform scales the whole set by one factor so that its smallest
  /// element increment becomes DT (no scaling where it is already above).
  enum class Type { BelowMin, Uniform };
  Real factor = 1.0;       ///< FACTOR=, > 0 (1: none)
  std::optional<Real> dt;  ///< DT=, s: the element stable increment (before the scale factor)
  Type type = Type::BelowMin;
  Index element_set = NO_INDEX;  ///< NO_INDEX: every deformable element
  SourceLocation where;
};

/// One `*STEP ... *END STEP` block with `*DYNAMIC, EXPLICIT`.
/// How a step's increment follows the stable increment (`*DYNAMIC, EXPLICIT`); the increment
/// itself is chosen by solver/increment_control.hpp.
struct IncrementControls {
  std::optional<Real> fixed;  ///< `*DYNAMIC, EXPLICIT, DIRECT USER CONTROL`: this increment, s
  /// Fourth value of the `*DYNAMIC, EXPLICIT` data line: the increment never exceeds it, s.
  std::optional<Real> max;
  Real scale_factor = 1.0;  ///< multiplies the stable increment (S2)
};

struct Step {
  std::string name;
  SourceLocation where;
  Real time_period = 0.0;       ///< s
  IncrementControls increment;  ///< scale factor, maximum or fixed increment
  Real bulk_linear = 0.06;      ///< `*BULK VISCOSITY` b1 (Abaqus default)
  Real bulk_quadratic = 1.2;    ///< `*BULK VISCOSITY` b2 (Abaqus default)
  bool ramp_amplitude = false;  ///< `*STEP, AMPLITUDE=RAMP`; default STEP for explicit
  /// Boundary conditions given in this step. Those of earlier steps stay active unless this
  /// step has `*BOUNDARY, OP=NEW` (then `boundaries_reset`). Later entries for the same
  /// node and DOF replace earlier ones.
  std::vector<BoundaryCondition> boundaries;
  bool boundaries_reset = false;
  std::vector<ConcentratedLoad> loads;  ///< same propagation rule as boundaries
  bool loads_reset = false;
  /// Pressures of `*DLOAD`/`*DSLOAD`, same propagation rule (a later entry for the same face
  /// replaces an earlier one; OP=NEW on either keyword clears all earlier pressures).
  std::vector<PressureLoad> pressures;
  bool pressures_reset = false;
  /// Gravity of `*DLOAD` GRAV lines, same propagation rule (keyed by element set).
  std::vector<GravityLoad> gravity;
  /// `*DLOAD, OP=NEW` in this step: gravity of earlier steps is removed (it also sets
  /// `pressures_reset`; `*DSLOAD, OP=NEW` sets only that).
  bool gravity_reset = false;
  /// General contact in effect from this step on, when the step has `*CONTACT`: complete, i.e.
  /// the definition of the latest earlier step with `*CONTACT` plus this step's options
  /// (`*CONTACT, OP=NEW`: this step's options only; no inclusions then means no general
  /// contact). Empty when the step has no `*CONTACT` (contact of an earlier step carries
  /// over, as Abaqus does).
  std::optional<GeneralContact> contact;
  std::vector<ContactPair> contact_pairs;  ///< `*CONTACT PAIR` given in this step
  /// `*DIAGNOSTICS` given in this step; those of earlier steps (or the model data) apply
  /// otherwise (Model::diagnostics_of).
  std::optional<Diagnostics> diagnostics;
  std::vector<OutputRequest> outputs;
  /// `*FIXED MASS SCALING` definitions (first step only), applied in this order.
  std::vector<FixedMassScaling> mass_scaling;
};

/// A part instance of an assembly (`*INSTANCE, NAME=, PART=`): its nodes and elements carry
/// the ids of the part, which repeat from instance to instance; the model numbers them
/// `offset + local id` (Model::node_ids, element_ids) and keeps the local ids beside.
struct PartInstance {
  std::string name;                                ///< upper-case instance name
  std::string part;                                ///< upper-case part name
  ExternalId node_offset = 0, element_offset = 0;  ///< model id = offset + local id
  Index nodes = 0, elements = 0;                   ///< how many the instance has
  SourceLocation where;                            ///< the *INSTANCE line
};

/// Something the deck reader wants the user to see in the .msg file (not an error).
struct DeckMessage {
  bool warning = false;  ///< false: a note
  std::string text;      ///< starts with `file:LINE: *KEYWORD:`
};

/// The whole analysis as read from a deck.
struct Model {
  std::string heading;  ///< the *HEADING lines joined by newlines, control characters escaped
  std::vector<DeckMessage> deck_messages;  ///< written to .msg by the solver at the start
  std::string job_name;                    ///< deck stem
  /// The unit system the deck states (`** xpl: UNITS=`), or how its numbers are labelled when
  /// it states none (common/units.hpp); the solver computes in the deck's numbers either way.
  ModelUnits units;

  // --- nodes -------------------------------------------------------------------------------
  std::vector<ExternalId> node_ids;  ///< deck id of each node (n_nodes)
  NodalVectors coordinates;          ///< reference coordinates (n_nodes × 3), m

  // --- elements (CSR connectivity, node indices) --------------------------------------------
  std::vector<ExternalId> element_ids;     ///< deck id of each element (n_elements)
  std::vector<ElementType> element_types;  ///< (n_elements)
  std::vector<Index> element_offsets{0};   ///< (n_elements + 1) into element_nodes
  std::vector<Index> element_nodes;        ///< node indices, Abaqus node order
  /// Section of each element: into solid_sections for solids, into shell_sections for
  /// shells (the element type says which), NO_INDEX if none.
  std::vector<Index> element_section;
  /// Deck line of each element, compact (6 bytes per element): file index and line.
  std::vector<std::string> source_files;
  std::vector<std::uint16_t> element_file;
  std::vector<std::int32_t> element_line;

  // --- properties --------------------------------------------------------------------------
  std::vector<Material> materials;
  std::vector<SectionControls> section_controls;
  std::vector<SolidSection> solid_sections;
  std::vector<ShellSection> shell_sections;

  // --- sets, surfaces, amplitudes ------------------------------------------------------------
  std::vector<NamedSet> node_sets;
  std::vector<NamedSet> element_sets;
  std::vector<Surface> surfaces;
  std::vector<Amplitude> amplitudes;

  // --- contact, rigid bodies, point inertia --------------------------------------------------
  std::vector<SurfaceInteraction> surface_interactions;
  std::vector<ContactPair> contact_pairs;  ///< model-level `*CONTACT PAIR` (CalculiX style)
  Diagnostics diagnostics;                 ///< model-level `*DIAGNOSTICS` (or the defaults)
  std::vector<ContactClearance> contact_clearances;  ///< `*CONTACT CLEARANCE`
  std::vector<NodalDistribution> distributions;      ///< `*DISTRIBUTION, LOCATION=NODE`
  std::vector<RigidBody> rigid_bodies;
  std::vector<Tie> ties;  ///< `*TIE`
  std::vector<PointInertia> point_inertias;

  // --- initial conditions and history --------------------------------------------------------
  NodalVectors initial_velocity;  ///< (n_nodes × 3) zero unless given, or empty (zero), m/s
  /// (n_nodes × 3) or empty, rad/s: dofs 4–6 of `*INITIAL CONDITIONS, TYPE=VELOCITY` and the
  /// spin of `ROTATING VELOCITY` on shell nodes (the only ones that rotate); zero unless given.
  NodalVectors initial_angular_velocity;
  std::vector<Step> steps;

  // --- assembly: decks with *PART and *INSTANCE; all empty for a flat deck ----------------------
  std::vector<PartInstance> instances;
  /// Instance of each node / element (n_nodes / n_elements): into `instances`, -1 for the
  /// assembly level (nodes and elements defined outside any part).
  std::vector<std::int32_t> node_instance, element_instance;
  /// Ids as the deck wrote them in the part (n_nodes / n_elements); node_ids and element_ids
  /// are unique over the model (PartInstance offsets).
  std::vector<ExternalId> node_local_ids, element_local_ids;
  /// Model-level offset of nodes and elements defined at the assembly level.
  ExternalId assembly_node_offset = 0, assembly_element_offset = 0;

  /// Whether any element is a shell (then nodes carry rotations; P2: otherwise nothing
  /// rotational is allocated or computed).
  bool has_shells() const;
  /// Whether any step has general contact or the model has a contact pair.
  bool has_contact() const;
  /// Whether any material is plastic (then PEEQ and ALLPD exist; P2: otherwise nothing
  /// plastic is allocated, computed or written).
  bool has_plasticity() const;
  /// Whether a shell section has a plastic material (then the shells' PEEQ per section point,
  /// PEEQ_SNEG/SMID/SPOS, is written).
  bool has_plastic_shells() const;

  Index node_count() const { return static_cast<Index>(node_ids.size()); }
  Index element_count() const { return static_cast<Index>(element_ids.size()); }
  /// Node indices of element e.
  const Index* nodes_of(Index e) const { return element_nodes.data() + element_offsets[e]; }
  /// Nodes of a surface (sorted, unique): the corners of an element surface's faces (hex face
  /// corners, the four nodes of a shell), or a node surface's nodes; indices outside the
  /// model (a deck with errors elsewhere) are left out.
  std::vector<Index> surface_nodes(const Surface& surface) const;
  /// The deck line of element e (for messages).
  SourceLocation element_where(Index e) const {
    return {source_files[element_file[e]], element_line[e]};
  }
  /// Records the deck line of the next element (used by io while reading).
  void add_element_source(const std::string& file, int line);
  /// Index of a set/amplitude/material by (case-insensitive) name, or NO_INDEX.
  Index find_node_set(const std::string& name) const;
  Index find_element_set(const std::string& name) const;
  Index find_surface(const std::string& name) const;
  Index find_amplitude(const std::string& name) const;
  Index find_material(const std::string& name) const;
  /// The `*DIAGNOSTICS` settings in effect in step `step`: the latest given in that step or an
  /// earlier one, else the model data's.
  const Diagnostics& diagnostics_of(int step) const;
};

/// Upper-case copy of an ASCII string (names and keywords are case-insensitive).
std::string to_upper(std::string text);

}  // namespace xpl
