// The gathers of a frame's rows to rank 0 (DistributedRun::gather_to_root,
// gather_elements_to_root): the nodal rows from each node's owner, the element rows from each
// element's rank, in rank order (`--gather-frames`, and the history's nodal rows); and the
// gathers of every increment to every rank (the batch totals, the chunk sums with the
// prescribed DOFs' rows), point to point.
#include "solver/distributed_run.hpp"

#if XPL_HAVE_MPI
#include <mpi.h>

#include <algorithm>

#include "solver/distributed_detail.hpp"

namespace xpl {

using distributed_detail::ExchangeTimer;
using distributed_detail::gather_layout;
using distributed_detail::GatherLayout;
using distributed_detail::wait;
using distributed_detail::wait_all;

namespace {

constexpr int TOTALS_TAG = 39;  // post_allgather()
constexpr int CHUNKS_TAG = 40;  // share_chunks()
/// Above this many ranks post_gather() is one MPI_Iallgatherv: N − 1 messages a rank (and
/// their latencies) would outgrow the collective's log N rounds.
constexpr int POINT_TO_POINT_RANKS = 8;

/// Starts the gather of every rank's `mine` (`counts[r]` values from rank r) into `all`
/// (resized) in rank order, point to point: `receives` complete when `all` is whole, `sends`
/// when the other ranks have `mine` (which must not change until then). Above
/// POINT_TO_POINT_RANKS ranks, one collective in `receives` and no `sends`.
void post_gather(int rank, int size, const std::vector<Real>& mine, std::vector<Real>& all,
                 const std::vector<int>& counts, int tag, std::vector<MPI_Request>& receives,
                 std::vector<MPI_Request>& sends) {
  // Point to point rather than MPI_Iallgatherv: a rank's data is in once its receives are
  // done, while a collective (and a send above the eager limit) also waits for the other
  // ranks to take this rank's data, that is for them to wake from their sleeping waits. The
  // sends complete later, before `mine` is filled again.
  const std::vector<int> displacement = distributed_detail::displacements(counts);
  all.resize(static_cast<std::size_t>(displacement.back() + counts.back()));
  receives.clear();
  sends.clear();
  if (size > POINT_TO_POINT_RANKS) {
    receives.emplace_back();
    MPI_Iallgatherv(mine.data(), static_cast<int>(mine.size()), MPI_DOUBLE, all.data(),
                    counts.data(), displacement.data(), MPI_DOUBLE, MPI_COMM_WORLD,
                    &receives.back());
    return;
  }
  std::copy(mine.begin(), mine.end(), all.begin() + displacement[rank]);
  for (int r = 0; r < size; ++r) {
    if (r == rank || counts[r] == 0) continue;
    receives.emplace_back();
    MPI_Irecv(all.data() + displacement[r], counts[r], MPI_DOUBLE, r, tag, MPI_COMM_WORLD,
              &receives.back());
  }
  for (int r = 0; r < size; ++r) {
    if (r == rank || mine.empty()) continue;
    sends.emplace_back();
    MPI_Isend(mine.data(), static_cast<int>(mine.size()), MPI_DOUBLE, r, tag, MPI_COMM_WORLD,
              &sends.back());
  }
}

/// The owned rows of `rows` packed node by node (3 values each).
std::vector<Real> pack_rows(const NodalVectors& rows, const std::vector<Index>& nodes) {
  std::vector<Real> packed;
  packed.reserve(nodes.size() * 3);
  for (const Index n : nodes)
    for (int c = 0; c < 3; ++c) packed.push_back(rows(n, c));
  return packed;
}

/// This rank's owned rows of `rows` packed (pack_rows) and the layout of every rank's owned
/// rows in rank order: the two halves of a gather of the owned rows.
struct OwnedRows {
  std::vector<Real> mine;
  GatherLayout layout;
};
OwnedRows owned_rows(const NodalVectors& rows, const partition::ExchangePlan& plan, int rank,
                     int size) {
  return {pack_rows(rows, plan.part[rank].owned),
          gather_layout(
              size, 3, [&plan](int r) -> const auto& { return plan.part[r].owned; })};
}

/// The inverse of pack_rows over every rank: `all` holds each rank's owned rows in rank order
/// (`part[r].owned`), written into `rows`.
void unpack_owned_rows(const std::vector<Real>& all, const std::vector<partition::PartPlan>& part,
                       NodalVectors& rows) {
  std::size_t k = 0;
  for (const auto& rank : part)
    for (const Index n : rank.owned)
      for (int c = 0; c < 3; ++c) rows(n, c) = all[k++];
}

/// Every rank's `mine` to rank 0 in rank order, laid out as `g` (MPI_Igatherv, waited for by
/// testing and sleeping); empty on the other ranks.
std::vector<Real> gather_on_root(const std::vector<Real>& mine, const GatherLayout& g, int rank) {
  std::vector<Real> all(rank == 0 ? g.total : 0);
  MPI_Request gathered = MPI_REQUEST_NULL;
  MPI_Igatherv(mine.data(), static_cast<int>(mine.size()), MPI_DOUBLE, all.data(), g.counts.data(),
               g.displacement.data(), MPI_DOUBLE, 0, MPI_COMM_WORLD, &gathered);
  wait(gathered);
  return all;
}

}  // namespace

void DistributedRun::gather_to_root(NodalVectors& rows) const {
  if (rows.rows() == 0) return;
  ExchangeTimer timer(m_seconds[GATHERS], m_seconds[WAITS]);
  const auto [mine, g] = owned_rows(rows, m_plan, m_rank, m_size);
  const std::vector<Real> all = gather_on_root(mine, g, m_rank);
  if (m_rank == 0) unpack_owned_rows(all, m_plan.part, rows);
}

void DistributedRun::allgather_rows(NodalVectors& rows) const {
  if (rows.rows() == 0) return;
  ExchangeTimer timer(m_seconds[GATHERS], m_seconds[WAITS]);
  const auto [mine, g] = owned_rows(rows, m_plan, m_rank, m_size);
  std::vector<Real> all(g.total);
  MPI_Request gathered = MPI_REQUEST_NULL;
  MPI_Iallgatherv(mine.data(), static_cast<int>(mine.size()), MPI_DOUBLE, all.data(),
                  g.counts.data(), g.displacement.data(), MPI_DOUBLE, MPI_COMM_WORLD, &gathered);
  wait(gathered);
  unpack_owned_rows(all, m_plan.part, rows);
}

void DistributedRun::gather_elements_to_root(std::vector<Real>& rows, int width) const {
  if (rows.empty()) return;
  ExchangeTimer timer(m_seconds[GATHERS], m_seconds[WAITS]);
  const auto w = static_cast<std::size_t>(width);
  std::vector<Real> mine;
  mine.reserve(plan().elements.size() * w);
  for (const Index e : plan().elements)
    mine.insert(mine.end(), rows.begin() + static_cast<std::ptrdiff_t>(e * w),
                rows.begin() + static_cast<std::ptrdiff_t>((e + 1) * w));
  const GatherLayout g = gather_layout(
      m_size, w, [this](int r) -> const auto& { return m_plan.part[r].elements; });
  const std::vector<Real> all = gather_on_root(mine, g, m_rank);
  if (m_rank != 0) return;
  std::size_t k = 0;
  for (int r = 0; r < m_size; ++r)
    for (const Index e : m_plan.part[r].elements)
      for (std::size_t c = 0; c < w; ++c) rows[e * w + c] = all[k++];
}

void DistributedRun::gather_nodes_to_root(const std::vector<Index>& nodes,
                                          const std::vector<NodalVectors*>& rows) const {
  std::vector<NodalVectors*> arrays;
  for (NodalVectors* a : rows)
    if (a->rows() > 0) arrays.push_back(a);
  if (nodes.empty() || arrays.empty()) return;
  ExchangeTimer timer(m_seconds[GATHERS], m_seconds[WAITS]);
  // Each rank's share of `nodes`, in the order of `nodes` (every rank finds the same lists).
  std::vector<std::vector<Index>> share(static_cast<std::size_t>(m_size));
  for (const Index n : nodes)
    for (int r = 0; r < m_size; ++r) {
      const std::vector<Index>& owned = m_plan.part[r].owned;
      if (std::binary_search(owned.begin(), owned.end(), n)) {
        share[static_cast<std::size_t>(r)].push_back(n);
        break;
      }
    }
  const std::size_t width = 3 * arrays.size();
  std::vector<Real> mine;
  mine.reserve(share[static_cast<std::size_t>(m_rank)].size() * width);
  for (const Index n : share[static_cast<std::size_t>(m_rank)])
    for (const NodalVectors* a : arrays)
      for (int c = 0; c < 3; ++c) mine.push_back((*a)(n, c));
  const GatherLayout g = gather_layout(
      m_size, width, [&share](int r) -> const auto& { return share[r]; });
  const std::vector<Real> all = gather_on_root(mine, g, m_rank);
  if (m_rank != 0) return;
  std::size_t k = 0;
  for (const auto& nodes_of_rank : share)
    for (const Index n : nodes_of_rank)
      for (NodalVectors* a : arrays)
        for (int c = 0; c < 3; ++c) (*a)(n, c) = all[k++];
}

void DistributedRun::route_rows(const RowRoute& route,
                                const std::vector<NodalVectors*>& rows) const {
  ExchangeTimer timer(m_seconds[SHIP], m_seconds[WAITS]);
  constexpr int ROUTE_TAG = 39;
  const std::size_t width = 3 * rows.size();
  std::vector<std::vector<Real>> in(static_cast<std::size_t>(m_size)), out(in.size());
  std::vector<MPI_Request> requests;
  for (int r = 0; r < m_size; ++r) {
    if (route.receive[r].empty()) continue;
    in[r].resize(route.receive[r].size() * width);
    requests.emplace_back();
    MPI_Irecv(in[r].data(), static_cast<int>(in[r].size()), MPI_DOUBLE, r, ROUTE_TAG,
              MPI_COMM_WORLD, &requests.back());
  }
  for (int r = 0; r < m_size; ++r) {
    if (route.send[r].empty()) continue;
    out[r].reserve(route.send[r].size() * width);
    for (const Index n : route.send[r])
      for (const NodalVectors* a : rows)
        for (int c = 0; c < 3; ++c) out[r].push_back((*a)(n, c));
    requests.emplace_back();
    MPI_Isend(out[r].data(), static_cast<int>(out[r].size()), MPI_DOUBLE, r, ROUTE_TAG,
              MPI_COMM_WORLD, &requests.back());
  }
  distributed_detail::wait_all(static_cast<int>(requests.size()), requests.data());
  for (int r = 0; r < m_size; ++r) {
    const Real* v = in[r].data();
    for (const Index n : route.receive[r])
      for (NodalVectors* a : rows)
        for (int c = 0; c < 3; ++c) (*a)(n, c) = *v++;
  }
}

void DistributedRun::post_allgather(std::vector<Real>& mine, const std::vector<int>& counts) {
  ExchangeTimer timer(m_seconds[GATHERS], m_seconds[WAITS]);
  wait_all(m_requests->gather_send);  // the previous call's, long done: its buffer is free
  m_posted_mine.swap(mine);
  post_gather(m_rank, m_size, m_posted_mine, m_posted_all, counts, TOTALS_TAG,
              m_requests->gather_receive, m_requests->gather_send);
}

const std::vector<Real>& DistributedRun::wait_allgather() {
  ExchangeTimer timer(m_seconds[GATHERS], m_seconds[WAITS]);
  wait_all(m_requests->gather_receive);
  return m_posted_all;
}

void DistributedRun::share_chunks(std::vector<Real>& values, int width, int blocks, int& largest,
                                  std::vector<Real>& rows, std::vector<int>& counts,
                                  bool counts_known) const {
  const auto n_chunks = m_chunk_owner.size();
  // Each rank's chunks, its `largest` (an int, exact in a double), then its rows (in
  // buffers kept between increments: the rows are 584 kB on the 46³ block's fixed face).
  std::vector<Real>& mine = m_chunk_mine;
  std::vector<Real>& all = m_chunk_all;
  {
    ExchangeTimer timer(m_seconds[GATHERS], m_seconds[WAITS]);
    wait_all(m_requests->chunk_send);  // the previous increment's, long done
  }
  mine.clear();
  for (int b = 0; b < blocks; ++b)
    for (std::size_t c = 0; c < n_chunks; ++c)
      if (m_chunk_owner[c] == m_rank)
        mine.insert(mine.end(),
                    values.begin() + static_cast<std::ptrdiff_t>((b * n_chunks + c) * width),
                    values.begin() + static_cast<std::ptrdiff_t>((b * n_chunks + c + 1) * width));
  mine.push_back(static_cast<Real>(largest));
  mine.insert(mine.end(), rows.begin(), rows.end());
  {
    ExchangeTimer timer(m_seconds[GATHERS], m_seconds[WAITS]);
    if (!counts_known)
      distributed_detail::gather_counts(m_size, static_cast<int>(mine.size()), counts);
    post_gather(m_rank, m_size, mine, all, counts, CHUNKS_TAG, m_requests->chunk_receive,
                m_requests->chunk_send);
    wait_all(m_requests->chunk_receive);
  }
  rows.clear();
  std::size_t at = 0;
  for (int r = 0; r < m_size; ++r) {
    const std::size_t end = at + static_cast<std::size_t>(counts[r]);
    for (int b = 0; b < blocks; ++b)
      for (std::size_t c = 0; c < n_chunks; ++c)
        if (m_chunk_owner[c] == r)
          for (int k = 0; k < width; ++k) values[(b * n_chunks + c) * width + k] = all[at++];
    largest = std::max(largest, static_cast<int>(all[at++]));
    rows.insert(rows.end(), all.begin() + static_cast<std::ptrdiff_t>(at),
                all.begin() + static_cast<std::ptrdiff_t>(end));
    at = end;
  }
}

}  // namespace xpl
#endif
