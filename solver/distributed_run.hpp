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
///   rank's per-batch values are gathered (MPI_Allgatherv) into the whole layout on every
///   rank and reduced there by the one-rank code, in batch order.
/// - Global stable-increment estimate (Lanczos, at the start of a step and when the element
///   estimate moves): the positions are gathered on every rank from their owners and every
///   rank runs the one-rank estimate on the whole mesh.
/// - Nodal sums (ALLKE, ALLKD, ALLWK): each rank sums the nodes it owns; the ranks' sums are
///   added in rank order. Not bitwise equal to the one-rank sums (a different association):
///   within a few ulps, see docs/dev/mpi.md.
/// Output: rank 0 writes; before a frame or history row it gathers the owners' rows.

#include <memory>
#include <string>
#include <vector>

#include "partition/exchange_plan.hpp"
#include "solver/model.hpp"
#include "solver/state.hpp"

namespace xpl {

/// One rank's view of a distributed run and its MPI operations (every operation that is
/// collective must be called by every rank in the same order).
class DistributedRun {
 public:
  /// MPI's rank and size in MPI_COMM_WORLD (0 and 1 without MPI or before MPI_Init).
  static int world_rank();
  static int world_size();
  /// What keeps `model` from running distributed today (one message per feature), empty if
  /// nothing: contact, rigid bodies, ties, loads (*CLOAD, *DLOAD, *DSLOAD, gravity), an
  /// imported state.
  static std::vector<std::string> refusals(const Model& model, bool imported);

  /// The largest `value` of the ranks of MPI_COMM_WORLD (collective; `value` without MPI).
  static int world_max(int value);

  DistributedRun();
  ~DistributedRun();
  DistributedRun(const DistributedRun&) = delete;
  DistributedRun& operator=(const DistributedRun&) = delete;

  int rank() const { return m_rank; }
  int size() const { return m_size; }

  /// Rank 0's `values` on every rank.
  void broadcast(std::vector<int>& values) const;
  /// Takes the partition of the run: the part of each element (n_elements) and the position
  /// of each element in the one-rank summation order (distinct). Builds the exchange plan.
  void set_partition(const Model& model, std::vector<int> element_part,
                     std::vector<Index> element_order);
  const partition::ExchangePlan& exchange_plan() const { return m_plan; }
  const partition::PartPlan& plan() const { return m_plan.part[m_rank]; }
  const std::vector<int>& element_part() const { return m_element_part; }
  /// Whether an element of this rank uses `node`; whether this rank owns it.
  bool in_part(Index node) const { return m_in_part[node] != 0; }
  bool owns(Index node) const { return m_node_owner[node] == m_rank; }

  /// \name The force exchange of an increment: post_receives() before the element pass,
  /// then the send buffers filled (width values per slot, NeighbourExchange::send order),
  /// then exchange(): sends, waits; returns the received buffers (one per neighbour).
  void post_receives(int width);
  std::vector<std::vector<Real>>& send_buffers() { return m_send; }
  const std::vector<std::vector<Real>>& exchange();

  /// Every rank's `mine` concatenated in rank order (MPI_Allgatherv); `counts` (size()) the
  /// number of values of each rank.
  std::vector<Real> allgather(const std::vector<Real>& mine, std::vector<int>& counts) const;
  /// The rows (n_nodes × 3) of the nodes each rank owns, from their owners to rank 0.
  void gather_to_root(NodalVectors& rows) const;
  /// The same, onto every rank, from `rows` into `out`.
  void allgather_rows(const NodalVectors& rows, NodalVectors& out) const;
  /// Element rows (`width` values per element) from each element's rank to rank 0.
  void gather_elements_to_root(std::vector<Real>& rows, int width) const;
  /// The largest of the ranks' values.
  int max(int value) const;

  /// Wall time spent in this rank's exchanges and collectives, s.
  double exchange_seconds() const { return m_seconds; }

 private:
  int m_rank = 0;
  int m_size = 1;
  partition::ExchangePlan m_plan;
  std::vector<int> m_element_part;
  std::vector<int> m_node_owner;
  std::vector<unsigned char> m_in_part;
  std::vector<std::vector<Real>> m_send, m_receive;
  struct Requests;
  std::unique_ptr<Requests> m_requests;
  mutable double m_seconds = 0.0;
};

}  // namespace xpl
