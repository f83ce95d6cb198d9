// What per-contribution slots cost against today's direct scatter (issue 37 item 3;
// partition/exchange_plan.hpp), on the hex block of the element benchmark (N³ C3D8R,
// make_block.py numbering, x fastest). The element kernel is left out: every variant starts
// from the same corner forces (n_elements × 8 × 3, as an element pass holds them in
// registers) and ends with the nodal force vector.
//   scatter:   today's one-thread pass: elements colour after colour (8 colours of a block
//              by index parity, element order within a colour), force[node] += corner force.
//   all slots: every corner force stored in its slot, then a node pass sums each node's
//              slots in the fixed order (colour-major rank, then corner), /PARITH/ON for
//              every node.
//   interface: scatter, except the corners at the interface nodes of a P-part bisection,
//              which go to slots summed by a node pass over the interface nodes alone.
// All three give the same bits (checked). Prints one CSV row per variant: variant, parts,
// bytes of slot storage (values + order), thread CPU ns per increment (min and median of
// REPS).
// Built and run by benchmarks/run_slot_assembly_micro.sh.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <vector>

#include "partition/exchange_plan.hpp"

using namespace xpl;

namespace {

struct Block {
  Index n = 0;
  std::vector<Index> offsets{0}, nodes;
  std::vector<Index> color_rank;  // colour-major position of each element
  NodalVectors coordinates;
  explicit Block(Index edge) : n(edge) {
    const auto node = [&](Index i, Index j, Index k) { return i + (n + 1) * (j + (n + 1) * k); };
    coordinates.resize((n + 1) * (n + 1) * (n + 1), 3);
    for (Index k = 0; k <= n; ++k)
      for (Index j = 0; j <= n; ++j)
        for (Index i = 0; i <= n; ++i) coordinates.row(node(i, j, k)) << i, j, k;
    std::vector<Index> color;
    for (Index k = 0; k < n; ++k)
      for (Index j = 0; j < n; ++j)
        for (Index i = 0; i < n; ++i) {
          for (const Index v : {node(i, j, k), node(i + 1, j, k), node(i + 1, j + 1, k),
                                node(i, j + 1, k), node(i, j, k + 1), node(i + 1, j, k + 1),
                                node(i + 1, j + 1, k + 1), node(i, j + 1, k + 1)})
            nodes.push_back(v);
          offsets.push_back(static_cast<Index>(nodes.size()));
          color.push_back((i % 2) + 2 * (j % 2) + 4 * (k % 2));
        }
    color_rank.resize(color.size());
    Index next = 0;
    for (int c = 0; c < 8; ++c)
      for (std::size_t e = 0; e < color.size(); ++e)
        if (color[e] == c) color_rank[e] = next++;
  }
  Index elements() const { return static_cast<Index>(offsets.size()) - 1; }
  Index node_count() const { return static_cast<Index>(coordinates.rows()); }
  partition::PartitionInput input() const {
    partition::PartitionInput in;
    in.node_count = node_count();
    in.element_offsets = offsets;
    in.element_nodes = nodes;
    in.coordinates = &coordinates;
    return in;
  }
};

template <class F>
std::pair<double, double> time_ns(int reps, int increments, F&& f) {
  std::vector<double> t;
  for (int r = 0; r < reps; ++r) {
    // CPU time of this thread: the shared machine's load does not count.
    timespec t0{}, t1{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t0);
    for (int i = 0; i < increments; ++i) f();
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t1);
    t.push_back(((t1.tv_sec - t0.tv_sec) * 1e9 + (t1.tv_nsec - t0.tv_nsec)) / increments);
  }
  std::sort(t.begin(), t.end());
  return {t.front(), t[t.size() / 2]};
}

}  // namespace

int main(int argc, char** argv) {
  const Index n = argc > 1 ? std::atoi(argv[1]) : 46;
  const int parts = argc > 2 ? std::atoi(argv[2]) : 8;
  const int reps = argc > 3 ? std::atoi(argv[3]) : 7;
  const int increments = 20;
  const Block block(n);
  const Index n_el = block.elements(), n_nodes = block.node_count();
  std::vector<Index> by_rank(static_cast<std::size_t>(n_el));
  for (Index e = 0; e < n_el; ++e) by_rank[block.color_rank[e]] = e;
  std::vector<Real> corner(static_cast<std::size_t>(n_el) * 24);
  unsigned x = 12345;
  for (Real& v : corner) {
    x = x * 1664525u + 1013904223u;
    v = std::ldexp(static_cast<Real>(x >> 8) / 16777216.0 - 0.5, static_cast<int>(x % 41) - 20);
  }
  const partition::PartitionInput input = block.input();
  std::vector<Real> f_scatter(static_cast<std::size_t>(n_nodes) * 3);
  std::vector<Real> f_slots(f_scatter.size()), f_interface(f_scatter.size());

  // Today: scatter in colour order.
  const auto scatter = [&] {
    std::fill(f_scatter.begin(), f_scatter.end(), 0.0);
    for (const Index e : by_rank)
      for (int a = 0; a < 8; ++a) {
        const Index node = block.nodes[8 * e + a];
        for (int c = 0; c < 3; ++c) f_scatter[3 * node + c] += corner[24 * e + 3 * a + c];
      }
  };
  // Every node by slots.
  const partition::SlotOrder order = partition::make_slot_order(input, block.color_rank);
  std::vector<Real> slot(corner.size());
  const auto all_slots = [&] {
    for (const Index e : by_rank) std::memcpy(&slot[24 * e], &corner[24 * e], 24 * sizeof(Real));
    partition::assemble(order, slot, 3, f_slots);
  };
  // Interface nodes only.
  const partition::MeshPartition p =
      partition::partition_mesh(input, parts, partition::Method::Bisection);
  std::vector<Index> interface_rank(static_cast<std::size_t>(n_nodes), NO_INDEX);
  for (std::size_t k = 0; k < p.interface_nodes.size(); ++k)
    interface_rank[p.interface_nodes[k]] = static_cast<Index>(k);
  std::vector<Index> islot_of_corner(static_cast<std::size_t>(n_el) * 8, NO_INDEX);
  std::vector<Index> istart(p.interface_nodes.size() + 1, 0);
  for (const Index node : p.interface_nodes)
    istart[interface_rank[node] + 1] = order.node_start[node + 1] - order.node_start[node];
  for (std::size_t k = 0; k < p.interface_nodes.size(); ++k) istart[k + 1] += istart[k];
  for (const Index node : p.interface_nodes)
    for (Index k = order.node_start[node]; k < order.node_start[node + 1]; ++k)
      islot_of_corner[order.slots[k]] = istart[interface_rank[node]] + (k - order.node_start[node]);
  std::vector<Real> islot(static_cast<std::size_t>(istart.back()) * 3);
  const auto interface = [&] {
    std::fill(f_interface.begin(), f_interface.end(), 0.0);
    for (const Index e : by_rank)
      for (int a = 0; a < 8; ++a) {
        const Index s = islot_of_corner[8 * e + a];
        const Real* v = &corner[24 * e + 3 * a];
        if (s == NO_INDEX) {
          const Index node = block.nodes[8 * e + a];
          for (int c = 0; c < 3; ++c) f_interface[3 * node + c] += v[c];
        } else
          for (int c = 0; c < 3; ++c) islot[3 * s + c] = v[c];
      }
    for (std::size_t k = 0; k < p.interface_nodes.size(); ++k) {
      const Index node = p.interface_nodes[k];
      for (int c = 0; c < 3; ++c) {
        Real sum = 0.0;
        for (Index s = istart[k]; s < istart[k + 1]; ++s) sum += islot[3 * s + c];
        f_interface[3 * node + c] = sum;
      }
    }
  };

  scatter();
  all_slots();
  interface();
  if (std::memcmp(f_scatter.data(), f_slots.data(), f_slots.size() * sizeof(Real)) != 0 ||
      std::memcmp(f_scatter.data(), f_interface.data(), f_slots.size() * sizeof(Real)) != 0) {
    std::fprintf(stderr, "slot sums differ from the scatter\n");
    return 1;
  }
  const double slot_bytes =
      static_cast<double>(slot.size() * sizeof(Real) + order.slots.size() * sizeof(Index) +
                          order.node_start.size() * sizeof(Index));
  const double islot_bytes =
      // the interface slots' values, their offsets, and a slot index per interface corner (a
      // sparse per-batch table as elements/thread_partition.hpp has; the dense table of this
      // micro benchmark is simpler to write)
      static_cast<double>(islot.size() * sizeof(Real) + istart.size() * sizeof(Index) +
                          static_cast<std::size_t>(istart.back()) * sizeof(Index));
  std::printf("# %d elements, %d nodes, %zu interface nodes (%d parts), %d increments x %d reps\n",
              n_el, n_nodes, p.interface_nodes.size(), parts, increments, reps);
  std::printf("variant,parts,slot_bytes,ns_per_increment_min,ns_per_increment_median\n");
  for (int round = 0; round < 1; ++round) {
    const auto a = time_ns(reps, increments, scatter);
    const auto b = time_ns(reps, increments, all_slots);
    const auto c = time_ns(reps, increments, interface);
    std::printf("scatter,%d,0,%.0f,%.0f\n", parts, a.first, a.second);
    std::printf("all_slots,%d,%.0f,%.0f,%.0f\n", parts, slot_bytes, b.first, b.second);
    std::printf("interface,%d,%.0f,%.0f,%.0f\n", parts, islot_bytes, c.first, c.second);
  }
  return 0;
}
