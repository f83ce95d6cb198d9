#pragma once
/// \file The contact definitions of a Model (model.hpp) as the deck gives them: surface
/// interactions, general contact and contact pairs, clearances and initialization data,
/// nodal distributions and the *DIAGNOSTICS of the initial-overclosure pass.

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "common/error.hpp"
#include "common/types.hpp"

namespace xpl {

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

}  // namespace xpl
