#pragma once
/// \file Reading xpl result files (JOB.h5) back: opening read-only with a clear refusal for a
/// missing or non-HDF5 file, datasets, attributes and group listings. Shared by --import
/// (import_state), `xpl compare` and `xpl history`.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/result_tools/h5_handles.hpp"

namespace xpl::io::h5 {

/// What most defects of a result file's structure expect.
inline constexpr const char* RESULT_FILE = "expected the .h5 result file of an xpl run";

/// A file that is not what the reader needs: what is wrong, and what is expected instead.
class FormatError : public std::runtime_error {
 public:
  FormatError(const std::string& problem, std::string expected)
      : std::runtime_error(problem), m_expected(std::move(expected)) {}
  const std::string& expected() const { return m_expected; }

 private:
  std::string m_expected;
};

/// Throws FormatError(problem, expected).
[[noreturn]] void refuse(const std::string& problem, std::string expected);

/// Opens `path` read-only. Throws FormatError when it does not exist, is not a regular file
/// or is not an HDF5 file (a truncated or damaged one included), Error when HDF5 fails. A
/// file another process holds for writing (a running job's JOB.h5 during a write) is retried
/// for up to 5 s.
Handle open_read_only(const std::filesystem::path& path, const std::string& expected = RESULT_FILE);

/// Whether the link `path` (absolute) exists, every intermediate group included.
bool has_link(hid_t file, const std::string& path);

/// Whether the object at `path` is a dataset (false for a group or a missing link).
bool is_dataset(hid_t file, const std::string& path);

/// Names of the links of the group at `path`, in name order (empty when there is none).
std::vector<std::string> group_members(hid_t file, const std::string& path);

/// Shape of the dataset at `path` (empty for a scalar).
std::vector<hsize_t> dataset_shape(hid_t file, const std::string& path);

/// Whether the dataset at `path` holds integers.
bool is_integer_dataset(hid_t file, const std::string& path);

/// The values (row-major) of the dataset `path`: one-dimensional when `width` is 0, else
/// rows × width; `rows` empty accepts any number of rows. Integers for T = int64, floats for
/// T = double; a missing dataset, another type class or another shape throws FormatError.
template <class T>
std::vector<T> read_array(hid_t file, const std::string& path, std::optional<hsize_t> rows,
                          hsize_t width, const std::string& expected = RESULT_FILE);

/// Every value of the dataset `path` as float64 (integers converted), row-major, any shape.
std::vector<double> read_as_real(hid_t file, const std::string& path);

/// A scalar numeric attribute `name` of the object at `path`, as T (double or int64);
/// FormatError when it is missing or not a single value.
template <class T>
T numeric_attribute(hid_t file, const std::string& path, const char* name,
                    const std::string& expected = RESULT_FILE);

/// A string attribute `name` of the object at `path`, or nothing when it is missing or not
/// a string.
std::optional<std::string> string_attribute(hid_t file, const std::string& path, const char* name);

/// A one-dimensional integer attribute `name` of the object at `path`, or nothing.
std::optional<std::vector<std::int64_t>> int64_array_attribute(hid_t file, const std::string& path,
                                                               const char* name);

/// Checks /mesh/element_ids (`element_ids`, the rows of every cell field) against the type
/// groups /mesh/C3D8R, /mesh/C3D8, /mesh/S4R that exist: each group lists its elements in row
/// order, at the rows its /mesh/TYPE/element_rows gives (a mixed mesh) or else as the next
/// rows of its type (results_mesh.hpp), and the groups together list every row once. A file
/// whose /mesh/element_ids was reordered without its fields (which would put each element's
/// values on another) throws FormatError naming the first row that disagrees.
void check_element_rows(hid_t file, const std::vector<std::int64_t>& element_ids,
                        const std::string& expected = RESULT_FILE);

}  // namespace xpl::io::h5
