#pragma once
/// \file `xpl compare REF.h5 NEW.h5`: two xpl result files compared value by value with a
/// combined tolerance, for regression tests. History is compared on the reference's times
/// (the new run's rows interpolated linearly), fields frame by frame, nodes and elements
/// matched by their deck ids.

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/result_tools/json_value.hpp"

namespace xpl::io {

/// What to compare and how closely.
struct CompareOptions {
  double rtol = 0.0;  ///< relative tolerance: a value passes when |new − ref| ≤ atol + rtol·|ref|
  double atol = 0.0;  ///< absolute tolerance, in the units of each dataset
  /// Absolute tolerance as a fraction of the dataset's largest |ref| (scale-free: one value
  /// serves energies in J, displacements in m and stresses in Pa); adds to atol + rtol·|ref|.
  double ftol = 0.0;
  bool history = true;             ///< /history/step_N/* series
  bool fields = true;              ///< field datasets of the frames
  bool tables = true;              ///< /overclosure tables and /mesh/coordinates
  std::vector<std::string> names;  ///< field names to compare (U, S, ...); empty: all
  bool all_frames = false;         ///< every frame (paired in order), else the last one
};

/// One value of a dataset: where it is, the two values and their difference.
struct CompareValue {
  std::string where;        ///< "node 17, U2", "element 5, S12", "row 3", "ALLKE"
  double time = 0.0;        ///< time of the row or frame, s (NaN for tables)
  double reference = 0.0;   ///< value in REF
  double value = 0.0;       ///< value in NEW (interpolated on REF's time for history)
  double difference = 0.0;  ///< |value − reference| (infinite when one of them is NaN)
  double tolerance = 0.0;   ///< atol + rtol·|reference| + ftol·max|reference| of the dataset
};

/// The comparison of one dataset.
struct DatasetComparison {
  std::string name;     ///< path in REF, e.g. "/history/step_1/energy/ALLKE", "/frames/000010/U"
  long compared = 0;    ///< values compared
  long failed = 0;      ///< values outside the tolerance
  std::string problem;  ///< why it could not be compared value by value ("" when it could)
  bool has_largest = false;
  CompareValue largest;  ///< the largest difference
  bool has_worst = false;
  CompareValue worst;  ///< the failing value furthest outside its tolerance
  bool passed() const { return problem.empty() && failed == 0; }
};

/// Every dataset compared, and notes (datasets only NEW has, frame times that differ).
struct CompareReport {
  std::vector<DatasetComparison> datasets;
  std::vector<std::string> notes;
  bool passed() const;
  /// The report for CI systems (`--json`).
  JsonValue json(const CompareOptions& options, const std::string& reference,
                 const std::string& candidate) const;
};

/// An input that cannot be compared at all (exit code 2): a missing or non-HDF5 file, not an
/// xpl result, a failed, interrupted or unfinished run, another mesh. what() names the file.
class UnusableInput : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Compares NEW (`candidate`) with REF (`reference`). Throws UnusableInput.
CompareReport compare_results(const std::filesystem::path& reference,
                              const std::filesystem::path& candidate,
                              const CompareOptions& options);

}  // namespace xpl::io
