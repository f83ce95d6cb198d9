#pragma once
/// \file The adjustment loop shared by the two start-of-step passes that move slave nodes
/// (contact clearances, SPEC C8; initial overclosures, C2–C4), and what both need to say why
/// a node does not move.
///
/// One adjustment is a sequence of *rounds*, each of Jacobi *passes*:
/// - a pass computes the move of every node that still has to move on the current positions,
///   then applies all the moves (what moves, how far and along which normal is the caller's:
///   AdjustmentMoves::pass), and the caller's search sees the moved geometry in the next pass;
/// - after the passes of a round, the distortion check: an element with a moved node one of
///   whose corner volumes (hex) or areas (shell) falls below MIN_CORNER_RATIO of its value as
///   read, or inverts, is refused, its moved nodes become held (AdjustmentMoves::hold), and
///   the next round starts again from the mesh as read (AdjustmentMoves::begin_round);
/// - the rounds end when nothing is refused, or after MAX_ADJUSTMENT_ROUNDS (the last
///   round's moves are kept as they are).

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "contact/contact_faces.hpp"
#include "contact/contact_options.hpp"

namespace xpl::contact {

/// Bits of a node's lock (the caller's view of what holds a node in place).
inline constexpr std::uint8_t LOCK_X = 1;  ///< translation 1 has a boundary condition
inline constexpr std::uint8_t LOCK_Y = 2;
inline constexpr std::uint8_t LOCK_Z = 4;
inline constexpr std::uint8_t LOCK_RIGID = 8;  ///< moves with a rigid body (member, pin, tie)
inline constexpr std::uint8_t LOCK_TIE = 16;   ///< a *TIE slave node or a corner it is bound to

/// Why a penetration is stored as an offset instead of being removed.
enum class OffsetReason : std::uint8_t {
  Boundary,    ///< a boundary condition acts along the contact normal
  Rigid,       ///< the node belongs to (or is tied to) a rigid body
  Pinched,     ///< the node penetrates two master faces that face each other
  Distortion,  ///< moving it would invert or badly distort an element
  Conflict,    ///< competing adjustments did not converge
  LaterStep,   ///< contact first defined after step 1: no node moves (C6)
  Import,      ///< the run starts from an imported state: no node moves (C6, S7)
  Tie,         ///< a *TIE slave node, or a master corner one is bound to (S6, C3)
};

/// Name of a reason for reports ("BC", "rigid", ...).
const char* offset_reason_name(OffsetReason reason);

/// What holds a node with lock bits `lock` (LOCK_*) from moving along the unit direction
/// `normal`: Rigid for a rigid-body node, Boundary when a DOF with a boundary condition has a
/// component above LOCK_COMPONENT along it, nothing when the node is free to move.
std::optional<OffsetReason> lock_reason(std::uint8_t lock, const Vec3& normal);

/// Elements with a node marked in `node_moved` (n_nodes) one of whose corner volumes (hex) or
/// corner areas (shell) at `position` falls below MIN_CORNER_RATIO of its value at `original`,
/// or inverts; also the smallest scaled corner measure of the elements with a moved node,
/// before and after (1 for a perfect element; 1 when there are none).
std::vector<Index> distorted_elements(const ElementTopology& topology, const NodalVectors& original,
                                      const NodalVectors& position,
                                      std::span<const char> node_moved, Real& quality_before,
                                      Real& quality_after);

/// The caller's part of an adjustment (see the file comment).
class AdjustmentMoves {
 public:
  virtual ~AdjustmentMoves() = default;
  /// Start of round `round`; for round > 0 the positions are back at the mesh as read.
  virtual void begin_round(int round) = 0;
  /// Pass `pass` of the current round: returns false, having moved nothing, when the round's
  /// passes are over (nothing left to move, or the passes stopped converging); else moves the
  /// nodes and returns true.
  virtual bool pass(int pass) = 0;
  /// Node `node`, moved in this round, belongs to a refused element: hold it (a node that is
  /// not the caller's, or already held, is left alone).
  virtual void hold(Index node) = 0;
};

/// What an adjustment did.
struct AdjustmentOutcome {
  int passes = 0;                       ///< passes that moved nodes, in the last round
  bool moved = false;                   ///< a node of `movable` ends away from its position as read
  std::vector<Index> refused_elements;  ///< every round's refusals, in order
  Real quality_before = 1.0, quality_after = 1.0;  ///< as distorted_elements, last round
};

/// Runs the rounds and passes of an adjustment on `position` (n_nodes × 3, m), which starts
/// as `original` (the mesh as read) and ends adjusted. `movable`: the nodes the caller may
/// move (the distortion check looks at the elements around those that did); at most
/// `max_passes` passes per round.
AdjustmentOutcome run_adjustment(const ElementTopology& topology, const NodalVectors& original,
                                 NodalVectors& position, std::span<const Index> movable,
                                 int max_passes, AdjustmentMoves& moves);

}  // namespace xpl::contact
