// The transport costs that the scaling model of issue 37 item 6 needs (benchmarks/RESULTS.md,
// "Scale on paper"), measured with the MPI of an XPL_MPI=ON build:
//   pingpong:  ranks 0 and 1 send a message back and forth; half the round trip, per size,
//              gives the latency (small messages) and the bandwidth (large ones);
//   halo:      every rank exchanges SIZE bytes with each of its two ring neighbours by
//              MPI_Isend/MPI_Irecv and MPI_Waitall, as the interface-force exchange of one
//              increment would (exchange_plan.hpp);
//   allreduce: MPI_Allreduce of 8 doubles (min of the stable increment, energy sums): the
//              global reduction of one increment.
// Best and median of the repetitions, in CSV on rank 0. Built only with XPL_MPI=ON
// (target xpl_mpi_pingpong); run, e.g.:
//   mpirun --allow-run-as-root --oversubscribe -np 2 build/mpi/xpl_mpi_pingpong [BYTES...]
#include <mpi.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <vector>

namespace {

/// Best and median seconds per iteration of `iterations` calls of f, over `reps` repetitions
/// (each started together on every rank).
template <class F>
std::pair<double, double> timed(int reps, int iterations, F&& f) {
  std::vector<double> t;
  for (int r = 0; r < reps; ++r) {
    MPI_Barrier(MPI_COMM_WORLD);
    const double t0 = MPI_Wtime();
    for (int i = 0; i < iterations; ++i) f();
    t.push_back((MPI_Wtime() - t0) / iterations);
  }
  std::sort(t.begin(), t.end());
  return {t.front(), t[t.size() / 2]};
}

}  // namespace

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (size < 2) {
    if (rank == 0) std::fprintf(stderr, "xpl_mpi_pingpong: run on 2 or more ranks\n");
    MPI_Finalize();
    return 1;
  }
  const int reps = 7;
  if (rank == 0) std::printf("test,ranks,bytes,seconds_best,seconds_median,MB_per_s_best\n");
  std::vector<char> out(1 << 24), in(1 << 24), in2(1 << 24);
  // Message sizes: the arguments (bytes, at most 16 MiB), else 8 B to 16 MiB by 4.
  std::vector<long> sizes;
  for (int a = 1; a < argc; ++a) sizes.push_back(std::clamp(std::atol(argv[a]), 1L, 1L << 24));
  if (sizes.empty())
    for (long bytes = 8; bytes <= (1L << 24); bytes *= 4) sizes.push_back(bytes);
  for (const long bytes : sizes) {
    const int iterations = bytes <= 65536 ? 200 : bytes <= (1 << 20) ? 40 : 8;
    const int n = static_cast<int>(bytes);
    const auto pp = timed(reps, iterations, [&] {
      if (rank == 0) {
        MPI_Send(out.data(), n, MPI_CHAR, 1, 0, MPI_COMM_WORLD);
        MPI_Recv(in.data(), n, MPI_CHAR, 1, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      } else if (rank == 1) {
        MPI_Recv(in.data(), n, MPI_CHAR, 0, 0, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        MPI_Send(out.data(), n, MPI_CHAR, 0, 0, MPI_COMM_WORLD);
      }
    });
    if (rank == 0)
      std::printf("pingpong,%d,%ld,%.3e,%.3e,%.1f\n", size, bytes, pp.first / 2, pp.second / 2,
                  bytes / (pp.first / 2) / 1e6);
    const int left = (rank + size - 1) % size, right = (rank + 1) % size;
    const auto halo = timed(reps, iterations, [&] {
      MPI_Request r[4];
      MPI_Irecv(in.data(), n, MPI_CHAR, left, 1, MPI_COMM_WORLD, &r[0]);
      MPI_Irecv(in2.data(), n, MPI_CHAR, right, 2, MPI_COMM_WORLD, &r[1]);
      MPI_Isend(out.data(), n, MPI_CHAR, right, 1, MPI_COMM_WORLD, &r[2]);
      MPI_Isend(out.data(), n, MPI_CHAR, left, 2, MPI_COMM_WORLD, &r[3]);
      MPI_Waitall(4, r, MPI_STATUSES_IGNORE);
    });
    if (rank == 0)
      std::printf("halo,%d,%ld,%.3e,%.3e,%.1f\n", size, bytes, halo.first, halo.second,
                  2.0 * bytes / halo.first / 1e6);
  }
  double local[8] = {1, 2, 3, 4, 5, 6, 7, static_cast<double>(rank)}, global[8];
  const auto ar = timed(
      reps, 2000, [&] { MPI_Allreduce(local, global, 8, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD); });
  if (rank == 0)
    std::printf("allreduce,%d,64,%.3e,%.3e,%.1f\n", size, ar.first, ar.second, 64 / ar.first / 1e6);
  MPI_Finalize();
  return 0;
}
