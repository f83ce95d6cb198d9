#include "mpi_session.hpp"

#include "solver/distributed_run.hpp"

#if XPL_HAVE_MPI
#include <mpi.h>

#include <chrono>
#include <cstdlib>
#include <thread>
#endif

namespace xpl::apps {

#if XPL_HAVE_MPI

namespace {

/// Whether a launcher started this process as a rank: mpirun/mpiexec of OpenMPI (and its
/// PMIx), MPICH's Hydra (PMI) or srun set one of these.
bool launched_as_rank() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE", "PMI_FD"})
    if (std::getenv(name) != nullptr) return true;
  return false;
}

}  // namespace

MpiSession::MpiSession(int* argc, char*** argv) {
  // Started without a launcher: one rank, exactly as without MPI. A singleton MPI_Init would
  // cost 0.4-0.5 s of start-up per run here and start OpenMPI's PMIx server, whose shared
  // state a killed run can leave behind (CI saw every later singleton fail with PMIx
  // "OUT-OF-RESOURCE" after a timed-out mpirun).
  if (!launched_as_rank()) return;
  m_initialized = true;
  int provided = 0;
  MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided);
  MPI_Comm_rank(MPI_COMM_WORLD, &m_rank);
  MPI_Comm_size(MPI_COMM_WORLD, &m_size);
  DistributedRun::open_end_channel();
}

MpiSession::~MpiSession() {
  if (m_initialized) MPI_Finalize();
}

int MpiSession::share_exit_code(int code) const {
  if (m_size == 1) return code;
  int shared = m_rank == 0 ? code : 0;
  MPI_Request request = MPI_REQUEST_NULL;
  MPI_Ibcast(&shared, 1, MPI_INT, 0, MPI_COMM_WORLD, &request);
  int done = 0;
  // Not MPI_Wait: OpenMPI spins in it, and the idle ranks would take the cores from rank 0.
  while (MPI_Test(&request, &done, MPI_STATUS_IGNORE) == MPI_SUCCESS && done == 0)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  return shared;
}

bool MpiSession::available() {
  return true;
}

#else

MpiSession::MpiSession(int*, char***) {}

MpiSession::~MpiSession() = default;

int MpiSession::share_exit_code(int code) const {
  return code;
}

bool MpiSession::available() {
  return false;
}

#endif

std::string MpiSession::note() const {
  const std::string idle =
      m_size == 2 ? "rank 1 waits" : "ranks 1-" + std::to_string(m_size - 1) + " wait";
  return "mpi: " + std::to_string(m_size) +
         " ranks; the model is not distributed yet (issue 37 items 3-5): rank 0 runs the whole "
         "model and writes every result file, " +
         idle + " idle; the partition below is the one a distributed run would use";
}

}  // namespace xpl::apps
