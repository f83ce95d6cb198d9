#pragma once
/// \file The result files of a job: JOB.h5 (+ JOB.xdmf), JOB.sta, JOB.msg.

#include <filesystem>
#include <memory>
#include <string>

#include "solver/output/output_sink.hpp"

namespace xpl::io {

/// Options of the result files.
struct ResultOptions {
  bool progress = true;  ///< a progress line on stderr for runs longer than ~2 s
  int threads = 0;       ///< OpenMP threads of the run, for the summary
};

/// An OutputSink that writes JOB.h5, JOB.xdmf, JOB.sta and JOB.msg into a directory, and at
/// the end of the run, however it ends, JOB.summary.json and /summary (run_summary_file.hpp).
/// JOB.h5 is closed between writes (results_h5.hpp), so it is complete if the run dies and
/// readable while it runs.
/// The constructor takes the job lock (JOB.lck, see JobLock) before it opens any file and
/// throws JobLocked if another run of the job holds it; the destructor releases it.
class ResultFiles final : public OutputSink {
 public:
  ResultFiles(const std::filesystem::path& directory, const std::string& job_name,
              ResultOptions options = {});
  ~ResultFiles() override;
  ResultFiles(const ResultFiles&) = delete;
  ResultFiles& operator=(const ResultFiles&) = delete;

  void begin_run(const Model& model) override;
  void begin_step(const Model& model, int step) override;
  void declare_history(const std::vector<HistorySeries>& series) override;
  void write_frame(const Model& model, const State& state, const FrameFields& fields,
                   const FrameRequest& what) override;
  void append_history(Real time, std::span<const Real> values) override;
  void status(const StatusLine& line) override;
  void message(Severity severity, const std::string& text) override;
  void status_note(const std::string& text) override;
  void energy_drift(const BalanceDrift& drift) override;
  void distribution(const DistributionSummary& summary) override;
  void write_table(const ResultTable& table) override;
  void end_run(RunStatus status, const std::string& error, const PhaseTimers& timers,
               double element_cycles_per_second) override;

  /// Ends a run abandoned by an exception outside the solver's time loop: status "failed"
  /// with `cause` wherever it can still be written. Does nothing after end_run.
  void fail(const std::string& cause) noexcept;

  /// Paths of the files written.
  std::filesystem::path h5_path() const;
  std::filesystem::path xdmf_path() const;
  std::filesystem::path sta_path() const;
  std::filesystem::path msg_path() const;
  std::filesystem::path summary_path() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

}  // namespace xpl::io
