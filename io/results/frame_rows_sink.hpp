#pragma once
/// \file The sink of a rank other than 0 in a distributed run whose ranks write each frame
/// together (issue 37 item 5, docs/dev/mpi.md): the rank's rows of each frame into JOB.h5,
/// which rank 0's ResultFiles created and writes everything else of.

#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "solver/output/output_sink.hpp"

namespace xpl::io {

class ResultsH5;

/// Writes the rows of this rank's nodes and elements of each frame (FrameRows) into the
/// existing `h5` with the other ranks (collective, parallel HDF5: every rank's sink gets
/// every frame); ignores everything else.
class FrameRowsSink final : public OutputSink {
 public:
  explicit FrameRowsSink(const std::filesystem::path& h5);
  ~FrameRowsSink() override;
  FrameRowsSink(const FrameRowsSink&) = delete;
  FrameRowsSink& operator=(const FrameRowsSink&) = delete;

  void begin_run(const Model& model) override;
  void begin_step(const Model&, int) override {}
  void declare_history(const std::vector<HistorySeries>&) override {}
  void write_frame(const Model& model, const State& state, const FrameFields& fields,
                   const FrameRequest& what) override;
  void append_history(Real, std::span<const Real>) override {}
  void status(const StatusLine&) override {}
  void message(Severity, const std::string&) override {}
  void end_run(RunStatus, const std::string&, const PhaseTimers&, double) override {}

 private:
  std::unique_ptr<ResultsH5> m_h5;
};

}  // namespace xpl::io
