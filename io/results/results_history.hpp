#pragma once
/// \file History output of one step in JOB.h5: /history/step_N/time and one extendible
/// dataset per HistorySeries, written from a row buffer in chunks.

#include <cstddef>
#include <optional>
#include <span>
#include <vector>

#include "common/units.hpp"
#include "io/result_tools/h5_handles.hpp"
#include "solver/output/output_sink.hpp"

namespace xpl::io {

/// Buffers history rows of the current step and appends them to JOB.h5 in blocks, so that
/// nothing touches the file on most append() calls. It holds no HDF5 handle: every call that
/// writes takes the open file, which the caller closes again (JOB.h5 is closed between writes
/// so that readers can open it during a run, results_h5.hpp).
class HistoryWriter {
 public:
  /// Rows buffered before they are written to the file.
  static constexpr std::size_t ROWS_PER_WRITE = 256;

  /// Starts the history of `step` (1-based; group /history/step_N of the open `file`) with
  /// the given columns, their `units` attributes labelled in `units` (the series give SI
  /// units). Ends the history of a previous step first.
  void begin(hid_t file, int step, const std::vector<HistorySeries>& series,
             const ModelUnits& units);
  /// Whether a step's history is open.
  bool active() const { return m_time.has_value(); }
  /// Buffers one row; `values` holds every series' columns back to back. Returns true when
  /// ROWS_PER_WRITE rows are buffered: the caller then writes them (write_pending).
  bool append(Real time, std::span<const Real> values);
  /// Whether rows are buffered that the file does not have yet.
  bool pending() const { return !m_times.empty(); }
  /// Writes the buffered rows to the open `file`.
  void write_pending(hid_t file);
  /// Ends the step's history; its rows must have been written (write_pending) first.
  void end();

 private:
  std::optional<h5::AppendableDataset> m_time;
  std::vector<h5::AppendableDataset> m_series;
  std::vector<hsize_t> m_columns;  ///< first column of each series in a row
  hsize_t m_row_width = 0;         ///< sum of the series widths
  std::vector<Real> m_times;       ///< buffered times (rows)
  std::vector<Real> m_values;      ///< buffered rows (rows × m_row_width), row-major
  int m_step = 0;
};

}  // namespace xpl::io
