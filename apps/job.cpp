// One `xpl run` / `xpl check` job (job.hpp): the deck, --import, the result files and the
// solver, with every failure turned into a message and an exit code.

#include "job.hpp"

#include <omp.h>

#include <cstdio>
#include <fstream>
#include <iostream>
#include <new>
#include <optional>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "io/deck/deck_reader.hpp"
#include "io/result_tools/import_state.hpp"
#include "io/results/frame_rows_sink.hpp"
#include "io/results/job_lock.hpp"
#include "io/results/result_files.hpp"
#include "solver/distributed_run.hpp"
#include "solver/explicit_solver.hpp"
#include "solver/output/output_schedule.hpp"
#include "solver/thread_team.hpp"

namespace xpl::apps {

namespace {

/// The sink of the ranks other than 0 in a distributed run whose rank 0 gathers every frame
/// (--gather-frames): rank 0 writes everything.
class NullSink final : public OutputSink {
 public:
  void begin_run(const Model&) override {}
  void begin_step(const Model&, int) override {}
  void declare_history(const std::vector<HistorySeries>&) override {}
  void write_frame(const Model&, const State&, const FrameFields&, const FrameRequest&) override {}
  void append_history(Real, std::span<const Real>) override {}
  void status(const StatusLine&) override {}
  void message(Severity, const std::string&) override {}
  void end_run(RunStatus, const std::string&, const PhaseTimers&, double) override {}
};

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

void print_summary(const RunSummary& s, const Model& model, int threads) {
  std::printf("xpl: element cycles per second: %.6e (%d elements x %ld increments, %d threads)\n",
              s.element_cycles_per_second, model.element_count(), s.increments, threads);
  for (int p = 0; p < static_cast<int>(Phase::COUNT); ++p) {
    const auto phase = static_cast<Phase>(p);
    std::printf("xpl: phase %s: %.3f s\n", std::string(phase_name(phase)).c_str(),
                s.timers.seconds(phase));
  }
  std::printf("xpl: largest energy balance drift: %.3g %% of the largest energy (t = %.6g %s)\n",
              100.0 * s.energy_drift, s.energy_drift_time, model.units.label("s").c_str());
  std::printf("xpl: peak memory: %.1f MB\n", peak_memory_mb());
}

/// --import: refusals of the model, then the earlier result read and checked; false (after
/// the messages) when the job must stop with EXIT_INPUT.
bool read_import(const JobArguments& args, Model& model, InitialState& initial) {
  std::vector<std::string> refusals;
  if (!model.rigid_bodies.empty())
    refusals.push_back(args.import.string() +
                       ": --import: the model has rigid bodies, whose orientation a result "
                       "file does not hold; expected a model without *RIGID BODY");
  // Clearances by adjustment move nodes strain free, which only the first step of a new
  // analysis may do (C7); an imported state takes them as permanent offsets.
  if (const auto& first = model.steps.front().contact; first)
    for (const ClearanceAssignment& a : first->clearances) {
      const ContactClearance& c = model.contact_clearances[a.clearance];
      if (c.adjust)
        refusals.push_back(a.where.file + ":" + std::to_string(a.where.line) + ": " +
                           assignment_keyword(c.initialization) + ": clearance " + c.name +
                           " has ADJUST=YES, but the run starts from --import " +
                           args.import.string() +
                           " (no node may move in an imported state); expected ADJUST=NO "
                           "(permanent contact offsets)");
    }
  if (!refusals.empty()) {
    for (const std::string& m : refusals) std::cerr << m << "\n";
    std::cerr << "xpl: " << refusals.size() << " error(s) in " << args.import.string()
              << "; nothing was written\n";
    return false;
  }
  try {
    io::ImportedState imported = io::read_imported_state(args.import, model);
    for (const std::string& note : imported.notes)
      model.deck_messages.push_back({false, args.import.string() + ": --import: " + note});
    initial = std::move(static_cast<InitialState&>(imported));
  } catch (const InputError& e) {
    for (const auto& m : e.messages()) std::cerr << m << "\n";
    std::cerr << "xpl: " << e.messages().size() << " error(s) in " << args.import.string()
              << "; nothing was written\n";
    return false;
  }
  return true;
}

/// How long a rank that stopped on a SolverError waits for the others to stop too, s: they
/// reach the same stop in the same increment and end within a second (rank 0 writes the
/// files); a rank still stepping after this long will not stop there (every_rank_ends()).
constexpr double RANKS_END_WITHIN = 20.0;

/// A failure of this rank of a distributed run alone (its files, its memory): the solver's own
/// stops (SolverError) come from reduced values and reach every rank together, but the other
/// ranks would wait for this one in their next collective for ever, so the job ends here on
/// every rank. Every rank says why: the others' std::cerr is silenced.
void end_every_rank(int rank, const std::string& cause) {
  std::fprintf(stderr, "xpl: error on rank %d: %s; ending the run on every rank\n", rank,
               escape_control(cause).c_str());
  DistributedRun::abort_world(EXIT_INTERNAL);
}

int run_job_unguarded(const JobArguments& args, volatile std::sig_atomic_t* stop_signal) {
  const auto stopped = [&] { return stop_signal != nullptr ? int(*stop_signal) : 0; };
  Model model;
  try {
    // A data check reports what only the element kernels cannot run yet as warnings.
    model =
        io::read_deck(args.deck, args.check ? io::ModelChecks::DataCheck : io::ModelChecks::Run);
  } catch (const InputError& e) {
    for (const auto& m : e.messages()) std::cerr << m << "\n";
    std::cerr << "xpl: " << e.messages().size() << " error(s) in " << args.deck.string()
              << "; nothing was written\n";
    return EXIT_INPUT;
  }

  // Distributed runs: the features not distributed yet are refused, on every rank alike.
  if (args.distributed) {
    const std::vector<std::string> refused = DistributedRun::refusals(model, !args.import.empty());
    if (!refused.empty()) {
      if (args.rank == 0) {
        for (const std::string& m : refused)
          std::cerr << args.deck.string() << ": mpirun with more than one rank: " << m << "\n";
        std::cerr << "xpl: " << refused.size() << " error(s) in " << args.deck.string()
                  << "; nothing was written\n";
      }
      return EXIT_INPUT;
    }
  }

  // --import: read and check the earlier result before anything is written.
  InitialState initial;
  if (!args.import.empty() && !read_import(args, model, initial)) return EXIT_INPUT;

  if (stopped() != 0) return 128 + stopped();  // stopped before anything was written
  // The .msg file has it too (OutputSchedule); on the terminal also with --quiet.
  if (uses_default_output(model)) std::cerr << "xpl: warning: " << default_output_warning() << "\n";
  if (model.units.dimensions_only)
    std::cerr << "xpl: warning: the deck does not state its units and its material data are not "
                 "SI: the results are labelled by dimension only ([stress], ...); see JOB.msg "
                 "for the system they fit and the '** xpl: UNITS=' line that states it\n";
  std::optional<io::ResultFiles> files;
  try {
    // The solver's choice (one thread for a small model unless --threads insists).
    const int threads = team_size(model, args.threads, omp_get_max_threads());
    // The team starts here, before the lock and the files: one the system cannot start (libgomp
    // then stops the program with its own message) leaves nothing behind, no status "running".
#pragma omp parallel num_threads(threads)
    {}
    io::ResultOptions ropts;
    ropts.progress = !args.quiet;
    ropts.threads = threads;
    // Distributed runs: rank 0 writes (the others their rows of each frame, unless
    // --gather-frames); the others go on only when it could open its files.
    NullSink discard;
    std::optional<io::FrameRowsSink> frame_rows;
    if (!args.distributed || args.rank == 0) {
      int opened = EXIT_INTERNAL;
      try {
        files.emplace(args.out_dir, model.job_name, ropts);
        opened = EXIT_DONE;
      } catch (...) {
        if (args.distributed) DistributedRun::world_max(opened);
        throw;
      }
      if (args.distributed) DistributedRun::world_max(opened);
    } else if (const int opened = DistributedRun::world_max(EXIT_DONE); opened != EXIT_DONE) {
      return opened;
    }
    const bool shared_frames = args.distributed && !args.gather_frames;
    if (!files && shared_frames) frame_rows.emplace(args.out_dir / (model.job_name + ".h5"));
    OutputSink& sink = files        ? static_cast<OutputSink&>(*files)
                       : frame_rows ? static_cast<OutputSink&>(*frame_rows)
                                    : discard;
    SolverOptions sopts;
    sopts.threads = args.threads;
    sopts.energy_limit = args.energy_limit / 100.0;
    sopts.stop_signal = stop_signal;
    sopts.partition_parts = args.partition;
    sopts.partition_note = args.partition_note;
    sopts.distributed = args.distributed;
    sopts.shared_frames = shared_frames;
    sopts.shared_contact = !args.contact_redundant;
    if (!args.import.empty()) sopts.initial_state = &initial;
    ExplicitSolver solver(model, sink, sopts);
    if (args.check) {
      solver.check();
      if (!args.quiet && files)
        std::printf("xpl: data check of %s completed; results in %s\n", model.job_name.c_str(),
                    files->h5_path().string().c_str());
      return EXIT_DONE;
    }
    const RunSummary summary = solver.run();
    if (!files) return summary.stop_signal != 0 ? 128 + summary.stop_signal : EXIT_DONE;
    if (summary.stop_signal != 0) {
      std::fprintf(stderr, "xpl: %s interrupted by signal %d at t = %.6g %s; results in %s\n",
                   model.job_name.c_str(), summary.stop_signal, summary.final_time,
                   model.units.label("s").c_str(), files->h5_path().string().c_str());
      return 128 + summary.stop_signal;
    }
    if (!args.quiet) {
      std::printf("xpl: %s completed: %ld increments to t = %.6g %s; results in %s\n",
                  model.job_name.c_str(), summary.increments, summary.final_time,
                  model.units.label("s").c_str(), files->h5_path().string().c_str());
      std::printf("xpl: units: %s\n", model.units.summary().c_str());
      print_summary(summary, model, threads);
    }
    return EXIT_DONE;
  } catch (const io::JobLocked& e) {
    std::cerr << "xpl: " << escape_control(e.what()) << "\n";
    return EXIT_LOCKED;
  } catch (const SolverError& e) {
    // The solver records its own failures; one outside the time loop (the data check, the
    // setup) is recorded here, so the file never says less than the terminal.
    if (files) files->fail(e.what());
    if (args.distributed && !DistributedRun::every_rank_ends(RANKS_END_WITHIN)) {
      files.reset();  // closed before MPI_Abort, which runs no destructor
      end_every_rank(args.rank, std::string(e.what()) + " (this rank alone stopped there)");
    }
    std::cerr << "xpl: " << escape_control(e.what()) << "\n"
              << "xpl: the run stopped; frames written so far are in the results file, "
                 "which records the error\n";
    return EXIT_FAILED;
  } catch (const std::exception& e) {
    const std::string cause = cause_of(e);
    if (files) files->fail(cause);
    if (args.distributed) {
      files.reset();  // closed before MPI_Abort, which runs no destructor
      end_every_rank(args.rank, cause);
    }
    std::cerr << "xpl: error: " << escape_control(cause) << "\n";
    return EXIT_INTERNAL;
  }
}

}  // namespace

std::string cause_of(const std::exception& e) {
  if (dynamic_cast<const std::bad_alloc*>(&e) != nullptr)
    return std::string("out of memory (") + e.what() + ")";
  return e.what();
}

int run_job(const JobArguments& args, volatile std::sig_atomic_t* stop_signal) noexcept {
  // Whatever escapes (std::bad_alloc reading a deck included) ends with a message and exit
  // code 4, never std::terminate.
  try {
    return run_job_unguarded(args, stop_signal);
  } catch (const std::exception& e) {
    try {
      if (args.distributed) end_every_rank(args.rank, cause_of(e));
      std::cerr << "xpl: error: " << escape_control(cause_of(e)) << "\n";
    } catch (...) {
    }
  } catch (...) {
    try {
      if (args.distributed) end_every_rank(args.rank, "an unknown internal error");
      std::cerr << "xpl: error: an unknown internal error\n";
    } catch (...) {
    }
  }
  return EXIT_INTERNAL;
}

}  // namespace xpl::apps
