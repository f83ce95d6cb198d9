#pragma once
/// \file Contact clearances (SPEC C7–C10): the gap a user asks for between two surfaces of the
/// contact domain at the start of a step, made true by moving slave nodes (ADJUST=YES) or by
/// permanent contact offsets (ADJUST=NO). Runs once, when a step's contact engine is built
/// new, before the automatic initial-overclosure pass, which then leaves the nodes handled
/// here alone.
///
/// One *view* is a slave surface against a master surface (a balanced assignment gives two).
/// For every node of the slave surface that may act as a slave of the contact domain:
/// 1. Its *nearest master face* is the face of the master surface whose contact surface (the
///    solid face, or a shell's mid-surface) is closest, on the configuration as read. A node
///    whose closest point is on a perimeter edge or corner of the master surface is skipped
///    (reported): beside the surface, a clearance means nothing.
/// 2. Its height h above that face is measured along the face normal at the closest point
///    (the normal of the surface as defined: the outward normal of a solid face, the SPOS or
///    SNEG normal of a shell face). With T the half thicknesses that separate contact
///    surfaces (the master shell's, interpolated at the closest point, plus the slave shell
///    node's), the gap above the surface is g = h − T. The node is in the *search zone* when
///    −below ≤ g ≤ above (SEARCH BELOW / ABOVE; defaults: a tenth of the facet size at a solid
///    slave node, the thickness of a shell slave node). Nodes outside are not touched.
///    A point node (of a node-based surface on no face of the domain, SPEC C13) has no facet
///    of its own: its facet size, for the default zone and the tolerances, is that of its
///    nearest master face, as in the initial-overclosure pass (it is a point against that
///    face, and the face's size is the scale of the mesh it meets).
/// 3. Its clearance c is the view's value, or the node's value of the distribution, or, when
///    the distribution has none there, the value interpolated at the closest point from the
///    face's corners; a node with neither is skipped (reported).
/// 4. Target height (sign convention of double-sided elements): h* = σ(|c| + T), σ = +1 for
///    c ≥ 0 (above the surface, gap c), σ = −1 for c < 0 (below a shell, gap |c| to its other
///    side). A negative clearance on solid faces is rejected by the deck reader.
///
/// ADJUST=YES (first step only): Jacobi passes move every free node along the face normal by
/// w·(h* − h), on its nearest face of the configuration as read (recomputed at the moved
/// positions), w = ½ when a corner of that face is moving in the same pass (the other view of
/// a balanced assignment closes the other half), 1 otherwise, until every node is within
/// OVERCLOSURE_TOLERANCE × its facet size of its target. Nodes held by a boundary condition along
/// the normal or by a rigid body do not move; element distortion is refused as in the
/// initial-overclosure pass (the shared loop of adjustment_pass.hpp). What remains becomes a
/// permanent offset (below).
///
/// Offsets (ADJUST=NO, and what ADJUST=YES could not resolve): d0 = σ(h* − h), the clearance
/// violation along the side the node belongs to, kept for the whole analysis
/// (`ContactConstraint::offset_permanent`). The effective gap g + d0 then starts at |c|: the
/// force k·max(0, −g − d0) begins when the node has closed by |c|, whatever its geometric
/// gap. d0 < 0 (a geometric gap wider than the clearance) moves the contact surface out
/// towards the node; the engine's search margin is widened by the largest such |d0|. A node
/// with ADJUST=NO on the wrong side of a shell master (below the mid-surface for c ≥ 0) is
/// skipped (reported): an offset cannot carry it through the shell.
///
/// The offset belongs to the slave node (as every offset in xpl): it applies against any face
/// the node touches during the analysis, which is the master surface of its clearance unless
/// the node slides off it.
///
/// Interference fits (`*CONTACT INITIALIZATION DATA, INTERFERENCE FIT`, SPEC C15) use the same
/// records, nearest faces, zones and passes. Without a distance, the nodes of the zone that
/// overclose their nearest face (gap g < 0; nodes with a gap are left alone) do not move:
/// their overclosure d = −g becomes an offset that ContactEngine::set_interference ramps to
/// zero over the view's ramp time, so the penalty pushes the surfaces apart with a force that
/// grows from zero and the parts end stressed. With a distance h, the target gap is −h (h* =
/// σ(T − h), σ the side of the node, +1 on solids): ADJUST=YES moves the nodes there first
/// (strain free), then the overclosure reached is ramped away; where a node could not reach
/// it (held, or ADJUST=NO), h is ramped and the rest, d − h, stays a permanent offset. The
/// automatic pass leaves every recorded node alone: an interference fit is not adjusted away.

#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "contact/initial_overclosure.hpp"

namespace xpl::contact {

/// One slave surface against one master surface, with the clearance that applies.
struct ClearanceView {
  Index assignment = NO_INDEX;  ///< the caller's number of the assignment (reports)
  Index slave_surface = NO_INDEX, master_surface = NO_INDEX;  ///< the caller's surface ids
  std::vector<FaceRef> slave_faces;
  /// The nodes of a node-based slave surface (SPEC C13; with or instead of `slave_faces`).
  std::vector<Index> slave_nodes{};
  std::vector<FaceRef> master_faces;
  bool adjust = true;  ///< ADJUST=YES: move nodes; NO: permanent offsets
  Real value = 0.0;    ///< the clearance where `nodal_values` has no say, m
  /// Per node (n_nodes), NaN where the distribution gives no value; empty: `value` everywhere.
  std::span<const Real> nodal_values;
  /// Search zone, m; NaN: the default (see the file comment).
  Real search_above = std::numeric_limits<Real>::quiet_NaN();
  Real search_below = std::numeric_limits<Real>::quiet_NaN();
  /// Interference fit (SPEC C15, file comment): `value` and `nodal_values` are unused.
  bool interference = false;
  /// The interference distance h, m; NaN: the overclosures as read.
  Real interference_distance = std::numeric_limits<Real>::quiet_NaN();
  /// Step time over which the interference offsets ramp to zero, s (> 0).
  Real ramp_time = 0.0;
};

/// Why a node of a slave surface got no clearance.
enum class ClearanceSkip : std::uint8_t {
  NoValue,        ///< neither the node nor every corner of its master face has a value
  PerimeterEdge,  ///< its closest point is on a perimeter edge or corner of the master surface
  WrongSide,      ///< ADJUST=NO and the node is on the other side of a shell master
  NotInDomain,    ///< the contact domain does not let it touch the master surface
  Repeated,       ///< an earlier assignment already gave it a clearance
};

/// Name of a skip reason for reports.
const char* clearance_skip_name(ClearanceSkip why);

/// A slave node that received its clearance.
struct ClearedNode {
  Index node = NO_INDEX;
  Index view = NO_INDEX;  ///< into the views passed in
  Index face = NO_INDEX;  ///< the engine's contact face (nearest master face as read)
  Real clearance = 0.0;   ///< c, m (sign convention of double-sided elements)
  Real gap_before = 0.0;  ///< g = h − T as read, m
  Real distance = 0.0;    ///< length of the move, m (0 with ADJUST=NO)
  Vec3 direction = Vec3::Zero();
  Real offset = 0.0;  ///< permanent offset d0, m (0: none)
  /// Why a node meant to move keeps an offset (Boundary, Rigid, Distortion, Conflict);
  /// meaningless when `offset` is 0 or the view has ADJUST=NO.
  OffsetReason reason = OffsetReason::Conflict;
  /// Interference fits: the overclosure ramped away over the view's ramp time, m (0: none).
  Real interference = 0.0;
};

/// A slave node of a view without a clearance.
struct SkippedNode {
  Index node = NO_INDEX;
  Index view = NO_INDEX;
  ClearanceSkip why = ClearanceSkip::NoValue;
};

/// What the clearance pass did.
struct ClearanceReport {
  std::vector<ClearedNode> nodes;
  std::vector<SkippedNode> skipped;
  /// Faces of a master surface that are not in the contact domain, per view (warned once).
  std::vector<Index> faces_outside_domain;
  int passes = 0;
  std::vector<Index> refused_elements;
  Real quality_before = 1.0, quality_after = 1.0;  ///< as OverclosureReport
  /// Per slave slot of the engine: 1 when the node has a clearance (the automatic pass
  /// leaves it alone).
  std::vector<char> handled;
  double seconds = 0.0;
};

/// Applies the clearances of `views` on `position` (moved in place where ADJUST=YES and
/// `adjust_allowed`; a view with ADJUST=YES where it is not allowed is resolved by offsets)
/// and stores the offsets in the engine's constraints. `node_lock` as for
/// resolve_initial_overclosures.
ClearanceReport apply_clearances(ContactEngine& engine, const ElementTopology& topology,
                                 NodalVectors& position, std::span<const Real> node_thickness,
                                 std::span<const std::uint8_t> node_lock,
                                 std::span<const ClearanceView> views, bool adjust_allowed);

}  // namespace xpl::contact
