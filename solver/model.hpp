#pragma once
/// \file The analysis model as read from a deck: mesh, sets, materials, sections, steps.
///
/// Everything inside xpl works on contiguous internal indices. Deck ids (arbitrary, sparse)
/// are mapped once by `io` and kept here only to be written back to results and messages.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "common/types.hpp"

namespace xpl {

/// Element formulations known to the solver.
enum class ElementType : std::uint8_t {
  C3D8R,  ///< 8-node hex, one-point integration, hourglass control
};

/// Number of nodes of an element type.
constexpr int nodes_per_element(ElementType type) {
  switch (type) {
    case ElementType::C3D8R:
      return 8;
  }
  return 0;
}

/// Isotropic linear elastic material with density (consistent units, e.g. SI).
struct Material {
  std::string name;    ///< upper-case name
  Real density = 0.0;  ///< mass density, kg/m^3
  Real young = 0.0;    ///< Young's modulus E, Pa
  Real poisson = 0.0;  ///< Poisson's ratio ν, -1 < ν < 0.5
  bool has_density = false;
  bool has_elastic = false;
  SourceLocation where;  ///< the *MATERIAL line
};

/// Hourglass control of reduced-integration elements (`*SECTION CONTROLS, HOURGLASS=`).
enum class HourglassType {
  Stiffness,       ///< Flanagan–Belytschko stiffness form (the xpl default)
  Viscous,         ///< Flanagan–Belytschko viscous form
  RelaxStiffness,  ///< Abaqus' integral-viscoelastic form; xpl runs it as Stiffness (noted in .msg)
};

/// `*SECTION CONTROLS, NAME=...`.
struct SectionControls {
  std::string name;
  HourglassType hourglass = HourglassType::Stiffness;
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

/// A named set of nodes or elements (internal indices, sorted, unique).
struct NamedSet {
  std::string name;  ///< upper-case name
  std::vector<Index> members;
  SourceLocation where;
};

/// One face of a solid element: C3D8R faces S1..S6 are stored as 0..5 (Abaqus numbering:
/// S1 = nodes 1-2-3-4, S2 = 5-8-7-6, S3 = 1-5-6-2, S4 = 2-6-7-3, S5 = 3-7-8-4, S6 = 4-8-5-1).
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
  std::vector<Index> nodes;        ///< TYPE=NODE
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
/// DOFs use Abaqus numbering 1..6; C3D8R nodes only have 1..3 (4..6 are accepted and ignored
/// until shells exist).
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

/// `*OUTPUT, FIELD|HISTORY` with the `*NODE OUTPUT`, `*ELEMENT OUTPUT`, `*ENERGY OUTPUT`
/// requests that follow it.
struct OutputRequest {
  enum class Kind { Field, History };
  Kind kind = Kind::Field;
  /// Exactly one of these is positive. Defaults (neither given): field NUMBER INTERVAL=20,
  /// history NUMBER INTERVAL=200 (as Abaqus/Explicit).
  int number_interval = 0;
  Real time_interval = 0.0;
  /// Node variables, upper case: field U V A RF; history also components U1..RF3.
  std::vector<std::string> node_variables;
  Index node_set = NO_INDEX;  ///< NO_INDEX: all nodes (field) / none (history)
  /// Element variables, upper case: S, EVOL, ...
  std::vector<std::string> element_variables;
  Index element_set = NO_INDEX;
  /// Whole-model energies (history): ALLKE ALLSE ALLAE ALLIE ALLVD ALLWK ETOTAL; `energy`
  /// with an empty list means all of them.
  bool energy = false;
  std::vector<std::string> energy_variables;
  SourceLocation where;
};

/// One `*STEP ... *END STEP` block with `*DYNAMIC, EXPLICIT`.
struct Step {
  std::string name;
  SourceLocation where;
  Real time_period = 0.0;               ///< s
  std::optional<Real> fixed_increment;  ///< `*DYNAMIC, EXPLICIT, DIRECT USER CONTROL`
  Real time_scale_factor = 1.0;         ///< multiplies the stable increment (S2)
  Real bulk_linear = 0.06;              ///< `*BULK VISCOSITY` b1 (Abaqus default)
  Real bulk_quadratic = 1.2;            ///< `*BULK VISCOSITY` b2 (Abaqus default)
  bool ramp_amplitude = false;          ///< `*STEP, AMPLITUDE=RAMP`; default STEP for explicit
  /// Boundary conditions given in this step. Those of earlier steps stay active unless this
  /// step has `*BOUNDARY, OP=NEW` (then `boundaries_reset`). Later entries for the same
  /// node and DOF replace earlier ones.
  std::vector<BoundaryCondition> boundaries;
  bool boundaries_reset = false;
  std::vector<ConcentratedLoad> loads;  ///< same propagation rule as boundaries
  bool loads_reset = false;
  std::vector<OutputRequest> outputs;
};

/// The whole analysis as read from a deck.
struct Model {
  std::string heading;
  std::string job_name;  ///< deck stem

  // --- nodes -------------------------------------------------------------------------------
  std::vector<ExternalId> node_ids;  ///< deck id of each node (n_nodes)
  NodalVectors coordinates;          ///< reference coordinates (n_nodes × 3), m

  // --- elements (CSR connectivity, node indices) --------------------------------------------
  std::vector<ExternalId> element_ids;     ///< deck id of each element (n_elements)
  std::vector<ElementType> element_types;  ///< (n_elements)
  std::vector<Index> element_offsets{0};   ///< (n_elements + 1) into element_nodes
  std::vector<Index> element_nodes;        ///< node indices, Abaqus node order
  std::vector<Index> element_section;      ///< into solid_sections, NO_INDEX if none
  /// Deck line of each element, compact (6 bytes per element): file index and line.
  std::vector<std::string> source_files;
  std::vector<std::uint16_t> element_file;
  std::vector<std::int32_t> element_line;

  // --- properties --------------------------------------------------------------------------
  std::vector<Material> materials;
  std::vector<SectionControls> section_controls;
  std::vector<SolidSection> solid_sections;

  // --- sets, surfaces, amplitudes ------------------------------------------------------------
  std::vector<NamedSet> node_sets;
  std::vector<NamedSet> element_sets;
  std::vector<Surface> surfaces;
  std::vector<Amplitude> amplitudes;

  // --- initial conditions and history --------------------------------------------------------
  NodalVectors initial_velocity;  ///< (n_nodes × 3), zero unless given, m/s
  std::vector<Step> steps;

  Index node_count() const { return static_cast<Index>(node_ids.size()); }
  Index element_count() const { return static_cast<Index>(element_ids.size()); }
  /// Node indices of element e.
  const Index* nodes_of(Index e) const { return element_nodes.data() + element_offsets[e]; }
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
};

/// Upper-case copy of an ASCII string (names and keywords are case-insensitive).
std::string to_upper(std::string text);

}  // namespace xpl
