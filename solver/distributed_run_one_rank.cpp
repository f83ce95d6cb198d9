// The distributed run's exchanges in a build without MPI (XPL_MPI=OFF): one rank, nothing to
// exchange; each collective returns what this rank holds.
#include "solver/distributed_run.hpp"

namespace xpl {

#if !XPL_HAVE_MPI

int DistributedRun::world_rank() {
  return 0;
}

int DistributedRun::world_size() {
  return 1;
}

int DistributedRun::world_max(int value) {
  return value;
}

void DistributedRun::abort_world(int) {}

void DistributedRun::broadcast(std::vector<int>&) const {}
void DistributedRun::broadcast_estimate(Real&, int&) const {}
void DistributedRun::post_receives(int) {}
void DistributedRun::send() {}
const std::vector<std::vector<Real>>& DistributedRun::receive() {
  return m_receive;
}
std::vector<Real> DistributedRun::allgather(const std::vector<Real>& mine, std::vector<int>& counts,
                                            bool) const {
  counts.assign(1, static_cast<int>(mine.size()));
  return mine;
}
void DistributedRun::alltoall_into(const std::vector<Real>& send, const std::vector<int>&,
                                   std::vector<Real>& receive, const std::vector<int>&) const {
  receive = send;
}
std::vector<int> DistributedRun::alltoall_counts(const std::vector<int>& send_counts) const {
  return send_counts;
}
void DistributedRun::post_allgather(std::vector<Real>& mine, const std::vector<int>&) {
  m_posted_all = mine;
}
const std::vector<Real>& DistributedRun::wait_allgather() {
  return m_posted_all;
}
void DistributedRun::gather_to_root(NodalVectors&) const {}
void DistributedRun::allgather_rows(NodalVectors&) const {}
void DistributedRun::gather_elements_to_root(std::vector<Real>&, int) const {}
void DistributedRun::open_end_channel() {}
bool DistributedRun::every_rank_ends(double) {
  return true;
}
void DistributedRun::gather_nodes_to_root(const std::vector<Index>&,
                                          const std::vector<NodalVectors*>&) const {}
void DistributedRun::ship_forces(NodalVectors&, NodalVectors*) {}
void DistributedRun::route_rows(const RowRoute&, const std::vector<NodalVectors*>&) const {}
void DistributedRun::share_chunks(std::vector<Real>&, int, int, int&, std::vector<Real>&,
                                  std::vector<int>&, bool) const {}
void DistributedRun::share_rows(const std::vector<Index>& nodes,
                                const std::vector<const NodalVectors*>& from,
                                const std::vector<NodalVectors*>& to) const {
  for (std::size_t k = 0; k < from.size(); ++k)
    for (const Index n : nodes) to[k]->row(n) = from[k]->row(n);
}

#endif

}  // namespace xpl
