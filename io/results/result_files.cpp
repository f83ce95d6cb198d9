#include "io/results/result_files.hpp"

#include <sys/statvfs.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <optional>
#include <stdexcept>

#include "io/results/job_lock.hpp"
#include "io/results/progress_line.hpp"
#include "io/results/results_h5.hpp"
#include "io/results/results_log.hpp"
#include "io/results/run_summary_file.hpp"
#include "io/results/xdmf_writer.hpp"

namespace xpl::io {

namespace {

using Clock = std::chrono::steady_clock;

/// Wall time before the progress line appears, s: short runs stay quiet.
constexpr double PROGRESS_DELAY = 2.0;
/// Minimum wall time between two updates of the progress line, s.
constexpr double PROGRESS_INTERVAL = 0.2;
/// Minimum wall time between two rewrites of JOB.xdmf and JOB_last.xdmf during a run, s. Each
/// rewrite is a new file renamed into place, and JOB.xdmf lists every frame: written after
/// every frame, small runs spent most of their wall time in these renames on a busy disk
/// (the 640-element example: 22 renames, up to 9 ms each) and long runs rewrote a file that
/// grows with the frame count at every frame. A reader of a running job sees frames at most
/// this much later than the .h5 has them; end_run writes the last ones.
constexpr double XDMF_INTERVAL = 1.0;
/// Free space kept on the disk beyond two frames' worth, bytes: the status attributes, the
/// pending history rows and the logs' last lines must still fit when a run stops there.
constexpr double SPACE_MARGIN = 64.0 * 1024.0;

const char* status_name(RunStatus status) {
  switch (status) {
    case RunStatus::Completed:
      return "completed";
    case RunStatus::Checked:
      return "checked";
    case RunStatus::Failed:
      return "failed";
    case RunStatus::Interrupted:
      return "interrupted";
  }
  return "failed";
}

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace

struct ResultFiles::Impl {
  std::filesystem::path h5;
  std::filesystem::path xdmf;
  std::filesystem::path sta;
  std::filesystem::path msg;
  std::filesystem::path summary_json;
  JobLock lock;  ///< taken before any file below is opened
  ResultOptions options;
  ResultsH5 h5_file;
  XdmfWriter xdmf_file;
  StaFile sta_file;
  MsgFile msg_file;

  int step = 0;                   ///< zero-based current step
  Real step_period = 0.0;         ///< time period of the current step, s
  std::string step_name;          ///< name of the current step
  bool ended = false;             ///< end_run was called
  Real time_reached = 0.0;        ///< total time of the last status line, s
  std::uintmax_t h5_size = 0;     ///< size of JOB.h5 after the last frame, bytes
  std::uintmax_t frame_size = 0;  ///< growth of JOB.h5 by the last frame (or the mesh), bytes
  bool progress_tty = false;      ///< stderr is a terminal
  bool progress_shown = false;    ///< a progress line is on the terminal
  Clock::time_point start = Clock::now();
  Clock::time_point last_progress{};        ///< when the progress line was last updated
  Clock::time_point opened = Clock::now();  ///< when the files were opened
  Clock::time_point xdmf_written = opened;  ///< when JOB.xdmf was last rewritten
  std::optional<ProgressMeter> meter;       ///< the progress line's rates (from begin_run)
  bool meter_started = false;               ///< the meter has its reference line
  SummaryRecord summary;                    ///< JOB.summary.json, filled as the run goes

  Impl(const std::filesystem::path& directory, const std::string& job, ResultOptions opts)
      : h5(prepared(directory) / (job + ".h5")),
        xdmf(directory / (job + ".xdmf")),
        sta(directory / (job + ".sta")),
        msg(directory / (job + ".msg")),
        summary_json(io::summary_path(h5)),
        lock(directory, job),
        options(opts),
        h5_file(h5, job),
        xdmf_file(xdmf, job + ".h5"),
        sta_file(sta, job),
        msg_file(msg, job),
        progress_tty(opts.progress && isatty(STDERR_FILENO) == 1) {
    summary.job = job;
    summary.threads = opts.threads;
    h5_file.set_wait_notice(
        [this](const std::string& text) { msg_file.message(Severity::Warning, text); });
    // A summary of an earlier run must not pass for this one's while it runs.
    std::error_code ignored;
    std::filesystem::remove(summary_json, ignored);
  }

  /// Creates the output directory (before any file in it is opened).
  static const std::filesystem::path& prepared(const std::filesystem::path& directory) {
    if (!directory.empty()) std::filesystem::create_directories(directory);
    return directory;
  }

  /// Updates the progress line on stderr (only on a terminal, after PROGRESS_DELAY).
  void progress(const StatusLine& line) {
    if (!progress_tty) return;
    // The first status line is the reference of the rates, shown or not.
    if (meter && !meter_started) {
      meter->text(line, step + 1, step_period, seconds_since(opened));
      meter_started = true;
    }
    if (seconds_since(start) < PROGRESS_DELAY) return;
    const auto now = Clock::now();
    if (progress_shown &&
        std::chrono::duration<double>(now - last_progress).count() < PROGRESS_INTERVAL) {
      return;
    }
    last_progress = now;
    if (!meter) return;
    const std::string text = meter->text(line, step + 1, step_period, seconds_since(opened));
    // Blanks after the text clear the end of a longer line it replaces.
    std::fprintf(stderr, "\r%s   ", text.c_str());
    std::fflush(stderr);
    progress_shown = true;
  }

  /// Stops the run before a frame that may not fit on the disk. HDF5 cannot recover from a
  /// write that fails half way (the file's metadata no longer agree and no frame can be
  /// read), so xpl stops while the frames written so far are whole and the status fits.
  void check_space() {
    std::error_code error;
    const std::uintmax_t size = std::filesystem::file_size(h5, error);
    if (error) return;
    frame_size = size > h5_size ? size - h5_size : frame_size;
    h5_size = size;
    struct statvfs disk {};
    if (statvfs(h5.c_str(), &disk) != 0) return;
    const double available = static_cast<double>(disk.f_bavail) * disk.f_frsize;
    const double needed = 2.0 * static_cast<double>(frame_size) + SPACE_MARGIN;
    if (available < needed)
      throw std::runtime_error(
          "disk full: " + std::to_string(disk.f_bavail * disk.f_frsize) + " bytes free for " +
          h5.string() + ", less than the " + std::to_string(static_cast<std::uintmax_t>(needed)) +
          " bytes xpl keeps free before a frame (twice the last frame's " +
          std::to_string(frame_size) + " bytes, and " +
          std::to_string(static_cast<std::uintmax_t>(SPACE_MARGIN)) +
          " bytes for the end of the run); frames written so far are complete");
  }

  /// Writes the mesh. HDF5 leaves a file whose write failed half way unreadable (no frame,
  /// no status can be read from it): such a JOB.h5 is removed, and the error says so.
  XdmfMesh write_mesh(const Model& model) {
    try {
      return h5_file.write_mesh(model);
    } catch (const std::exception& e) {
      std::string cause = e.what();
      struct statvfs disk {};
      if (statvfs(h5.parent_path().empty() ? "." : h5.parent_path().c_str(), &disk) == 0 &&
          static_cast<double>(disk.f_bavail) * disk.f_frsize < SPACE_MARGIN)
        cause = "disk full (" + std::to_string(disk.f_bavail * disk.f_frsize) +
                " bytes free) while writing the mesh: " + cause;
      std::error_code error;
      const bool removed = std::filesystem::remove(h5, error);
      throw std::runtime_error(cause + "; " + h5.string() +
                               (removed ? " was removed (a half-written mesh leaves it unreadable)"
                                        : " could not be removed and is not readable"));
    }
  }

  /// Completes the summary record for a run that ends with `status`.
  JsonValue final_summary(const char* status, const std::string& error, const PhaseTimers& timers,
                          double element_cycles_per_second) {
    summary.status = status;
    summary.exit_reason = error;
    summary.timers = timers;
    summary.element_cycles_per_second = element_cycles_per_second;
    summary.elapsed_seconds = seconds_since(opened);
    return summary.json();
  }

  void end_progress() {
    if (!progress_shown) return;
    std::fputc('\n', stderr);
    progress_shown = false;
  }
};

ResultFiles::ResultFiles(const std::filesystem::path& directory, const std::string& job_name,
                         ResultOptions options)
    : m_impl(std::make_unique<Impl>(directory, job_name, options)) {}

ResultFiles::~ResultFiles() {
  if (m_impl->ended) return;
  // The run was abandoned (an exception passed the solver): say so rather than "running".
  try {
    m_impl->end_progress();
    const std::string cause = "the run ended without end_run";
    const JsonValue summary = m_impl->final_summary("failed", cause, PhaseTimers{}, 0.0);
    try {
      write_summary_json(m_impl->summary_json, summary);
    } catch (...) {  // NOLINT(bugprone-empty-catch): the .h5 status below matters more
    }
    m_impl->h5_file.write_summary(summary);
    m_impl->h5_file.finish("failed", cause);
  } catch (...) {  // NOLINT(bugprone-empty-catch): a destructor must not throw
  }
}

void ResultFiles::begin_run(const Model& model) {
  m_impl->start = Clock::now();
  Real analysis_time = 0.0;
  for (const Step& s : model.steps) analysis_time += s.time_period;
  m_impl->meter.emplace(analysis_time, static_cast<int>(model.steps.size()),
                        model.units.label("s"));
  m_impl->xdmf_file.set_mesh(m_impl->write_mesh(model));
  m_impl->msg_file.summary(model);
  m_impl->summary.nodes = model.node_count();
  m_impl->summary.elements = model.element_count();
  m_impl->summary.steps = static_cast<int>(model.steps.size());
  m_impl->summary.units = model.units;
  if (const std::string& owner = m_impl->lock.stale_owner(); !owner.empty())
    m_impl->msg_file.message(Severity::Note, "the lock file " + m_impl->lock.path().string() +
                                                 " of process " + owner +
                                                 " (no longer running) was taken over");
}

void ResultFiles::begin_step(const Model& model, int step) {
  Impl& impl = *m_impl;
  impl.step = step;
  impl.summary.steps_started = step + 1;
  const auto index = static_cast<std::size_t>(step);
  impl.step_period = index < model.steps.size() ? model.steps[index].time_period : 0.0;
  impl.step_name = index < model.steps.size() ? model.steps[index].name : "";
  impl.h5_file.begin_step(step);
  impl.sta_file.begin_step(step + 1, impl.step_name);
  impl.msg_file.begin_step(model, step);
}

void ResultFiles::declare_history(const std::vector<HistorySeries>& series) {
  m_impl->h5_file.declare_history(series);
}

void ResultFiles::write_frame(const Model& model, const State& state, const FrameFields& fields,
                              const FrameRequest& what) {
  m_impl->check_space();
  const std::string frame = m_impl->h5_file.write_frame(model, state, fields, what);
  const auto step = static_cast<std::size_t>(state.step);
  m_impl->xdmf_file.add_frame(frame, state.time, what, state.step + 1,
                              step < model.steps.size() ? model.steps[step].name : "",
                              state.step_time);
  if (seconds_since(m_impl->xdmf_written) >= XDMF_INTERVAL) {
    m_impl->xdmf_file.write_pending();
    m_impl->xdmf_written = Clock::now();
  }
}

void ResultFiles::append_history(Real time, std::span<const Real> values) {
  m_impl->h5_file.append_history(time, values);
}

void ResultFiles::status(const StatusLine& line) {
  m_impl->sta_file.line(m_impl->step + 1, line, seconds_since(m_impl->opened));
  m_impl->time_reached = line.total_time;
  m_impl->summary.add_status(line);
  m_impl->progress(line);
}

void ResultFiles::message(Severity severity, const std::string& text) {
  m_impl->msg_file.message(severity, text);
}

void ResultFiles::distribution(const DistributionSummary& summary) {
  m_impl->summary.distribution = summary;
}

void ResultFiles::energy_drift(const BalanceDrift& drift) {
  m_impl->summary.set_drift(drift);
}

void ResultFiles::status_note(const std::string& text) {
  m_impl->sta_file.note(text);
}

void ResultFiles::write_table(const ResultTable& table) {
  m_impl->h5_file.write_table(table);
}

void ResultFiles::end_run(RunStatus status, const std::string& error, const PhaseTimers& timers,
                          double element_cycles_per_second) {
  Impl& impl = *m_impl;
  impl.ended = true;
  impl.end_progress();
  // Each file records the end even if another cannot (a full disk): the first error is
  // rethrown once all have been tried.
  std::exception_ptr first_error;
  auto attempt = [&first_error](auto&& write) {
    try {
      write();
    } catch (...) {
      if (!first_error) first_error = std::current_exception();
    }
  };
  attempt([&] { impl.xdmf_file.write_pending(); });
  attempt([&] { impl.sta_file.finish(status, error, timers, element_cycles_per_second); });
  attempt([&] { impl.msg_file.finish(status, error, timers, element_cycles_per_second); });
  const bool ended_early = status == RunStatus::Failed || status == RunStatus::Interrupted;
  const std::optional<double> reached =
      ended_early ? std::optional<double>(impl.time_reached) : std::nullopt;
  const JsonValue summary =
      impl.final_summary(status_name(status), error, timers, element_cycles_per_second);
  attempt([&] { write_summary_json(impl.summary_json, summary); });
  try {
    impl.h5_file.write_summary(summary);
    impl.h5_file.finish(status_name(status), error, reached);
  } catch (...) {
    if (!first_error) first_error = std::current_exception();
    attempt([&] { impl.h5_file.record_status(status_name(status), error, reached); });
  }
  if (first_error) std::rethrow_exception(first_error);
}

void ResultFiles::fail(const std::string& cause) noexcept {
  if (m_impl->ended) return;
  try {
    end_run(RunStatus::Failed, cause, PhaseTimers{}, 0.0);
  } catch (...) {  // NOLINT(bugprone-empty-catch): the caller reports the cause itself
  }
}

std::filesystem::path ResultFiles::h5_path() const {
  return m_impl->h5;
}
std::filesystem::path ResultFiles::xdmf_path() const {
  return m_impl->xdmf;
}
std::filesystem::path ResultFiles::sta_path() const {
  return m_impl->sta;
}
std::filesystem::path ResultFiles::msg_path() const {
  return m_impl->msg;
}
std::filesystem::path ResultFiles::summary_path() const {
  return m_impl->summary_json;
}

}  // namespace xpl::io
