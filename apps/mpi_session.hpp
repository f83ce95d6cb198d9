#pragma once
/// \file MPI for `mpirun -np N xpl run` (XPL_MPI=ON, issue 37 item 1). Without XPL_MPI the
/// session is one rank of one and does nothing.
///
/// For now the model is not distributed: rank 0 runs the whole job (the result files are
/// its own, exactly as without MPI) and reports the partition it would use for N ranks in
/// the .msg; ranks 1 .. N − 1 read nothing, write nothing and wait for rank 0's exit code,
/// asleep (they poll a non-blocking broadcast every few milliseconds instead of spinning in a
/// blocking one, so that an oversubscribed rank 0 keeps its core).

#include <string>

namespace xpl::apps {

/// MPI_Init_thread (funneled: only the main thread calls MPI) to MPI_Finalize.
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
};

}  // namespace xpl::apps
