// xpl command line: `xpl run DECK.inp [-o DIR] [--threads N] [--quiet] [--import PREV.h5]`,
// `xpl check DECK.inp`; the result-file tools `xpl compare` and `xpl history` are in
// compare.cpp and history.cpp.

#include <omp.h>

#include <unistd.h>

#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <new>
#include <optional>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "io/deck/deck_reader.hpp"
#include "io/results/import_state.hpp"
#include "io/results/job_lock.hpp"
#include "io/results/result_files.hpp"
#include "solver/explicit_solver.hpp"
#include "solver/thread_team.hpp"
#include "subcommands.hpp"

namespace {

constexpr const char* USAGE =
    "usage: xpl run DECK.inp [-o DIR] [--threads N] [--quiet] [--import PREV.h5]\n"
    "               [--energy-limit PERCENT]\n"
    "       xpl check DECK.inp [-o DIR]\n"
    "       xpl compare REF.h5 NEW.h5 [--rtol R] [--atol A] [--ftol F] [--history]\n"
    "                   [--fields U,S,...] [--frames last|all] [--json]\n"
    "       xpl history JOB.h5 [--step N] [--csv FILE]\n"
    "       xpl --help | --version\n"
    "\n"
    "  run     read the deck, run every step, write JOB.h5, JOB.xdmf, JOB.sta, JOB.msg\n"
    "  check   data check: read the deck, build the model, write frame 0 and the logs,\n"
    "          stop before the first increment\n"
    "  -o DIR  directory for the result files (default: the current directory)\n"
    "  --threads N  OpenMP threads (default: OMP_NUM_THREADS or all cores; one thread for\n"
    "               models of fewer than 2000 elements); more than the cores is warned of\n"
    "  --quiet      no progress line and no summary on the terminal\n"
    "  --import PREV.h5  start from the last frame of an earlier result of the same mesh\n"
    "               (positions, velocities, stresses); penetrations there become contact\n"
    "               offsets without force\n"
    "  --energy-limit PERCENT  the run fails (exit 3) when ETOTAL drifts by more than\n"
    "               PERCENT of the largest energy (default 10; a drift above 1 % is warned\n"
    "               of once in JOB.msg and JOB.sta)\n"
    "  compare  compare two result files for a regression test: a value passes when\n"
    "          |new - ref| <= A + R |ref| + F max|ref of the dataset| (default 0);\n"
    "          history on REF's times\n"
    "          (NEW interpolated), fields of the last frame (--frames all: every frame),\n"
    "          nodes and elements matched by id; --history / --fields U,S select (default:\n"
    "          everything); --json: the report as JSON. Exit 0 all pass, 1 something\n"
    "          differs, 2 unusable input (missing, not HDF5, other mesh, failed or\n"
    "          truncated run)\n"
    "  history  every history series as CSV (time, then RF2@N17, ALLKE, ...), all steps or\n"
    "          --step N, to stdout or --csv FILE\n"
    "Every run and check writes JOB.summary.json (status, timing, energies).\n"
    "The job name is the deck's file name without its extension. A run holds DIR/JOB.lck;\n"
    "a second run of the job in DIR is refused. SIGINT/SIGTERM end the run after the\n"
    "current increment with its last frame written (status interrupted).\n"
    "OpenMP threads wait passively (OMP_WAIT_POLICY=PASSIVE: they sleep instead of\n"
    "spinning, so a second job on the machine keeps its core) unless OMP_WAIT_POLICY or\n"
    "GOMP_SPINCOUNT is set; OMP_WAIT_POLICY=ACTIVE lets them spin (a little faster on a\n"
    "machine with nothing else to run).\n"
    "Exit codes: 0 done, 1 deck or --import error, 2 usage, 3 the analysis failed,\n"
    "  4 I/O or internal error, 5 the job is already running, 130/143 SIGINT/SIGTERM.\n";

/// Makes OpenMP threads sleep at barriers instead of spinning, unless the user chose
/// (OMP_WAIT_POLICY or GOMP_SPINCOUNT set). libgomp reads its environment when it is loaded,
/// before main, so xpl sets OMP_WAIT_POLICY=PASSIVE and executes itself again; the second
/// time the variable is set and this returns. If the exec fails, the run goes on with the
/// runtime's default.
void default_to_passive_wait(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY") != nullptr || std::getenv("GOMP_SPINCOUNT") != nullptr) return;
  if (setenv("OMP_WAIT_POLICY", "PASSIVE", 1) != 0) return;
  execv("/proc/self/exe", argv);
}

/// Exit code of a run refused because another run of the job holds its lock.
constexpr int EXIT_LOCKED = 5;

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

/// What an exception says, for the terminal and the result files.
std::string cause_of(const std::exception& e) {
  if (dynamic_cast<const std::bad_alloc*>(&e) != nullptr)
    return std::string("out of memory (") + e.what() + ")";
  return e.what();
}

struct Arguments {
  std::string command;
  std::filesystem::path deck;
  std::filesystem::path out_dir = ".";
  int threads = 0;
  double energy_limit = 10.0;  ///< --energy-limit, percent of the largest energy
  bool quiet = false;
  std::filesystem::path import;  ///< --import: a result file to start from
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
        if (used != v->size() || args.threads < 1) throw std::invalid_argument(*v);
      } catch (const std::exception&) {
        std::cerr << "xpl: --threads: '" << *v << "' is not a positive whole number\n";
        return false;
      }
    } else if (w == "--energy-limit") {
      const std::string* v = value("a percentage");
      if (!v) return false;
      try {
        std::size_t used = 0;
        args.energy_limit = std::stod(*v, &used);
        if (used != v->size() || !(args.energy_limit > 0.0) || args.energy_limit > 1e6)
          throw std::invalid_argument(*v);
      } catch (const std::exception&) {
        std::cerr << "xpl: --energy-limit: '" << *v
                  << "' is not a percentage > 0 (such as 10 for 10 %)\n";
        return false;
      }
    } else if (w == "--import") {
      const std::string* v = value("a result file (.h5)");
      if (!v) return false;
      args.import = *v;
    } else if (w == "--quiet" || w == "-q") {
      args.quiet = true;
    } else if (!w.empty() && w[0] == '-') {
      std::cerr << "xpl: unknown option '" << w << "'\n" << USAGE;
      return false;
    } else if (args.deck.empty()) {
      args.deck = w;
    } else {
      std::cerr << "xpl: more than one deck given ('" << w << "')\n";
      return false;
    }
  }
  if (args.deck.empty()) {
    std::cerr << "xpl: " << args.command << ": no deck given\n" << USAGE;
    return false;
  }
  return true;
}

/// Peak resident memory of this process in MB (VmHWM), or 0 if unknown.
double peak_memory_mb() {
  std::ifstream status("/proc/self/status");
  std::string key;
  while (status >> key) {
    if (key == "VmHWM:") {
      double kb = 0.0;
      status >> kb;
      return kb / 1024.0;
    }
    status.ignore(1 << 20, '\n');
  }
  return 0.0;
}

void print_summary(const xpl::RunSummary& s, const xpl::Model& model, int threads) {
  std::printf("xpl: element cycles per second: %.6e (%d elements x %ld increments, %d threads)\n",
              s.element_cycles_per_second, model.element_count(), s.increments, threads);
  for (int p = 0; p < static_cast<int>(xpl::Phase::COUNT); ++p) {
    const auto phase = static_cast<xpl::Phase>(p);
    std::printf("xpl: phase %s: %.3f s\n", std::string(xpl::phase_name(phase)).c_str(),
                s.timers.seconds(phase));
  }
  std::printf("xpl: largest energy balance drift: %.3g %% of the largest energy (t = %.6g s)\n",
              100.0 * s.energy_drift, s.energy_drift_time);
  std::printf("xpl: peak memory: %.1f MB\n", peak_memory_mb());
}

/// Reads the deck (and --import), then runs or checks it; returns the exit code.
int run_job(const Arguments& args);

}  // namespace

int main(int argc, char** argv) {
  default_to_passive_wait(argv);  // first of all: before anything starts OpenMP threads
  if (argc >= 2 && (std::string(argv[1]) == "compare" || std::string(argv[1]) == "history")) {
    const std::vector<std::string> rest(argv + 2, argv + argc);
    try {
      return std::string(argv[1]) == "compare" ? xpl::apps::compare_main(rest)
                                               : xpl::apps::history_main(rest);
    } catch (const std::exception& e) {
      std::cerr << "xpl " << argv[1] << ": error: " << cause_of(e) << "\n";
      return 4;
    }
  }
  if (argc == 2 && (std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h")) {
    std::cout << USAGE;
    return 0;
  }
  if (argc == 2 && std::string(argv[1]) == "--version") {
    std::cout << "xpl " << XPL_VERSION << "\n";
    return 0;
  }
  Arguments args;
  if (!parse(argc, argv, args)) return 2;
  if (args.command != "run" && args.command != "check") {
    std::cerr << "xpl: unknown command '" << args.command << "'\n" << USAGE;
    return 2;
  }
  if (args.threads > omp_get_num_procs())
    std::cerr << "xpl: warning: --threads " << args.threads << " is more than the "
              << omp_get_num_procs()
              << " core(s) available: the threads take turns on the cores and every barrier "
                 "waits for a descheduled one (slower; the results are the same)\n";
  install_stop_handlers();
  // Whatever escapes (std::bad_alloc reading a deck included) ends with a message and exit
  // code 4, never std::terminate.
  try {
    return run_job(args);
  } catch (const std::exception& e) {
    std::cerr << "xpl: error: " << cause_of(e) << "\n";
  } catch (...) {
    std::cerr << "xpl: error: an unknown internal error\n";
  }
  return 4;
}

namespace {

int run_job(const Arguments& args) {
  xpl::Model model;
  try {
    // A data check reports what only the element kernels cannot run yet as warnings.
    model = xpl::io::read_deck(args.deck, args.command == "check" ? xpl::io::ModelChecks::DataCheck
                                                                  : xpl::io::ModelChecks::Run);
  } catch (const xpl::InputError& e) {
    for (const auto& m : e.messages()) std::cerr << m << "\n";
    std::cerr << "xpl: " << e.messages().size() << " error(s) in " << args.deck.string()
              << "; nothing was written\n";
    return 1;
  }

  // --import: read and check the earlier result before anything is written.
  xpl::InitialState initial;
  if (!args.import.empty()) {
    std::vector<std::string> refusals;
    if (!model.rigid_bodies.empty())
      refusals.push_back(args.import.string() +
                         ": --import: the model has rigid bodies, whose orientation a result "
                         "file does not hold; expected a model without *RIGID BODY");
    // Clearances by adjustment move nodes strain free, which only the first step of a new
    // analysis may do (C7); an imported state takes them as permanent offsets.
    if (const auto& first = model.steps.front().contact; first)
      for (const xpl::ClearanceAssignment& a : first->clearances) {
        const xpl::ContactClearance& c = model.contact_clearances[a.clearance];
        if (c.adjust)
          refusals.push_back(a.where.file + ":" + std::to_string(a.where.line) +
                             ": *CONTACT CLEARANCE ASSIGNMENT: clearance " + c.name +
                             " has ADJUST=YES, but the run starts from --import " +
                             args.import.string() +
                             " (no node may move in an imported state); expected ADJUST=NO "
                             "(permanent contact offsets)");
      }
    if (!refusals.empty()) {
      for (const std::string& m : refusals) std::cerr << m << "\n";
      std::cerr << "xpl: " << refusals.size() << " error(s) in " << args.import.string()
                << "; nothing was written\n";
      return 1;
    }
    try {
      xpl::io::ImportedState imported = xpl::io::read_imported_state(args.import, model);
      for (const std::string& note : imported.notes)
        model.deck_messages.push_back({false, args.import.string() + ": --import: " + note});
      initial = std::move(static_cast<xpl::InitialState&>(imported));
    } catch (const xpl::InputError& e) {
      for (const auto& m : e.messages()) std::cerr << m << "\n";
      std::cerr << "xpl: " << e.messages().size() << " error(s) in " << args.import.string()
                << "; nothing was written\n";
      return 1;
    }
  }

  if (g_stop_signal != 0) return 128 + g_stop_signal;  // stopped before anything was written
  std::optional<xpl::io::ResultFiles> files;
  try {
    xpl::io::ResultOptions ropts;
    ropts.progress = !args.quiet;
    // The solver's choice (one thread for a small model unless --threads insists).
    const int threads = xpl::team_size(model, args.threads, omp_get_max_threads());
    ropts.threads = threads;
    files.emplace(args.out_dir, model.job_name, ropts);
    xpl::SolverOptions sopts;
    sopts.threads = args.threads;
    sopts.energy_limit = args.energy_limit / 100.0;
    sopts.stop_signal = &g_stop_signal;
    if (!args.import.empty()) sopts.initial_state = &initial;
    xpl::ExplicitSolver solver(model, *files, sopts);
    if (args.command == "check") {
      solver.check();
      if (!args.quiet)
        std::printf("xpl: data check of %s completed; results in %s\n", model.job_name.c_str(),
                    files->h5_path().string().c_str());
      return 0;
    }
    const xpl::RunSummary summary = solver.run();
    if (summary.stop_signal != 0) {
      std::fprintf(stderr, "xpl: %s interrupted by signal %d at t = %.6g s; results in %s\n",
                   model.job_name.c_str(), summary.stop_signal, summary.final_time,
                   files->h5_path().string().c_str());
      return 128 + summary.stop_signal;
    }
    if (!args.quiet) {
      std::printf("xpl: %s completed: %ld increments to t = %.6g s; results in %s\n",
                  model.job_name.c_str(), summary.increments, summary.final_time,
                  files->h5_path().string().c_str());
      print_summary(summary, model, threads);
    }
    return 0;
  } catch (const xpl::io::JobLocked& e) {
    std::cerr << "xpl: " << e.what() << "\n";
    return EXIT_LOCKED;
  } catch (const xpl::SolverError& e) {
    // The solver records its own failures; one outside the time loop (the data check, the
    // setup) is recorded here, so the file never says less than the terminal.
    if (files) files->fail(e.what());
    std::cerr << "xpl: " << e.what() << "\n"
              << "xpl: the run stopped; frames written so far are in the results file, "
                 "which records the error\n";
    return 3;
  } catch (const std::exception& e) {
    const std::string cause = cause_of(e);
    if (files) files->fail(cause);
    std::cerr << "xpl: error: " << cause << "\n";
    return 4;
  }
}

}  // namespace
