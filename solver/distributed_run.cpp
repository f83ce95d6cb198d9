#include "solver/distributed_run.hpp"

#include <algorithm>
#include <chrono>
#include <stdexcept>

#if XPL_HAVE_MPI
#include <mpi.h>
#endif

namespace xpl {

namespace {

/// Times one exchange or collective into `seconds`.
class ExchangeTimer {
 public:
  explicit ExchangeTimer(double& seconds)
      : m_seconds(seconds), m_start(std::chrono::steady_clock::now()) {}
  ~ExchangeTimer() {
    m_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
  }
  ExchangeTimer(const ExchangeTimer&) = delete;
  ExchangeTimer& operator=(const ExchangeTimer&) = delete;

 private:
  double& m_seconds;
  std::chrono::steady_clock::time_point m_start;
};

}  // namespace

#if XPL_HAVE_MPI
struct DistributedRun::Requests {
  std::vector<MPI_Request> receive, send;
};

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
  int result = value;
  MPI_Allreduce(&value, &result, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  return result;
}
#else
struct DistributedRun::Requests {};

int DistributedRun::world_rank() {
  return 0;
}

int DistributedRun::world_size() {
  return 1;
}

int DistributedRun::world_max(int value) {
  return value;
}
#endif

std::vector<std::string> DistributedRun::refusals(const Model& model, bool imported) {
  std::vector<std::string> r;
  const std::string not_yet = ": not distributed yet (issue 37); expected a run on one rank";
  bool contact = !model.contact_pairs.empty(), loads = false, pressure = false, gravity = false;
  for (const Step& s : model.steps) {
    contact = contact || s.contact.has_value() || !s.contact_pairs.empty();
    loads = loads || !s.loads.empty();
    pressure = pressure || !s.pressures.empty();
    gravity = gravity || !s.gravity.empty();
  }
  if (contact) r.push_back("contact (*CONTACT, *CONTACT PAIR)" + not_yet);
  if (!model.rigid_bodies.empty()) r.push_back("*RIGID BODY" + not_yet);
  if (!model.ties.empty()) r.push_back("*TIE" + not_yet);
  if (loads) r.push_back("*CLOAD" + not_yet);
  if (pressure) r.push_back("pressure loads (*DLOAD, *DSLOAD)" + not_yet);
  if (gravity) r.push_back("gravity (*DLOAD, GRAV)" + not_yet);
  if (imported) r.push_back("--import" + not_yet);
  return r;
}

DistributedRun::DistributedRun()
    : m_rank(world_rank()), m_size(world_size()), m_requests(std::make_unique<Requests>()) {}

DistributedRun::~DistributedRun() = default;

void DistributedRun::set_partition(const Model& model, std::vector<int> element_part,
                                   std::vector<Index> element_order) {
  m_element_part = std::move(element_part);
  const Index n_nodes = model.node_count();
  partition::MeshPartition p;
  p.parts = m_size;
  p.element_part = m_element_part;
  p.node_owner.assign(static_cast<std::size_t>(n_nodes), m_size);
  for (Index e = 0; e < model.element_count(); ++e)
    for (Index k = model.element_offsets[e]; k < model.element_offsets[e + 1]; ++k) {
      int& owner = p.node_owner[model.element_nodes[k]];
      owner = std::min(owner, m_element_part[e]);
    }
  for (int& owner : p.node_owner)
    if (owner == m_size) owner = 0;  // a node of no element: rank 0's
  m_node_owner = p.node_owner;
  partition::PartitionInput input;
  input.node_count = n_nodes;
  input.element_offsets = model.element_offsets;
  input.element_nodes = model.element_nodes;
  m_plan = partition::make_exchange_plan(input, p, element_order);
  m_in_part.assign(static_cast<std::size_t>(n_nodes), 0);
  for (const Index n : plan().nodes) m_in_part[n] = 1;
}

#if XPL_HAVE_MPI

namespace {
constexpr int FORCE_TAG = 37;
}

void DistributedRun::broadcast(std::vector<int>& values) const {
  int n = static_cast<int>(values.size());
  MPI_Bcast(&n, 1, MPI_INT, 0, MPI_COMM_WORLD);
  values.resize(static_cast<std::size_t>(n));
  MPI_Bcast(values.data(), n, MPI_INT, 0, MPI_COMM_WORLD);
}

void DistributedRun::post_receives(int width) {
  ExchangeTimer timer(m_seconds);
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

const std::vector<std::vector<Real>>& DistributedRun::exchange() {
  ExchangeTimer timer(m_seconds);
  const auto& neighbours = plan().neighbours;
  m_requests->send.assign(neighbours.size(), MPI_REQUEST_NULL);
  for (std::size_t j = 0; j < neighbours.size(); ++j)
    MPI_Isend(m_send[j].data(), static_cast<int>(m_send[j].size()), MPI_DOUBLE, neighbours[j].part,
              FORCE_TAG, MPI_COMM_WORLD, &m_requests->send[j]);
  MPI_Waitall(static_cast<int>(m_requests->receive.size()), m_requests->receive.data(),
              MPI_STATUSES_IGNORE);
  MPI_Waitall(static_cast<int>(m_requests->send.size()), m_requests->send.data(),
              MPI_STATUSES_IGNORE);
  return m_receive;
}

std::vector<Real> DistributedRun::allgather(const std::vector<Real>& mine,
                                            std::vector<int>& counts) const {
  ExchangeTimer timer(m_seconds);
  counts.assign(static_cast<std::size_t>(m_size), 0);
  const int n = static_cast<int>(mine.size());
  MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, MPI_COMM_WORLD);
  std::vector<int> displacement(static_cast<std::size_t>(m_size), 0);
  for (int r = 1; r < m_size; ++r) displacement[r] = displacement[r - 1] + counts[r - 1];
  std::vector<Real> all(static_cast<std::size_t>(displacement.back() + counts.back()));
  MPI_Allgatherv(mine.data(), n, MPI_DOUBLE, all.data(), counts.data(), displacement.data(),
                 MPI_DOUBLE, MPI_COMM_WORLD);
  return all;
}

namespace {

/// The owned rows of `rows` packed node by node (3 values each).
std::vector<Real> pack_rows(const NodalVectors& rows, const std::vector<Index>& nodes) {
  std::vector<Real> packed;
  packed.reserve(nodes.size() * 3);
  for (const Index n : nodes)
    for (int c = 0; c < 3; ++c) packed.push_back(rows(n, c));
  return packed;
}

}  // namespace

void DistributedRun::gather_to_root(NodalVectors& rows) const {
  if (rows.rows() == 0) return;
  ExchangeTimer timer(m_seconds);
  const std::vector<Real> mine = pack_rows(rows, plan().owned);
  std::vector<int> counts(static_cast<std::size_t>(m_size)), displacement(counts.size(), 0);
  for (int r = 0; r < m_size; ++r) counts[r] = static_cast<int>(m_plan.part[r].owned.size() * 3);
  for (int r = 1; r < m_size; ++r) displacement[r] = displacement[r - 1] + counts[r - 1];
  std::vector<Real> all(m_rank == 0 ? static_cast<std::size_t>(displacement.back() + counts.back())
                                    : 0);
  MPI_Gatherv(mine.data(), static_cast<int>(mine.size()), MPI_DOUBLE, all.data(), counts.data(),
              displacement.data(), MPI_DOUBLE, 0, MPI_COMM_WORLD);
  if (m_rank != 0) return;
  std::size_t k = 0;
  for (int r = 0; r < m_size; ++r)
    for (const Index n : m_plan.part[r].owned)
      for (int c = 0; c < 3; ++c) rows(n, c) = all[k++];
}

void DistributedRun::allgather_rows(const NodalVectors& rows, NodalVectors& out) const {
  ExchangeTimer timer(m_seconds);
  const std::vector<Real> mine = pack_rows(rows, plan().owned);
  std::vector<int> counts(static_cast<std::size_t>(m_size)), displacement(counts.size(), 0);
  for (int r = 0; r < m_size; ++r) counts[r] = static_cast<int>(m_plan.part[r].owned.size() * 3);
  for (int r = 1; r < m_size; ++r) displacement[r] = displacement[r - 1] + counts[r - 1];
  std::vector<Real> all(static_cast<std::size_t>(displacement.back() + counts.back()));
  MPI_Allgatherv(mine.data(), static_cast<int>(mine.size()), MPI_DOUBLE, all.data(), counts.data(),
                 displacement.data(), MPI_DOUBLE, MPI_COMM_WORLD);
  out.resize(rows.rows(), 3);
  std::size_t k = 0;
  for (int r = 0; r < m_size; ++r)
    for (const Index n : m_plan.part[r].owned)
      for (int c = 0; c < 3; ++c) out(n, c) = all[k++];
}

void DistributedRun::gather_elements_to_root(std::vector<Real>& rows, int width) const {
  if (rows.empty()) return;
  ExchangeTimer timer(m_seconds);
  const auto w = static_cast<std::size_t>(width);
  std::vector<Real> mine;
  mine.reserve(plan().elements.size() * w);
  for (const Index e : plan().elements)
    mine.insert(mine.end(), rows.begin() + static_cast<std::ptrdiff_t>(e * w),
                rows.begin() + static_cast<std::ptrdiff_t>((e + 1) * w));
  std::vector<int> counts(static_cast<std::size_t>(m_size)), displacement(counts.size(), 0);
  for (int r = 0; r < m_size; ++r) counts[r] = static_cast<int>(m_plan.part[r].elements.size() * w);
  for (int r = 1; r < m_size; ++r) displacement[r] = displacement[r - 1] + counts[r - 1];
  std::vector<Real> all(m_rank == 0 ? static_cast<std::size_t>(displacement.back() + counts.back())
                                    : 0);
  MPI_Gatherv(mine.data(), static_cast<int>(mine.size()), MPI_DOUBLE, all.data(), counts.data(),
              displacement.data(), MPI_DOUBLE, 0, MPI_COMM_WORLD);
  if (m_rank != 0) return;
  std::size_t k = 0;
  for (int r = 0; r < m_size; ++r)
    for (const Index e : m_plan.part[r].elements)
      for (std::size_t c = 0; c < w; ++c) rows[e * w + c] = all[k++];
}

int DistributedRun::max(int value) const {
  ExchangeTimer timer(m_seconds);
  int result = value;
  MPI_Allreduce(&value, &result, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  return result;
}

#else

// One rank: nothing to exchange (a distributed run needs XPL_MPI=ON).
void DistributedRun::broadcast(std::vector<int>&) const {}
void DistributedRun::post_receives(int) {}
const std::vector<std::vector<Real>>& DistributedRun::exchange() {
  return m_receive;
}
std::vector<Real> DistributedRun::allgather(const std::vector<Real>& mine,
                                            std::vector<int>& counts) const {
  counts.assign(1, static_cast<int>(mine.size()));
  return mine;
}
void DistributedRun::gather_to_root(NodalVectors&) const {}
void DistributedRun::allgather_rows(const NodalVectors& rows, NodalVectors& out) const {
  out = rows;
}
void DistributedRun::gather_elements_to_root(std::vector<Real>&, int) const {}
int DistributedRun::max(int value) const {
  return value;
}

#endif

}  // namespace xpl
