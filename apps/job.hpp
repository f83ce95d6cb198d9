#pragma once
/// \file One `xpl run` or `xpl check` job: read the deck (and --import), build the model,
/// run or check it, write the result files. The command line (xpl.cpp) and the in-process
/// deck fuzzer (tests/fuzz/fuzz_check.cpp) both call run_job, so the fuzzer checks decks
/// through exactly the code `xpl check` runs.

#include <csignal>
#include <exception>
#include <filesystem>
#include <string>

namespace xpl::apps {

/// Exit codes of a job (the `xpl --help` text lists them for users).
constexpr int EXIT_DONE = 0;
constexpr int EXIT_INPUT = 1;     ///< deck or --import error, nothing written
constexpr int EXIT_FAILED = 3;    ///< the analysis failed (a SolverError)
constexpr int EXIT_INTERNAL = 4;  ///< I/O or internal error
constexpr int EXIT_LOCKED = 5;    ///< another run of the job holds its lock

/// What the command line asks of a job.
struct JobArguments {
  bool check = false;  ///< `xpl check` (data check) instead of `xpl run`
  std::filesystem::path deck;
  std::filesystem::path out_dir = ".";
  int threads = 0;               ///< --threads; 0: OMP_NUM_THREADS or all cores
  double energy_limit = 10.0;    ///< --energy-limit, percent of the largest energy
  bool quiet = false;            ///< --quiet: no progress line and no summary on stdout
  std::filesystem::path import;  ///< --import: a result file to start from
  /// --partition N, or the number of MPI ranks: report the partition into N parts in the .msg
  /// (SolverOptions::partition_parts); 0: none.
  int partition = 0;
  /// A note for the .msg before the partition report (how the MPI ranks share the run).
  std::string partition_note;
  /// `xpl run` on every MPI rank, the model distributed (SolverOptions::distributed): rank 0
  /// writes the result files, the other ranks write nothing.
  bool distributed = false;
  /// --gather-frames: in a distributed run rank 0 gathers every frame's rows and writes them
  /// alone, instead of every rank writing its own into JOB.h5 (parallel HDF5).
  bool gather_frames = false;
  /// --contact-redundant: in a distributed run every rank runs the whole contact pass.
  bool contact_redundant = false;
  int rank = 0;
};

/// Runs one job; messages go to std::cerr, the progress and summary to stdout. Never throws:
/// whatever escapes (std::bad_alloc reading a deck included) is reported with its cause and
/// ends as EXIT_INTERNAL. `stop_signal` (may be null) is the SIGINT/SIGTERM flag the time loop
/// polls. Returns the exit code (EXIT_*, or 128 + the signal that stopped the run).
int run_job(const JobArguments& args, volatile std::sig_atomic_t* stop_signal) noexcept;

/// What an exception says, for the terminal and the result files (out of memory named).
std::string cause_of(const std::exception& e);

}  // namespace xpl::apps
