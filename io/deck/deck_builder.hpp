#pragma once
/// \file Semantic layer of the deck reader: turns keyword blocks into a Model. References
/// (node and element ids, set, material, amplitude and controls names) are recorded while
/// reading and resolved once the whole deck is known, so definition order does not matter
/// within the model data.

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include "io/deck/deck_lines.hpp"
#include "solver/model.hpp"

namespace xpl::io {

/// One accepted parameter of a keyword: `NAME=value` or a flag.
struct ParameterSpec {
  std::string_view name;
  bool takes_value = true;
  bool value_optional = false;  ///< both `NAME` and `NAME=value` are fine (NLGEOM)
};

/// A node or element given by id (numeric) or by set name, still to be resolved.
struct DeckReference {
  std::string token;  ///< id as written, or upper-case set name
  SourceLocation where;
  std::string keyword;  ///< "*BOUNDARY", for messages
};

/// `file:LINE`, as messages name a place in the deck.
std::string location_text(const SourceLocation& where);

/// A real number as messages show it (6 significant digits, e.g. 2.1e+11).
std::string number_text(Real value);

/// Builds a Model from keyword blocks; every problem goes into one InputErrors.
class DeckBuilder {
 public:
  /// `file_name`: the deck as named in messages; its stem becomes the job name.
  DeckBuilder(InputErrors& errors, std::string file_name);
  /// Reads the blocks in deck order.
  void read(const std::vector<DeckBlock>& blocks);
  /// Resolves references and checks the whole model; returns it (valid only if no errors).
  Model finish();

 private:
  // --- one set item, resolved in finish() -------------------------------------------------
  struct SetItem {
    enum class Kind { Id, Range, SetName, NodesOfElementSet };
    Kind kind = Kind::Id;
    long long first = 0, last = 0, increment = 1;  ///< Kind::Id (first), Kind::Range
    std::string name;                              ///< Kind::SetName, Kind::NodesOfElementSet
    SourceLocation where;
    std::string keyword;
  };
  struct PendingSet {
    std::vector<Index> members;  ///< members known while reading (*NODE, NSET= / *ELEMENT, ELSET=)
    /// Element sets: MASS/ROTARYI elements (into m_point_elements), which the Model's element
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
  struct PendingVelocity {
    DeckReference target;
    int dof = 1;
    Real value = 0.0;
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
    std::string clearance;  ///< upper case
    ClearanceAssignment assignment;
  };
  /// A `*ELEMENT, TYPE=MASS|ROTARYI` element: the solver has no point elements, so it stays
  /// out of the Model's element arrays; `*MASS`/`*ROTARY INERTIA` make it a PointInertia.
  struct PointElement {
    ExternalId id = 0;
    ExternalId node_id = 0;
    Index node = NO_INDEX;      ///< resolved in finish()
    bool rotary = false;        ///< ROTARYI, else MASS
    Index property = NO_INDEX;  ///< into m_point_properties: the *MASS/*ROTARY INERTIA covering it
    SourceLocation where;
  };
  /// `*MASS` (mass in values[0]) or `*ROTARY INERTIA` (I11 I22 I33 I12 I13 I23).
  struct PointProperty {
    std::string element_set;
    bool rotary = false;
    Real values[6] = {0, 0, 0, 0, 0, 0};
    SourceLocation where;
  };

  // --- keyword handlers (deck_mesh.cpp, deck_properties.cpp, deck_step.cpp, deck_output.cpp)
  void read_block(const DeckBlock& block);
  void read_heading(const DeckBlock& block);
  void read_node(const DeckBlock& block);
  void read_element(const DeckBlock& block);
  void read_set(const DeckBlock& block, bool node_set);
  void read_surface(const DeckBlock& block);
  /// `*ELEMENT, TYPE=MASS|ROTARYI` (deck_point_mass.cpp).
  void read_point_elements(const DeckBlock& block, bool rotary);
  /// `*MASS` or (`rotary`) `*ROTARY INERTIA` (deck_point_mass.cpp).
  void read_point_property(const DeckBlock& block, bool rotary);
  void read_rigid_body(const DeckBlock& block);  ///< deck_rigid.cpp
  void read_material(const DeckBlock& block);
  void read_density(const DeckBlock& block);
  void read_elastic(const DeckBlock& block);
  void read_solid_section(const DeckBlock& block);
  void read_shell_section(const DeckBlock& block);
  void read_shell_general_section(const DeckBlock& block);
  void read_section_controls(const DeckBlock& block);
  void read_amplitude(const DeckBlock& block);
  void read_initial_conditions(const DeckBlock& block);
  void read_step(const DeckBlock& block);
  void read_end_step(const DeckBlock& block);
  void read_dynamic(const DeckBlock& block);
  void read_bulk_viscosity(const DeckBlock& block);
  void read_boundary(const DeckBlock& block);
  void read_cload(const DeckBlock& block);
  void read_dload(const DeckBlock& block);
  void read_dsload(const DeckBlock& block);
  void read_gravity(const DeckDataLine& line, const DeckKeyword& keyword,
                    const std::string& amplitude);
  // --- contact (deck_interaction.cpp, deck_contact.cpp) ---------------------------------------
  void read_surface_interaction(const DeckBlock& block);
  void read_friction(const DeckBlock& block);
  void read_surface_behavior(const DeckBlock& block);
  void read_contact(const DeckBlock& block);
  void read_diagnostics(const DeckBlock& block);
  /// *CONTACT INCLUSIONS (`inclusions`) or *CONTACT EXCLUSIONS.
  void read_contact_inclusions(const DeckBlock& block, bool inclusions);
  void read_contact_property_assignment(const DeckBlock& block);
  void read_contact_controls_assignment(const DeckBlock& block);
  void read_contact_pair(const DeckBlock& block);
  // --- clearances (deck_clearance.cpp, deck_clearance_checks.cpp, deck_distribution.cpp) ------
  void read_contact_clearance(const DeckBlock& block);
  void read_clearance_assignment(const DeckBlock& block);
  void read_distribution(const DeckBlock& block);
  void read_distribution_table(const DeckBlock& block);
  /// The general contact of the open step; nullptr (reported) if the step has no *CONTACT.
  GeneralContact* open_contact(const DeckKeyword& keyword);
  /// Surfaces 1 and 2 of a contact data line (blank: all exterior; surface 2 blank: self
  /// contact of surface 1); nothing (reported) if a surface is undefined.
  std::optional<SurfacePair> surface_pair(const DeckDataLine& line, const DeckKeyword& keyword);
  /// A surface by name, or NO_INDEX (reported).
  Index contact_surface(const std::string& name, const SourceLocation& where,
                        const std::string& keyword);
  Index surface_interaction(const std::string& name, const SourceLocation& where,
                            const std::string& keyword);
  /// OP= of *CLOAD, *DLOAD, *DSLOAD: false (reported) if bad; sets `reset` for OP=NEW.
  bool read_load_op(const DeckKeyword& keyword, bool& reset);
  void read_output(const DeckBlock& block);
  void read_node_output(const DeckBlock& block);
  void read_element_output(const DeckBlock& block);
  void read_energy_output(const DeckBlock& block);
  void read_contact_output(const DeckBlock& block);
  // --- CalculiX output keywords (deck_calculix_output.cpp) -----------------------------------
  /// *NODE FILE (`node`) or *EL FILE: a field output request.
  void read_file_output(const DeckBlock& block, bool node);
  void read_node_print(const DeckBlock& block);
  /// *EL PRINT, *CONTACT FILE, *CONTACT PRINT: accepted with a note, nothing written.
  void read_ignored_output(const DeckBlock& block, const std::string& why);
  /// Names on the data lines of `block`, normalized, without repeats; names not in `known`
  /// are reported as "unknown <what> NAME".
  std::vector<std::string> read_names(const DeckBlock& block,
                                      std::span<const std::string_view> known,
                                      const std::string& what);

  // --- helpers (deck_builder.cpp) ------------------------------------------------------------
  void error(const SourceLocation& where, const DeckKeyword& keyword, const std::string& problem,
             const std::string& expected);
  /// Reports unknown, repeated or malformed parameters; false if any.
  bool check_parameters(const DeckKeyword& keyword, std::initializer_list<ParameterSpec> accepted);
  static const DeckParameter* find_parameter(const DeckKeyword& keyword, std::string_view name);
  /// Value of a required parameter, upper case and blank-collapsed; reported if missing.
  std::optional<std::string> required_name(const DeckKeyword& keyword, std::string_view name);
  /// Value of an optional name parameter (upper case), empty if absent.
  std::string optional_name(const DeckKeyword& keyword, std::string_view name);
  void expect_no_data(const DeckBlock& block);
  /// Adds a note (not an error) for the .msg file: `file:LINE: *KEYWORD: text`.
  void note(const SourceLocation& where, const DeckKeyword& keyword, const std::string& text);
  /// Field i of a data line as a real; empty fields give `blank` if it has a value.
  std::optional<Real> real_field(const DeckDataLine& line, const DeckKeyword& keyword,
                                 std::size_t i, std::string_view what,
                                 std::optional<Real> blank = std::nullopt);
  std::optional<long long> integer_field(const DeckDataLine& line, const DeckKeyword& keyword,
                                         std::size_t i, std::string_view what);
  /// Reports a data line with more than `count` fields.
  bool check_field_count(const DeckDataLine& line, const DeckKeyword& keyword, std::size_t count,
                         const std::string& expected);
  DeckReference reference(const DeckDataLine& line, const DeckKeyword& keyword, std::size_t i);
  Index node_set_index(const std::string& name, const SourceLocation& where);
  Index element_set_index(const std::string& name, const SourceLocation& where);
  /// Adds an error unless `count` errors of this category were already reported, then a
  /// summary at the end: keeps the report readable for a mesh with a million bad elements.
  static constexpr int ERROR_CAP = 20;  ///< errors shown per capped category
  void capped_error(int& count, const SourceLocation& where, const std::string& keyword,
                    const std::string& problem, const std::string& expected);

  // --- resolution (deck_resolve.cpp) ---------------------------------------------------------
  void resolve_element_nodes();
  void resolve_sets(bool node_sets);
  void resolve_set(bool node_sets, Index set, int depth);
  std::vector<Index> resolve_nodes(const DeckReference& reference);
  std::vector<Index> resolve_elements(const DeckReference& reference);
  /// "S4R element 7" (with " of set NAME" if `reference` names a set), for messages.
  std::string element_text(Index e, const DeckReference& reference) const;
  Index resolve_amplitude(const std::string& name, const SourceLocation& where,
                          const std::string& keyword);
  void resolve_sections();
  /// Material and controls of a section (reported if undefined); returns its element set or
  /// NO_INDEX (reported).
  Index resolve_section_references(const PendingSection& pending, const std::string& keyword,
                                   const SourceLocation& where, Index& material, Index& controls,
                                   std::vector<bool>& material_checked);
  /// Gives section `section` (of the shell or solid kind) to the elements of `set`.
  void assign_section(Index set, Index section, bool shell, const SourceLocation& where);
  void resolve_surfaces();
  void resolve_initial_velocity();
  void resolve_steps();
  void resolve_pressures();
  void resolve_gravity();
  void resolve_contact_pairs();
  void resolve_rigid_bodies();
  void resolve_point_inertias();
  void resolve_distributions();
  /// Distribution names of the clearances, then the assignments: clearance names, surfaces,
  /// signs of the values and the step rules (SPEC C7–C10).
  void resolve_clearances();
  /// Whether assignment `pending` may act in its step (SPEC C7): reported if not.
  bool check_clearance_step(const PendingClearanceAssignment& pending);
  /// Whether a negative value of the assignment's clearance meets a solid surface (SPEC C8):
  /// reported if so.
  bool check_clearance_sign(const PendingClearanceAssignment& pending);
  /// Whether the assignment has slave nodes off rigid bodies: reported if not.
  bool check_clearance_slaves(const PendingClearanceAssignment& pending);
  /// Whether surface `surface` suits a clearance (SPEC C10): element based, single sided, each
  /// edge on at most two faces, consistent normals. Reported (once per surface) if not.
  bool check_clearance_surface(Index surface, const SourceLocation& where);
  /// Faces of the C3D8R elements of `elements` (unique) that no other C3D8R element shares,
  /// ordered by element and face.
  std::vector<ElementFace> exposed_hex_faces(const std::vector<Index>& elements);
  void check_element_geometry();
  void check_hex_geometry(Index element);
  void check_shell_geometry(Index element);

  InputErrors& m_errors;
  std::string m_file_name;
  Model m_model;
  std::vector<Real> m_coordinates;             ///< x y z per node, copied into the Model at the end
  std::vector<ExternalId> m_element_node_ids;  ///< parallel to Model::element_nodes
  std::unordered_map<ExternalId, Index> m_node_index;
  /// Nodes whose coordinates had a bad number (already reported): their elements are not
  /// checked for inversion, which would only repeat the same mistake as a second error.
  std::vector<Index> m_bad_coordinate_nodes;
  std::unordered_map<ExternalId, Index> m_element_index;
  std::unordered_map<std::string, Index> m_node_set_index, m_element_set_index;
  std::vector<PendingSet> m_node_sets, m_element_sets;  ///< parallel to the Model's sets
  std::vector<PendingSection> m_sections;               ///< parallel to Model::solid_sections
  std::vector<PendingSection> m_shell_sections;         ///< parallel to Model::shell_sections
  /// ELSET= of refused section keywords (*SHELL GENERAL SECTION): their elements are not
  /// reported again as having no section.
  std::vector<std::string> m_refused_section_sets;
  /// Elements whose section problem is reported already (refused section, section of the
  /// wrong kind): no "has no section" follow-up. Empty while there are none.
  std::vector<char> m_section_reported;
  std::vector<std::vector<PendingSurfaceItem>> m_surface_items;  ///< parallel to surfaces
  std::vector<PendingBoundary> m_boundaries;
  std::vector<PendingLoad> m_loads;
  std::vector<PendingPressure> m_pressures;
  std::vector<PendingVelocity> m_velocities;
  std::vector<PendingOutputSet> m_output_sets;
  std::vector<PendingGravity> m_gravity;
  std::vector<PendingContactPair> m_contact_pairs;
  std::vector<PendingRigidBody> m_rigid_bodies;  ///< parallel to Model::rigid_bodies
  std::vector<PointElement> m_point_elements;
  std::unordered_map<ExternalId, Index> m_point_element_index;  ///< into m_point_elements
  std::vector<PointProperty> m_point_properties;
  std::vector<PendingDistribution> m_distributions;  ///< parallel to Model::distributions
  std::vector<DistributionTable> m_distribution_tables;
  /// CLEARANCE=name of each clearance (parallel to Model::contact_clearances), upper case;
  /// empty for a value.
  std::vector<std::string> m_clearance_distributions;
  std::vector<PendingClearanceAssignment> m_clearance_assignments;
  /// check_clearance_surface verdict per surface: 0 not checked, 1 fit, 2 reported.
  std::vector<std::uint8_t> m_clearance_surface_state;

  // --- position in the deck ------------------------------------------------------------------
  Index m_material = NO_INDEX;     ///< the *MATERIAL that *DENSITY/*ELASTIC attach to
  Index m_interaction = NO_INDEX;  ///< the *SURFACE INTERACTION that *FRICTION & co. attach to
  bool m_has_friction = false, m_has_behavior = false;  ///< given for m_interaction already
  bool m_in_step = false;
  bool m_step_has_dynamic = false;
  Index m_output = NO_INDEX;  ///< the latest *OUTPUT of the open step
  SourceLocation m_step_where;
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
  int m_error_counts[ERROR_CATEGORIES] = {};
};

}  // namespace xpl::io
