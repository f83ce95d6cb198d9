#pragma once
/// \file Small RAII layer over the HDF5 C API: owned handles, errors as exceptions, and the
/// few dataset and attribute helpers the result files need.

#include <hdf5.h>

#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace xpl::io::h5 {

/// A failed HDF5 call; what() says what xpl tried to do and the innermost HDF5 reason.
class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Switches off HDF5's automatic printing of error stacks (errors become exceptions).
void silence_errors();

/// Throws Error("HDF5: <what>: <innermost HDF5 message>") and clears the error stack.
[[noreturn]] void fail(const std::string& what);

/// Whether the current HDF5 error stack holds a refused file lock (HDF5 1.10 locks a file
/// for its writer; an open by another process fails until the writer closes it). Leaves the
/// stack as it is.
bool lock_refused();

/// Returns `id`, or throws Error if it is negative (an HDF5 failure).
hid_t check_id(hid_t id, const std::string& what);

/// Throws Error if `status` is negative (an HDF5 failure).
void check(herr_t status, const std::string& what);

/// An owned HDF5 identifier, closed with the matching H5?close in the destructor.
class Handle {
 public:
  using Closer = herr_t (*)(hid_t);
  Handle() = default;
  /// Takes ownership of `id` (which must be valid: check_id it first).
  Handle(hid_t id, Closer closer) : m_id(id), m_closer(closer) {}
  ~Handle() { reset(); }
  Handle(Handle&& other) noexcept;
  Handle& operator=(Handle&& other) noexcept;
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;

  /// The raw identifier, for HDF5 calls.
  hid_t get() const { return m_id; }
  bool valid() const { return m_id >= 0; }
  /// Closes the identifier now (errors on close are ignored: nothing useful can be done).
  void reset();
  /// Gives up ownership: returns the identifier, which the caller must close (e.g. to check
  /// the result of H5Fclose, which writes the file's last metadata).
  hid_t release();

 private:
  hid_t m_id = -1;
  Closer m_closer = nullptr;
};

/// Opens (or creates, with intermediate groups) the group at `path` below `parent`.
Handle require_group(hid_t parent, const std::string& path);

/// Writes a new int64 dataset `name` below `parent` with shape `dims` (row-major data).
void write_int64(hid_t parent, const std::string& name, std::span<const std::int64_t> data,
                 const std::vector<hsize_t>& dims);

/// Writes a new uint8 dataset `name` below `parent` with shape `dims` (flags).
void write_uint8(hid_t parent, const std::string& name, std::span<const std::uint8_t> data,
                 const std::vector<hsize_t>& dims);

/// Writes a new float64 dataset `name` below `parent` with shape `dims` (row-major data).
void write_real(hid_t parent, const std::string& name, std::span<const double> data,
                const std::vector<hsize_t>& dims);

/// Runs of consecutive rows of a dataset, [first, first + count), in ascending order.
using RowRuns = std::vector<std::pair<hsize_t, hsize_t>>;

/// write_real of the rows `runs` only: `data` holds the whole shape `dims` (row-major; the
/// other rows are not read), and the rows go where they belong in the new dataset. In a file
/// opened with MPI-IO (parallel HDF5) a collective write: every process of the file calls it
/// with the same name and dims and its own runs (the runs of the processes apart, together
/// every row), an empty `runs` included.
void write_real_rows(hid_t parent, const std::string& name, std::span<const double> data,
                     const std::vector<hsize_t>& dims, const RowRuns& runs);

/// Sets (creates or overwrites) a variable-length UTF-8 string attribute.
void set_string_attribute(hid_t object, const std::string& name, const std::string& value);

/// Sets a scalar float64 attribute.
void set_real_attribute(hid_t object, const std::string& name, double value);

/// Sets a scalar int64 attribute.
void set_int64_attribute(hid_t object, const std::string& name, std::int64_t value);

/// Sets a one-dimensional int64 attribute.
void set_int64_array_attribute(hid_t object, const std::string& name,
                               std::span<const std::int64_t> values);

/// A float64 dataset of shape (rows) or (rows × width) that grows by appending rows. It keeps
/// no HDF5 handle, only its path and row count: the file may be closed between two appends
/// (JOB.h5 is closed between writes so that readers can open it, results_h5.hpp).
class AppendableDataset {
 public:
  /// Creates the chunked dataset `path` (below the root of the open `file`; its groups must
  /// exist) with zero rows. `width` 0 means a one-dimensional dataset.
  AppendableDataset(hid_t file, const std::string& path, hsize_t width);

  /// Appends `rows` rows taken from a row-major buffer of `buffer_width` columns, starting at
  /// column `column` (the values of all series sit side by side in one buffer), to the dataset
  /// in the open `file`.
  void append(hid_t file, const double* buffer, hsize_t rows, hsize_t buffer_width, hsize_t column);

  /// Opens the dataset in the open `file` (for attributes).
  Handle open(hid_t file) const;
  hsize_t rows() const { return m_rows; }

 private:
  std::string m_path;
  hsize_t m_width = 0;  ///< 0: one-dimensional
  hsize_t m_rows = 0;
};

}  // namespace xpl::io::h5
