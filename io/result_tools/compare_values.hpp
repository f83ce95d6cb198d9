#pragma once
/// \file The value-by-value part of `xpl compare` (result_compare.hpp): one dataset of REF
/// against the same dataset of NEW, rows matched by deck id, history interpolated on REF's
/// times, the largest and the worst difference kept.

#include <hdf5.h>

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "io/result_tools/result_compare.hpp"

namespace xpl::io {

/// How REF's history times fall in NEW's: NEW's value at REF's row i is
/// (1 − weight[i])·v[lower[i]] + weight[i]·v[lower[i] + 1], exactly v[lower[i]] when the times
/// are equal, and none when REF's time lies outside NEW's history.
class TimeMap {
 public:
  /// `reference` and `candidate`: the time columns (s), each non-decreasing.
  TimeMap(const std::vector<double>& reference, const std::vector<double>& candidate);
  /// Whether REF's row i lies inside NEW's times (within 1e-9 of the time span).
  bool inside(std::size_t i) const { return m_inside[i]; }
  /// NEW's value at REF's row i from NEW's column `column` of `values` (rows × width).
  double at(std::size_t i, const std::vector<double>& values, std::size_t width,
            std::size_t column) const;
  /// NEW's first and last time, s (0 when NEW has no rows).
  double first() const { return m_first; }
  double last() const { return m_last; }
  /// Rows of NEW's history.
  std::size_t rows() const { return m_rows; }

 private:
  std::size_t m_rows = 0;
  std::vector<std::size_t> m_lower;
  std::vector<double> m_weight;
  std::vector<bool> m_inside;
  double m_first = 0.0, m_last = 0.0;
};

/// Rows of REF mapped to rows of NEW by deck id (node_map[r]: NEW's row of REF's node row r),
/// and which field names are per node.
struct RowMaps {
  const std::vector<std::size_t>* node_map;
  const std::vector<std::size_t>* element_map;
  std::function<bool(const std::string&)> nodal;
};

/// Every dataset below the group `group`, recursively, in name order (empty if none).
std::vector<std::string> dataset_paths(hid_t file, const std::string& group);

/// A history series `path` (nt × width, columns matched by their node_ids attribute).
DatasetComparison compare_series(hid_t ref, hid_t cand, const std::string& path,
                                 const TimeMap& times, const std::vector<double>& ref_time,
                                 const CompareOptions& options);

/// A field `name` of a frame at time `time` (s), rows mapped by `maps`.
DatasetComparison compare_field(hid_t ref, hid_t cand, const std::string& ref_path,
                                const std::string& cand_path, const std::string& name, double time,
                                const RowMaps& maps, const CompareOptions& options);

/// A table column (/overclosure/...): the same shape, values in row order; both empty is equal.
DatasetComparison compare_table(hid_t ref, hid_t cand, const std::string& path,
                                const CompareOptions& options);

/// A number as "%.6g".
std::string format_number(double value);

}  // namespace xpl::io
