#pragma once
/// \file The analysis model as read from a deck: mesh, sets, materials, sections, steps.
/// Its parts are declared by subject: mesh.hpp (element types, faces, sets, surfaces,
/// instances), materials.hpp (materials, sections), contact_definitions.hpp (interactions,
/// contact, clearances), step.hpp (steps with their loads and output requests); this file
/// holds the constraints and point inertias and the Model that owns them all.
///
/// Everything inside xpl works on contiguous internal indices. Deck ids (arbitrary, sparse)
/// are mapped once by `io` and kept here only to be written back to results and messages.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "common/types.hpp"
#include "common/units.hpp"
#include "solver/model/contact_definitions.hpp"
#include "solver/model/materials.hpp"
#include "solver/model/mesh.hpp"
#include "solver/model/step.hpp"

namespace xpl {

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
/// closest point there (solver/motion/ties.hpp).
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
