#include "io/result_tools/h5_reader.hpp"

#include <algorithm>
#include <chrono>
#include <sstream>
#include <system_error>
#include <thread>
#include <type_traits>

namespace xpl::io::h5 {

namespace {

/// Longest wait for a writer to release a file it holds (xpl writing a frame of a running
/// job holds JOB.h5 for milliseconds), s; the message below says 5 s.
constexpr double WRITER_WAIT = 5.0;

Handle open_dataset(hid_t file, const std::string& path, const std::string& expected) {
  if (!has_link(file, path)) refuse("the file has no " + path, expected);
  return {check_id(H5Dopen2(file, path.c_str(), H5P_DEFAULT), path), H5Dclose};
}

std::vector<hsize_t> shape_of(hid_t dataset, const std::string& path) {
  const Handle space{check_id(H5Dget_space(dataset), path), H5Sclose};
  const int rank = H5Sget_simple_extent_ndims(space.get());
  std::vector<hsize_t> dims(static_cast<std::size_t>(std::max(rank, 0)));
  if (rank < 0 || H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr) < 0) {
    fail("cannot read the shape of " + path);
  }
  return dims;
}

/// The attribute `name` of the object at `path`, or an invalid handle when it is missing.
Handle open_attribute(hid_t file, const std::string& path, const char* name) {
  const htri_t exists = H5Aexists_by_name(file, path.c_str(), name, H5P_DEFAULT);
  if (exists < 0) fail("cannot look up attribute " + std::string(name) + " of " + path);
  if (exists == 0) return {};
  return {check_id(H5Aopen_by_name(file, path.c_str(), name, H5P_DEFAULT, H5P_DEFAULT), name),
          H5Aclose};
}

}  // namespace

void refuse(const std::string& problem, std::string expected) {
  throw FormatError(problem, std::move(expected));
}

Handle open_read_only(const std::filesystem::path& path, const std::string& expected) {
  std::error_code error;
  if (!std::filesystem::exists(path, error)) refuse("the file does not exist", expected);
  if (!std::filesystem::is_regular_file(path, error)) refuse("not a file", expected);
  silence_errors();
  if (H5Fis_hdf5(path.c_str()) <= 0) {
    H5Eclear2(H5E_DEFAULT);
    refuse("not an HDF5 file", expected + " (JOB.h5, not JOB.xdmf)");
  }
  // A running job's JOB.h5 is closed between writes (results_h5.hpp): while xpl writes, the
  // open is refused by HDF5's lock; try again for a while.
  const auto start = std::chrono::steady_clock::now();
  for (;;) {
    const hid_t id = H5Fopen(path.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
    if (id >= 0) return {id, H5Fclose};
    const bool locked = h5::lock_refused();
    H5Eclear2(H5E_DEFAULT);
    if (!locked) refuse("cannot be opened as HDF5 (truncated or damaged)", expected);
    const std::chrono::duration<double> waited = std::chrono::steady_clock::now() - start;
    if (waited.count() > WRITER_WAIT)
      refuse("another process keeps it open for writing (waited 5 s)", expected);
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

bool has_link(hid_t file, const std::string& path) {
  std::string prefix;
  std::stringstream parts(path);
  for (std::string part; std::getline(parts, part, '/');) {
    if (part.empty()) continue;
    prefix += "/" + part;
    const htri_t exists = H5Lexists(file, prefix.c_str(), H5P_DEFAULT);
    if (exists < 0) fail("cannot look up " + prefix);
    if (exists == 0) return false;
  }
  return true;
}

bool is_dataset(hid_t file, const std::string& path) {
  if (!has_link(file, path)) return false;
  const hid_t id = H5Oopen(file, path.c_str(), H5P_DEFAULT);
  if (id < 0) fail("cannot open " + path);
  const Handle object{id, H5Oclose};
  return H5Iget_type(object.get()) == H5I_DATASET;
}

std::vector<std::string> group_members(hid_t file, const std::string& path) {
  std::vector<std::string> names;
  if (!has_link(file, path)) return names;
  const Handle group{check_id(H5Gopen2(file, path.c_str(), H5P_DEFAULT), path), H5Gclose};
  H5G_info_t info;
  check(H5Gget_info(group.get(), &info), "cannot list " + path);
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    const ssize_t length = H5Lget_name_by_idx(group.get(), ".", H5_INDEX_NAME, H5_ITER_INC, i,
                                              nullptr, 0, H5P_DEFAULT);
    if (length < 0) fail("cannot list " + path);
    std::string name(static_cast<std::size_t>(length) + 1, '\0');
    H5Lget_name_by_idx(group.get(), ".", H5_INDEX_NAME, H5_ITER_INC, i, name.data(), name.size(),
                       H5P_DEFAULT);
    name.resize(static_cast<std::size_t>(length));
    names.push_back(name);
  }
  return names;
}

std::vector<hsize_t> dataset_shape(hid_t file, const std::string& path) {
  const Handle dataset = open_dataset(file, path, RESULT_FILE);
  return shape_of(dataset.get(), path);
}

bool is_integer_dataset(hid_t file, const std::string& path) {
  const Handle dataset = open_dataset(file, path, RESULT_FILE);
  const Handle type{check_id(H5Dget_type(dataset.get()), path), H5Tclose};
  return H5Tget_class(type.get()) == H5T_INTEGER;
}

template <class T>
std::vector<T> read_array(hid_t file, const std::string& path, std::optional<hsize_t> rows,
                          hsize_t width, const std::string& expected) {
  const Handle dataset = open_dataset(file, path, expected);
  const Handle type{check_id(H5Dget_type(dataset.get()), path), H5Tclose};
  constexpr bool integer = std::is_integral_v<T>;
  const H5T_class_t type_class = H5Tget_class(type.get());
  if (type_class != (integer ? H5T_INTEGER : H5T_FLOAT)) {
    refuse(path + " is not " + (integer ? "an integer" : "a floating-point") + " dataset",
           expected);
  }
  const std::vector<hsize_t> dims = shape_of(dataset.get(), path);
  const int rank = static_cast<int>(dims.size());
  const bool shape_ok =
      (width == 0 ? rank == 1 : rank == 2 && dims[1] == width) && (!rows || dims[0] == *rows);
  if (!shape_ok) {
    std::string shape, want = rows ? std::to_string(*rows) : "n";
    for (hsize_t d : dims) shape += (shape.empty() ? "" : " × ") + std::to_string(d);
    if (width > 0) want += " × " + std::to_string(width);
    refuse(path + " has shape (" + shape + ")", "expected (" + want + ") " + "for this model");
  }
  std::vector<T> values(static_cast<std::size_t>(dims.empty() ? 0 : dims[0]) *
                        static_cast<std::size_t>(std::max<hsize_t>(width, 1)));
  if (!values.empty()) {
    const hid_t memory_type = integer ? H5T_NATIVE_INT64 : H5T_NATIVE_DOUBLE;
    check(H5Dread(dataset.get(), memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()),
          "cannot read " + path);
  }
  return values;
}

template std::vector<std::int64_t> read_array(hid_t, const std::string&, std::optional<hsize_t>,
                                              hsize_t, const std::string&);
template std::vector<double> read_array(hid_t, const std::string&, std::optional<hsize_t>, hsize_t,
                                        const std::string&);

std::vector<double> read_as_real(hid_t file, const std::string& path) {
  const Handle dataset = open_dataset(file, path, RESULT_FILE);
  const Handle type{check_id(H5Dget_type(dataset.get()), path), H5Tclose};
  const H5T_class_t type_class = H5Tget_class(type.get());
  if (type_class != H5T_INTEGER && type_class != H5T_FLOAT)
    refuse(path + " is not a numeric dataset", RESULT_FILE);
  std::size_t count = 1;
  for (hsize_t d : shape_of(dataset.get(), path)) count *= static_cast<std::size_t>(d);
  std::vector<double> values(count);
  if (count > 0)
    check(H5Dread(dataset.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()),
          "cannot read " + path);
  return values;
}

template <class T>
T numeric_attribute(hid_t file, const std::string& path, const char* name,
                    const std::string& expected) {
  const Handle attribute = open_attribute(file, path, name);
  if (!attribute.valid()) refuse(path + " has no attribute " + name, expected);
  const Handle space{check_id(H5Aget_space(attribute.get()), name), H5Sclose};
  if (H5Sget_simple_extent_npoints(space.get()) != 1) {
    refuse("attribute " + std::string(name) + " of " + path + " is not a single value", expected);
  }
  T value{};
  const hid_t type = std::is_integral_v<T> ? H5T_NATIVE_INT64 : H5T_NATIVE_DOUBLE;
  check(H5Aread(attribute.get(), type, &value),
        "cannot read attribute " + std::string(name) + " of " + path);
  return value;
}

template double numeric_attribute(hid_t, const std::string&, const char*, const std::string&);
template std::int64_t numeric_attribute(hid_t, const std::string&, const char*, const std::string&);

std::optional<std::string> string_attribute(hid_t file, const std::string& path, const char* name) {
  const Handle attribute = open_attribute(file, path, name);
  if (!attribute.valid()) return std::nullopt;
  const Handle stored{check_id(H5Aget_type(attribute.get()), name), H5Tclose};
  if (H5Tget_class(stored.get()) != H5T_STRING || H5Tis_variable_str(stored.get()) <= 0)
    return std::nullopt;
  const Handle type{check_id(H5Tcopy(H5T_C_S1), name), H5Tclose};
  check(H5Tset_size(type.get(), H5T_VARIABLE), name);
  check(H5Tset_cset(type.get(), H5T_CSET_UTF8), name);  // as the writer stores it
  char* text = nullptr;
  if (H5Aread(attribute.get(), type.get(), static_cast<void*>(&text)) < 0) {
    H5Eclear2(H5E_DEFAULT);
    return std::nullopt;
  }
  std::string value = text != nullptr ? text : "";
  H5free_memory(text);
  return value;
}

std::optional<std::vector<std::int64_t>> int64_array_attribute(hid_t file, const std::string& path,
                                                               const char* name) {
  const Handle attribute = open_attribute(file, path, name);
  if (!attribute.valid()) return std::nullopt;
  const Handle type{check_id(H5Aget_type(attribute.get()), name), H5Tclose};
  if (H5Tget_class(type.get()) != H5T_INTEGER) return std::nullopt;
  const Handle space{check_id(H5Aget_space(attribute.get()), name), H5Sclose};
  const hssize_t count = H5Sget_simple_extent_npoints(space.get());
  if (count < 0) return std::nullopt;
  std::vector<std::int64_t> values(static_cast<std::size_t>(count));
  if (count > 0)
    check(H5Aread(attribute.get(), H5T_NATIVE_INT64, values.data()),
          "cannot read attribute " + std::string(name) + " of " + path);
  return values;
}

void check_element_rows(hid_t file, const std::vector<std::int64_t>& element_ids,
                        const std::string& expected) {
  struct Group {
    std::string path;
    std::vector<std::int64_t> ids;
    std::size_t next = 0;  ///< the next of `ids` to meet in row order
  };
  std::vector<Group> groups;
  for (const char* type : {"C3D8R", "C3D8", "S4R"}) {
    const std::string path = std::string("/mesh/") + type;
    if (!has_link(file, path)) continue;
    groups.push_back(
        {path, read_array<std::int64_t>(file, path + "/element_ids", std::nullopt, 0, expected)});
  }
  const auto id_text = [](std::int64_t id) { return std::to_string(id); };
  std::vector<char> listed(element_ids.size(), 0);
  for (Group& g : groups) {
    if (!has_link(file, g.path + "/element_rows")) continue;
    const auto rows =
        read_array<std::int64_t>(file, g.path + "/element_rows", g.ids.size(), 0, expected);
    for (std::size_t j = 0; j < rows.size(); ++j) {
      const std::int64_t row = rows[j];
      if (row < 0 || static_cast<std::size_t>(row) >= element_ids.size() ||
          (j > 0 && row <= rows[j - 1]))
        refuse(g.path + "/element_rows lists row " + id_text(row) + " for element " +
                   id_text(g.ids[j]) + ", outside /mesh/element_ids or out of order",
               expected);
      if (element_ids[static_cast<std::size_t>(row)] != g.ids[j])
        refuse("/mesh/element_ids has element " +
                   id_text(element_ids[static_cast<std::size_t>(row)]) + " at row " + id_text(row) +
                   ", where " + g.path + " has element " + id_text(g.ids[j]) +
                   " (the rows of the element fields would go to other elements)",
               expected);
      listed[static_cast<std::size_t>(row)] = 1;
    }
    g.next = g.ids.size();
  }
  // Groups without element_rows (a single-type mesh): their elements are the remaining rows,
  // each group in its own order.
  for (std::size_t r = 0; r < element_ids.size(); ++r) {
    if (listed[r]) continue;
    bool found = false;
    for (Group& g : groups)
      if (g.next < g.ids.size() && g.ids[g.next] == element_ids[r]) {
        ++g.next;
        found = true;
        break;
      }
    if (!found)
      refuse("/mesh/element_ids has element " + id_text(element_ids[r]) + " at row " +
                 id_text(static_cast<std::int64_t>(r)) +
                 ", which no /mesh/TYPE group lists next (the rows of the element fields "
                 "would go to other elements)",
             expected);
  }
  for (const Group& g : groups)
    if (g.next < g.ids.size())
      refuse(g.path + "/element_ids lists element " + id_text(g.ids[g.next]) +
                 ", which is not at its row of /mesh/element_ids",
             expected);
}

}  // namespace xpl::io::h5
