#pragma once
/// \file What the parts of a partition exchange each increment so that every nodal sum is
/// bitwise independent of the number of parts (issue 37 items 3 and 6; docs/dev/mpi.md).
///
/// A contribution of element e at its corner a is a *slot* (slot id = the position of that
/// corner in the element connectivity, element_offsets[e] + a). Every node sums its slots in
/// one fixed global order: by the element's order rank, then by corner (rank = the element
/// number, or e.g. the element colour of the one-thread pass, so that the order is today's).
/// A node used by one part only is summed by that part alone in that order. A node several
/// parts use (an interface node) is summed by each of them, from the part's own slots and
/// the slots its neighbours send, never from partial sums: a left fold over the same values
/// in the same order gives the same bits, whatever the number of parts (OpenRadioss'
/// /PARITH/ON idea). One exchange round per increment, no position exchange: every part that
/// uses a node integrates it itself, with the same force and mass, hence the same motion.
///
/// Ownership (the lowest part using a node, MeshPartition::node_owner) then only decides who
/// counts a node in global sums (energies, momentum) and who writes it to the results.

#include <span>
#include <vector>

#include "partition/mesh_partition.hpp"

namespace xpl::partition {

/// Every node's slots in the fixed global order (CSR over nodes).
struct SlotOrder {
  std::vector<Index> node_start;  ///< (n_nodes + 1) into slots
  std::vector<Index> slots;       ///< slot ids, node by node, each node's in the fixed order
  Index node_count() const { return static_cast<Index>(node_start.size()) - 1; }
};

/// The slot order of the elements of `input`: at each node by `element_rank[e]` (distinct
/// ranks; empty: the element number), then by corner.
SlotOrder make_slot_order(const PartitionInput& input, std::span<const Index> element_rank = {});

/// Where one contribution to an interface node comes from when a part sums it.
struct SlotSource {
  int neighbour = -1;  ///< -1: the part's own slot; else position in PartPlan::neighbours
  Index index = 0;     ///< slot id (own), or position in that neighbour's receive buffer
};

/// What a part exchanges with one neighbour part.
struct NeighbourExchange {
  int part = 0;
  std::vector<Index> nodes;  ///< the nodes both parts use, ascending
  /// This part's slots at `nodes`, node by node, each node's in the fixed order: the layout of
  /// the send buffer (width values per slot). The neighbour's receive buffer from this part.
  std::vector<Index> send;
  Index receive_count = 0;  ///< slots the neighbour sends (its `send` towards this part)
};

/// One part's view of the exchange.
struct PartPlan {
  std::vector<Index> elements;                ///< its elements, ascending
  std::vector<Index> nodes;                   ///< the nodes its elements use, ascending
  std::vector<Index> owned;                   ///< the nodes it owns, ascending
  std::vector<Index> interface_nodes;         ///< its nodes that other parts use too, ascending
  std::vector<NeighbourExchange> neighbours;  ///< parts sharing a node with it, ascending
  /// Contributions of interface node k, in the fixed order: combine[combine_start[k] ...
  /// combine_start[k + 1]).
  std::vector<Index> combine_start;
  std::vector<SlotSource> combine;
  /// Slots sent per increment (all neighbours).
  Index send_slots() const;
};

/// The exchange of a partition: the global slot order and each part's plan.
struct ExchangePlan {
  int parts = 1;
  SlotOrder order;
  std::vector<PartPlan> part;  ///< (parts)
};

/// The plan of `partition` (made by partition_mesh() from `input`), slots ordered by
/// `element_rank` as in make_slot_order(). An element whose part is negative is in no part:
/// its slots are neither summed nor sent (a rigid body's element, which has no kernel).
ExchangePlan make_exchange_plan(const PartitionInput& input, const MeshPartition& partition,
                                std::span<const Index> element_rank = {});

/// Serial reference: every node's slots summed in the fixed order (a left fold from +0),
/// `width` values per slot and per node. slot_values: (n_slots × width); nodal: (n_nodes ×
/// width), overwritten. This is the one-part result that every partition must reproduce.
void assemble(const SlotOrder& order, std::span<const Real> slot_values, int width,
              std::span<Real> nodal);

/// The send buffer of part `p` to its neighbour `j` (position in PartPlan::neighbours): its
/// slot values in NeighbourExchange::send order (only slots of p's elements are read).
std::vector<Real> pack(const ExchangePlan& plan, int p, int j, std::span<const Real> slot_values,
                       int width);

/// Part `p`'s nodal sums: its nodes' rows of `nodal` (n_nodes × width; other rows untouched)
/// from its own slots (only slots of p's elements are read) and `received[j]`, the buffer
/// neighbour j packed for it. Bitwise equal to assemble() on those rows.
void assemble_part(const ExchangePlan& plan, int p, std::span<const Real> slot_values,
                   const std::vector<std::vector<Real>>& received, int width,
                   std::span<Real> nodal);

}  // namespace xpl::partition
