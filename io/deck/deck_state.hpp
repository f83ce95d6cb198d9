#pragma once
/// \file State of the deck reader while it turns keyword blocks into a Model: the Model under
/// construction, the error list, name -> index maps, the references still to resolve and the
/// position in the deck (open material, step, output request). The keyword handlers
/// (deck_handlers.hpp) are free functions operating on it. References (node and element ids,
/// set, material, amplitude and controls names) are recorded while reading and resolved once
/// the whole deck is known, so definition order does not matter within the model data.

#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

#include "io/deck/deck_lines.hpp"
#include "solver/model/model.hpp"

namespace xpl::io {

/// Node and element ids of a part instance live in their own range of the id maps (DeckState::
/// id_key): key = scope · 2^SCOPE_SHIFT + id, scope 0 (model and assembly level) keeping the id
/// itself, so that a flat deck reads exactly as before. Ids of a deck with parts stay below
/// 2^SCOPE_SHIFT (about 10^12).
constexpr int SCOPE_SHIFT = 40;
constexpr ExternalId MAX_SCOPED_ID = (ExternalId(1) << SCOPE_SHIFT) - 1;

/// A node or element given by id (numeric) or by set name, still to be resolved.
struct DeckReference {
  std::string token;  ///< id as written, or upper-case set name (already scoped, see scoped_name)
  SourceLocation where;
  std::string keyword;  ///< "*BOUNDARY", for messages
  Index scope = 0;  ///< of a numeric token: 0 model/assembly level, k: DeckState::instances[k-1]
};

/// Categories of capped_error, one counter each.
enum ErrorCategory {
  UNDEFINED_NODES,
  NO_SECTION,
  TWO_SECTIONS,
  WRONG_SECTION_KIND,
  INVERTED,
  DEGENERATE,
  ERROR_CATEGORIES
};

/// Errors shown per capped category (capped_error): keeps the report readable for a mesh with
/// a million bad elements.
constexpr int ERROR_CAP = 20;

/// One item of a *NSET/*ELSET data line, resolved in finish().
struct SetItem {
  enum class Kind { Id, Range, SetName, NodesOfElementSet };
  Kind kind = Kind::Id;
  /// Kind::Id (first), Kind::Range: id keys (DeckState::id_key) of the item's scope.
  long long first = 0, last = 0, increment = 1;
  std::string name;  ///< Kind::SetName, Kind::NodesOfElementSet
  SourceLocation where;
  std::string keyword;
};
struct PendingSet {
  std::vector<Index> members;  ///< members known while reading (*NODE, NSET= / *ELEMENT, ELSET=)
  /// Element sets: geometry elements (into DeckState::geometry_elements) of section-less
  /// lower-dimensional blocks; sorted and unique once resolved.
  std::vector<Index> geometry_members;
  /// Element sets: MASS/ROTARYI elements (into point_elements), which the Model's element
  /// arrays do not hold; sorted and unique once resolved.
  std::vector<Index> point_members;
  std::vector<SetItem> items;
  int state = 0;  ///< 0 unresolved, 1 being resolved, 2 done
};
struct PendingSection {
  std::string element_set, material, controls;
};
struct PendingSurfaceItem {
  DeckReference target;
  int face = -1;       ///< 0..5 (S1..S6), SHELL_FACE_NEG/POS if `shell`, -1 for a node surface
  bool shell = false;  ///< SPOS/SNEG: only shell elements fit
  /// No face label: both sides of shells, the exposed faces of solids (as Abaqus).
  bool all_faces = false;
  std::string label;  ///< the face word, upper case, for messages
  /// Node surface: the area (weight) of the data line's nodes, m²; NaN when not given.
  Real node_area = std::numeric_limits<Real>::quiet_NaN();
};
struct PendingBoundary {
  Index step = NO_INDEX;  ///< NO_INDEX: model level, goes to the first step
  DeckReference target;
  BoundaryCondition condition;
  std::string amplitude;
};
struct PendingLoad {
  Index step = NO_INDEX;
  DeckReference target;
  ConcentratedLoad load;
  std::string amplitude;
};
/// A `*DLOAD` (element or element set, `P` or `P1`..`P6`) or `*DSLOAD` (surface, `P`) line.
struct PendingPressure {
  Index step = NO_INDEX;
  DeckReference target;  ///< element/element set, or the surface name (`on_surface`)
  bool on_surface = false;
  int solid_face = -1;    ///< *DLOAD P1..P6: 0..5; -1 for P (shells, face SPOS)
  std::string load_type;  ///< upper case, for messages
  PressureLoad load;
  std::string amplitude;
};
/// A `*DLOAD` GRAV line.
struct PendingGravity {
  Index step = NO_INDEX;
  std::string element_set;  ///< upper case; empty: the whole model
  GravityLoad load;
  std::string amplitude;
};
/// `*INITIAL CONDITIONS, TYPE=VELOCITY` (dof 1–6, value) or `TYPE=ROTATING VELOCITY`
/// (rotating: ω about the axis from a to b).
struct PendingVelocity {
  DeckReference target;
  int dof = 1;
  Real value = 0.0;
  bool rotating = false;
  Real omega = 0.0;
  std::array<Real, 3> a{}, b{};
};
struct PendingOutputSet {
  Index step = NO_INDEX, output = NO_INDEX;
  bool node = true;
  DeckReference set;
};
/// `*CONTACT PAIR` data line; names upper case.
struct PendingContactPair {
  Index step = NO_INDEX;  ///< NO_INDEX: model level
  std::string slave, master, interaction;
  SourceLocation where;
};
/// `*RIGID BODY`; set names upper case, empty when not given.
struct PendingRigidBody {
  DeckReference reference_node;
  std::string element_set, pin_node_set, tie_node_set;
};
/// `*TIE` data line (parallel to Model::ties); names upper case.
struct PendingTie {
  std::string slave, master;
  SourceLocation where;
};
/// `*DISTRIBUTION, LOCATION=NODE` (parallel to Model::distributions): its data lines.
struct PendingDistribution {
  std::optional<Real> default_value;                   ///< first line with a blank node field
  std::vector<std::pair<DeckReference, Real>> values;  ///< node or node set, value
  std::string table;                                   ///< TABLE=, upper case; empty if none
};
/// `*DISTRIBUTION TABLE, NAME=`: only a single scalar column is accepted.
struct DistributionTable {
  std::string name;  ///< upper case
  SourceLocation where;
};
/// A `*CONTACT CLEARANCE ASSIGNMENT` line: surfaces resolved while reading, the clearance
/// (which may be defined later) and the checks that need the whole deck in finish().
struct PendingClearanceAssignment {
  Index step = NO_INDEX;
  std::string clearance;        ///< upper case
  bool initialization = false;  ///< `*CONTACT INITIALIZATION ASSIGNMENT` (SPEC C14)
  ClearanceAssignment assignment;
};
/// CalculiX's `*CLEARANCE, MASTER=, SLAVE=, VALUE=` (names upper case).
struct PendingPairClearance {
  std::string master, slave;
  Real value = 0.0;
  SourceLocation where;
};
/// A `*ELEMENT, TYPE=MASS|ROTARYI` element: the solver has no point elements, so it stays
/// out of the Model's element arrays; `*MASS`/`*ROTARY INERTIA` make it a PointInertia.
struct PointElement {
  ExternalId id = 0;
  ExternalId node_id = 0;
  Index node = NO_INDEX;      ///< resolved in finish()
  bool rotary = false;        ///< ROTARYI, else MASS
  Index property = NO_INDEX;  ///< into point_properties: the *MASS/*ROTARY INERTIA covering it
  SourceLocation where;
};
/// An element of a lower-dimensional block that a mesher writes for every physical surface or
/// curve (gmsh: CPS4, CPS3 faces; T3D2, T3D3 edges): without a section it is geometry, not
/// part of the analysis; its nodes form node sets and its faces can define *SURFACEs
/// (deck_mesh_export.cpp). A CPS4 under a *SHELL SECTION runs as S4R (`promoted`).
struct GeometryElement {
  ExternalId id = 0;                     ///< key (DeckState::id_key)
  std::array<ExternalId, 4> node_ids{};  ///< keys
  int n_nodes = 0;
  Index block = NO_INDEX;  ///< into DeckState::geometry_blocks
  bool promoted = false;   ///< made an S4R element of the Model
};
/// A `*ELEMENT` block of geometry elements.
struct GeometryBlock {
  std::string type;         ///< CPS4, CPS3, T3D2 or T3D3
  std::string element_set;  ///< ELSET=, scoped; empty if none
  SourceLocation where;
  Index count = 0, promoted = 0;
  /// A section over the block's elements that they cannot take: reported once.
  bool section_reported = false;
};

/// `*MASS` (mass in values[0]) or `*ROTARY INERTIA` (I11 I22 I33 I12 I13 I23).
struct PointProperty {
  std::string element_set;
  bool rotary = false;
  Real values[6] = {0, 0, 0, 0, 0, 0};
  SourceLocation where;
};

/// `*PART, NAME=` … `*END PART`: its part-level blocks (KeywordPlace::Part), read once for each
/// `*INSTANCE` of the part, in the instance's scope.
struct PartDefinition {
  std::string name;  ///< upper case
  SourceLocation where;
  std::vector<const DeckBlock*> blocks;  ///< into the deck's blocks, which outlive read_blocks
  int instances = 0;
};

/// `*INSTANCE, NAME=, PART=` with its placement: translation t, then a rotation by `angle`
/// (degrees, right-handed) about the axis from a to b, as Abaqus applies them:
/// x' = a + R (x + t − a).
struct DeckInstance {
  std::string name, part;  ///< upper case
  SourceLocation where;
  std::array<Real, 3> translation{};
  bool rotated = false;
  std::array<Real, 3> axis_a{}, axis_b{};
  Real angle = 0.0;                ///< degrees
  std::array<Real, 9> rotation{};  ///< R, row major (when `rotated`)
};

/// The `*PLASTIC` and `*RATE DEPENDENT` lines of one material, valid or not (line 0: none):
/// a bad `*PLASTIC` leaves Material::plastic empty but still counts as given, so that it draws
/// no "no *PLASTIC" or "given twice" follow-up error.
struct PlasticLines {
  SourceLocation plastic, rate_dependent;
};

/// What the keyword handlers share while a deck is read; every problem goes into `errors`.
struct DeckState {
  /// `file_name`: the deck as named in messages; its stem becomes the job name.
  DeckState(InputErrors& errors, std::string file_name);

  InputErrors& errors;
  std::string file_name;
  Model model;
  std::vector<Real> coordinates;             ///< x y z per node, copied into the Model at the end
  std::vector<ExternalId> element_node_ids;  ///< parallel to Model::element_nodes
  std::unordered_map<ExternalId, Index> node_index;
  /// Nodes whose coordinates had a bad number (already reported): their elements are not
  /// checked for inversion, which would only repeat the same mistake as a second error.
  std::vector<Index> bad_coordinate_nodes;
  std::unordered_map<ExternalId, Index> element_index;
  std::unordered_map<std::string, Index> node_set_by_name, element_set_by_name;
  std::vector<PendingSet> node_sets, element_sets;  ///< parallel to the Model's sets
  std::vector<PendingSection> sections;             ///< parallel to Model::solid_sections
  std::vector<PendingSection> shell_sections;       ///< parallel to Model::shell_sections
  /// Per material (index into Model::materials; grown on demand by *PLASTIC).
  std::vector<PlasticLines> plastic_lines;
  /// ELSET= of refused section keywords (*SHELL GENERAL SECTION): their elements are not
  /// reported again as having no section.
  std::vector<std::string> refused_section_sets;
  /// Elements whose section problem is reported already (refused section, section of the
  /// wrong kind): no "has no section" follow-up. Empty while there are none.
  std::vector<char> section_reported;
  /// Element ids and ELSET= names (upper case) of refused *ELEMENT blocks (a type xpl does not
  /// read): references to them draw no "undefined" follow-up error (one error per cause).
  std::unordered_set<ExternalId> refused_element_ids;
  std::vector<std::string> refused_element_sets;
  /// Whether element id `id` / element set `name` (upper case) belongs to a refused block.
  bool refused_element(ExternalId id) const { return refused_element_ids.count(id) > 0; }
  bool refused_element_set(const std::string& name) const {
    for (const std::string& refused : refused_element_sets)
      if (refused == name) return true;
    return false;
  }
  std::vector<std::vector<PendingSurfaceItem>> surface_items;  ///< parallel to surfaces
  std::vector<PendingBoundary> boundaries;
  std::vector<PendingLoad> loads;
  std::vector<PendingPressure> pressures;
  std::vector<PendingVelocity> velocities;
  std::vector<PendingOutputSet> output_sets;
  std::vector<PendingGravity> gravity;
  std::vector<PendingContactPair> contact_pairs;
  std::vector<PendingRigidBody> rigid_bodies;  ///< parallel to Model::rigid_bodies
  std::vector<PendingTie> ties;                ///< parallel to Model::ties
  std::vector<PointElement> point_elements;
  std::unordered_map<ExternalId, Index> point_element_index;  ///< into point_elements
  std::vector<GeometryElement> geometry_elements;
  std::unordered_map<ExternalId, Index> geometry_index;  ///< key -> into geometry_elements
  std::vector<GeometryBlock> geometry_blocks;
  /// Types refused with a hint (C3D8RH, CAX4P, ...): reported at their first block only.
  std::vector<std::string> refused_types;
  std::vector<PointProperty> point_properties;
  std::vector<PendingDistribution> distributions;  ///< parallel to Model::distributions
  std::vector<DistributionTable> distribution_tables;
  /// CLEARANCE=name of each clearance (parallel to Model::contact_clearances), upper case;
  /// empty for a value.
  std::vector<std::string> clearance_distributions;
  std::vector<PendingClearanceAssignment> clearance_assignments;
  std::vector<PendingPairClearance> pair_clearances;
  /// check_clearance_surface verdict per surface: 0 not checked, 1 fit, 2 reported.
  std::vector<std::uint8_t> clearance_surface_state;

  // --- position in the deck ------------------------------------------------------------------
  Index material = NO_INDEX;  ///< the *MATERIAL that *DENSITY/*ELASTIC/*PLASTIC attach to
  /// A *PLASTIC outside a material (reported) opened the block: its *RATE DEPENDENT is not
  /// reported again for the same missing *MATERIAL.
  bool plastic_without_material = false;
  Index interaction = NO_INDEX;  ///< the *SURFACE INTERACTION that *FRICTION & co. attach to
  bool has_friction = false, has_behavior = false;  ///< given for interaction already
  bool in_step = false;
  bool step_has_dynamic = false;
  Index output = NO_INDEX;  ///< the latest *OUTPUT of the open step
  SourceLocation step_where;
  int error_counts[ERROR_CATEGORIES] = {};

  // --- parts and assemblies (deck_assembly.cpp) ------------------------------------------------
  std::vector<PartDefinition> parts;
  std::vector<DeckInstance> instances;
  /// A *PART, *ASSEMBLY or *INSTANCE was read: ids must stay below MAX_SCOPED_ID and every node
  /// and element records its scope (node_scopes, element_scopes).
  bool assembly_model = false;
  std::vector<Index> node_scopes, element_scopes;  ///< parallel to the Model's nodes, elements
  Index open_part = NO_INDEX;                      ///< the *PART whose blocks are being collected
  bool in_assembly = false;                        ///< between *ASSEMBLY and *END ASSEMBLY
  bool in_instance = false;                        ///< between *INSTANCE and *END INSTANCE
  SourceLocation assembly_where, instance_where;
  /// Scope of what is read: 0 model or assembly level, k: instances[k-1] (its part's blocks
  /// and the blocks of its *INSTANCE … *END INSTANCE).
  Index scope = 0;

  /// Key of id `id` of scope `in_scope` in node_index, element_index & co.
  static ExternalId id_key(Index in_scope, ExternalId id) {
    return in_scope == 0 ? id : (static_cast<ExternalId>(in_scope) << SCOPE_SHIFT) + id;
  }
  /// The id as written of a key (the key itself in a deck without instances).
  ExternalId local_id(ExternalId key) const {
    return instances.empty() ? key : key & MAX_SCOPED_ID;
  }
  /// "5", or "5 of instance PART-1-2" for a key in an instance's range: ids in messages.
  std::string id_text(ExternalId key) const;
  /// A set or surface name as defined in scope `in_scope`: "INSTANCE.NAME" in an instance.
  std::string scoped_name(Index in_scope, const std::string& name) const {
    return in_scope == 0 || name.empty() ? name : instances[in_scope - 1].name + "." + name;
  }
  /// The same in the scope being read.
  std::string scoped_name(const std::string& name) const { return scoped_name(scope, name); }
};

}  // namespace xpl::io
