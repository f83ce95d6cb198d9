#pragma once
/// \file Initial overclosures of a contact step (SPEC C2–C6): what happens to slave nodes that
/// penetrate a master face before the first increment. Runs once, when a step's contact
/// engine is built, on the engine's own search, so that "penetrating" means exactly what the
/// force loop will see.
///
/// First step of an analysis (`adjust`, C2–C4):
/// 1. Classify every penetrating slave node on the mesh as read. It is
///    - *ignored* when it lies deeper than `depth_fraction` (≈15 %) of the size of the facets
///      around it below a solid master face: the pass only corrects mesh-generation
///      mismatches. (Below a shell face any node within the thickness counts, C4; deeper ones
///      are not admissible to that side at all, see contact_engine.hpp.) An ignored node gets
///      no offset: the penalty pushes it out;
///    - *pinched* when it penetrates two admissible faces that look at each other (normals
///      more than 120° apart): leaving one means entering the other;
///    - *held* when it cannot move along the contact normal: a translational DOF with a
///      boundary condition has a component along it, or the node is tied to a rigid body;
///    - otherwise free.
/// 2. Adjust, by passes (the shared loop of adjustment_pass.hpp): every free node that penetrates
/// its nearest face moves along the
///    contact normal by w·d, d the penetration, w = ½ when a corner of that face moves in the
///    same pass (the other view of a balanced pair corrects the other half) and 1 otherwise.
///    The search is repeated on the moved geometry until no free node penetrates by more than
///    OVERCLOSURE_TOLERANCE × its facet size. Only positions move, and the solver keeps the
///    velocities: the elements compute strain from the motion during increments, so the move is
///    strain free, and the displacement output of frame 0 is the adjustment.
/// 3. Safety: an element one of whose corner volumes (hex) or areas (shell) would drop below
///    half its value as read is not distorted: its moved nodes become held (reason
///    Distortion) and the passes restart from the mesh as read.
/// 4. Offsets (C3): every slave node that still penetrates its nearest face stores the
///    penetration as the temporary offset d0 of its constraint, with the reason it could not
///    move; the force k·max(0, d − d0) is zero for it at t = 0.
///
/// Later steps and imports (`adjust == false`, C6): nothing moves; every penetration becomes
/// a temporary offset with the caller's reason.
///
/// Crossed surfaces (C5, `detect_crossed`): after the adjustment, every facet edge between two
/// slave nodes is tested against the master faces its nodes may touch; the edge is reported
/// when it passes through a face (its segment meets the face's mid-surface) with its two nodes
/// on opposite sides, unless the penetrating node is one the pass has handled (within the
/// depth limit of a solid face). A shell face is tested at its mid-surface, so two nodes
/// trapped on the two sides of a shell are found however far apart. Corners (the seed's
/// caveat: at a corner of a master surface, one face's two sides are not the surface's two
/// sides): an edge that meets a face within `depth_fraction` of the facet size of a corner
/// edge of the master surface (a rim, or a fold of more than 60°, CROSSED_FOLD_COSINE) only
/// grazes it and is not reported. After an adjustment the edges leaving the other body's
/// footprint meet its side faces there (on the rim with matching meshes, within ~1 % of the
/// facet otherwise); an edge through a face's interior, or through an edge between two faces
/// that continue the surface, is still reported. A dedicated broad phase with the longest
/// slave edge as margin finds every face an edge can meet; its cost is timed. Point nodes
/// (node-based surfaces, SPEC C13) have no facet edges and are not tested; for them the facet
/// size of steps 1–2 (tolerance, 15 % limit) is that of the master face they touch.

#include <cstdint>
#include <span>
#include <vector>

#include "contact/adjustment_pass.hpp"
#include "contact/contact_engine.hpp"

namespace xpl::contact {

/// Settings of the pass.
struct OverclosureSettings {
  bool adjust = true;  ///< false: offsets only (later step, import)
  OffsetReason offset_reason = OffsetReason::LaterStep;  ///< for offsets when !adjust
  bool detect_crossed = true;                            ///< crossed-surface check (C5)
  /// Deepest penetration below a solid face that is adjusted, as a fraction of the facet size
  /// around the slave node (mean square root of the face areas).
  Real depth_fraction = IGNORED_DEPTH_FRACTION;
  int max_passes = MAX_ADJUSTMENT_PASSES;  ///< Jacobi passes per round
  /// Per slave slot: 1 for a node the pass leaves alone (it has a contact clearance); empty:
  /// none.
  std::span<const char> exclude;
};

/// A slave node moved onto the surface.
struct AdjustedNode {
  Index node = NO_INDEX;
  Index face = NO_INDEX;                                      ///< master face it penetrated first
  Index slave_surface = NO_INDEX, master_surface = NO_INDEX;  ///< domain surfaces
  Real penetration = 0.0;                                     ///< as read, m
  Real distance = 0.0;                                        ///< length of the move, m
  Vec3 direction = Vec3::Zero();                              ///< unit direction of the move
};

/// A penetration stored as an offset d0.
struct OffsetNode {
  Index node = NO_INDEX;
  Index face = NO_INDEX;
  Index slave_surface = NO_INDEX, master_surface = NO_INDEX;
  Real offset = 0.0;  ///< d0, m
  OffsetReason reason = OffsetReason::Conflict;
};

/// A penetration too deep for the automatic pass.
struct IgnoredNode {
  Index node = NO_INDEX;
  Index face = NO_INDEX;
  Index slave_surface = NO_INDEX, master_surface = NO_INDEX;
  Real depth = 0.0;  ///< m
  Real limit = 0.0;  ///< the depth limit at this node, m
};

/// A slave facet edge whose nodes lie on opposite sides of a master face.
struct CrossedEdge {
  Index node_a = NO_INDEX, node_b = NO_INDEX;
  Index face = NO_INDEX;
};

/// Everything the pass did, for the reports (C11).
struct OverclosureReport {
  std::vector<AdjustedNode> adjusted;
  std::vector<OffsetNode> offsets;
  std::vector<IgnoredNode> ignored;
  std::vector<CrossedEdge> crossed;
  Real max_overclosure = 0.0;  ///< deepest penetration as read (every category), m
  int passes = 0;              ///< adjustment passes of the last round
  /// Elements whose distortion was refused (their nodes hold offsets instead).
  std::vector<Index> refused_elements;
  /// Smallest scaled corner Jacobian (hex) or corner area ratio (shell) of the elements with
  /// moved nodes, before and after the adjustment (1 for a perfect element; 1 when none).
  Real quality_before = 1.0, quality_after = 1.0;
  double crossed_seconds = 0.0;  ///< wall time of the crossed-surface check
  double seconds = 0.0;          ///< wall time of the whole pass
};

/// Runs the pass on `position` (n_nodes × 3, m; moved in place when adjusting) for the
/// domain of `engine`, whose constraints receive the offsets. `topology`: the elements (for
/// the distortion check); `node_thickness`: shell node thickness (or empty); `node_lock`:
/// per node LOCK_* bits (n_nodes, or empty: nothing is held).
OverclosureReport resolve_initial_overclosures(ContactEngine& engine,
                                               const ElementTopology& topology,
                                               NodalVectors& position,
                                               std::span<const Real> node_thickness,
                                               std::span<const std::uint8_t> node_lock,
                                               const OverclosureSettings& settings);

/// Facet size around each slave slot of `engine` on `position`: the mean square root of the
/// areas of the faces around the node, m; 0 for a point node (ContactDomain::slave_point).
std::vector<Real> slave_facet_sizes(const ContactEngine& engine, const NodalVectors& position);

/// Carries offsets from the engine of an earlier step to a rebuilt one (a contact domain
/// changed after step 1, C6): a slave node of both keeps its offset; new slave nodes start
/// with none.
void carry_offsets(const ContactEngine& from, ContactEngine& to);

}  // namespace xpl::contact
