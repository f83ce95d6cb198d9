#pragma once
/// \file The tunables of general contact, each defined once with its reason: the user options
/// of the engine (ContactOptions) and the fixed constants of every stage of the pipeline
/// (faces → broad phase → closest point → penalty law → assembly) and of the two start-of-step
/// passes (contact clearances, initial overclosures). The stages include this header rather
/// than keeping local copies, so a value changed here changes everywhere it is used.

#include "common/types.hpp"

namespace xpl::contact {

// ---- Penalty law (penalty.hpp) ----------------------------------------------------------

/// α of the default penalty stiffness k = α·s·m_eff/Δt². With α = ½ the contact spring alone
/// reaches ω²Δt² = ½, an eighth of the central-difference limit 4: room for the element
/// stiffness on the node and for several springs on one node (derivation in penalty.hpp).
inline constexpr Real DEFAULT_PENALTY_FACTOR = 0.5;

/// Default of the user's penalty scale factor s: 1 keeps the stiffness at the stable value above.
inline constexpr Real DEFAULT_PENALTY_SCALE = 1.0;

/// ω_c²Δt² a deck's own penalty stiffness (a LINEAR pressure–overclosure slope) may reach
/// before it shortens the increment (penalty_increment.hpp): α, what the default penalty
/// reaches by construction, so a user's spring no stiffer than the default leaves the
/// increment alone and a stiffer one gets the default's share of the stability budget.
inline constexpr Real PENALTY_INCREMENT_BUDGET = DEFAULT_PENALTY_FACTOR;

/// ω_c²Δt² a user's spring may reach on its own, whatever the elements: 2, half the linear
/// limit 4. A spring that opens and closes loses its energy balance well before the linear
/// limit: bar on bar with a 1e15 Pa/m slope (ω_c ≈ 3.5 ω_e) ran with ETOTAL drift 0.5 % at
/// ω_cΔt = 1.49, 6 % at 1.67 and failed at 1.86.
inline constexpr Real PENALTY_ALONE_BUDGET = 2.0;

/// Largest ω²Δt² bound that the default-penalty springs on one node may reach together
/// (row-sum bound of penalty_increment.hpp). A spring on a rigid master, or the two views of
/// equal masses face to face, reach DEFAULT_PENALTY_FACTOR (½) by construction; a light node
/// against a heavy face in a balanced pair reaches up to twice that (its own spring and its
/// share of the other view's spring, each ½ k/m of the light node: 0.80–0.97 measured on the
/// example decks). A node pinched between two faces, under folded shell layers or at a corner
/// pressed from several sides would reach more: its springs are scaled down to this bound,
/// which every single contact stays within. The bound is for the penalty scale factor 1: a
/// user's factor s multiplies it (the scale is the user's choice of stiffness, not undone).
/// The bound is loose (Gershgorin, and the contact direction is rarely the elements' stiffest
/// mode): the contact stability stress tests hold at it.
inline constexpr Real DEFAULT_PENALTY_NODE_BUDGET = 1.0;

/// The bound on ω²Δt² of a rigid body's bounce on its default springs (its translation rows
/// over the body's mass, cap_default_springs), below the node budget: a free rigid body's
/// motion has no element stiffness to spread an impact over, so its contact lasts ~π/(ωΔt)
/// increments, and a spring's onset and release inside an increment cost an energy error of
/// the order of √k (docs/theory/contact.md). At 0.25 a bounce spans ≥ 6 increments.
inline constexpr Real DEFAULT_PENALTY_BODY_BUDGET = 0.25;

/// The nearest penetrated faces a slave node keeps in the search for the face on its other
/// side (a pinched node); a node under more (the shared corner of four faces on each side)
/// searches its candidates once more.
inline constexpr int PENETRATED_KEPT = 8;

/// A user-stiffness spring counts in the increment limit when it is closed, or open but
/// closing within this many increments at its current normal approach speed: a spring that
/// closes during the next increment is then already in the increment that takes it.
inline constexpr Real PENALTY_LOOKAHEAD_INCREMENTS = 2.0;

// ---- Search (contact_engine.cpp, broad_phase.hpp) ---------------------------------------

/// Default search margin as a fraction of the mean face size (mean square root of the face
/// areas): a node moves much less than a face size per increment, and 0.3 keeps the candidate
/// lists short while the broad phase is rebuilt only every few increments.
inline constexpr Real MARGIN_FRACTION = 0.3;

/// Search margin (m) used when the faces give none (no faces, or faces of zero area): any
/// positive value keeps the broad phase well defined; nothing can touch then anyway.
inline constexpr Real FALLBACK_MARGIN = 1e-3;

/// Cosine below which a face counts as looking at a slave node: the node normal and the face
/// normal must be more than ≈100° apart (cos 101.5° = −0.2). Faces at 90° (the side face
/// beside a block's top, the side faces of another bar at a bar end) are not admissible, a
/// face tilted by a fold of a few tens of degrees still is.
inline constexpr Real OPPOSING_COSINE = 0.2;

/// Sine of the angle by which a solid surface must turn up in front of a face at its edge to
/// count as a concave corner there (≈0.6°): a flat or convex edge hands a node beside it to
/// the next face (contact_search.cpp, admissible()); a mesh that is flat to round-off is flat.
inline constexpr Real CONCAVE_EDGE_SINE = 0.01;

/// How far in front of the next face's plane, as a fraction of the depth of the element behind a
/// face, a node beside the face's convex edge is outside the body rather than at the edge.
inline constexpr Real OUTSIDE_EDGE_FRACTION = 0.05;

/// Contact area (m², model units) of a node of a node-based surface (SPEC C13) whose `*SURFACE,
/// TYPE=NODE` data line gives none: 1, the unit area Abaqus takes for a blank area field. It
/// enters only what needs an area (a LINEAR pressure–overclosure slope, the CPRESS output);
/// the default penalty is set by masses (penalty.hpp) and does not see it.
inline constexpr Real POINT_NODE_DEFAULT_AREA = 1.0;

/// Deepest admissible penetration behind a solid face as a fraction of the depth of the
/// element behind it (the distance between the face centre and the opposite face centre), and
/// behind a shell face as a fraction of its mean thickness: ½, so a node on the outer skin of
/// a thin wall never touches the inner skin of that wall.
inline constexpr Real DEPTH_LIMIT_FRACTION = 0.5;

/// A touch on a face other than last increment's is taken as it is while it is no
/// deeper than this many times the relative approach of the increment along its normal (plus
/// the penetration carried over from a face on the same side), else what lies beyond the
/// approach becomes offset (onset_offset, penalty.hpp). 2 leaves the rounding and the face's
/// turning within the increment to the first case: a node sliding on to the next face of a
/// pressed wall keeps its force, and only penetrations far beyond one increment's motion (a
/// shell thickness in the crash tube, against approaches of micrometres) are offset.
inline constexpr Real ONSET_REACH_FACTOR = 2.0;

/// A listed slot sleeps (is not searched) only while its distance bound keeps it this fraction
/// of its touch distance beyond any touch (ContactEngine, sleeping slots), so that it wakes and
/// is searched for many increments (motions of micrometres against a tenth of a shell
/// thickness in the crash tube) before it can touch, with an open touch's memory as before.
inline constexpr Real SLEEP_GUARD = 0.1;

// ---- Start-of-step passes (adjustment_pass.hpp, initial_overclosure.hpp,
// ---- contact_clearance.hpp)

/// Relative tolerance (of the facet size) under which a node counts as on the surface (its
/// penetration or clearance violation is resolved): far below any geometric feature, well
/// above the rounding of a closest-point projection.
inline constexpr Real OVERCLOSURE_TOLERANCE = 1e-10;

/// Deepest penetration below a solid face that the overclosure pass adjusts, as a fraction of
/// the facet size around the slave node (the default of OverclosureSettings::depth_fraction):
/// mesh-generation mismatches are a few percent of an element; deeper ones are modelling
/// errors, "ignored" and pushed out by the penalty instead.
inline constexpr Real IGNORED_DEPTH_FRACTION = 0.15;

/// Crossed-surface check (C5): a master face edge is a corner of its surface (a rim, or a fold
/// such as a block's edge) unless a face across it has a normal within 60° of its own (cosine
/// at least ½); a slave edge meeting a face within the depth limit (IGNORED_DEPTH_FRACTION of
/// the facet) of such a corner edge grazes it and is not reported.
inline constexpr Real CROSSED_FOLD_COSINE = 0.5;

/// Two penetrated faces whose normals are more than 120° apart (cosine below −½) pinch the
/// node: leaving one means entering the other, so it keeps an offset instead of moving.
inline constexpr Real PINCH_COSINE = -0.5;

/// A shell node pressed by two penetrated faces of different elements whose normals are more
/// than 60° apart (cosine below ½) sits in a corner (a wall's round edge met side-on while the
/// node lies on a plate, a fold): it holds a spring on each, so that neither face's depth
/// grows unresisted while the other holds it (ContactEngine, from an engine's second update).
inline constexpr Real CORNER_COSINE = 0.5;

/// A shell element next to the one a node is held on (sharing a corner, not folded back over
/// it) continues that wall when its normal is within 45° of the held face's: the node's side
/// memory (no pass-through) covers it (ContactEngine::admissible).
inline constexpr Real WALL_COSINE = 0.70710678118654752;

/// A move is refused when an element corner keeps less than this share of its volume (hex) or
/// area (shell) as read: half, well before an inversion, so the adjusted mesh stays usable.
inline constexpr Real MIN_CORNER_RATIO = 0.5;

/// A boundary condition on DOF c holds a node when |n_c| of the move direction exceeds this:
/// a move exactly perpendicular to a fixed DOF (up to rounding) does not fight it.
inline constexpr Real LOCK_COMPONENT = 1e-6;

/// Jacobi passes of one adjustment round before what remains becomes an offset. Consistent
/// overclosures and clearances converge in a handful of passes (flat surfaces in one); 60
/// only bounds the cost of inconsistent ones.
inline constexpr int MAX_ADJUSTMENT_PASSES = 60;

/// Rounds of "adjust, then refuse distorting moves" before giving up on further refusals:
/// each round holds the nodes of the refused elements, and a few rounds settle every case
/// seen; the last round's refusals are kept as they are.
inline constexpr int MAX_ADJUSTMENT_ROUNDS = 5;

/// The clearance passes stop as soon as one pass fails to bring the largest residual below
/// this share of the previous pass's (what remains becomes permanent offsets, reason
/// conflict). Consistent clearances converge by a large factor per pass (flat surfaces in
/// one), but balanced clearances between curved surfaces are inconsistent (the seed's
/// curvature change): for two concentric polygons with different chord sags the only state
/// meeting every clearance has both surfaces shrunk to a fraction of their radius, and further
/// passes would creep towards it.
inline constexpr Real CLEARANCE_CONVERGENCE_RATIO = 0.5;

/// Share of the facet size at a solid slave node used as the default clearance search zone
/// (SPEC C9): mesh mismatches are far smaller, neighbouring surfaces far farther.
inline constexpr Real DEFAULT_ZONE_FRACTION = 0.1;

/// A node farther than this share of its facet size beside a perimeter edge of the master
/// surface lies outside the surface (C9); closer, it is taken as right above the edge (the
/// edge nodes of two matching meshes, up to rounding).
inline constexpr Real PERIMETER_TOLERANCE = 1e-6;

// ---- User options -----------------------------------------------------------------------

/// Options of the contact engine (the deck's, per step).
struct ContactOptions {
  Real penalty_scale = DEFAULT_PENALTY_SCALE;  ///< s, multiplies the default penalty stiffness
  /// Search margin, m; 0: MARGIN_FRACTION × the mean face size plus the largest half shell
  /// thickness.
  Real margin = 0.0;
};

}  // namespace xpl::contact
