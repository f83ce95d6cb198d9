#include "partition/metis_graph.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#if XPL_HAVE_METIS
#include <metis.h>
#endif

namespace xpl::partition {

#if XPL_HAVE_METIS

std::vector<int> metis_parts(const ElementGraph& graph, int parts) {
  idx_t n_vertices = graph.vertex_count();
  idx_t constraints = 1;
  idx_t n_parts = parts;
  std::vector<idx_t> xadj(graph.offsets.begin(), graph.offsets.end());
  std::vector<idx_t> adjncy(graph.neighbours.begin(), graph.neighbours.end());
  // Integer weights: element costs are relative to a C3D8R (1.0); hundredths keep the ratio
  // of the kinds, and a rigid element (cost 0) still counts as 1.
  std::vector<idx_t> vwgt(graph.weight.size());
  for (std::size_t v = 0; v < vwgt.size(); ++v)
    vwgt[v] = std::max<idx_t>(1, static_cast<idx_t>(std::lround(100.0 * graph.weight[v])));
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_NUMBERING] = 0;
  options[METIS_OPTION_SEED] = 37;  // fixed: the same graph gives the same parts
  idx_t cut = 0;
  std::vector<idx_t> part(graph.weight.size(), 0);
  const int status =
      METIS_PartGraphKway(&n_vertices, &constraints, xadj.data(), adjncy.data(), vwgt.data(),
                          nullptr, nullptr, &n_parts, nullptr, nullptr, options, &cut, part.data());
  if (status != METIS_OK)
    throw std::runtime_error("METIS_PartGraphKway failed (status " + std::to_string(status) +
                             ") on " + std::to_string(n_vertices) + " vertices, " +
                             std::to_string(parts) + " parts");
  return {part.begin(), part.end()};
}

#else

std::vector<int> metis_parts(const ElementGraph&, int) {
  throw std::runtime_error("this build has no METIS (configure with -DXPL_MPI=ON)");
}

#endif

}  // namespace xpl::partition

namespace xpl::partition {

bool metis_available() {
  return XPL_HAVE_METIS != 0;
}

}  // namespace xpl::partition
