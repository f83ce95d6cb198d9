#pragma once
/// \file A run distributed over MPI ranks (issue 37 item 3, docs/dev/mpi.md): what one rank
/// owns and what the ranks exchange each increment. Every rank reads the whole model and
/// builds its whole setup (masses, colours, the whole element layout); the elements are then
/// split by SIMD batches (each batch of the one-rank layout goes to the part that holds most
/// of its lanes), and each rank computes the forces of its batches only.
///
/// Bitwise independence of the rank count:
/// - Nodal forces: a node used by one rank only receives its contributions in the one-rank
///   order (the rank's batches are the one-rank batches, in the one-rank order). An interface
///   node (used by two or more ranks) is summed by every rank using it from per-contribution
///   slots (partition/exchange_plan.hpp): its own corners' values and those its neighbours
///   send (MPI_Isend/MPI_Irecv, one message per neighbour and increment), folded from +0 in
///   the one-rank order (block, batch, lane). Every rank using a node integrates it with the
///   same force and mass, so no positions are exchanged.
/// - Element totals (energy increments, stable increment, critical and failed element): each
///   rank's per-batch values are gathered (point to point) into the whole layout on every
///   rank and reduced there by the one-rank code, in batch order.
/// - Global stable-increment estimate (Lanczos, at the start of a step and when the element
///   estimate moves): the positions are gathered to rank 0 from their owners, rank 0 runs the
///   one-rank estimate on the whole mesh and broadcasts its largest eigenvalue.
/// - Nodal sums (ALLKE, ALLKD, ALLWK): the one-rank code sums the nodes in chunks of
///   CentralDifference::NODE_CHUNK and adds the chunks in order. Each chunk is counted by one
///   rank (the one owning most of its nodes), which integrates every node of the chunk: the
///   nodes of the chunk its elements do not use get their finished force from their owner
///   each increment (ship_forces(), point to point), so its chunk sums are the one-rank
///   ones; the chunk sums are then gathered and added in chunk order. The prescribed DOFs'
///   terms are gathered with them (share_chunks()) and folded in DOF order. A rank's nodal
///   passes visit only the nodes it moves (CentralDifference::set_distribution()).
/// Output: every rank writes its rows of each frame into JOB.h5 (FrameRows, parallel HDF5);
/// rank 0 writes everything else, and gathers the owners' rows before a history row that
/// reads nodes (and before a frame with --gather-frames).

#include <memory>
#include <string>
#include <vector>

#include "partition/exchange_plan.hpp"
#include "solver/model/model.hpp"
#include "solver/model/state.hpp"

namespace xpl {

/// One rank's view of a distributed run and its MPI operations (every operation that is
/// collective must be called by every rank in the same order).
class DistributedRun {
 public:
  /// MPI's rank and size in MPI_COMM_WORLD (0 and 1 without MPI or before MPI_Init).
  static int world_rank();
  static int world_size();
  /// What keeps `model` from running distributed today (one message per feature), empty if
  /// nothing: an imported state (--import).
  static std::vector<std::string> refusals(const Model& model, bool imported);

  /// The largest `value` of the ranks of MPI_COMM_WORLD (collective; `value` without MPI).
  static int world_max(int value);
  /// Ends every rank of MPI_COMM_WORLD with exit code `code` (MPI_Abort): for a failure of this
  /// rank alone, which the others would wait for in their next collective. Returns only when
  /// there is no other rank to end.
  static void abort_world(int code);
  /// A communicator of its own for ending a run (every_rank_ends()); collective, once, right
  /// after MPI_Init (apps/mpi_session.cpp).
  static void open_end_channel();
  /// After a stop of the solver (a SolverError), which comes from reduced values and so
  /// reaches every rank together: whether every rank gets here within `seconds` (a
  /// non-blocking barrier on the end channel, which no collective of the run can match). A
  /// rank that stopped alone, which is a bug, would otherwise enter the end-of-run collective
  /// while the others wait in the time loop's; false tells it to end every rank.
  static bool every_rank_ends(double seconds);

  DistributedRun();
  ~DistributedRun();
  DistributedRun(const DistributedRun&) = delete;
  DistributedRun& operator=(const DistributedRun&) = delete;

  int rank() const { return m_rank; }
  int size() const { return m_size; }

  /// Rank 0's `values` on every rank.
  void broadcast(std::vector<int>& values) const;
  /// Rank 0's `value` and `count` on every rank (one collective).
  void broadcast_estimate(Real& value, int& count) const;
  /// Takes the partition of the run: the part of each element (n_elements) and the position
  /// of each element in the one-rank summation order (distinct). Builds the exchange plan.
  /// Nodal chunks of `chunk` nodes are each counted by one rank. The elements of rigid
  /// bodies (`element_body`, RigidBodies::element_body(); empty: none) are in no part.
  void set_partition(const Model& model, std::vector<int> element_part,
                     std::vector<Index> element_order, Index chunk,
                     const std::vector<Index>& element_body);
  const partition::ExchangePlan& exchange_plan() const { return m_plan; }
  const partition::PartPlan& plan() const { return m_plan.part[m_rank]; }
  const std::vector<int>& element_part() const { return m_element_part; }
  /// Whether an element of this rank uses `node`; whether this rank owns it.
  bool in_part(Index node) const { return m_in_part[node] != 0; }
  bool owns(Index node) const { return m_node_owner[node] == m_rank; }
  /// Whether this rank counts (and so integrates) the nodal chunk of `node`, or chunk `c`.
  bool counts(Index node) const { return m_chunk_owner[node / m_chunk] == m_rank; }
  bool counts_chunk(Index c) const { return m_chunk_owner[c] == m_rank; }
  /// The rank that counts the nodal chunk of `node`.
  int chunk_counter(Index node) const { return m_chunk_owner[node / m_chunk]; }

  /// The finished forces (and moments, if not null; n_nodes × 3) of the nodes of this rank's
  /// chunks that its elements do not use, from their owners (Isend/Irecv).
  void ship_forces(NodalVectors& force, NodalVectors* moment);
  /// The chunk values `per_chunk` (values per chunk: `width`, chunk after chunk; `blocks`
  /// such arrays back to back, e.g. translations then rotations) of every chunk from the
  /// rank that counts it (point to point to every rank; the sends complete at the next
  /// call). Two more values ride along (no exchange of their own): `largest` (e.g. a stop signal):
  /// in, this rank's value; out, the largest of the ranks'; `rows`: in, this rank's; out, every
  /// rank's in rank order. `counts`: the number of values each rank sends (found, one collective
  /// more, unless `counts_known`: they change only with the number of rows).
  void share_chunks(std::vector<Real>& values, int width, int blocks, int& largest,
                    std::vector<Real>& rows, std::vector<int>& counts, bool counts_known) const;

  /// \name The force exchange of an increment: post_receives() before the element pass,
  /// then the send buffers filled (width values per slot, NeighbourExchange::send order) once
  /// the interface batches are computed, send() (returns at once), and after the interior
  /// batches receive(): waits; returns the received buffers (one per neighbour).
  void post_receives(int width);
  std::vector<std::vector<Real>>& send_buffers() { return m_send; }
  void send();
  const std::vector<std::vector<Real>>& receive();

  /// Every rank's `mine` concatenated in rank order (MPI_Allgatherv); `counts` (size()) the
  /// number of values of each rank: found, or with `counts_known` given (one collective less).
  std::vector<Real> allgather(const std::vector<Real>& mine, std::vector<int>& counts,
                              bool counts_known = false) const;
  /// Point to point (MPI_Alltoallv): `send` holds the values for rank 0, 1, ... back to
  /// back, `send_counts[r]` of them for rank r; into `receive` (resized: a buffer the caller
  /// keeps) the values each rank sends this one, `receive_counts[r]` from rank r, in rank
  /// order. Collective; the counts must match the senders' (alltoall_counts()).
  void alltoall_into(const std::vector<Real>& send, const std::vector<int>& send_counts,
                     std::vector<Real>& receive, const std::vector<int>& receive_counts) const;
  /// The number of values each rank will send this one, from the number this one sends each
  /// (`send_counts`, size()) (MPI_Alltoall). Collective.
  std::vector<int> alltoall_counts(const std::vector<int>& send_counts) const;
  /// allgather() in two halves, so that it travels while the rank does other work (one at a
  /// time): post_allgather() starts it with every rank's count known, wait_allgather() waits
  /// and returns every rank's values in rank order. post_allgather() keeps `mine` until the
  /// wait and hands back the buffer of the previous call in its place (cleared by the caller
  /// before it fills it again): two buffers that keep their capacity between increments.
  void post_allgather(std::vector<Real>& mine, const std::vector<int>& counts);
  const std::vector<Real>& wait_allgather();
  /// The rows (n_nodes × 3) of the nodes each rank owns, from their owners to rank 0.
  void gather_to_root(NodalVectors& rows) const;
  /// The same to every rank: each node's row from its owner (MPI_Iallgatherv).
  void allgather_rows(NodalVectors& rows) const;
  /// Element rows (`width` values per element) from each element's rank to rank 0.
  void gather_elements_to_root(std::vector<Real>& rows, int width) const;
  /// The rows of `nodes` (ascending, the same list on every rank) in every array of `rows`
  /// (n_nodes × 3 each, empty ones skipped), from each node's owner to rank 0 in one
  /// collective; rows of nodes no rank owns are left as rank 0 holds them (as in
  /// gather_to_root()).
  void gather_nodes_to_root(const std::vector<Index>& nodes,
                            const std::vector<NodalVectors*>& rows) const;
  /// The rows (n_nodes × 3 each) of `nodes` (the same list on every rank) from the rank that
  /// integrates each node (row_source())
  /// onto every rank, from `from[k]` into `to[k]` (MPI_Allgatherv; rows not listed are left
  /// as they are). Collective.
  void share_rows(const std::vector<Index>& nodes, const std::vector<const NodalVectors*>& from,
                  const std::vector<NodalVectors*>& to) const;
  /// Rows that travel point to point between fixed pairs of ranks (route_rows()): per rank,
  /// the nodes this rank sends it and the nodes it receives from it, in the same order on
  /// both sides.
  struct RowRoute {
    std::vector<std::vector<Index>> send, receive;
  };
  /// The rows (n_nodes × 3 each) of the nodes of `route`, from `rows` of the sending rank
  /// into `rows` of the receiving one (MPI_Isend/MPI_Irecv between the listed pairs only).
  void route_rows(const RowRoute& route, const std::vector<NodalVectors*>& rows) const;
  /// The rank whose rows of `node` are the run's: its owner, or for a node of no deformable
  /// element the rank counting its chunk.
  int row_source(Index node) const { return m_row_source[node]; }
  /// The rank that owns `node` and writes its rows of each frame (rank 0 for a node of no
  /// deformable element).
  int owner(Index node) const { return m_node_owner[node]; }

  /// Wall time spent in this rank's exchanges and collectives, s: with the neighbours (the
  /// interface forces), shipping the chunks' forces, and gathers and reductions; WAITS: the
  /// part of them spent waiting for the other ranks (for a message to arrive, a collective
  /// to complete), included in the three.
  enum Timing { NEIGHBOURS, SHIP, GATHERS, WAITS, TIMINGS };
  double exchange_seconds(Timing t) const { return m_seconds[t]; }
  double exchange_seconds() const { return m_seconds[0] + m_seconds[1] + m_seconds[2]; }
  /// Nodes rank r receives forces of each increment for the chunks it counts.
  Index ship_count(int r) const { return m_ship_count[r]; }

 private:
  int m_rank = 0;
  int m_size = 1;
  partition::ExchangePlan m_plan;
  std::vector<int> m_element_part;
  std::vector<int> m_node_owner;
  std::vector<int> m_row_source;  ///< row_source()
  std::vector<unsigned char> m_in_part;
  Index m_chunk = 1;
  std::vector<int> m_chunk_owner;
  /// ship_forces(): per rank, the nodes this rank sends it and the nodes it receives from it.
  std::vector<std::vector<Index>> m_ship_send, m_ship_receive;
  std::vector<std::vector<Real>> m_ship_send_buffer, m_ship_receive_buffer;
  std::vector<std::vector<Real>> m_send, m_receive;
  std::vector<Real> m_posted_mine, m_posted_all;                         ///< post_allgather()
  mutable std::vector<int> m_send_displacement, m_receive_displacement;  ///< alltoall_into()
  mutable std::vector<Real> m_chunk_mine, m_chunk_all;                   ///< share_chunks()
  struct Requests;
  std::unique_ptr<Requests> m_requests;
  mutable double m_seconds[TIMINGS] = {};
  std::vector<Index> m_ship_count;
};

}  // namespace xpl
