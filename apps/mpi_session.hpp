#pragma once
/// \file MPI for `mpirun -np N xpl run` (XPL_MPI=ON, issue 37 item 1). Without XPL_MPI, or
/// started without a launcher (no mpirun, mpiexec or srun), the session is one rank of one,
/// does nothing and MPI is never initialised.
///
/// `xpl run` on N > 1 ranks runs distributed (apps/job.hpp, solver/distributed_run.hpp); other
/// commands run on rank 0 while ranks 1 .. N − 1 wait for its exit code, asleep (they poll a
/// non-blocking broadcast every few milliseconds instead of spinning in a blocking one, so
/// that an oversubscribed rank 0 keeps its core).

#include <string>

namespace xpl::apps {

/// MPI_Init_thread (funneled: only the main thread calls MPI) to MPI_Finalize, when a launcher
/// started the process.
class MpiSession {
 public:
  MpiSession(int* argc, char*** argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

  int rank() const { return m_rank; }
  int size() const { return m_size; }
  /// Rank 0: sends its exit code `code` to the other ranks and returns it. Other ranks: wait
  /// (asleep) for rank 0's code and return it. One call per rank, once.
  int share_exit_code(int code) const;
  /// Whether this build has MPI.
  static bool available();
  /// The .msg note of a run on N > 1 ranks: what the ranks do (rank 0 alone, for now).
  std::string note() const;

 private:
  int m_rank = 0;
  int m_size = 1;
  bool m_initialized = false;
};

}  // namespace xpl::apps
