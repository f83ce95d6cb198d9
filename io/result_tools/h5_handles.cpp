#include "io/result_tools/h5_handles.hpp"

#include <algorithm>
#include <array>
#include <utility>

namespace xpl::io::h5 {

namespace {

/// Collects the description of the deepest entry of the HDF5 error stack.
herr_t collect_error(unsigned /*n*/, const H5E_error2_t* error, void* client_data) {
  auto* text = static_cast<std::string*>(client_data);
  if (error->desc != nullptr && error->desc[0] != '\0') *text = error->desc;
  return 0;
}

Handle make_space(const std::vector<hsize_t>& dims, const std::vector<hsize_t>& max_dims = {}) {
  const hsize_t* max = max_dims.empty() ? nullptr : max_dims.data();
  return {check_id(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), max),
                   "cannot create a dataspace"),
          H5Sclose};
}

void write_dataset(hid_t parent, const std::string& name, hid_t type, const void* data,
                   std::size_t size, const std::vector<hsize_t>& dims) {
  hsize_t expected = 1;
  for (hsize_t d : dims) expected *= d;
  if (expected != size) {
    throw Error("HDF5: dataset " + name + ": " + std::to_string(size) +
                " values do not fill the requested shape");
  }
  const Handle space = make_space(dims);
  const Handle dataset{check_id(H5Dcreate2(parent, name.c_str(), type, space.get(), H5P_DEFAULT,
                                           H5P_DEFAULT, H5P_DEFAULT),
                                "cannot create dataset " + name),
                       H5Dclose};
  if (size == 0) return;
  check(H5Dwrite(dataset.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data),
        "cannot write dataset " + name);
}

/// A copy of `space` (rows × width, or rows) with the rows of runs[first, last) selected.
/// Halves merged (H5Scombine_select): HDF5 1.10 adds a block to a selection of k blocks in
/// O(k), so one block after the other costs O(k²) (2 s for 6000 runs of a 97k-row dataset
/// here); by halves O(k log k) (0.03 s).
Handle select_runs(hid_t space, const RowRuns& runs, std::size_t first, std::size_t last) {
  constexpr std::size_t ONE_BY_ONE = 32;
  if (last - first > ONE_BY_ONE) {
    const std::size_t middle = first + (last - first) / 2;
    const Handle low = select_runs(space, runs, first, middle);
    const Handle high = select_runs(space, runs, middle, last);
    return {check_id(H5Scombine_select(low.get(), H5S_SELECT_OR, high.get()), "cannot select rows"),
            H5Sclose};
  }
  Handle rows{check_id(H5Scopy(space), "cannot copy a dataspace"), H5Sclose};
  check(H5Sselect_none(rows.get()), "cannot select rows");
  hsize_t dims[2] = {0, 1};  // one-dimensional: dims[1] stays 1 (and is not read)
  check(H5Sget_simple_extent_dims(space, dims, nullptr), "cannot read a dataspace");
  for (std::size_t k = first; k < last; ++k) {
    const std::array<hsize_t, 2> start{runs[k].first, 0}, block{runs[k].second, dims[1]};
    check(H5Sselect_hyperslab(rows.get(), H5S_SELECT_OR, start.data(), nullptr, block.data(),
                              nullptr),
          "cannot select rows");
  }
  return rows;
}

/// Creates the attribute `name` of `object`, replacing an existing one (e.g. the status).
Handle require_attribute(hid_t object, const std::string& name, hid_t type, hid_t space) {
  const htri_t exists = H5Aexists(object, name.c_str());
  if (exists < 0) fail("cannot query attribute " + name);
  if (exists > 0) check(H5Adelete(object, name.c_str()), "cannot replace attribute " + name);
  return {check_id(H5Acreate2(object, name.c_str(), type, space, H5P_DEFAULT, H5P_DEFAULT),
                   "cannot create attribute " + name),
          H5Aclose};
}

void set_scalar_attribute(hid_t object, const std::string& name, hid_t type, const void* value) {
  const Handle space{check_id(H5Screate(H5S_SCALAR), "cannot create a dataspace"), H5Sclose};
  const Handle attribute = require_attribute(object, name, type, space.get());
  check(H5Awrite(attribute.get(), type, value), "cannot write attribute " + name);
}

}  // namespace

void silence_errors() {
  // No library shutdown at exit: after a failed write (a full disk) H5Fclose leaves the file
  // half closed, and HDF5's exit handler then crashes closing it again. Every file xpl opens
  // is closed by its Handle before main returns. (Effective only before the first HDF5 call;
  // later calls fail harmlessly.)
  H5dont_atexit();
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

void fail(const std::string& what) {
  std::string reason;
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_DOWNWARD, collect_error, &reason);
  H5Eclear2(H5E_DEFAULT);
  throw Error("HDF5: " + what + (reason.empty() ? std::string() : ": " + reason));
}

bool lock_refused() {
  bool refused = false;
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_DOWNWARD,
      [](unsigned /*n*/, const H5E_error2_t* error, void* data) -> herr_t {
        if (error->min_num == H5E_CANTLOCKFILE) *static_cast<bool*>(data) = true;
        return 0;
      },
      &refused);
  return refused;
}

hid_t check_id(hid_t id, const std::string& what) {
  if (id < 0) fail(what);
  return id;
}

void check(herr_t status, const std::string& what) {
  if (status < 0) fail(what);
}

Handle::Handle(Handle&& other) noexcept
    : m_id(std::exchange(other.m_id, -1)), m_closer(other.m_closer) {}

Handle& Handle::operator=(Handle&& other) noexcept {
  if (this != &other) {
    reset();
    m_id = std::exchange(other.m_id, -1);
    m_closer = other.m_closer;
  }
  return *this;
}

void Handle::reset() {
  if (m_id >= 0 && m_closer != nullptr) m_closer(m_id);
  m_id = -1;
}

hid_t Handle::release() {
  return std::exchange(m_id, -1);
}

Handle require_group(hid_t parent, const std::string& path) {
  const htri_t exists = H5Lexists(parent, path.c_str(), H5P_DEFAULT);
  if (exists > 0) {
    return {check_id(H5Gopen2(parent, path.c_str(), H5P_DEFAULT), "cannot open group " + path),
            H5Gclose};
  }
  H5Eclear2(H5E_DEFAULT);  // H5Lexists fails (harmlessly) when an intermediate link is missing
  const Handle link_properties{check_id(H5Pcreate(H5P_LINK_CREATE), "cannot create properties"),
                               H5Pclose};
  check(H5Pset_create_intermediate_group(link_properties.get(), 1), "cannot set properties");
  return {
      check_id(H5Gcreate2(parent, path.c_str(), link_properties.get(), H5P_DEFAULT, H5P_DEFAULT),
               "cannot create group " + path),
      H5Gclose};
}

void write_int64(hid_t parent, const std::string& name, std::span<const std::int64_t> data,
                 const std::vector<hsize_t>& dims) {
  write_dataset(parent, name, H5T_NATIVE_INT64, data.data(), data.size(), dims);
}

void write_uint8(hid_t parent, const std::string& name, std::span<const std::uint8_t> data,
                 const std::vector<hsize_t>& dims) {
  write_dataset(parent, name, H5T_NATIVE_UINT8, data.data(), data.size(), dims);
}

void write_real(hid_t parent, const std::string& name, std::span<const double> data,
                const std::vector<hsize_t>& dims) {
  write_dataset(parent, name, H5T_NATIVE_DOUBLE, data.data(), data.size(), dims);
}

void write_real_rows(hid_t parent, const std::string& name, std::span<const double> data,
                     const std::vector<hsize_t>& dims, const RowRuns& runs) {
  hsize_t expected = 1;
  for (hsize_t d : dims) expected *= d;
  if (expected != data.size()) {
    throw Error("HDF5: dataset " + name + ": " + std::to_string(data.size()) +
                " values do not fill the requested shape");
  }
  const Handle space = make_space(dims);
  const Handle dataset{check_id(H5Dcreate2(parent, name.c_str(), H5T_NATIVE_DOUBLE, space.get(),
                                           H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                                "cannot create dataset " + name),
                       H5Dclose};
  // The same selection in memory (the whole shape) and in the file: the rows stay where they
  // are; an empty selection still takes part in the collective write.
  const Handle rows = select_runs(space.get(), runs, 0, runs.size());
  const Handle transfer{check_id(H5Pcreate(H5P_DATASET_XFER), "cannot create properties"),
                        H5Pclose};
#ifdef H5_HAVE_PARALLEL
  check(H5Pset_dxpl_mpio(transfer.get(), H5FD_MPIO_COLLECTIVE), "cannot set collective writes");
#endif
  check(H5Dwrite(dataset.get(), H5T_NATIVE_DOUBLE, rows.get(), rows.get(), transfer.get(),
                 data.data()),
        "cannot write dataset " + name);
}

void set_string_attribute(hid_t object, const std::string& name, const std::string& value) {
  const Handle type{check_id(H5Tcopy(H5T_C_S1), "cannot create a string type"), H5Tclose};
  check(H5Tset_size(type.get(), H5T_VARIABLE), "cannot create a string type");
  check(H5Tset_cset(type.get(), H5T_CSET_UTF8), "cannot create a string type");
  const char* text = value.c_str();
  set_scalar_attribute(object, name, type.get(), static_cast<const void*>(&text));
}

void set_real_attribute(hid_t object, const std::string& name, double value) {
  set_scalar_attribute(object, name, H5T_NATIVE_DOUBLE, &value);
}

void set_int64_attribute(hid_t object, const std::string& name, std::int64_t value) {
  set_scalar_attribute(object, name, H5T_NATIVE_INT64, &value);
}

void set_int64_array_attribute(hid_t object, const std::string& name,
                               std::span<const std::int64_t> values) {
  const Handle space = make_space({static_cast<hsize_t>(values.size())});
  const Handle attribute = require_attribute(object, name, H5T_NATIVE_INT64, space.get());
  if (values.empty()) return;
  check(H5Awrite(attribute.get(), H5T_NATIVE_INT64, values.data()),
        "cannot write attribute " + name);
}

AppendableDataset::AppendableDataset(hid_t file, const std::string& path, hsize_t width)
    : m_path(path), m_width(width) {
  // Chunks of about 128 KiB at most: a few hundred rows of a narrow series, fewer of a wide one.
  const hsize_t chunk_rows = std::clamp<hsize_t>(16384 / std::max<hsize_t>(width, 1), 1, 256);
  std::vector<hsize_t> dims{0}, max_dims{H5S_UNLIMITED}, chunk{chunk_rows};
  if (width > 0) {
    dims.push_back(width);
    max_dims.push_back(width);
    chunk.push_back(width);
  }
  const Handle space = make_space(dims, max_dims);
  const Handle properties{check_id(H5Pcreate(H5P_DATASET_CREATE), "cannot create properties"),
                          H5Pclose};
  check(H5Pset_chunk(properties.get(), static_cast<int>(chunk.size()), chunk.data()),
        "cannot set the chunk size of " + path);
  const Handle dataset{check_id(H5Dcreate2(file, path.c_str(), H5T_NATIVE_DOUBLE, space.get(),
                                           H5P_DEFAULT, properties.get(), H5P_DEFAULT),
                                "cannot create dataset " + path),
                       H5Dclose};
}

Handle AppendableDataset::open(hid_t file) const {
  return {check_id(H5Dopen2(file, m_path.c_str(), H5P_DEFAULT), "cannot open " + m_path), H5Dclose};
}

void AppendableDataset::append(hid_t file, const double* buffer, hsize_t rows, hsize_t buffer_width,
                               hsize_t column) {
  if (rows == 0) return;
  const Handle dataset = open(file);
  const hsize_t width = std::max<hsize_t>(m_width, 1);
  // For a one-dimensional dataset HDF5 reads only the first entry of these arrays.
  const std::array<hsize_t, 2> new_dims{m_rows + rows, width};
  check(H5Dset_extent(dataset.get(), new_dims.data()), "cannot extend dataset " + m_path);

  const Handle file_space{check_id(H5Dget_space(dataset.get()), "cannot get a dataspace"),
                          H5Sclose};
  const std::array<hsize_t, 2> file_start{m_rows, 0}, count{rows, width};
  check(H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, file_start.data(), nullptr,
                            count.data(), nullptr),
        "cannot select rows of " + m_path);

  // The memory side is the whole row buffer; HDF5 gathers this series' columns from it.
  const Handle memory_space = make_space({rows, buffer_width});
  const std::array<hsize_t, 2> memory_start{0, column};
  check(H5Sselect_hyperslab(memory_space.get(), H5S_SELECT_SET, memory_start.data(), nullptr,
                            count.data(), nullptr),
        "cannot select columns for " + m_path);
  check(H5Dwrite(dataset.get(), H5T_NATIVE_DOUBLE, memory_space.get(), file_space.get(),
                 H5P_DEFAULT, buffer),
        "cannot write rows of " + m_path);
  m_rows += rows;
}

}  // namespace xpl::io::h5
