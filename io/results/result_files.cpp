#include "io/results/result_files.hpp"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <optional>

#include "io/results/results_h5.hpp"
#include "io/results/results_log.hpp"
#include "io/results/xdmf_writer.hpp"

namespace xpl::io {

namespace {

using Clock = std::chrono::steady_clock;

/// Wall time before the progress line appears, s: short runs stay quiet.
constexpr double PROGRESS_DELAY = 2.0;
/// Minimum wall time between two updates of the progress line, s.
constexpr double PROGRESS_INTERVAL = 0.2;

const char* status_name(RunStatus status) {
  switch (status) {
    case RunStatus::Completed:
      return "completed";
    case RunStatus::Checked:
      return "checked";
    case RunStatus::Failed:
      return "failed";
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
  ResultOptions options;
  ResultsH5 h5_file;
  XdmfWriter xdmf_file;
  StaFile sta_file;
  MsgFile msg_file;

  int step = 0;                 ///< zero-based current step
  Real step_period = 0.0;       ///< time period of the current step, s
  std::string step_name;        ///< name of the current step
  bool ended = false;           ///< end_run was called
  bool progress_tty = false;    ///< stderr is a terminal
  bool progress_shown = false;  ///< a progress line is on the terminal
  Clock::time_point start = Clock::now();
  Clock::time_point last_progress{};  ///< when the progress line was last updated

  Impl(const std::filesystem::path& directory, const std::string& job, ResultOptions opts)
      : h5(prepared(directory) / (job + ".h5")),
        xdmf(directory / (job + ".xdmf")),
        sta(directory / (job + ".sta")),
        msg(directory / (job + ".msg")),
        options(opts),
        h5_file(h5, job),
        xdmf_file(xdmf, job + ".h5"),
        sta_file(sta, job),
        msg_file(msg, job),
        progress_tty(opts.progress && isatty(STDERR_FILENO) == 1) {}

  /// Creates the output directory (before any file in it is opened).
  static const std::filesystem::path& prepared(const std::filesystem::path& directory) {
    if (!directory.empty()) std::filesystem::create_directories(directory);
    return directory;
  }

  /// Updates the progress line on stderr (only on a terminal, after PROGRESS_DELAY).
  void progress(const StatusLine& line) {
    if (!progress_tty || seconds_since(start) < PROGRESS_DELAY) return;
    const auto now = Clock::now();
    if (progress_shown &&
        std::chrono::duration<double>(now - last_progress).count() < PROGRESS_INTERVAL) {
      return;
    }
    last_progress = now;
    const double percent = step_period > 0.0 ? 100.0 * line.step_time / step_period : 0.0;
    std::fprintf(stderr, "\rstep %d  t = %.4e / %.4e s (%5.1f%%)  increment %ld  dt = %.3e   ",
                 step + 1, line.step_time, step_period, percent, line.increment, line.dt);
    std::fflush(stderr);
    progress_shown = true;
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
    m_impl->h5_file.finish("failed", "the run ended without end_run");
  } catch (...) {  // NOLINT(bugprone-empty-catch): a destructor must not throw
  }
}

void ResultFiles::begin_run(const Model& model) {
  m_impl->start = Clock::now();
  m_impl->xdmf_file.set_mesh(m_impl->h5_file.write_mesh(model));
  m_impl->msg_file.summary(model);
}

void ResultFiles::begin_step(const Model& model, int step) {
  Impl& impl = *m_impl;
  impl.step = step;
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

void ResultFiles::write_frame(const Model& model, const State& state, const FrameRequest& what) {
  const std::string frame = m_impl->h5_file.write_frame(model, state, what);
  m_impl->xdmf_file.add_frame(frame, state.time, what);
}

void ResultFiles::append_history(Real time, std::span<const Real> values) {
  m_impl->h5_file.append_history(time, values);
}

void ResultFiles::status(const StatusLine& line) {
  m_impl->sta_file.line(m_impl->step + 1, line);
  m_impl->progress(line);
}

void ResultFiles::message(Severity severity, const std::string& text) {
  m_impl->msg_file.message(severity, text);
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
  impl.sta_file.finish(status, error, timers, element_cycles_per_second);
  impl.msg_file.finish(status, error, timers, element_cycles_per_second);
  impl.h5_file.finish(status_name(status), error);
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

}  // namespace xpl::io
