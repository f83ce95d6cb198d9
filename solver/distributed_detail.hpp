#pragma once
/// \file How a rank waits for the other ranks, the timing of its exchanges and the layout of a
/// gather (distributed_run.cpp, distributed_gathers.cpp). Internal to the MPI build of the solver.

#include <mpi.h>

#include <chrono>
#include <cstddef>
#include <utility>
#include <vector>

#include "solver/distributed_run.hpp"

namespace xpl::distributed_detail {

/// Where wait_all() adds the time it waits: the waits of the exchange an ExchangeTimer
/// times (only the main thread calls MPI), or nowhere outside one.
extern double* g_waits;

/// Times one exchange or collective into `seconds`, and its waits for the other ranks
/// (wait_all()) also into `waits`.
class ExchangeTimer {
 public:
  ExchangeTimer(double& seconds, double& waits)
      : m_seconds(seconds),
        m_outer(std::exchange(g_waits, &waits)),
        m_start(std::chrono::steady_clock::now()) {}
  ~ExchangeTimer() {
    m_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - m_start).count();
    g_waits = m_outer;
  }
  ExchangeTimer(const ExchangeTimer&) = delete;
  ExchangeTimer& operator=(const ExchangeTimer&) = delete;

 private:
  double& m_seconds;
  double* m_outer;
  std::chrono::steady_clock::time_point m_start;
};

/// Waits for `n` requests, testing and sleeping (distributed_run.cpp); the time goes to
/// g_waits.
void wait_all(int n, MPI_Request* requests);
/// Waits for one request (wait_all()).
void wait(MPI_Request& request);
/// Waits for the requests of `requests` (wait_all()), then clears it.
void wait_all(std::vector<MPI_Request>& requests);
/// Every rank's `n` into `counts` (size ranks; MPI_Iallgather, waited for).
void gather_counts(int size, int n, std::vector<int>& counts);
/// Where each rank's values start in a gather of `counts[r]` values from rank r (rank order).
std::vector<int> displacements(const std::vector<int>& counts);

/// Receive counts and displacements of a gather of `width` values per item of every rank
/// (`items(r)`: rank r's items), in rank order; `total` is their sum.
struct GatherLayout {
  std::vector<int> counts, displacement;
  std::size_t total = 0;
};
template <class Items>
GatherLayout gather_layout(int size, std::size_t width, Items items) {
  GatherLayout g;
  g.counts.resize(static_cast<std::size_t>(size));
  g.displacement.assign(g.counts.size(), 0);
  for (int r = 0; r < size; ++r) g.counts[r] = static_cast<int>(items(r).size() * width);
  for (int r = 1; r < size; ++r) g.displacement[r] = g.displacement[r - 1] + g.counts[r - 1];
  g.total = static_cast<std::size_t>(g.displacement.back() + g.counts.back());
  return g;
}

}  // namespace xpl::distributed_detail

namespace xpl {

/// A rank's requests in flight between the calls that start and finish an exchange.
struct DistributedRun::Requests {
  std::vector<MPI_Request> receive, send;
  /// post_allgather()'s and share_chunks()' messages, point to point; ship_forces()' sends.
  std::vector<MPI_Request> gather_receive, gather_send, chunk_receive, chunk_send, ship_send;
};

}  // namespace xpl
