#pragma once
/// \file The text logs of a job: JOB.sta (one line per status report, like Abaqus' status
/// file) and JOB.msg (model summary, step headers, notes, warnings, errors, timings). Text
/// that can come from a deck (names, messages, the heading) is written with its control
/// characters escaped (escape_control, common/error.hpp).

#include <filesystem>
#include <fstream>
#include <string>

#include "solver/output/output_sink.hpp"

namespace xpl::io {

/// JOB.sta: fixed-width columns, scientific notation, flushed after every line.
class StaFile {
 public:
  /// Creates (truncates) `path` and writes the header (xpl version, job, date).
  StaFile(const std::filesystem::path& path, const std::string& job);
  /// Header of step `step` (1-based) with the column titles.
  void begin_step(int step, const std::string& name);
  /// One status line of step `step` (1-based), `wall` seconds after the job's files were
  /// opened (the last column, WALL TIME).
  void line(int step, const StatusLine& line, double wall);
  /// A free text line (a summary between status lines), indented by one blank.
  void note(const std::string& text);
  /// The completion line, the error text if any, the phase timings and the speed.
  void finish(RunStatus status, const std::string& error, const PhaseTimers& timers,
              double element_cycles_per_second);

 private:
  std::ofstream m_out;
};

/// JOB.msg: the message file, flushed after every entry.
class MsgFile {
 public:
  /// Creates (truncates) `path` and writes the header (xpl version, job, date).
  MsgFile(const std::filesystem::path& path, const std::string& job);
  /// Model summary: the units, nodes, elements per type, materials, sets, surfaces, steps.
  void summary(const Model& model);
  /// Header of step `step` (zero-based index into model.steps).
  void begin_step(const Model& model, int step);
  /// One entry, prefixed "***NOTE:", "***WARNING:" or "***ERROR:" (nothing for Info).
  void message(Severity severity, const std::string& text);
  /// The outcome, the error text if any, the phase timings and the speed.
  void finish(RunStatus status, const std::string& error, const PhaseTimers& timers,
              double element_cycles_per_second);

 private:
  std::ofstream m_out;
};

/// The line that says how a run ended ("THE ANALYSIS HAS COMPLETED SUCCESSFULLY", ...).
const char* completion_text(RunStatus status);

}  // namespace xpl::io
