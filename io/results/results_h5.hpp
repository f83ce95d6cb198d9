#pragma once
/// \file JOB.h5: mesh, field frames, history and the run status (layout in docs/user/results.md).

#include <filesystem>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "io/result_tools/h5_handles.hpp"
#include "io/result_tools/json_value.hpp"
#include "io/results/results_frame.hpp"
#include "io/results/results_history.hpp"
#include "io/results/xdmf_writer.hpp"
#include "solver/output/output_sink.hpp"

namespace xpl::io {

/// The HDF5 result file of one job. Every write (the mesh, a frame, a block of history rows,
/// a table, the status) opens JOB.h5, writes and closes it again with every handle, so that
/// between writes the file on disk is complete and unlocked: a reader (h5py, ParaView) may
/// open it during the run and sees a consistent prefix of the frames, and a run that dies
/// leaves the file as of its last write. While the writer holds the file (milliseconds per
/// frame), HDF5's file lock makes a reader's open fail ("unable to lock file"): the reader
/// retries. While a reader holds the file, the writer waits (up to LOCK_WAIT, then the write
/// fails).
class ResultsH5 {
 public:
  /// Longest wait for a reader to release JOB.h5 before a write, s.
  static constexpr double LOCK_WAIT = 300.0;
  /// Waits longer than this are reported through the wait notice (set_wait_notice), s.
  static constexpr double LOCK_NOTICE = 1.0;

  /// Creates (truncates) `path` with status "running".
  ResultsH5(const std::filesystem::path& path, const std::string& job);
  /// The file `path` that another rank of a distributed run created and writes, of which
  /// this rank writes its rows of each frame with the others (write_frame with
  /// FrameRows::collective) and nothing else. The model's units come with set_units.
  struct FramesOnly {};
  ResultsH5(const std::filesystem::path& path, FramesOnly);
  /// How the model's numbers are labelled (write_mesh sets them too).
  void set_units(const ModelUnits& units);

  /// Writes /mesh (results_mesh.hpp) and the heading attribute; returns how the XDMF file
  /// finds the mesh.
  XdmfMesh write_mesh(const Model& model);
  /// A new step (zero-based) starts: ends the history of the previous one.
  void begin_step(int step);
  /// Declares the history columns of the current step (/history/step_N).
  void declare_history(const std::vector<HistorySeries>& series);
  /// Buffers one history row (written every HistoryWriter::ROWS_PER_WRITE rows).
  void append_history(Real time, std::span<const Real> values);
  /// Writes /frames/NNNNNN and returns its name ("000000"). With fields.rows.collective
  /// every rank of the distributed run calls it for the frame, each writing its rows, in one
  /// opening of the file with MPI-IO (with_shared_file); rank 0 writes the pending history
  /// rows before, alone. On shell models U, V, RF, S come
  /// with UR, VR, RM, S_SNEG + S_SPOS; STH is written only on shell models.
  std::string write_frame(const Model& model, const State& state, const FrameFields& fields,
                          const FrameRequest& what);
  /// Writes a setup table as a group of column datasets (OutputSink::write_table).
  void write_table(const ResultTable& table);
  /// Writes pending history rows, the final status and error text. A run that
  /// did not complete also records `time_reached` (total time of its last status line, s).
  void finish(const std::string& status, const std::string& error,
              std::optional<double> time_reached = std::nullopt);
  /// Writes the status attributes only (as finish): the fallback when finish
  /// failed, e.g. on a full disk, where the pending history rows do not fit but a small
  /// attribute may still.
  void record_status(const std::string& status, const std::string& error,
                     std::optional<double> time_reached = std::nullopt);
  /// Writes the run summary (run_summary_file.hpp) as attributes of the group /summary:
  /// nested keys joined by '.' ("wall_time.setup"), booleans as int64 0/1, null as NaN.
  void write_summary(const JsonValue& summary);
  /// Called with a sentence when a write waited more than LOCK_NOTICE for a reader.
  void set_wait_notice(std::function<void(const std::string&)> notice) {
    m_wait_notice = std::move(notice);
  }
  /// Number of frames written.
  int frame_count() const { return m_frames; }

 private:
  /// `text` with each word "m" (a length in the solver's SI descriptions) in the model's
  /// length unit.
  std::string with_length_unit(const std::string& text) const;
  /// Opens JOB.h5 for writing (waiting while a reader holds HDF5's lock on it), calls
  /// `write` with the file id, then flushes and closes the file; on an exception the file is
  /// closed too and the exception passes on.
  void with_file(const std::function<void(hid_t)>& write);
  /// with_file() on every rank of MPI_COMM_WORLD together (collective): JOB.h5 opened with
  /// MPI-IO (parallel HDF5; XPL_MPI=ON builds only, else std::logic_error).
  void with_shared_file(const std::function<void(hid_t)>& write);

  h5::Handle m_access;  ///< file access properties (a property list, not an open file)
  HistoryWriter m_history;
  ModelUnits m_units;  ///< how the model's numbers are labelled (from write_mesh)
  std::function<void(const std::string&)> m_wait_notice;
  std::string m_path;
  int m_step = 0;  ///< zero-based current step
  int m_frames = 0;
};

}  // namespace xpl::io
