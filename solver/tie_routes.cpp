#include "solver/tie_routes.hpp"

#include <algorithm>

namespace xpl {

TieRoutes make_tie_routes(const std::vector<std::pair<Index, Index>>& pairs,
                          const DistributedRun& run, Index n_nodes) {
  const auto size = static_cast<std::size_t>(run.size());
  const auto n = static_cast<std::size_t>(n_nodes);
  TieRoutes routes;
  routes.gathers.assign(n, 0);
  routes.follows.assign(n, 0);
  routes.ranks.resize(size);
  // lists[from][to]: the nodes whose rows `from` sends `to`, in the order both sides use.
  using Lists = std::vector<std::vector<std::vector<Index>>>;
  Lists force_lists(size, std::vector<std::vector<Index>>(size)), motion_lists = force_lists;
  std::vector<unsigned char> uses(n), master(n), slave(n), force_in(n), motion_in(n);
  std::vector<unsigned char> whole_force(n), whole_motion(n);
  for (std::size_t r = 0; r < size; ++r) {
    const int rank = static_cast<int>(r);
    for (std::vector<unsigned char>* mark :
         {&uses, &master, &slave, &force_in, &motion_in, &whole_force, &whole_motion})
      std::fill(mark->begin(), mark->end(), 0);
    for (const Index i : run.exchange_plan().part[r].nodes) uses[i] = 1;
    // The rank integrates the node from its finished force (its elements use it, or it
    // counts its chunk and receives its force): its rows are the one-rank rows.
    const auto holds = [&](Index i) { return uses[i] != 0 || run.chunk_counter(i) == rank; };
    TieRoutes::Rank& k = routes.ranks[r];
    for (const auto& [s, c] : pairs) {
      // The first design gathered every listed slave's force and corner's motion.
      if (run.row_source(s) != rank && whole_force[s] == 0) whole_force[s] = 1, ++k.whole_forces;
      if (run.row_source(c) != rank && whole_motion[c] == 0) whole_motion[c] = 1, ++k.whole_motion;
      if (holds(c)) {
        if (master[c] == 0) master[c] = 1, ++k.masters;
        // A slave this rank does not hold is integrated by its row_source(), which holds it.
        if (!holds(s) && force_in[s] == 0) {
          force_in[s] = 1;
          force_lists[static_cast<std::size_t>(run.row_source(s))][r].push_back(s);
        }
      }
      if (holds(s)) {
        if (slave[s] == 0) slave[s] = 1, ++k.slaves;
        if (!holds(c) && motion_in[c] == 0) {
          motion_in[c] = 1;
          motion_lists[static_cast<std::size_t>(run.row_source(c))][r].push_back(c);
        }
      }
    }
    if (rank == run.rank()) {
      routes.gathers = master;
      routes.follows = slave;
    }
  }
  const auto me = static_cast<std::size_t>(run.rank());
  for (DistributedRun::RowRoute* route : {&routes.forces, &routes.motion}) {
    route->send.assign(size, {});
    route->receive.assign(size, {});
  }
  for (std::size_t from = 0; from < size; ++from)
    for (std::size_t to = 0; to < size; ++to) {
      const auto forces = static_cast<Index>(force_lists[from][to].size());
      const auto motion = static_cast<Index>(motion_lists[from][to].size());
      routes.ranks[from].forces_sent += forces;
      routes.ranks[to].forces_received += forces;
      routes.ranks[from].motion_sent += motion;
      routes.ranks[to].motion_received += motion;
    }
  for (std::size_t r = 0; r < size; ++r) {
    routes.forces.send[r] = std::move(force_lists[me][r]);
    routes.forces.receive[r] = std::move(force_lists[r][me]);
    routes.motion.send[r] = std::move(motion_lists[me][r]);
    routes.motion.receive[r] = std::move(motion_lists[r][me]);
  }
  return routes;
}

}  // namespace xpl
