#include "io/result_tools/compare_values.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <optional>
#include <unordered_map>

#include "io/result_tools/h5_reader.hpp"

namespace xpl::io {

namespace {

/// A dataset as rows × columns (a one-dimensional one has one column).
struct Matrix {
  std::vector<double> values;
  std::size_t rows = 0, columns = 1;
};

Matrix read_matrix(hid_t file, const std::string& path) {
  Matrix m;
  const std::vector<hsize_t> dims = h5::dataset_shape(file, path);
  m.rows = dims.empty() ? 1 : static_cast<std::size_t>(dims[0]);
  for (std::size_t k = 1; k < dims.size(); ++k) m.columns *= static_cast<std::size_t>(dims[k]);
  m.values = h5::read_as_real(file, path);
  return m;
}

std::string shape_text(const Matrix& m) {
  // snprintf, not "(" + std::to_string(...): GCC 12 warns falsely (-Wrestrict, bug 105329).
  char text[64];
  std::snprintf(text, sizeof text, "(%zu × %zu)", m.rows, m.columns);
  return text;
}

/// Takes in one pair of values: counts it, keeps the largest and the worst difference.
/// The largest finite |value| of REF's dataset, for CompareOptions::ftol.
double largest_magnitude(const std::vector<double>& values) {
  double largest = 0.0;
  for (double v : values)
    if (std::isfinite(v)) largest = std::max(largest, std::abs(v));
  return largest;
}

/// Takes in one pair of values: counts it, keeps the largest and the worst difference.
/// `scale`: the dataset's largest |ref| (CompareOptions::ftol).
template <class Where>
void add(DatasetComparison& d, const CompareOptions& o, double scale, double ref, double value,
         double time, const Where& where) {
  ++d.compared;
  const double tolerance = o.atol + o.rtol * std::abs(ref) + o.ftol * scale;
  double difference = 0.0;
  bool ok = true;
  if (std::isnan(ref) || std::isnan(value)) {
    ok = std::isnan(ref) && std::isnan(value);  // NaN rows (shell stresses of solids) agree
    difference = ok ? 0.0 : std::numeric_limits<double>::infinity();
  } else if (ref != value) {
    difference = std::abs(value - ref);
    ok = difference <= tolerance;
  }
  const auto record = [&] {
    return CompareValue{where(), time, ref, value, difference, tolerance};
  };
  if (!d.has_largest || difference > d.largest.difference) {
    d.largest = record();
    d.has_largest = true;
  }
  if (ok) return;
  ++d.failed;
  const double excess = difference - tolerance;
  if (!d.has_worst || excess > d.worst.difference - d.worst.tolerance) {
    d.worst = record();
    d.has_worst = true;
  }
}

/// Name of column `c` of a field `name` with `columns` columns: U2, S12, MISES, X3.
std::string component(const std::string& name, std::size_t c, std::size_t columns) {
  static const char* const TENSOR[] = {"11", "22", "33", "12", "13", "23"};
  if (columns == 1) return name;
  if (columns == 3) return name + std::to_string(c + 1);
  if (columns == 6) return name + TENSOR[c];
  return name + "[" + std::to_string(c) + "]";
}

std::vector<std::int64_t> mesh_ids(hid_t file, const char* path) {
  return h5::read_array<std::int64_t>(file, path, std::nullopt, 0);
}

}  // namespace

TimeMap::TimeMap(const std::vector<double>& reference, const std::vector<double>& candidate) {
  const std::size_t n = reference.size();
  m_lower.assign(n, 0);
  m_weight.assign(n, 0.0);
  m_inside.assign(n, false);
  m_rows = candidate.size();
  if (candidate.empty()) return;
  m_first = candidate.front();
  m_last = candidate.back();
  const double span = std::max({std::abs(m_first), std::abs(m_last), std::abs(reference.back())});
  const double slack = 1e-9 * span;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = reference[i];
    if (t < m_first - slack || t > m_last + slack) continue;
    m_inside[i] = true;
    // The last NEW row at or before t.
    const auto after = std::upper_bound(candidate.begin(), candidate.end(), t);
    std::size_t k =
        after == candidate.begin() ? 0 : static_cast<std::size_t>(after - candidate.begin()) - 1;
    m_lower[i] = k;
    if (candidate[k] >= t || k + 1 >= candidate.size()) continue;  // equal, or clamped at an end
    m_weight[i] = (t - candidate[k]) / (candidate[k + 1] - candidate[k]);
  }
}

double TimeMap::at(std::size_t i, const std::vector<double>& values, std::size_t width,
                   std::size_t column) const {
  const std::size_t k = m_lower[i];
  const double a = values[k * width + column];
  if (m_weight[i] == 0.0) return a;
  const double b = values[(k + 1) * width + column];
  return a + m_weight[i] * (b - a);
}

std::vector<std::string> dataset_paths(hid_t file, const std::string& group) {
  std::vector<std::string> paths;
  for (const std::string& name : h5::group_members(file, group)) {
    const std::string path = group + "/" + name;
    if (h5::is_dataset(file, path)) {
      paths.push_back(path);
    } else {
      const auto below = dataset_paths(file, path);
      paths.insert(paths.end(), below.begin(), below.end());
    }
  }
  return paths;
}

DatasetComparison compare_series(hid_t ref, hid_t cand, const std::string& path,
                                 const TimeMap& times, const std::vector<double>& ref_time,
                                 const CompareOptions& options) {
  DatasetComparison d;
  d.name = path;
  if (!h5::is_dataset(cand, path)) {
    d.problem = "missing in NEW";
    return d;
  }
  const Matrix a = read_matrix(ref, path), b = read_matrix(cand, path);
  // Columns matched by node id where the series has them, else by position.
  const auto ref_ids = h5::int64_array_attribute(ref, path, "node_ids");
  const auto cand_ids = h5::int64_array_attribute(cand, path, "node_ids");
  std::vector<std::size_t> column(a.columns);
  for (std::size_t c = 0; c < a.columns; ++c) column[c] = c;
  if (ref_ids && cand_ids) {
    std::unordered_map<std::int64_t, std::size_t> where;
    for (std::size_t c = 0; c < cand_ids->size(); ++c) where.emplace((*cand_ids)[c], c);
    for (std::size_t c = 0; c < a.columns && c < ref_ids->size(); ++c) {
      const auto found = where.find((*ref_ids)[c]);
      if (found == where.end()) {
        d.problem = "node " + std::to_string((*ref_ids)[c]) + " missing in NEW";
        return d;
      }
      column[c] = found->second;
    }
  } else if (a.columns != b.columns) {
    d.problem =
        std::to_string(a.columns) + " columns in REF, " + std::to_string(b.columns) + " in NEW";
    return d;
  }
  if (b.rows != times.rows() || a.rows != ref_time.size()) {
    d.problem = "the rows do not match the time column (" + std::to_string(a.rows) + " of " +
                std::to_string(ref_time.size()) + " in REF, " + std::to_string(b.rows) + " of " +
                std::to_string(times.rows()) + " in NEW)";
    return d;
  }
  const double scale = largest_magnitude(a.values);
  for (std::size_t i = 0; i < a.rows && i < ref_time.size(); ++i) {
    if (!times.inside(i)) {
      d.problem = "REF's time " + format_number(ref_time[i]) + " s lies outside NEW's history (" +
                  format_number(times.first()) + " to " + format_number(times.last()) + " s)";
      return d;
    }
    for (std::size_t c = 0; c < a.columns; ++c) {
      const double value = times.at(i, b.values, b.columns, column[c]);
      add(d, options, scale, a.values[i * a.columns + c], value, ref_time[i], [&] {
        return ref_ids && c < ref_ids->size() ? "node " + std::to_string((*ref_ids)[c])
                                              : std::string();
      });
    }
  }
  return d;
}

DatasetComparison compare_field(hid_t ref, hid_t cand, const std::string& ref_path,
                                const std::string& cand_path, const std::string& name, double time,
                                const RowMaps& maps, const CompareOptions& options) {
  DatasetComparison d;
  d.name = ref_path;
  if (!h5::is_dataset(cand, cand_path)) {
    d.problem = "missing in NEW";
    return d;
  }
  const Matrix a = read_matrix(ref, ref_path), b = read_matrix(cand, cand_path);
  if (a.columns != b.columns || a.rows != b.rows) {
    d.problem = "shape " + shape_text(a) + " in REF, " + shape_text(b) + " in NEW";
    return d;
  }
  // Rows per node or per element, by the field's name and the row count.
  const std::vector<std::size_t>* map = nullptr;
  const char* kind = "row";
  const char* ids_path = nullptr;
  if (maps.nodal(name) && a.rows == maps.node_map->size()) {
    map = maps.node_map, kind = "node", ids_path = "/mesh/node_ids";
  } else if (a.rows == maps.element_map->size()) {
    map = maps.element_map, kind = "element", ids_path = "/mesh/element_ids";
  } else if (a.rows == maps.node_map->size()) {
    map = maps.node_map, kind = "node", ids_path = "/mesh/node_ids";
  }
  const std::vector<std::int64_t> ids =
      ids_path ? mesh_ids(ref, ids_path) : std::vector<std::int64_t>{};
  const double scale = largest_magnitude(a.values);
  for (std::size_t r = 0; r < a.rows; ++r) {
    const std::size_t row = map ? (*map)[r] : r;
    for (std::size_t c = 0; c < a.columns; ++c)
      add(d, options, scale, a.values[r * a.columns + c], b.values[row * b.columns + c], time, [&] {
        const std::int64_t id = map ? ids[r] : static_cast<std::int64_t>(r);
        return std::string(kind) + " " + std::to_string(id) + ", " + component(name, c, a.columns);
      });
  }
  return d;
}

DatasetComparison compare_table(hid_t ref, hid_t cand, const std::string& path,
                                const CompareOptions& options) {
  DatasetComparison d;
  d.name = path;
  if (!h5::is_dataset(cand, path)) {
    d.problem = "missing in NEW";
    return d;
  }
  const Matrix a = read_matrix(ref, path), b = read_matrix(cand, path);
  if (a.values.size() != b.values.size() || a.columns != b.columns) {
    d.problem = "shape " + shape_text(a) + " in REF, " + shape_text(b) + " in NEW";
    return d;
  }
  const double scale = largest_magnitude(a.values);
  for (std::size_t k = 0; k < a.values.size(); ++k)  // both empty: nothing differs
    add(d, options, scale, a.values[k], b.values[k], std::nan(""), [&] {
      return "row " + std::to_string(k / a.columns) +
             (a.columns > 1 ? ", column " + std::to_string(k % a.columns) : std::string());
    });
  return d;
}

std::string format_number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

}  // namespace xpl::io
