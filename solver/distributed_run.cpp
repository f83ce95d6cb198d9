#include "solver/distributed_run.hpp"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <utility>

#if XPL_HAVE_MPI
#include <mpi.h>

#include <thread>

#include "solver/distributed_detail.hpp"
#endif

namespace xpl {

#if XPL_HAVE_MPI

namespace {

constexpr int FORCE_TAG = 37;

}  // namespace

namespace distributed_detail {

double* g_waits = nullptr;

/// Waits for `n` requests. Not MPI_Waitall: OpenMPI spins in it, and on an oversubscribed or
/// shared machine the spinning rank takes the core from the rank it waits for (2 ranks on 2
/// loaded cores spent 70-85 % of the loop waiting). Tests for 50 us, then sleeps between
/// tests, 10 us at first, doubling up to 200 us.
/// The time from the first test to the last goes to g_waits.
void wait_all(int n, MPI_Request* requests) {
  using namespace std::chrono_literals;
  const auto start = std::chrono::steady_clock::now();
  auto pause = 10us;
  for (int done = 0;;) {
    MPI_Testall(n, requests, &done, MPI_STATUSES_IGNORE);
    if (done != 0) {
      if (g_waits != nullptr)
        *g_waits += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      return;
    }
    if (std::chrono::steady_clock::now() - start < 50us) continue;
    std::this_thread::sleep_for(pause);
    pause = std::min<std::chrono::microseconds>(2 * pause, 200us);
  }
}

void wait(MPI_Request& request) {
  wait_all(1, &request);
}

/// Waits for the requests of `requests` (completes them; cleared).
void wait_all(std::vector<MPI_Request>& requests) {
  if (requests.empty()) return;
  wait_all(static_cast<int>(requests.size()), requests.data());
  requests.clear();
}

void gather_counts(int size, int n, std::vector<int>& counts) {
  counts.assign(static_cast<std::size_t>(size), 0);
  MPI_Request request = MPI_REQUEST_NULL;
  MPI_Iallgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD, &request);
  wait(request);
}

std::vector<int> displacements(const std::vector<int>& counts) {
  std::vector<int> displacement(counts.size(), 0);
  for (std::size_t r = 1; r < counts.size(); ++r)
    displacement[r] = displacement[r - 1] + counts[r - 1];
  return displacement;
}

}  // namespace distributed_detail

using distributed_detail::ExchangeTimer;
using distributed_detail::gather_layout;
using distributed_detail::GatherLayout;
using distributed_detail::wait;
using distributed_detail::wait_all;

int DistributedRun::world_rank() {
  int initialized = 0;
  MPI_Initialized(&initialized);
  if (initialized == 0) return 0;
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  return rank;
}

int DistributedRun::world_size() {
  int initialized = 0;
  MPI_Initialized(&initialized);
  if (initialized == 0) return 1;
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  return size;
}

int DistributedRun::world_max(int value) {
  if (world_size() == 1) return value;
  // Not the blocking MPI_Allreduce, which spins (wait_all()) while rank 0 opens its files.
  int result = value;
  MPI_Request request = MPI_REQUEST_NULL;
  MPI_Iallreduce(&value, &result, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD, &request);
  wait(request);
  return result;
}

void DistributedRun::abort_world(int code) {
  if (world_size() > 1) MPI_Abort(MPI_COMM_WORLD, code);
}

namespace {
MPI_Comm end_channel = MPI_COMM_NULL;  ///< DistributedRun::open_end_channel()
}  // namespace

void DistributedRun::open_end_channel() {
  if (world_size() > 1 && end_channel == MPI_COMM_NULL) MPI_Comm_dup(MPI_COMM_WORLD, &end_channel);
}

bool DistributedRun::every_rank_ends(double seconds) {
  if (end_channel == MPI_COMM_NULL) return true;
  MPI_Request request = MPI_REQUEST_NULL;
  MPI_Ibarrier(end_channel, &request);
  const auto limit = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  int done = 0;
  // Testing and sleeping, not OpenMPI's spinning MPI_Wait (it would take a shared core).
  while (MPI_Test(&request, &done, MPI_STATUS_IGNORE) == MPI_SUCCESS && done == 0) {
    if (std::chrono::steady_clock::now() > limit) return false;  // the caller ends the job
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  return true;
}
#else
struct DistributedRun::Requests {};  // the one-rank functions: distributed_run_one_rank.cpp
#endif

std::vector<std::string> DistributedRun::refusals(const Model&, bool imported) {
  std::vector<std::string> r;
  const std::string not_yet = ": not distributed yet (issue 37); expected a run on one rank";
  if (imported) r.push_back("--import" + not_yet);
  return r;
}

DistributedRun::DistributedRun()
    : m_rank(world_rank()), m_size(world_size()), m_requests(std::make_unique<Requests>()) {}

DistributedRun::~DistributedRun() {
#if XPL_HAVE_MPI
  // Sends still in flight read buffers this object owns (their receivers have them all: every
  // rank made the same exchanges).
  if (m_requests == nullptr) return;
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (finalized != 0) return;
  for (auto* pending : {&m_requests->send, &m_requests->gather_send, &m_requests->chunk_send,
                        &m_requests->ship_send})
    wait_all(*pending);
#endif
}

void DistributedRun::set_partition(const Model& model, std::vector<int> element_part,
                                   std::vector<Index> element_order, Index chunk,
                                   const std::vector<Index>& element_body) {
  m_element_part = std::move(element_part);
  const Index n_nodes = model.node_count();
  partition::MeshPartition p;
  p.parts = m_size;
  p.element_part = m_element_part;
  // A rigid body's elements run no kernel: in no part (their nodes are every rank's).
  for (std::size_t e = 0; e < element_body.size(); ++e)
    if (element_body[e] != NO_INDEX) p.element_part[e] = -1;
  p.node_owner.assign(static_cast<std::size_t>(n_nodes), m_size);
  for (Index e = 0; e < model.element_count(); ++e)
    for (Index k = model.element_offsets[e]; k < model.element_offsets[e + 1]; ++k) {
      int& owner = p.node_owner[model.element_nodes[k]];
      if (p.element_part[e] >= 0) owner = std::min(owner, p.element_part[e]);
    }
  std::vector<unsigned char> in_element(static_cast<std::size_t>(n_nodes), 0);
  for (Index i = 0; i < n_nodes; ++i) in_element[i] = p.node_owner[i] < m_size ? 1 : 0;
  for (int& owner : p.node_owner)
    if (owner == m_size) owner = 0;  // a node of no (deformable) element: rank 0's
  m_node_owner = p.node_owner;
  partition::PartitionInput input;
  input.node_count = n_nodes;
  input.element_offsets = model.element_offsets;
  input.element_nodes = model.element_nodes;
  m_plan = partition::make_exchange_plan(input, p, element_order);
  m_in_part.assign(static_cast<std::size_t>(n_nodes), 0);
  for (const Index n : plan().nodes) m_in_part[n] = 1;

  // Each nodal chunk is counted by the rank owning most of its nodes (ties: the lowest); the
  // nodes of its chunks that no element of it uses come from their owners.
  m_chunk = chunk;
  const Index n_chunks = (n_nodes + chunk - 1) / chunk;
  m_chunk_owner.assign(static_cast<std::size_t>(n_chunks), 0);
  std::vector<Index> owned(static_cast<std::size_t>(m_size));
  for (Index c = 0; c < n_chunks; ++c) {
    std::fill(owned.begin(), owned.end(), 0);
    for (Index i = c * chunk; i < std::min(n_nodes, (c + 1) * chunk); ++i) ++owned[m_node_owner[i]];
    m_chunk_owner[c] =
        static_cast<int>(std::max_element(owned.begin(), owned.end()) - owned.begin());
  }
  m_row_source = m_node_owner;
  for (Index i = 0; i < n_nodes; ++i)
    if (in_element[i] == 0) m_row_source[i] = m_chunk_owner[i / chunk];
  std::vector<unsigned char> uses(static_cast<std::size_t>(n_nodes));
  m_ship_send.assign(static_cast<std::size_t>(m_size), {});
  m_ship_count.assign(static_cast<std::size_t>(m_size), 0);
  m_ship_receive.assign(static_cast<std::size_t>(m_size), {});
  for (int r = 0; r < m_size; ++r) {
    std::fill(uses.begin(), uses.end(), 0);
    for (const Index n : m_plan.part[r].nodes) uses[n] = 1;
    for (Index i = 0; i < n_nodes; ++i) {
      if (m_chunk_owner[i / chunk] != r || uses[i] != 0) continue;
      const int from = m_node_owner[i];
      ++m_ship_count[r];
      if (from == m_rank) m_ship_send[r].push_back(i);
      if (r == m_rank) m_ship_receive[from].push_back(i);
    }
  }
}

#if XPL_HAVE_MPI

void DistributedRun::broadcast(std::vector<int>& values) const {
  // Non-blocking, waited for without spinning (wait_all()) while rank 0 partitions.
  int n = static_cast<int>(values.size());
  MPI_Request request = MPI_REQUEST_NULL;
  MPI_Ibcast(&n, 1, MPI_INT, 0, MPI_COMM_WORLD, &request);
  wait(request);
  values.resize(static_cast<std::size_t>(n));
  MPI_Ibcast(values.data(), n, MPI_INT, 0, MPI_COMM_WORLD, &request);
  wait(request);
}

void DistributedRun::broadcast_estimate(Real& value, int& count) const {
  ExchangeTimer timer(m_seconds[GATHERS], m_seconds[WAITS]);
  Real both[2] = {value, static_cast<Real>(count)};  // an int is exact in a double
  MPI_Request request = MPI_REQUEST_NULL;
  MPI_Ibcast(both, 2, MPI_DOUBLE, 0, MPI_COMM_WORLD, &request);
  wait(request);
  value = both[0];
  count = static_cast<int>(both[1]);
}

void DistributedRun::post_receives(int width) {
  ExchangeTimer timer(m_seconds[NEIGHBOURS], m_seconds[WAITS]);
  wait_all(m_requests->send);  // the last increment's, long done: the buffers are free
  const auto& neighbours = plan().neighbours;
  m_receive.resize(neighbours.size());
  m_send.resize(neighbours.size());
  m_requests->receive.assign(neighbours.size(), MPI_REQUEST_NULL);
  for (std::size_t j = 0; j < neighbours.size(); ++j) {
    m_receive[j].resize(static_cast<std::size_t>(neighbours[j].receive_count) * width);
    m_send[j].resize(neighbours[j].send.size() * static_cast<std::size_t>(width));
    MPI_Irecv(m_receive[j].data(), static_cast<int>(m_receive[j].size()), MPI_DOUBLE,
              neighbours[j].part, FORCE_TAG, MPI_COMM_WORLD, &m_requests->receive[j]);
  }
}

void DistributedRun::send() {
  ExchangeTimer timer(m_seconds[NEIGHBOURS], m_seconds[WAITS]);
  const auto& neighbours = plan().neighbours;
  m_requests->send.assign(neighbours.size(), MPI_REQUEST_NULL);
  for (std::size_t j = 0; j < neighbours.size(); ++j)
    MPI_Isend(m_send[j].data(), static_cast<int>(m_send[j].size()), MPI_DOUBLE, neighbours[j].part,
              FORCE_TAG, MPI_COMM_WORLD, &m_requests->send[j]);
}

const std::vector<std::vector<Real>>& DistributedRun::receive() {
  // The receives only: the sends complete at the next post_receives(), so that the last rank
  // in does not wait for its neighbours to wake and take its values.
  ExchangeTimer timer(m_seconds[NEIGHBOURS], m_seconds[WAITS]);
  wait_all(static_cast<int>(m_requests->receive.size()), m_requests->receive.data());
  return m_receive;
}

std::vector<Real> DistributedRun::allgather(const std::vector<Real>& mine, std::vector<int>& counts,
                                            bool counts_known) const {
  ExchangeTimer timer(m_seconds[GATHERS], m_seconds[WAITS]);
  const int n = static_cast<int>(mine.size());
  if (!counts_known) distributed_detail::gather_counts(m_size, n, counts);
  const std::vector<int> displacement = distributed_detail::displacements(counts);
  std::vector<Real> all(static_cast<std::size_t>(displacement.back() + counts.back()));
  MPI_Request gathered = MPI_REQUEST_NULL;
  MPI_Iallgatherv(mine.data(), n, MPI_DOUBLE, all.data(), counts.data(), displacement.data(),
                  MPI_DOUBLE, MPI_COMM_WORLD, &gathered);
  wait(gathered);
  return all;
}

void DistributedRun::alltoall_into(const std::vector<Real>& send,
                                   const std::vector<int>& send_counts, std::vector<Real>& receive,
                                   const std::vector<int>& receive_counts) const {
  ExchangeTimer timer(m_seconds[GATHERS], m_seconds[WAITS]);
  m_send_displacement.assign(static_cast<std::size_t>(m_size), 0);
  m_receive_displacement.assign(static_cast<std::size_t>(m_size), 0);
  for (int r = 1; r < m_size; ++r) {
    m_send_displacement[r] = m_send_displacement[r - 1] + send_counts[r - 1];
    m_receive_displacement[r] = m_receive_displacement[r - 1] + receive_counts[r - 1];
  }
  receive.resize(static_cast<std::size_t>(m_receive_displacement.back() + receive_counts.back()));
  MPI_Request request = MPI_REQUEST_NULL;
  MPI_Ialltoallv(send.data(), send_counts.data(), m_send_displacement.data(), MPI_DOUBLE,
                 receive.data(), receive_counts.data(), m_receive_displacement.data(), MPI_DOUBLE,
                 MPI_COMM_WORLD, &request);
  wait(request);
}

std::vector<int> DistributedRun::alltoall_counts(const std::vector<int>& send_counts) const {
  ExchangeTimer timer(m_seconds[GATHERS], m_seconds[WAITS]);
  std::vector<int> receive_counts(static_cast<std::size_t>(m_size), 0);
  MPI_Request request = MPI_REQUEST_NULL;
  MPI_Ialltoall(send_counts.data(), 1, MPI_INT, receive_counts.data(), 1, MPI_INT, MPI_COMM_WORLD,
                &request);
  wait(request);
  return receive_counts;
}

void DistributedRun::ship_forces(NodalVectors& force, NodalVectors* moment) {
  ExchangeTimer timer(m_seconds[SHIP], m_seconds[WAITS]);
  const int width = moment != nullptr ? 6 : 3;
  constexpr int SHIP_TAG = 38;
  wait_all(m_requests->ship_send);  // the last increment's, long done: the buffers are free
  m_ship_send_buffer.resize(static_cast<std::size_t>(m_size));
  m_ship_receive_buffer.resize(static_cast<std::size_t>(m_size));
  std::vector<MPI_Request> requests;
  std::vector<MPI_Request>& sends = m_requests->ship_send;
  for (int r = 0; r < m_size; ++r) {
    if (m_ship_receive[r].empty()) continue;
    m_ship_receive_buffer[r].resize(m_ship_receive[r].size() * width);
    requests.emplace_back();
    MPI_Irecv(m_ship_receive_buffer[r].data(), static_cast<int>(m_ship_receive_buffer[r].size()),
              MPI_DOUBLE, r, SHIP_TAG, MPI_COMM_WORLD, &requests.back());
  }
  for (int r = 0; r < m_size; ++r) {
    if (m_ship_send[r].empty()) continue;
    std::vector<Real>& buffer = m_ship_send_buffer[r];
    buffer.clear();
    for (const Index n : m_ship_send[r]) {
      for (int c = 0; c < 3; ++c) buffer.push_back(force(n, c));
      if (moment != nullptr)
        for (int c = 0; c < 3; ++c) buffer.push_back((*moment)(n, c));
    }
    sends.emplace_back();
    MPI_Isend(buffer.data(), static_cast<int>(buffer.size()), MPI_DOUBLE, r, SHIP_TAG,
              MPI_COMM_WORLD, &sends.back());
  }
  wait_all(requests);  // the receives: the sends complete at the next call
  for (int r = 0; r < m_size; ++r) {
    const Real* in = m_ship_receive_buffer[r].data();
    for (const Index n : m_ship_receive[r]) {
      for (int c = 0; c < 3; ++c) force(n, c) = *in++;
      if (moment != nullptr)
        for (int c = 0; c < 3; ++c) (*moment)(n, c) = *in++;
    }
  }
}

void DistributedRun::share_rows(const std::vector<Index>& nodes,
                                const std::vector<const NodalVectors*>& from,
                                const std::vector<NodalVectors*>& to) const {
  ExchangeTimer timer(m_seconds[GATHERS], m_seconds[WAITS]);
  const std::size_t width = 3 * from.size();
  std::vector<std::vector<Index>> of_rank(static_cast<std::size_t>(m_size));
  for (const Index n : nodes) of_rank[m_row_source[n]].push_back(n);
  std::vector<Real> mine;
  mine.reserve(of_rank[m_rank].size() * width);
  for (const Index n : of_rank[m_rank])
    for (const NodalVectors* rows : from)
      for (int c = 0; c < 3; ++c) mine.push_back((*rows)(n, c));
  const GatherLayout g = gather_layout(
      m_size, width, [&of_rank](int r) -> const auto& { return of_rank[r]; });
  std::vector<Real> all(g.total);
  MPI_Request gathered = MPI_REQUEST_NULL;
  MPI_Iallgatherv(mine.data(), static_cast<int>(mine.size()), MPI_DOUBLE, all.data(),
                  g.counts.data(), g.displacement.data(), MPI_DOUBLE, MPI_COMM_WORLD, &gathered);
  wait(gathered);
  std::size_t k = 0;
  for (int r = 0; r < m_size; ++r)
    for (const Index n : of_rank[r])
      for (NodalVectors* rows : to)
        for (int c = 0; c < 3; ++c) (*rows)(n, c) = all[k++];
}

#endif

}  // namespace xpl
