#pragma once
/// \file Keyword handlers of the deck reader, free functions on the DeckState, grouped by
/// keyword family (one or a few .cpp files each). Each `read_KEYWORD` takes one keyword block;
/// the keyword table (deck_keywords.cpp) calls them. The `resolve_*` and `check_*` functions run
/// in finish(), once the whole deck is known.

#include <array>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "io/deck/deck_fields.hpp"
#include "io/deck/deck_state.hpp"

namespace xpl::io {

// --- Parts, assemblies and instances (deck_assembly.cpp)

/// `*PART, NAME=`: opens a part; its part-level blocks are kept until `*END PART`.
void read_part(DeckState& deck, const DeckBlock& block);
/// `*END PART`.
void read_end_part(DeckState& deck, const DeckBlock& block);
/// `*ASSEMBLY, NAME=`.
void read_assembly(DeckState& deck, const DeckBlock& block);
/// `*END ASSEMBLY`.
void read_end_assembly(DeckState& deck, const DeckBlock& block);
/// `*INSTANCE, NAME=, PART=` with its translation and rotation lines: reads the part's blocks
/// in the new instance's scope.
void read_instance(DeckState& deck, const DeckBlock& block);
/// `*END INSTANCE`.
void read_end_instance(DeckState& deck, const DeckBlock& block);
/// `*RESTART`: accepted with a note (xpl continues a run with `--import`).
void read_restart(DeckState& deck, const DeckBlock& block);
/// The instance whose scope holds `name` ("PART-1-1.5" or "PART-1-1.SET"): its scope (1-based)
/// and the rest of the name; scope 0 if `name` is not qualified by a known instance.
std::pair<Index, std::string> split_qualified(const DeckState& deck, const std::string& name);

// --- Mesh and sets (deck_mesh.cpp, deck_surfaces.cpp; resolution in deck_resolve.cpp and
// deck_references.cpp, element shapes in deck_geometry.cpp)

/// `*HEADING`: the data lines become the title.
void read_heading(DeckState& deck, const DeckBlock& block);
/// `*NODE`.
void read_node(DeckState& deck, const DeckBlock& block);
/// `*ELEMENT`.
void read_element(DeckState& deck, const DeckBlock& block);
/// `*NSET` (`node_set`) or `*ELSET`.
void read_set(DeckState& deck, const DeckBlock& block, bool node_set);
/// `*SURFACE`.
void read_surface(DeckState& deck, const DeckBlock& block);
/// Resolves references and checks the whole model; returns it (valid only if `deck.errors` is
/// empty).
Model finish(DeckState& deck);
/// Element node ids to node indices (reported if undefined).
void resolve_element_nodes(DeckState& deck);
/// Set items (ids, ranges, other sets) into members, node sets (`node_sets`) or element sets.
void resolve_sets(DeckState& deck, bool node_sets);
/// One set, its nested sets first (`depth` guards against cycles).
void resolve_set(DeckState& deck, bool node_sets, Index set, int depth);
/// The nodes a reference names (reported if undefined).
std::vector<Index> resolve_nodes(DeckState& deck, const DeckReference& reference);
/// The elements a reference names (reported if undefined).
std::vector<Index> resolve_elements(DeckState& deck, const DeckReference& reference);
/// "S4R element 7" (with " of set NAME" if `reference` names a set), for messages.
std::string element_text(const DeckState& deck, Index e, const DeckReference& reference);
/// An amplitude by name, NO_INDEX for none (reported if undefined).
Index resolve_amplitude(DeckState& deck, const std::string& name, const SourceLocation& where,
                        const std::string& keyword);
/// Resolves the recorded initial velocity (in finish()).
void resolve_initial_velocity(DeckState& deck);
/// Boundary conditions, loads and output sets into their steps.
void resolve_steps(DeckState& deck);
/// Resolves the recorded surfaces (in finish()).
void resolve_surfaces(DeckState& deck);
/// Faces of the C3D8R elements of `elements` (unique) that no other C3D8R element shares,
/// ordered by element and face.
std::vector<ElementFace> exposed_hex_faces(DeckState& deck, const std::vector<Index>& elements);
/// Inverted and degenerate elements (capped per category).
void check_element_geometry(DeckState& deck);
/// One C3D8R element: inverted or degenerate (reported).
void check_hex_geometry(DeckState& deck, Index element);
/// One S4R element: degenerate (reported).
void check_shell_geometry(DeckState& deck, Index element);

// --- Mesh exports (deck_mesh_export.cpp): section-less lower-dimensional blocks as geometry

/// Whether `type` is read as geometry without a section: CPS4, CPS3, T3D2, T3D3.
bool is_geometry_type(std::string_view type);
/// The supported element type nearest to an unsupported `type`, with why (for its error);
/// empty if none is known.
std::string nearest_supported_type(std::string_view type);
/// `*ELEMENT, TYPE=CPS4|CPS3|T3D2|T3D3`: kept as geometry elements.
void read_geometry_elements(DeckState& deck, const DeckBlock& block, const std::string& type);
/// At the start of finish(): CPS4 geometry under a *SHELL SECTION becomes S4R elements (in deck
/// order, after the elements read); other geometry under a section is reported.
void promote_shell_geometry(DeckState& deck);
/// Geometry element nodes that are not defined (reported, capped).
void resolve_geometry_node_ids(DeckState& deck);
/// After the element sets: each element set of geometry only becomes a node set of its nodes
/// (unless a node set of that name exists); the .msg notes say what was done.
void geometry_node_sets(DeckState& deck);
/// The geometry elements a reference names (an id or an element set), unpromoted only.
std::vector<Index> geometry_of(const DeckState& deck, const DeckReference& reference);
/// Every hex face and shell of the model by its sorted distinct corner nodes.
struct ModelFaceIndex {
  std::vector<std::pair<std::array<Index, 4>, ElementFace>> faces;  ///< sorted by key
};
/// Builds the index of the model's faces (after the element nodes are resolved).
ModelFaceIndex index_model_faces(const Model& model);
/// Adds to `surface` the solid faces (or both sides of the shells) that the geometry faces
/// `geometry` of surface line `item` lie on; reported if a face lies on none, inside the body,
/// is an edge, or the line has a face label.
void add_geometry_faces(DeckState& deck, const ModelFaceIndex& index,
                        const std::vector<Index>& geometry, const PendingSurfaceItem& item,
                        Surface& surface);

// --- Materials, sections, amplitudes and initial conditions (deck_properties.cpp,
// deck_sections.cpp)

/// `*MATERIAL`.
void read_material(DeckState& deck, const DeckBlock& block);
/// `*DENSITY`.
void read_density(DeckState& deck, const DeckBlock& block);
/// `*ELASTIC`.
void read_elastic(DeckState& deck, const DeckBlock& block);
/// `*PLASTIC` (deck_plastic.cpp): tabular or Johnson–Cook isotropic hardening.
void read_plastic(DeckState& deck, const DeckBlock& block);
/// `*RATE DEPENDENT` (deck_plastic.cpp): power-law or Johnson–Cook rate factor of the
/// material's `*PLASTIC`.
void read_rate_dependent(DeckState& deck, const DeckBlock& block);
/// Plastic materials without `*ELASTIC`, reported at their `*PLASTIC` line (in finish(),
/// before the sections, which then do not report the missing elastic data again).
void check_plastic_materials(DeckState& deck);
/// `*SECTION CONTROLS`.
void read_section_controls(DeckState& deck, const DeckBlock& block);
/// `*AMPLITUDE`.
void read_amplitude(DeckState& deck, const DeckBlock& block);
/// `*INITIAL CONDITIONS`.
void read_initial_conditions(DeckState& deck, const DeckBlock& block);
/// `*SOLID SECTION`.
void read_solid_section(DeckState& deck, const DeckBlock& block);
/// `*SHELL SECTION`.
void read_shell_section(DeckState& deck, const DeckBlock& block);
/// `*SHELL GENERAL SECTION`: refused with the reason (its elements get no second error).
void read_shell_general_section(DeckState& deck, const DeckBlock& block);
/// Resolves the recorded sections (in finish()).
void resolve_sections(DeckState& deck);
/// Material and controls of a section (reported if undefined); returns its element set or
/// NO_INDEX (reported).
Index resolve_section_references(DeckState& deck, const PendingSection& pending,
                                 const std::string& keyword, const SourceLocation& where,
                                 Index& material, Index& controls,
                                 std::vector<bool>& material_checked);
/// Gives section `section` (of the shell or solid kind) to the elements of `set`.
void assign_section(DeckState& deck, Index set, Index section, bool shell,
                    const SourceLocation& where);

// --- Steps, boundary conditions and loads (deck_step.cpp, deck_pressure.cpp)

/// `*STEP`.
void read_step(DeckState& deck, const DeckBlock& block);
/// `*END STEP`.
void read_end_step(DeckState& deck, const DeckBlock& block);
/// `*DYNAMIC`.
void read_dynamic(DeckState& deck, const DeckBlock& block);
/// `*BULK VISCOSITY`.
void read_bulk_viscosity(DeckState& deck, const DeckBlock& block);
/// *FIXED MASS SCALING (deck_mass_scaling.cpp).
void read_fixed_mass_scaling(DeckState& deck, const DeckBlock& block);
/// Refuses a *FIXED MASS SCALING whose ELSET= holds only rigid-body elements (after the sets
/// and rigid bodies are resolved).
void check_mass_scaling_sets(DeckState& deck);
/// `*BOUNDARY`.
void read_boundary(DeckState& deck, const DeckBlock& block);
/// OP= of *CLOAD, *DLOAD, *DSLOAD: false (reported) if bad; sets `reset` for OP=NEW.
bool read_load_op(DeckState& deck, const DeckKeyword& keyword, bool& reset);
/// `*CLOAD`.
void read_cload(DeckState& deck, const DeckBlock& block);
/// `*DLOAD` (pressures P, P1..P6 and GRAV).
void read_dload(DeckState& deck, const DeckBlock& block);
/// `*DSLOAD`.
void read_dsload(DeckState& deck, const DeckBlock& block);
/// One `*DLOAD` GRAV data line.
void read_gravity(DeckState& deck, const DeckDataLine& line, const DeckKeyword& keyword,
                  const std::string& amplitude);
/// Resolves the recorded pressures (in finish()).
void resolve_pressures(DeckState& deck);
/// Resolves the recorded gravity (in finish()).
void resolve_gravity(DeckState& deck);

// --- Output requests (deck_output.cpp)

/// `*OUTPUT, FIELD|HISTORY`: opens a request that `*NODE OUTPUT` & co. fill.
void read_output(DeckState& deck, const DeckBlock& block);
/// `*NODE OUTPUT`.
void read_node_output(DeckState& deck, const DeckBlock& block);
/// `*ELEMENT OUTPUT`.
void read_element_output(DeckState& deck, const DeckBlock& block);
/// `*ENERGY OUTPUT`.
void read_energy_output(DeckState& deck, const DeckBlock& block);
/// `*CONTACT OUTPUT`.
void read_contact_output(DeckState& deck, const DeckBlock& block);
/// Names on the data lines of `block`, normalized, without repeats; names not in `known`
/// are reported as "unknown <what> NAME".
std::vector<std::string> read_names(DeckState& deck, const DeckBlock& block,
                                    std::span<const std::string_view> known,
                                    const std::string& what);

// --- Contact, interactions and clearances (deck_interaction.cpp, deck_contact.cpp,
// deck_clearance.cpp, deck_clearance_checks.cpp, deck_distribution.cpp)

/// `*SURFACE INTERACTION`.
void read_surface_interaction(DeckState& deck, const DeckBlock& block);
/// `*FRICTION`.
void read_friction(DeckState& deck, const DeckBlock& block);
/// `*SURFACE BEHAVIOR`.
void read_surface_behavior(DeckState& deck, const DeckBlock& block);
/// `*CONTACT`: the general contact of the open step.
void read_contact(DeckState& deck, const DeckBlock& block);
/// `*DIAGNOSTICS`.
void read_diagnostics(DeckState& deck, const DeckBlock& block);
/// *CONTACT INCLUSIONS (`inclusions`) or *CONTACT EXCLUSIONS.
void read_contact_inclusions(DeckState& deck, const DeckBlock& block, bool inclusions);
/// `*CONTACT PROPERTY ASSIGNMENT`.
void read_contact_property_assignment(DeckState& deck, const DeckBlock& block);
/// `*CONTACT CONTROLS ASSIGNMENT`.
void read_contact_controls_assignment(DeckState& deck, const DeckBlock& block);
/// `*CONTACT PAIR`.
void read_contact_pair(DeckState& deck, const DeckBlock& block);
/// A surface by name, or NO_INDEX (reported).
Index contact_surface(DeckState& deck, const std::string& name, const SourceLocation& where,
                      const std::string& keyword);
/// A *SURFACE INTERACTION by name, or NO_INDEX (reported).
Index surface_interaction(DeckState& deck, const std::string& name, const SourceLocation& where,
                          const std::string& keyword);
/// Surfaces 1 and 2 of a contact data line (blank: all exterior; surface 2 blank: self
/// contact of surface 1); nothing (reported) if a surface is undefined.
std::optional<SurfacePair> surface_pair(DeckState& deck, const DeckDataLine& line,
                                        const DeckKeyword& keyword);
/// The general contact of the open step; nullptr (reported) if the step has no *CONTACT.
GeneralContact* open_contact(DeckState& deck, const DeckKeyword& keyword);
/// Resolves the recorded contact pairs (in finish()).
void resolve_contact_pairs(DeckState& deck);
/// `*CONTACT CLEARANCE`.
void read_contact_clearance(DeckState& deck, const DeckBlock& block);
/// `*CONTACT CLEARANCE ASSIGNMENT`.
void read_clearance_assignment(DeckState& deck, const DeckBlock& block);
/// `*CONTACT INITIALIZATION DATA` (SPEC C14, C15): the same definition as `*CONTACT CLEARANCE`.
void read_contact_initialization(DeckState& deck, const DeckBlock& block);
/// `*CONTACT INITIALIZATION ASSIGNMENT`: the same lines as `*CONTACT CLEARANCE ASSIGNMENT`.
void read_initialization_assignment(DeckState& deck, const DeckBlock& block);
/// `*DISTRIBUTION`.
void read_distribution(DeckState& deck, const DeckBlock& block);
/// `*DISTRIBUTION TABLE`.
void read_distribution_table(DeckState& deck, const DeckBlock& block);
/// Resolves the recorded distributions (in finish()).
void resolve_distributions(DeckState& deck);
/// Distribution names of the clearances, then the assignments: clearance names, surfaces,
/// signs of the values and the step rules (SPEC C7–C10).
void resolve_clearances(DeckState& deck);
/// Whether assignment `pending` may act in its step (SPEC C7): reported if not.
bool check_clearance_step(DeckState& deck, const PendingClearanceAssignment& pending);
/// Whether a negative value of the assignment's clearance meets a solid surface (SPEC C8):
/// reported if so.
bool check_clearance_sign(DeckState& deck, const PendingClearanceAssignment& pending);
/// Whether the assignment has slave nodes off rigid bodies: reported if not.
bool check_clearance_slaves(DeckState& deck, const PendingClearanceAssignment& pending);
/// Whether surface `surface` suits a clearance (SPEC C10): element based, single sided, each
/// edge on at most two faces, consistent normals. Reported (once per surface) if not.
/// `keyword`: the assignment keyword, for the message.
bool check_clearance_surface(DeckState& deck, Index surface, const SourceLocation& where,
                             const char* keyword);

// --- Rigid bodies and point masses (deck_rigid.cpp, deck_point_mass.cpp)

/// `*RIGID BODY`.
void read_rigid_body(DeckState& deck, const DeckBlock& block);
/// Resolves the recorded rigid bodies (in finish()).
void resolve_rigid_bodies(DeckState& deck);

// --- Ties (deck_tie.cpp)

/// `*TIE, NAME=, POSITION TOLERANCE=, ADJUST=`: one data line `slave, master`.
void read_tie(DeckState& deck, const DeckBlock& block);
/// Surfaces of the ties, and the node conflicts (slave of two ties, slave on another tie's
/// master, slave with a translational BC or in a rigid body): after rigid bodies and steps.
void resolve_ties(DeckState& deck);
/// `*ELEMENT, TYPE=MASS|ROTARYI`.
void read_point_elements(DeckState& deck, const DeckBlock& block, bool rotary);
/// `*MASS` or (`rotary`) `*ROTARY INERTIA`.
void read_point_property(DeckState& deck, const DeckBlock& block, bool rotary);
/// Resolves the recorded point inertias (in finish()).
void resolve_point_inertias(DeckState& deck);

// --- CalculiX output requests (deck_calculix_output.cpp)

/// *NODE FILE (`node`) or *EL FILE: a field output request.
void read_file_output(DeckState& deck, const DeckBlock& block, bool node);
/// `*NODE PRINT`.
void read_node_print(DeckState& deck, const DeckBlock& block);
/// *EL PRINT, *CONTACT FILE, *CONTACT PRINT: accepted with a note, nothing written.
void read_ignored_output(DeckState& deck, const DeckBlock& block, const std::string& why);

/// `*STATIC` (deck_calculix.cpp): refused, one error; counts as the step's procedure.
void read_static(DeckState& deck, const DeckBlock& block);
/// `*EQUATION`: refused, one error.
void read_equation(DeckState& deck, const DeckBlock& block);
/// CalculiX's `*CLEARANCE, MASTER=, SLAVE=, VALUE=` of a contact pair.
void read_clearance(DeckState& deck, const DeckBlock& block);
/// The *CLEARANCE lines as clearances with ADJUST=NO of the first step (in finish(), after the
/// contact pairs and the *CONTACT CLEARANCE assignments).
void resolve_pair_clearances(DeckState& deck);

/// *EL PRINT: accepted with a note (no element history output in xpl).
void read_el_print(DeckState& deck, const DeckBlock& block);
/// *CONTACT FILE or *CONTACT PRINT: accepted with a note naming xpl's contact output.
void read_contact_file(DeckState& deck, const DeckBlock& block);

}  // namespace xpl::io
