// `xpl bench` (subcommands.hpp): the standard benchmark models built in memory
// (bench_decks.hpp) and read by the deck reader, each run with 1 and 2 threads alternated,
// without result files; a table (or JSON) of median element-cycles per second, speed-up,
// phase shares and peak memory per element, with the machine's description.

#include <malloc.h>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "bench_decks.hpp"
#include "common/error.hpp"
#include "elements/parallel/simd.hpp"
#include "io/deck/deck_reader.hpp"
#include "io/result_tools/json_value.hpp"
#include "solver/explicit_solver.hpp"
#include "subcommands.hpp"

namespace xpl::apps {

namespace {

constexpr const char* BENCH_USAGE =
    "usage: xpl bench [--repeat N] [--quick] [--json] [--models NAME,...]\n"
    "       xpl bench --deck NAME [--quick]\n"
    "\n"
    "Builds the standard benchmark models in memory (the decks of benchmarks/make_block.py,\n"
    "make_plate_benchmark.py and make_contact_benchmark.py), runs each N times with 1 and\n"
    "with 2 OpenMP threads, alternated, without writing result files, and prints the median\n"
    "element-cycles per second (elements x increments / wall time of the time loop), the\n"
    "speed-up of 2 threads, the phase shares of the time loop at 2 threads and the peak\n"
    "memory per element, with the machine and the build. Models: hex, shell, contact,\n"
    "plastic-hex, plastic-shell (about a minute in all on a 2-core machine).\n"
    "  --repeat N     runs per model and thread count (default 3; the median is reported)\n"
    "  --quick        tiny models, one run each: shows that everything runs, times nothing\n"
    "  --json         the results as JSON (docs/user/cli.md describes the fields)\n"
    "  --models LIST  only these models (comma-separated)\n"
    "  --deck NAME    print the deck of model NAME (to run it with xpl run) and stop\n"
    "Exit codes: 0 done, 2 usage, 3 a run failed.\n";

/// Collects nothing: the benchmark times the solver, not the writer.
class NullSink : public OutputSink {
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

/// A field of /proc/self/status in kB ("VmRSS:", "VmHWM:"), or -1.
long status_kb(const std::string& field) {
  std::ifstream status("/proc/self/status");
  std::string key;
  while (status >> key) {
    if (key == field) {
      long kb = -1;
      status >> kb;
      return kb;
    }
    status.ignore(1 << 20, '\n');
  }
  return -1;
}

/// Resets the peak resident size (VmHWM) to the current one (Linux 4.0+); false if refused.
bool reset_peak_memory() {
  std::ofstream clear("/proc/self/clear_refs");
  clear << "5";
  clear.flush();
  return bool(clear);
}

/// "model name" of /proc/cpuinfo, or "unknown".
std::string cpu_model() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line))
    if (line.rfind("model name", 0) == 0) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) return line.substr(line.find_first_not_of(" \t", colon + 1));
    }
  return "unknown";
}

std::string load_average() {
  std::ifstream loadavg("/proc/loadavg");
  double a = 0, b = 0, c = 0;
  loadavg >> a >> b >> c;
  char text[64];
  std::snprintf(text, sizeof text, "%.2f %.2f %.2f", a, b, c);
  return text;
}

/// The vector instructions the element batches are compiled for.
struct Simd {
  const char* name;
  int bits;
};
constexpr Simd BUILD_SIMD =
#if defined(__AVX512F__)
    {"AVX-512", 512};
#elif defined(__AVX2__)
    {"AVX2", 256};
#elif defined(__AVX__)
    {"AVX", 256};
#elif defined(__SSE2__)
    {"SSE2", 128};
#else
    {"none", 64};
#endif

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

/// The phases of the time loop the table reports, as shares of its wall time.
struct ShareColumn {
  const char* key;
  std::vector<Phase> phases;
};
const std::vector<ShareColumn> SHARES = {{"internal_force", {Phase::InternalForce}},
                                         {"contact", {Phase::ContactSearch, Phase::ContactForce}},
                                         {"integration", {Phase::Integration}},
                                         {"output", {Phase::Output}}};

/// The runs of one model with one thread count.
struct Runs {
  std::vector<double> rates;                          ///< element-cycles/s per run
  std::map<std::string, std::vector<double>> shares;  ///< SHARES key (and "other") per run
  std::vector<double> setup;                          ///< s per run
  long increments = 0;
};

struct ModelResult {
  BenchModel model;
  Index elements = 0;
  double read_seconds = 0.0;
  long peak_bytes_per_element = -1;  ///< -1: unknown
  std::map<int, Runs> by_threads;
};

/// Runs `model` once; false (after the message) when the solver fails.
bool run_once(const Model& model, int threads, Runs& runs) {
  NullSink sink;
  SolverOptions options;
  options.threads = threads;
  RunSummary s;
  try {
    ExplicitSolver solver(model, sink, options);
    s = solver.run();
  } catch (const SolverError& e) {
    std::cerr << "xpl bench: " << model.job_name << " with " << threads
              << " thread(s) failed: " << e.what() << "\n";
    return false;
  }
  runs.rates.push_back(s.element_cycles_per_second);
  runs.increments = s.increments;
  runs.setup.push_back(s.timers.seconds(Phase::Setup));
  // Shares of the time loop's wall time; the phase timers also hold the forces of the initial
  // state (before the loop), which on a tiny model can outweigh the loop: then shares of
  // their sum.
  double timed = 0.0;
  for (const ShareColumn& column : SHARES)
    for (Phase p : column.phases) timed += s.timers.seconds(p);
  const double loop =
      s.element_cycles_per_second > 0.0
          ? double(model.element_count()) * double(s.increments) / s.element_cycles_per_second
          : 0.0;
  const double whole = std::max(loop, timed);
  for (const ShareColumn& column : SHARES) {
    double seconds = 0.0;
    for (Phase p : column.phases) seconds += s.timers.seconds(p);
    runs.shares[column.key].push_back(whole > 0.0 ? seconds / whole : 0.0);
  }
  runs.shares["other"].push_back(whole > 0.0 ? (whole - timed) / whole : 0.0);
  return true;
}

/// Builds, reads and runs one model `repeat` times with 1 and 2 threads, alternating which
/// goes first so that a shared machine's slow spells hit both alike.
bool bench_model(const BenchModel& spec, int repeat, ModelResult& result, bool progress) {
  result.model = spec;
  malloc_trim(0);  // what earlier models freed goes back to the system before the baseline
  const long baseline_kb = status_kb("VmRSS:");
  const bool peak_known = reset_peak_memory() && baseline_kb >= 0;
  const auto start = std::chrono::steady_clock::now();
  Model model = io::read_deck_text(spec.deck(), "bench_" + spec.name + ".inp");
  result.read_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.elements = model.element_count();
  for (int r = 0; r < repeat; ++r)
    for (int threads : r % 2 == 0 ? std::vector<int>{1, 2} : std::vector<int>{2, 1}) {
      if (progress)
        std::fprintf(stderr, "xpl bench: %s, %d thread(s), run %d of %d\n", spec.name.c_str(),
                     threads, r + 1, repeat);
      if (!run_once(model, threads, result.by_threads[threads])) return false;
    }
  const long peak_kb = status_kb("VmHWM:");
  if (peak_known && peak_kb >= baseline_kb && result.elements > 0)
    result.peak_bytes_per_element = (peak_kb - baseline_kb) * 1024 / result.elements;
  return true;
}

io::JsonValue runs_json(const Runs& runs) {
  io::JsonValue out = io::JsonValue::object();
  out.set("cycles_per_second", median(runs.rates));
  io::JsonValue all = io::JsonValue::array();
  for (double r : runs.rates) all.push(r);
  out.set("cycles_per_second_runs", std::move(all));
  out.set("increments", runs.increments);
  out.set("setup_seconds", median(runs.setup));
  io::JsonValue shares = io::JsonValue::object();
  for (const ShareColumn& column : SHARES)
    shares.set(column.key, median(runs.shares.at(column.key)));
  shares.set("other", median(runs.shares.at("other")));
  out.set("phase_shares", std::move(shares));
  return out;
}

double speed_up(const ModelResult& r) {
  const double one = median(r.by_threads.at(1).rates);
  return one > 0.0 ? median(r.by_threads.at(2).rates) / one : 0.0;
}

io::JsonValue machine_json() {
  io::JsonValue out = io::JsonValue::object();
  out.set("cpu", cpu_model());
  out.set("cores", omp_get_num_procs());
  out.set("hardware_threads", int(std::thread::hardware_concurrency()));
  out.set("simd", BUILD_SIMD.name);
  out.set("simd_bits", BUILD_SIMD.bits);
  out.set("batch_lanes", simd::W);
  out.set("compiler", "g++ " __VERSION__);
  out.set("load_average", load_average());
  return out;
}

io::JsonValue results_json(const std::vector<ModelResult>& results, int repeat, bool quick) {
  io::JsonValue out = io::JsonValue::object();
  out.set("xpl_version", XPL_VERSION);
  out.set("machine", machine_json());
  out.set("repeat", repeat);
  out.set("quick", quick);
  io::JsonValue models = io::JsonValue::array();
  for (const ModelResult& r : results) {
    io::JsonValue m = io::JsonValue::object();
    m.set("name", r.model.name);
    m.set("description", r.model.description);
    m.set("deck", "benchmarks/" + r.model.script());
    m.set("elements", long(r.elements));
    m.set("read_seconds", r.read_seconds);
    m.set("peak_bytes_per_element", r.peak_bytes_per_element >= 0
                                        ? io::JsonValue(r.peak_bytes_per_element)
                                        : io::JsonValue());
    io::JsonValue threads = io::JsonValue::object();
    for (const auto& [t, runs] : r.by_threads) threads.set(std::to_string(t), runs_json(runs));
    m.set("threads", std::move(threads));
    m.set("speed_up", speed_up(r));
    models.push(std::move(m));
  }
  out.set("models", std::move(models));
  return out;
}

void print_table(const std::vector<ModelResult>& results, int repeat) {
  std::printf("xpl bench: xpl %s; %s, %d cores; %s (%d-bit) element batches of %d lanes; %s\n",
              XPL_VERSION, cpu_model().c_str(), omp_get_num_procs(), BUILD_SIMD.name,
              BUILD_SIMD.bits, simd::W, "g++ " __VERSION__);
  std::printf(
      "load average %s; %d run(s) per model and thread count, 1 and 2 threads "
      "alternated; medians\n\n",
      load_average().c_str(), repeat);
  std::printf("%-14s %8s %5s %9s %9s %7s %8s %8s %8s %8s %8s\n", "model", "elements", "incr",
              "1T M/s", "2T M/s", "speedup", "element", "contact", "nodal", "other", "B/elem");
  for (const ModelResult& r : results) {
    const Runs& two = r.by_threads.at(2);
    const auto share = [&](const char* key) { return 100.0 * median(two.shares.at(key)); };
    std::printf("%-14s %8ld %5ld %9.2f %9.2f %7.2f %7.0f%% %7.0f%% %7.0f%% %7.0f%% ",
                r.model.name.c_str(), long(r.elements), two.increments,
                median(r.by_threads.at(1).rates) / 1e6, median(two.rates) / 1e6, speed_up(r),
                share("internal_force"), share("contact"), share("integration"),
                share("output") + share("other"));
    if (r.peak_bytes_per_element >= 0)
      std::printf("%8ld\n", r.peak_bytes_per_element);
    else
      std::printf("%8s\n", "?");
  }
  std::printf(
      "\nM/s: million element-cycles per second (elements x increments / time-loop wall "
      "time)\nshares: of the time loop at 2 threads (element = internal force, contact = "
      "search + force,\nnodal = integration, other = output and the rest); B/elem: peak "
      "memory per element\n(the process's peak over its size before the model was "
      "built)\n");
  for (const ModelResult& r : results)
    std::printf("  %-14s %s: benchmarks/%s\n", r.model.name.c_str(), r.model.description.c_str(),
                r.model.script().c_str());
}

}  // namespace

int bench_main(const std::vector<std::string>& args) {
  int repeat = 0;
  bool quick = false, json = false;
  std::string deck_of, only;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& w = args[i];
    const auto value = [&]() -> const std::string* {
      if (i + 1 < args.size()) return &args[++i];
      std::cerr << "xpl bench: " << w << " needs a value\n" << BENCH_USAGE;
      return nullptr;
    };
    if (w == "--help" || w == "-h") {
      std::cout << BENCH_USAGE;
      return 0;
    } else if (w == "--quick") {
      quick = true;
    } else if (w == "--json") {
      json = true;
    } else if (w == "--repeat") {
      const std::string* v = value();
      if (!v) return 2;
      try {
        std::size_t used = 0;
        repeat = std::stoi(*v, &used);
        if (used != v->size() || repeat < 1 || repeat > 1000) throw std::invalid_argument(*v);
      } catch (const std::exception&) {
        std::cerr << "xpl bench: --repeat: '" << *v << "' is not a whole number from 1 to 1000\n";
        return 2;
      }
    } else if (w == "--models" || w == "--deck") {
      const std::string* v = value();
      if (!v) return 2;
      (w == "--deck" ? deck_of : only) = *v;
    } else {
      std::cerr << "xpl bench: unknown option '" << w << "'\n" << BENCH_USAGE;
      return 2;
    }
  }
  if (repeat == 0) repeat = quick ? 1 : 3;

  std::vector<BenchModel> models = bench_models(quick);
  if (!deck_of.empty()) {
    for (const BenchModel& m : models)
      if (m.name == deck_of) {
        std::cout << m.deck();
        return 0;
      }
    std::cerr << "xpl bench: --deck: no model '" << deck_of
              << "'; expected hex, shell, contact, plastic-hex or plastic-shell\n";
    return 2;
  }
  if (!only.empty()) {
    std::vector<BenchModel> chosen;
    std::stringstream names(only);
    std::string name;
    while (std::getline(names, name, ',')) {
      const auto it = std::find_if(models.begin(), models.end(),
                                   [&](const BenchModel& m) { return m.name == name; });
      if (it == models.end()) {
        std::cerr << "xpl bench: --models: no model '" << name
                  << "'; expected hex, shell, contact, plastic-hex or plastic-shell\n";
        return 2;
      }
      chosen.push_back(*it);
    }
    models = chosen;
  }

  std::vector<ModelResult> results;
  for (const BenchModel& m : models) {
    ModelResult r;
    if (!bench_model(m, repeat, r, !json)) return 3;
    results.push_back(std::move(r));
  }
  if (json)
    std::cout << results_json(results, repeat, quick).text() << "\n";
  else
    print_table(results, repeat);
  return 0;
}

}  // namespace xpl::apps
