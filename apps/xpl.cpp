// xpl command line: `xpl run DECK.inp [-o DIR] [--threads N] [--quiet] [--import PREV.h5]`,
// `xpl check DECK.inp`; the result-file tools `xpl compare` and `xpl history` are in
// compare.cpp and history.cpp, the benchmark `xpl bench` in bench.cpp.

#include <omp.h>

#include <unistd.h>

#include <cmath>
#include <csignal>
#include <cstdlib>
#include <iostream>
#include <stdexcept>
#include <string>
#include <vector>

#include "contact/slot_sleep.hpp"
#include "job.hpp"
#include "mpi_session.hpp"
#include "subcommands.hpp"

namespace {

/// Most OpenMP threads --threads accepts: more than the hardware threads of any machine xpl
/// runs on (libgomp itself fails to start a team of ~40,000 and crashes at 65,536).
constexpr int MAX_THREADS = 1024;

/// Most parts --partition accepts.
constexpr int MAX_PARTS = 65536;

/// `xpl run --help`: the run's synopsis and options.
constexpr const char* RUN_USAGE =
    "usage: xpl run DECK.inp [-o DIR] [--threads N] [--quiet] [--import PREV.h5]\n"
    "               [--energy-limit PERCENT] [--partition N]\n"
    "\n"
    "Reads the deck, runs every step and writes JOB.h5, JOB.xdmf (ParaView), JOB.sta,\n"
    "JOB.msg and JOB.summary.json into DIR; JOB is the deck's file name without its\n"
    "extension. A deck without output requests gets the last frame of each step (U, V, S,\n"
    "PEEQ where plastic) and the energy history, with a warning.\n"
    "  -o DIR  directory for the result files (default: the current directory)\n"
    "  --threads N  OpenMP threads (default: OMP_NUM_THREADS or all cores; one thread for\n"
    "               models of fewer than 10,000 elements); more than the cores is warned of\n"
    "  --quiet      no progress line and no summary on the terminal\n"
    "  --import PREV.h5  start from the last frame of an earlier result of the same mesh\n"
    "               (positions, velocities, stresses); penetrations there become contact\n"
    "               offsets without force\n"
    "  --energy-limit PERCENT  the run fails (exit 3) when ETOTAL drifts by more than\n"
    "               PERCENT of the largest energy (default 10; a drift above 1 % is warned\n"
    "               of once in JOB.msg and JOB.sta)\n"
    "  --partition N  report in JOB.msg how the model would be split into N parts for a\n"
    "               distributed run (elements, owned and interface nodes, imbalance per\n"
    "               part); the run itself is unchanged\n"
    "  --gather-frames  under mpirun -np N > 1: rank 0 gathers each frame and writes it\n"
    "               alone (default: every rank writes its nodes and elements into JOB.h5,\n"
    "               parallel HDF5)\n"
    "  --contact-redundant  under mpirun -np N > 1: every rank runs the whole contact\n"
    "               pass (default: each rank searches the contact nodes it integrates and\n"
    "               the ranks exchange the results, two collectives more per increment)\n"
    "Under mpirun -np N > 1 (a build with XPL_MPI=ON) the run is distributed over the N\n"
    "ranks, its results bitwise those of one rank (docs/dev/mpi.md).\n"
    "A run holds DIR/JOB.lck; a second run of the job in DIR is refused. SIGINT/SIGTERM end\n"
    "the run after the current increment with its last frame written (status interrupted).\n"
    "OpenMP threads wait passively (OMP_WAIT_POLICY=PASSIVE: they sleep instead of\n"
    "spinning, so a second job on the machine keeps its core) unless OMP_WAIT_POLICY or\n"
    "GOMP_SPINCOUNT is set; OMP_WAIT_POLICY=ACTIVE lets them spin (a little faster on a\n"
    "machine with nothing else to run).\n"
    "Exit codes: 0 done, 1 deck or --import error, 2 usage, 3 the analysis failed,\n"
    "  4 I/O or internal error, 5 the job is already running, 130/143 SIGINT/SIGTERM.\n";

/// `xpl check --help`.
constexpr const char* CHECK_USAGE =
    "usage: xpl check DECK.inp [-o DIR] [--quiet] [--import PREV.h5] [--partition N]\n"
    "\n"
    "Data check: reads the deck, builds the model (contact search, initial overclosures),\n"
    "writes frame 0, JOB.sta, JOB.msg and JOB.summary.json into DIR and stops before the\n"
    "first increment. Every error in the deck is reported, as deck.inp:LINE: *KEYWORD: ...\n"
    "  -o DIR  directory for the result files (default: the current directory)\n"
    "  --quiet      no summary on the terminal\n"
    "  --partition N  report in JOB.msg how the model would be split into N parts (as run)\n"
    "Exit codes: 0 checked, 1 deck or --import error, 2 usage, 4 I/O or internal error,\n"
    "  5 the job is already running.\n";

/// `xpl --help`: every command's synopsis.
constexpr const char* USAGE =
    "usage: xpl run DECK.inp [-o DIR] [--threads N] [--quiet] [--import PREV.h5]\n"
    "               [--energy-limit PERCENT] [--partition N]\n"
    "       xpl check DECK.inp [-o DIR]\n"
    "       xpl compare REF.h5 NEW.h5 [--rtol R] [--atol A] [--ftol F] [--history]\n"
    "                   [--fields U,S,...] [--frames last|all] [--json]\n"
    "       xpl history JOB.h5 [--step N] [--csv FILE]\n"
    "       xpl bench [--repeat N] [--quick] [--json] [--models NAME,...]\n"
    "       xpl --help | --version\n"
    "       xpl COMMAND --help   (the command's options)\n"
    "\n"
    "  run      read the deck, run every step, write JOB.h5, JOB.xdmf, JOB.sta, JOB.msg\n"
    "  check    data check: read the deck, build the model, write frame 0 and the logs,\n"
    "           stop before the first increment\n"
    "  compare  compare two result files for a regression test (exit 0 equal within the\n"
    "           tolerances, 1 different, 2 unusable input)\n"
    "  history  every history series of a result as CSV\n"
    "  bench    the standard benchmark models, built in memory, timed with 1 and 2 threads\n"
    "Every run and check writes JOB.summary.json (status, timing, energies).\n"
    "OpenMP threads sleep at barriers (OMP_WAIT_POLICY=PASSIVE) unless OMP_WAIT_POLICY or\n"
    "GOMP_SPINCOUNT is set (xpl run --help says more).\n"
    "Exit codes: 0 done, 1 deck or --import error, 2 usage, 3 the analysis failed,\n"
    "  4 I/O or internal error, 5 the job is already running, 130/143 SIGINT/SIGTERM.\n";

/// The commands xpl knows, for the message about an unknown one.
constexpr const char* COMMANDS = "run, check, compare, history or bench";

bool is_help(const std::string& word) {
  return word == "--help" || word == "-h";
}

/// Whether the user chose how OpenMP threads wait (OMP_WAIT_POLICY or GOMP_SPINCOUNT set).
bool wait_policy_chosen() {
  return std::getenv("OMP_WAIT_POLICY") != nullptr || std::getenv("GOMP_SPINCOUNT") != nullptr;
}

#if XPL_STATIC_OPENMP
/// Makes OpenMP threads sleep at barriers instead of spinning, unless the user chose. libgomp
/// reads OMP_WAIT_POLICY once, in its initialiser. Linked statically (CMakeLists.txt,
/// XPL_STATIC_OPENMP), that initialiser is one of the program's constructors of default
/// priority; the linker orders constructors by priority, so this one (101, the first a
/// program may use) sets the variable before libgomp reads it, and after the C library has
/// set up the environment (which a .preinit_array function would be too early for: glibc
/// sets `environ` in its own initialiser). The variable stays set for child processes, as
/// the re-exec below leaves it. tests/apps/check_wait_policy.py checks both.
__attribute__((constructor(101))) void default_to_passive_wait() {
  if (!wait_policy_chosen()) setenv("OMP_WAIT_POLICY", "PASSIVE", 1);
}
#else
/// As above, with a shared libgomp, which reads its environment when it is loaded, before any
/// code of xpl runs: xpl sets OMP_WAIT_POLICY=PASSIVE and executes itself again; the second
/// time the variable is set and this returns. If the exec fails, the run goes on with the
/// runtime's default.
void default_to_passive_wait(char** argv) {
  if (wait_policy_chosen()) return;
  if (setenv("OMP_WAIT_POLICY", "PASSIVE", 1) != 0) return;
  execv("/proc/self/exe", argv);
}
#endif

/// The signal that asks the run to stop (SIGINT/SIGTERM), 0 until one arrives. The handler
/// only sets it; the time loop looks at it once per increment.
volatile std::sig_atomic_t g_stop_signal = 0;

extern "C" void on_stop_signal(int signal) {
  g_stop_signal = signal;
}

/// SIGINT and SIGTERM end the run after the current increment instead of killing it.
void install_stop_handlers() {
  struct sigaction action {};
  action.sa_handler = on_stop_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;  // a write the signal interrupts goes on
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

struct Arguments : xpl::apps::JobArguments {
  std::string command;
  bool help = false;  ///< --help among the words: print the command's usage, exit 0
};

/// Parses argv; returns false (after printing why) on a usage error.
bool parse(int argc, char** argv, Arguments& args) {
  std::vector<std::string> words(argv + 1, argv + argc);
  if (words.empty()) {
    std::cerr << USAGE;
    return false;
  }
  args.command = words[0];
  for (std::size_t i = 1; i < words.size(); ++i) {
    const std::string& w = words[i];
    if (is_help(w)) {
      args.help = true;
      return true;
    }
    auto value = [&](const char* what) -> const std::string* {
      if (i + 1 >= words.size()) {
        std::cerr << "xpl: " << w << " needs " << what << "\n";
        return nullptr;
      }
      return &words[++i];
    };
    if (w == "-o" || w == "--output") {
      const std::string* v = value("a directory");
      if (!v) return false;
      args.out_dir = *v;
    } else if (w == "--threads") {
      const std::string* v = value("a number");
      if (!v) return false;
      try {
        std::size_t used = 0;
        args.threads = std::stoi(*v, &used);
        if (used != v->size() || args.threads < 1 || args.threads > MAX_THREADS)
          throw std::invalid_argument(*v);
      } catch (const std::exception&) {
        std::cerr << "xpl: --threads: '" << *v << "' is not a whole number from 1 to "
                  << MAX_THREADS << "\n";
        return false;
      }
    } else if (w == "--energy-limit") {
      const std::string* v = value("a percentage");
      if (!v) return false;
      try {
        std::size_t used = 0;
        args.energy_limit = std::stod(*v, &used);
        if (used != v->size() || !(args.energy_limit > 0.0) || !std::isfinite(args.energy_limit))
          throw std::invalid_argument(*v);
      } catch (const std::exception&) {
        std::cerr << "xpl: --energy-limit: '" << *v
                  << "' is not a finite number > 0 (a percentage, such as 10 for 10 %)\n";
        return false;
      }
    } else if (w == "--partition") {
      const std::string* v = value("a number of parts");
      if (!v) return false;
      try {
        std::size_t used = 0;
        args.partition = std::stoi(*v, &used);
        if (used != v->size() || args.partition < 1 || args.partition > MAX_PARTS)
          throw std::invalid_argument(*v);
      } catch (const std::exception&) {
        std::cerr << "xpl: --partition: '" << *v << "' is not a whole number from 1 to "
                  << MAX_PARTS << "\n";
        return false;
      }
    } else if (w == "--import") {
      const std::string* v = value("a result file (.h5)");
      if (!v) return false;
      args.import = *v;
    } else if (w == "--quiet" || w == "-q") {
      args.quiet = true;
    } else if (w == "--gather-frames" && args.command == "run") {
      args.gather_frames = true;
    } else if (w == "--contact-redundant" && args.command == "run") {
      args.contact_redundant = true;
    } else if (!w.empty() && w[0] == '-') {
      std::cerr << "xpl " << args.command << ": unknown option '" << w << "'\n"
                << (args.command == "check" ? CHECK_USAGE : RUN_USAGE);
      return false;
    } else if (args.deck.empty()) {
      args.deck = w;
    } else {
      std::cerr << "xpl: more than one deck given ('" << w << "')\n";
      return false;
    }
  }
  if (args.deck.empty()) {
    std::cerr << "xpl " << args.command << ": no deck given\n"
              << (args.command == "check" ? CHECK_USAGE : RUN_USAGE);
    return false;
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
#if !XPL_STATIC_OPENMP
  default_to_passive_wait(argv);  // first of all: before anything starts OpenMP threads
#endif
  if (argc == 2 && is_help(argv[1])) {
    std::cout << USAGE;
    return 0;
  }
  if (argc == 2 && std::string(argv[1]) == "--version") {
    std::cout << "xpl " << XPL_VERSION << "\n";
    return 0;
  }
  if (argc < 2) {
    std::cerr << USAGE;
    return 2;
  }
  const std::string command = argv[1];
  if (command == "compare" || command == "history" || command == "bench") {
    const std::vector<std::string> rest(argv + 2, argv + argc);
    try {
      if (command == "bench") return xpl::apps::bench_main(rest);
      return command == "compare" ? xpl::apps::compare_main(rest) : xpl::apps::history_main(rest);
    } catch (const std::exception& e) {
      std::cerr << "xpl " << command << ": error: " << xpl::apps::cause_of(e) << "\n";
      return xpl::apps::EXIT_INTERNAL;
    }
  }
  if (command != "run" && command != "check") {
    std::cerr << "xpl: unknown command '" << command << "'; expected " << COMMANDS << "\n" << USAGE;
    return 2;
  }
  Arguments args;
  if (!parse(argc, argv, args)) return 2;
  try {
    (void)xpl::contact::sleep_mode_from_environment();  // a bad setting is a usage error
  } catch (const std::invalid_argument& e) {
    std::cerr << "xpl: " << e.what() << "\n";
    return 2;
  }
  if (args.help) {
    std::cout << (command == "check" ? CHECK_USAGE : RUN_USAGE);
    return 0;
  }
  // mpirun -np N (XPL_MPI=ON): rank 0 runs the job, the others wait for its exit code
  // (mpi_session.hpp); one rank runs exactly as without MPI.
  // `xpl run` under mpirun -np N > 1 runs distributed on every rank (job.hpp); `xpl check`
  // runs on rank 0 while the others wait.
  const xpl::apps::MpiSession mpi(&argc, &argv);
  args.distributed = mpi.size() > 1 && command == "run";
  args.rank = mpi.rank();
  if (args.distributed && mpi.rank() != 0) {
    args.quiet = true;
    std::cerr.setstate(std::ios::failbit);  // rank 0 reports; the others would repeat it
  }
  if (!args.distributed && mpi.rank() != 0) return mpi.share_exit_code(0);
  if (mpi.size() > 1 && !args.distributed) {
    if (args.partition == 0) args.partition = mpi.size();
    args.partition_note = mpi.note();
  }
  if (args.threads > omp_get_num_procs())
    std::cerr << "xpl: warning: --threads " << args.threads << " is more than the "
              << omp_get_num_procs()
              << " core(s) available: the threads take turns on the cores and every barrier "
                 "waits for a descheduled one (slower; the results are the same)\n";
  install_stop_handlers();
  args.check = command == "check";
  return mpi.share_exit_code(xpl::apps::run_job(args, &g_stop_signal));
}
