#pragma once
/// \file Ties under N ranks (issue 37 item 2, docs/dev/mpi.md, "Ties where their nodes
/// live"): which rank moves which slave force to its master corners, which rank makes which
/// slave follow its corners, and the rows that travel for it, point to point.
///
/// The one-rank passes (solver/motion/ties.hpp) are, per master node i, force(i) += N_I f_s
/// over its bindings in binding order, and per slave s, v_s = Σ N_I v_I over its corners. Each
/// is a function of one node's finished rows, so any rank holding those rows bit for bit gets
/// the one-rank bits. A rank *holds* a node when its elements use it or it counts the node's
/// chunk (DistributedRun: such a rank integrates the node from its finished force). So:
/// - every rank holding a master corner gathers the slave forces into it; the forces of the
///   slaves it does not hold come from the rank integrating them (row_source());
/// - every rank holding a slave makes it follow; the motion of the corners it does not hold
///   comes from the rank integrating them, after their update.
/// No rank runs a pass for nodes it does not move, and no per-contribution slots are needed:
/// the sum at a corner is made whole on each rank that holds the corner, from the same rows.

#include <utility>
#include <vector>

#include "common/types.hpp"
#include "solver/distributed_run.hpp"

namespace xpl {

/// The tie passes of one rank and the rows they need from the others, fixed at set-up.
struct TieRoutes {
  /// This rank's nodes (n_nodes each): 1 for the master corners it gathers into, and for the
  /// slaves it makes follow (Ties::set_local()).
  std::vector<unsigned char> gathers, follows;
  /// The slaves' forces before the gather, the corners' motion before the follow.
  DistributedRun::RowRoute forces, motion;
  /// Per rank: master corners it gathers into, slaves it makes follow, and the nodes whose
  /// rows it receives and sends per increment (slave forces, corner motion); `whole_*`: the
  /// rows of the first design's two gathers it received (every listed slave and corner not
  /// integrated by itself).
  struct Rank {
    Index masters = 0, slaves = 0;
    Index forces_received = 0, forces_sent = 0, motion_received = 0, motion_sent = 0;
    Index whole_forces = 0, whole_motion = 0;
  };
  std::vector<Rank> ranks;
};

/// The routes of the tie bindings `pairs` (Ties::slave_master_nodes(): slave, master corner)
/// over the partition of `run`; every rank derives the same lists from the same data.
TieRoutes make_tie_routes(const std::vector<std::pair<Index, Index>>& pairs,
                          const DistributedRun& run, Index n_nodes);

}  // namespace xpl
