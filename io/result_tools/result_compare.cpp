#include "io/result_tools/result_compare.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <unordered_map>

#include "io/result_tools/compare_values.hpp"
#include "io/result_tools/h5_reader.hpp"

namespace xpl::io {

namespace {

/// Fields written per node (docs/user/results.md); every other field is per element.
bool is_nodal_field(const std::string& name) {
  static const char* const NODAL[] = {"U",  "V",      "A",       "RF",     "UR",     "VR",
                                      "RM", "CPRESS", "CSTATUS", "CSHEAR", "CNORMF", "CSHEARF"};
  return std::any_of(std::begin(NODAL), std::end(NODAL), [&](const char* n) { return name == n; });
}

/// One opened result file with its mesh ids.
struct ResultFile {
  std::string label;  ///< "REF.h5" as given, for messages
  h5::Handle file;
  std::vector<std::int64_t> node_ids, element_ids;
};

[[noreturn]] void unusable(const ResultFile& f, const std::string& why) {
  throw UnusableInput(f.label + ": " + why);
}

/// Opens `path` and checks that it is a finished xpl result.
ResultFile open_result(const std::filesystem::path& path) {
  ResultFile result;
  result.label = path.string();
  try {
    result.file = h5::open_read_only(path);
    const hid_t f = result.file.get();
    const std::optional<std::string> status = h5::string_attribute(f, "/", "status");
    if (!status || !h5::has_link(f, "/mesh/node_ids"))
      h5::refuse("not an xpl result file (no status attribute or no /mesh)", h5::RESULT_FILE);
    const std::string error = h5::string_attribute(f, "/", "error").value_or("");
    if (*status == "failed") unusable(result, "the run failed (status failed: " + error + ")");
    if (*status == "interrupted")
      unusable(result, "the run is truncated (status interrupted: " + error + ")");
    if (*status == "running")
      unusable(result, "the run did not finish (status running: it was killed, or still runs)");
    if (*status != "completed" && *status != "checked")
      unusable(result, "unknown status '" + *status + "'");
    result.node_ids = h5::read_array<std::int64_t>(f, "/mesh/node_ids", std::nullopt, 0);
    result.element_ids = h5::read_array<std::int64_t>(f, "/mesh/element_ids", std::nullopt, 0);
    // Fields are matched by these ids: they must agree with the type groups.
    h5::check_element_rows(f, result.element_ids);
  } catch (const h5::FormatError& e) {
    unusable(result, std::string(e.what()) + "; " + e.expected());
  } catch (const h5::Error& e) {
    unusable(result, e.what());
  }
  return result;
}

/// For each id of `ref`, its row in `ids`; throws UnusableInput naming the first id that one
/// file has and the other lacks.
std::vector<std::size_t> map_ids(const ResultFile& ref, const ResultFile& cand,
                                 const std::vector<std::int64_t>& ref_ids,
                                 const std::vector<std::int64_t>& cand_ids, const char* what) {
  std::unordered_map<std::int64_t, std::size_t> row;
  for (std::size_t r = 0; r < cand_ids.size(); ++r) row.emplace(cand_ids[r], r);
  std::vector<std::size_t> map(ref_ids.size());
  for (std::size_t r = 0; r < ref_ids.size(); ++r) {
    const auto found = row.find(ref_ids[r]);
    if (found == row.end())
      throw UnusableInput(cand.label + ": another mesh: " + what + " " +
                          std::to_string(ref_ids[r]) + " of " + ref.label + " is not in it");
    map[r] = found->second;
  }
  if (cand_ids.size() != ref_ids.size())
    throw UnusableInput(cand.label + ": another mesh: " + std::to_string(cand_ids.size()) + " " +
                        what + "s, " + ref.label + " has " + std::to_string(ref_ids.size()));
  return map;
}

/// Element types and connectivity (as node ids) must agree element by element.
void check_topology(const ResultFile& ref, const ResultFile& cand) {
  for (const char* type : {"C3D8R", "C3D8", "S4R"}) {
    const std::string group = std::string("/mesh/") + type;
    const bool in_ref = h5::has_link(ref.file.get(), group);
    if (in_ref != h5::has_link(cand.file.get(), group))
      throw UnusableInput(cand.label + ": another mesh: " + (in_ref ? "no " : "") + type +
                          " elements where " + ref.label + " has " + (in_ref ? "some" : "none"));
    if (!in_ref) continue;
    std::map<std::int64_t, std::vector<std::int64_t>> corners[2];
    const ResultFile* files[2] = {&ref, &cand};
    for (int k = 0; k < 2; ++k) {
      const hid_t f = files[k]->file.get();
      const auto ids = h5::read_array<std::int64_t>(f, group + "/element_ids", std::nullopt, 0);
      const std::size_t n = ids.empty() ? 0 : h5::dataset_shape(f, group + "/connectivity")[1];
      const auto rows = h5::read_array<std::int64_t>(f, group + "/connectivity", ids.size(), n);
      for (std::size_t j = 0; j < ids.size(); ++j)
        for (std::size_t a = 0; a < n; ++a) {
          const auto row = static_cast<std::size_t>(rows[j * n + a]);
          corners[k][ids[j]].push_back(row < files[k]->node_ids.size() ? files[k]->node_ids[row]
                                                                       : -1);
        }
    }
    for (const auto& [id, nodes] : corners[0]) {
      const auto found = corners[1].find(id);
      if (found == corners[1].end() || found->second != nodes)
        throw UnusableInput(cand.label + ": another mesh: " + type + " element " +
                            std::to_string(id) + " has other nodes (or another type) than in " +
                            ref.label);
    }
  }
}

/// History of every step of REF, on REF's times.
void compare_history(const ResultFile& ref, const ResultFile& cand, const CompareOptions& options,
                     CompareReport& report) {
  for (const std::string& step : h5::group_members(ref.file.get(), "/history")) {
    const std::string group = "/history/" + step;
    const auto ref_time = h5::read_array<double>(ref.file.get(), group + "/time", std::nullopt, 0);
    if (!h5::has_link(cand.file.get(), group + "/time")) {
      DatasetComparison missing;
      missing.name = group;
      missing.problem = "missing in NEW";
      report.datasets.push_back(missing);
      continue;
    }
    const auto cand_time =
        h5::read_array<double>(cand.file.get(), group + "/time", std::nullopt, 0);
    const TimeMap times(ref_time, cand_time);
    for (const std::string& path : dataset_paths(ref.file.get(), group)) {
      if (path == group + "/time") continue;
      report.datasets.push_back(
          compare_series(ref.file.get(), cand.file.get(), path, times, ref_time, options));
    }
    for (const std::string& path : dataset_paths(cand.file.get(), group))
      if (!h5::has_link(ref.file.get(), path))
        report.notes.push_back(path + " is only in NEW (not compared)");
  }
}

/// The frames of REF (sorted by name) and NEW paired: the last ones, or all in order.
void compare_frames(const ResultFile& ref, const ResultFile& cand, const CompareOptions& options,
                    const std::vector<std::size_t>& node_map,
                    const std::vector<std::size_t>& element_map, CompareReport& report) {
  const auto ref_frames = h5::group_members(ref.file.get(), "/frames");
  const auto cand_frames = h5::group_members(cand.file.get(), "/frames");
  std::vector<std::pair<std::string, std::string>> pairs;
  if (options.all_frames || ref_frames.empty() || cand_frames.empty()) {
    if (ref_frames.size() != cand_frames.size()) {
      DatasetComparison count;
      count.name = "/frames";
      count.problem = "REF has " + std::to_string(ref_frames.size()) + " frames, NEW " +
                      std::to_string(cand_frames.size());
      report.datasets.push_back(count);
    }
    for (std::size_t k = 0; k < std::min(ref_frames.size(), cand_frames.size()); ++k)
      pairs.emplace_back(ref_frames[k], cand_frames[k]);
  } else {
    pairs.emplace_back(ref_frames.back(), cand_frames.back());
  }
  // A field asked for by name must be in REF's frames: a typo must not pass as "0 differ".
  for (const std::string& name : options.names) {
    const bool found = std::any_of(pairs.begin(), pairs.end(), [&](const auto& pair) {
      return h5::has_link(ref.file.get(), "/frames/" + pair.first + "/" + name);
    });
    if (!found) {
      std::string present;
      for (const auto& pair : pairs)
        for (const std::string& field : h5::group_members(ref.file.get(), "/frames/" + pair.first))
          if (present.find(" " + field + ",") == std::string::npos) present += " " + field + ",";
      if (!present.empty()) present.pop_back();
      throw UnusableInput(ref.label + ": --fields " + name + ": no such field in the frame" +
                          (pairs.size() == 1 ? "" : "s") + " compared (" +
                          (present.empty() ? std::string("no fields") : "fields:" + present) + ")");
    }
  }
  const RowMaps maps{&node_map, &element_map, is_nodal_field};
  for (const auto& [ref_name, cand_name] : pairs) {
    const std::string rf = "/frames/" + ref_name, cf = "/frames/" + cand_name;
    const double t_ref = h5::numeric_attribute<double>(ref.file.get(), rf, "time");
    const double t_cand = h5::numeric_attribute<double>(cand.file.get(), cf, "time");
    if (t_ref != t_cand)
      report.notes.push_back(rf + " at t = " + format_number(t_ref) + " s is compared with " + cf +
                             " at t = " + format_number(t_cand) + " s");
    for (const std::string& field : h5::group_members(ref.file.get(), rf)) {
      if (!options.names.empty() &&
          std::find(options.names.begin(), options.names.end(), field) == options.names.end())
        continue;
      report.datasets.push_back(compare_field(ref.file.get(), cand.file.get(), rf + "/" + field,
                                              cf + "/" + field, field, t_ref, maps, options));
    }
  }
}

JsonValue value_json(const CompareValue& v) {
  JsonValue out = JsonValue::object();
  out.set("where", v.where);
  out.set("time", v.time);  // null for tables
  out.set("reference", v.reference);
  out.set("new", v.value);
  out.set("difference", v.difference);  // null when one side is NaN
  out.set("tolerance", v.tolerance);
  return out;
}

}  // namespace

JsonValue CompareReport::json(const CompareOptions& options, const std::string& reference,
                              const std::string& candidate) const {
  JsonValue out = JsonValue::object();
  out.set("reference", reference);
  out.set("new", candidate);
  out.set("rtol", options.rtol);
  out.set("atol", options.atol);
  out.set("ftol", options.ftol);
  out.set("passed", passed());
  long failed = 0;
  for (const DatasetComparison& d : datasets) failed += d.passed() ? 0 : 1;
  out.set("datasets_compared", static_cast<long>(datasets.size()));
  out.set("datasets_failed", failed);
  JsonValue& list = out.set("datasets", JsonValue::array());
  for (const DatasetComparison& d : datasets) {
    JsonValue& item = list.push(JsonValue::object());
    item.set("name", d.name);
    item.set("passed", d.passed());
    item.set("compared", d.compared);
    item.set("failed", d.failed);
    item.set("problem", d.problem);
    item.set("largest", d.has_largest ? value_json(d.largest) : JsonValue());
    item.set("worst", d.has_worst ? value_json(d.worst) : JsonValue());
  }
  JsonValue& notes_out = out.set("notes", JsonValue::array());
  for (const std::string& note : notes) notes_out.push(note);
  return out;
}

bool CompareReport::passed() const {
  return std::all_of(datasets.begin(), datasets.end(),
                     [](const DatasetComparison& d) { return d.passed(); });
}

CompareReport compare_results(const std::filesystem::path& reference,
                              const std::filesystem::path& candidate,
                              const CompareOptions& options) {
  const ResultFile ref = open_result(reference);
  const ResultFile cand = open_result(candidate);
  CompareReport report;
  try {
    const auto node_map = map_ids(ref, cand, ref.node_ids, cand.node_ids, "node");
    const auto element_map = map_ids(ref, cand, ref.element_ids, cand.element_ids, "element");
    check_topology(ref, cand);
    if (options.tables) {
      const RowMaps maps{&node_map, &element_map, [](const std::string&) { return true; }};
      report.datasets.push_back(compare_field(ref.file.get(), cand.file.get(), "/mesh/coordinates",
                                              "/mesh/coordinates", "X", std::nan(""), maps,
                                              options));
      for (const std::string& path : dataset_paths(ref.file.get(), "/overclosure"))
        report.datasets.push_back(compare_table(ref.file.get(), cand.file.get(), path, options));
    }
    if (options.history) compare_history(ref, cand, options, report);
    if (options.fields) compare_frames(ref, cand, options, node_map, element_map, report);
  } catch (const h5::FormatError& e) {
    throw UnusableInput(std::string(e.what()) + "; " + e.expected());
  } catch (const h5::Error& e) {
    throw UnusableInput(e.what());
  }
  return report;
}

}  // namespace xpl::io
