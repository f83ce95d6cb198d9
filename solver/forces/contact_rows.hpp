#pragma once
/// \file The contact nodes' rows a rank of a distributed run gathers each increment before
/// the contact pass (docs/dev/mpi.md, "Contact shared out among the ranks"). Before a first
/// shared pass has run, every contact node's position and v(n+½) from the rank integrating
/// it; each increment the rows this rank's pass reads, point to point from the ranks
/// integrating them (MPI_Alltoallv, the lists fixed at each build): its slots' nodes, their
/// candidate faces' corners and the faces their state holds
/// (ContactEngine::mark_read_nodes), the nodes of any rank's marks whose output rows it
/// writes, and the faces around each of those (their node areas and normals). The rebuild
/// decision rides along: each rank's largest motion of the contact nodes it integrates,
/// reduced by max (exact), so every rank decides as one rank does on the whole positions.
/// When the broad phase is to be built, the ghost faces (build_ghosts()): each rank's box of
/// the slots it scans to every rank, and from the rank sourcing each face (the one
/// integrating its first corner) the positions of its corners to every rank whose box its
/// inflated box meets; the broad phase is built on those, then the new lists' rows travel.

#include <span>
#include <vector>

#include "contact/contact_engine.hpp"
#include "solver/model/state.hpp"

namespace xpl {

class DistributedRun;

/// Which contact rows travel each increment, rebuilt with the broad phase.
class ContactRows {
 public:
  /// The engine's contact nodes (ascending, every face node and point node) on `run`, whose
  /// ranks share the slots out (share_slots()); the next gather is whole. `root_writes`: rank
  /// 0 writes every node's frame rows (--gather-frames), else each node's owner.
  void reset(const DistributedRun& run, const contact::ContactEngine& engine,
             std::vector<Index> nodes, Index n_nodes, bool root_writes);
  /// Every contact node (reset()).
  const std::vector<Index>& nodes() const { return m_all; }
  /// Before the contact pass (collective): the rows `state` holds of the nodes each rank
  /// integrates into `position` and `velocity` (n_nodes × 3, copies the engine reads) on
  /// every rank: every contact node's, or, while the broad phase stays, the read ones only;
  /// then gives `engine` the rebuild decision of its next update() (decide_rebuild()).
  /// Returns whether the broad phase is to be built first (build_ghosts()).
  bool gather(contact::ContactEngine& engine, const State& state, NodalVectors& position,
              NodalVectors& velocity);
  /// When gather() says so (collective): the ghost faces' rows into `position`, the broad
  /// phase built on them (ContactEngine::build_shared_broad_phase()), the lists made anew and
  /// the rows they read into `position` and `velocity`; the engine's next update() then does
  /// not build again. `node_thickness` (n_nodes or empty) as the engine takes it.
  void build_ghosts(contact::ContactEngine& engine, const State& state,
                    std::span<const Real> node_thickness, NodalVectors& position,
                    NodalVectors& velocity);
  /// After the pass (collective when it builds the lists): the lists of read rows made anew
  /// when the broad phase was built (`rebuilt`) or when there are none yet.
  void update_lists(const contact::ContactEngine& engine, bool rebuilt);
  /// Values this rank received per gather, on average (0 before the first), and what
  /// every contact node's rows would have been.
  double values_per_gather() const {
    return m_gathers > 0 ? m_values / static_cast<double>(m_gathers) : 0.0;
  }
  long gathers() const { return m_gathers; }
  double whole_values_per_gather() const {
    return static_cast<double>(6 * (m_all.size() - static_cast<std::size_t>(m_integrated_count)));
  }
  /// Values this rank sent per gather, on average (rows and motions, builds included).
  double values_sent_per_gather() const {
    return m_gathers > 0 ? m_sent / static_cast<double>(m_gathers) : 0.0;
  }
  /// Per build of the broad phase in a shared pass, on average: the rows' values this rank
  /// received and sent for the build beyond the increment's own rows (the ghost faces and
  /// the new lists' rows); per making of the lists (update_lists()), the values that makes
  /// travel (the marks' union, the counts and the node numbers asked for).
  struct BuildValues {
    double received = 0.0, sent = 0.0, lists_received = 0.0, lists_sent = 0.0;
  };
  BuildValues values_per_build() const;

 private:
  /// Every contact node's rows (share_rows()).
  void gather_all(const State& state, NodalVectors& position, NodalVectors& velocity);
  /// The rows of the lists (update_lists()) and this rank's largest motion `motion` and step
  /// motion `step` (m², the sleeping slots' path), point to point; returns the largest motion
  /// of all ranks and sets `largest_step` to the largest step motion. Counts the values into
  /// `received` and `sent`.
  Real exchange_listed(const State& state, NodalVectors& position, NodalVectors& velocity,
                       Real motion, Real step, Real& largest_step, double& received, double& sent);
  /// update_lists(): each of this rank's marks (n_nodes) to the rank integrating the node and
  /// to the rank writing its output rows (collective); the marks received into `anyone`.
  void tell_marks(const std::vector<char>& mark, std::vector<char>& anyone);
  /// build_ghosts()'s first part: the positions of the corners of the faces this rank
  /// sources that other ranks integrate, then of the ghost faces, into `position`; marks in
  /// `fresh` (n_nodes) every node whose position is now current.
  void exchange_ghost_positions(const contact::ContactEngine& engine, const State& state,
                                std::span<const Real> node_thickness, NodalVectors& position,
                                std::vector<char>& fresh);

  const DistributedRun* m_run = nullptr;
  bool m_root_writes = false;      ///< reset()
  std::vector<Index> m_all;        ///< every contact node, ascending
  std::vector<char> m_integrated;  ///< the contact nodes this rank integrates
  Index m_integrated_count = 0;    ///< of m_all
  /// Between builds (update_lists()): the rows this rank sends each rank and receives from
  /// each (by rank), and those it copies from its own `state`; the values of each exchange
  /// (rows and the largest motion) to and from each rank.
  std::vector<std::vector<Index>> m_send_nodes, m_receive_nodes;
  std::vector<Index> m_local;
  std::vector<int> m_send_counts, m_receive_counts;
  std::vector<Real> m_send, m_receive;  ///< gather()'s buffers, kept between increments
  /// The ghost faces (reset(), fixed while the partition is): the faces this rank sources,
  /// and the corners of faces sourced elsewhere that it integrates, per sourcing rank, and
  /// those of its own faces it receives, per integrating rank (ascending).
  std::vector<Index> m_sourced;
  std::vector<std::vector<Index>> m_corner_send, m_corner_receive;
  bool m_lists = false;        ///< the lists of the build are made
  bool m_partial = false;      ///< the last gather was of the read rows only
  bool m_ghost_built = false;  ///< build_ghosts() built the broad phase of this increment
  double m_values = 0.0, m_sent = 0.0;
  long m_gathers = 0;
  BuildValues m_build_values;  ///< summed over m_builds
  long m_builds = 0, m_list_makings = 0;
};

}  // namespace xpl
