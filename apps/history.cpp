// `xpl history JOB.h5 [--step N] [--csv FILE]`: the history output of a result file as one
// CSV table (time, then one column per variable and node), for spreadsheets and pandas.

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "io/result_tools/compare_values.hpp"
#include "io/result_tools/h5_reader.hpp"
#include "subcommands.hpp"

namespace xpl::apps {

namespace {

constexpr int EXIT_UNUSABLE = 2;

constexpr const char* HISTORY_USAGE = "usage: xpl history JOB.h5 [--step N] [--csv FILE]\n";

/// `xpl history --help`: the synopsis and what the options mean.
constexpr const char* HISTORY_HELP =
    "\n"
    "Writes the history output of a result file as one CSV table: a header `time`, then one\n"
    "column per variable and node or pair (ALLKE, RF2@N17, CFN@ALL_EXTERIOR), 17\n"
    "significant digits (the values read back bitwise); all steps one after another (the\n"
    "union of their columns, empty cells where a step lacks one).\n"
    "  --step N    step N only (1, 2, ...)\n"
    "  --csv FILE  write FILE instead of stdout\n"
    "Exit codes: 0 written, 2 unusable input (no such step, no history, not a result file)\n"
    "  or a usage error, 4 the CSV could not be written.\n";

/// The columns of one step: names and, per column, the dataset and its column.
struct StepTable {
  std::vector<double> time;
  std::vector<std::string> names;
  std::vector<std::vector<double>> columns;  ///< columns[k][row]
};

/// The last component of `path` and the one before it: ("node/FIXED/RF1") → ("FIXED", "RF1").
std::pair<std::string, std::string> split(const std::string& path) {
  const auto slash = path.rfind('/');
  const std::string variable = path.substr(slash + 1);
  const std::string parent = path.substr(0, slash);
  return {parent.substr(parent.rfind('/') + 1), variable};
}

StepTable read_step(hid_t file, const std::string& group) {
  StepTable table;
  table.time = io::h5::read_array<double>(file, group + "/time", std::nullopt, 0);
  const std::size_t rows = table.time.size();
  std::map<std::string, bool> seen;
  for (const std::string& path : io::dataset_paths(file, group)) {
    if (path == group + "/time") continue;
    const auto [owner, variable] = split(path);
    const std::vector<double> values = io::h5::read_as_real(file, path);
    const std::size_t width = rows > 0 ? values.size() / rows : 1;
    const auto nodes = io::h5::int64_array_attribute(file, path, "node_ids");
    const auto elements = io::h5::int64_array_attribute(file, path, "element_ids");
    for (std::size_t c = 0; c < width; ++c) {
      // energy/ALLKE → ALLKE; node/SET/RF2 → RF2@N17; contact/PAIR/CFN → CFN@PAIR.
      // (appends, not "[" + ...: GCC 12 warns falsely on that, -Wrestrict bug 105329)
      std::string name = variable;
      if (nodes && c < nodes->size()) {
        name.append("@N").append(std::to_string((*nodes)[c]));
      } else if (elements && c < elements->size()) {
        name.append("@E").append(std::to_string((*elements)[c]));
      } else if (owner != "energy" && path.rfind('/') > group.size()) {
        name.append("@").append(owner);
        if (width > 1) name.append("[").append(std::to_string(c)).append("]");
      }
      // A node in two sets gives the same series twice: one column.
      if (!seen.emplace(name, true).second) continue;
      std::vector<double> column(rows);
      for (std::size_t r = 0; r < rows; ++r) column[r] = values[r * width + c];
      table.names.push_back(name);
      table.columns.push_back(std::move(column));
    }
  }
  return table;
}

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

/// Writes the steps as one table: the union of their columns, empty where a step lacks one.
void write_csv(std::ostream& out, const std::vector<StepTable>& steps) {
  std::vector<std::string> names;
  std::map<std::string, std::size_t> index;
  for (const StepTable& s : steps)
    for (const std::string& n : s.names)
      if (index.emplace(n, names.size()).second) names.push_back(n);
  out << "time";
  // Column names come from the file's datasets: control characters escaped, as everywhere.
  for (const std::string& n : names) out << "," << csv_field(escape_control(n));
  out << "\n";
  char number[32];
  for (const StepTable& s : steps) {
    std::vector<int> column_of(names.size(), -1);
    for (std::size_t k = 0; k < s.names.size(); ++k)
      column_of[index[s.names[k]]] = static_cast<int>(k);
    for (std::size_t r = 0; r < s.time.size(); ++r) {
      std::snprintf(number, sizeof number, "%.17g", s.time[r]);  // reads back bitwise
      out << number;
      for (std::size_t k = 0; k < names.size(); ++k) {
        out << ",";
        if (column_of[k] < 0) continue;
        std::snprintf(number, sizeof number, "%.17g", s.columns[column_of[k]][r]);
        out << number;
      }
      out << "\n";
    }
  }
}

/// The step count of the model a result file holds: /summary's model.steps (written when the
/// run ends), else the largest step of a frame, else 0 (unknown).
long result_steps(hid_t file) {
  if (io::h5::has_link(file, "/summary")) {
    try {
      return static_cast<long>(
          io::h5::numeric_attribute<std::int64_t>(file, "/summary", "model.steps"));
    } catch (const std::runtime_error&) {  // NOLINT(bugprone-empty-catch): try the frames
    }
  }
  long steps = 0;
  if (!io::h5::has_link(file, "/frames")) return 0;
  for (const std::string& frame : io::h5::group_members(file, "/frames")) {
    try {
      steps = std::max(steps, static_cast<long>(io::h5::numeric_attribute<std::int64_t>(
                                  file, "/frames/" + frame, "step")));
    } catch (const std::runtime_error&) {  // NOLINT(bugprone-empty-catch): no step there
    }
  }
  return steps;
}

/// "1", "1, 2", "1..4": the step numbers of `steps` (ascending) as the user would write them.
std::string step_list(const std::vector<int>& steps) {
  std::string text;
  for (std::size_t i = 0; i < steps.size();) {
    std::size_t j = i;
    while (j + 1 < steps.size() && steps[j + 1] == steps[j] + 1) ++j;
    text += (text.empty() ? "" : ", ") + std::to_string(steps[i]);
    if (j > i) text += (j == i + 1 ? ", " : "..") + std::to_string(steps[j]);
    i = j + 1;
  }
  return text;
}

/// Why a result has no history to write for `step` (0: any step), and what the user can do.
std::string missing_history(hid_t file, int step, const std::vector<int>& with_history) {
  const long steps = result_steps(file);
  const std::string have = with_history.empty()
                               ? std::string("no step has history output")
                               : "history exists for step(s) " + step_list(with_history);
  if (step == 0)
    return "the file has no history output (/history); expected a result of a run (a data "
           "check writes none) or of a deck with *OUTPUT, HISTORY";
  if (steps > 0 && step > steps)
    return "no step " + std::to_string(step) + ": the result has " +
           (steps == 1 ? std::string("one step (1)")
                       : std::to_string(steps) + " steps (1.." + std::to_string(steps) + ")") +
           "; " + have;
  return "step " + std::to_string(step) + " has no history output (" + have +
         "); expected a step that ran, with history output";
}

}  // namespace

int history_main(const std::vector<std::string>& args) {
  std::string file_name, csv;
  int step = 0;  // 0: every step
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& w = args[i];
    if (w == "--help" || w == "-h") {
      std::cout << HISTORY_USAGE << HISTORY_HELP;
      return 0;
    }
    if ((w == "--step" || w == "--csv") && i + 1 >= args.size()) {
      std::cerr << "xpl history: " << w << " needs a value\n" << HISTORY_USAGE;
      return EXIT_UNUSABLE;
    }
    if (w == "--step") {
      const std::string& v = args[++i];
      std::size_t used = 0;
      try {
        step = std::stoi(v, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != v.size() || step < 1) {
        std::cerr << "xpl history: --step: '" << v << "' is not a step number (1, 2, ...)\n";
        return EXIT_UNUSABLE;
      }
    } else if (w == "--csv") {
      csv = args[++i];
    } else if (!w.empty() && w[0] == '-') {
      std::cerr << "xpl history: unknown option '" << w << "'\n" << HISTORY_USAGE;
      return EXIT_UNUSABLE;
    } else if (file_name.empty()) {
      file_name = w;
    } else {
      std::cerr << "xpl history: more than one result file given ('" << w << "')\n";
      return EXIT_UNUSABLE;
    }
  }
  if (file_name.empty()) {
    std::cerr << "xpl history: no result file given\n" << HISTORY_USAGE;
    return EXIT_UNUSABLE;
  }
  std::vector<StepTable> steps;
  try {
    const io::h5::Handle file = io::h5::open_read_only(file_name);
    const std::vector<std::string> groups = io::h5::group_members(file.get(), "/history");
    std::vector<std::string> chosen;
    std::vector<int> with_history;  // the steps that have a history group, in order
    for (int n = 1; n <= static_cast<int>(groups.size()) + 1; ++n) {  // numeric order
      const std::string g = "step_" + std::to_string(n);
      if (!io::h5::has_link(file.get(), "/history/" + g)) continue;
      with_history.push_back(n);
      if (step == 0 || step == n) chosen.push_back(g);
    }
    if (chosen.empty()) {
      std::cerr << "xpl history: " << file_name << ": "
                << missing_history(file.get(), step, with_history) << "\n";
      return EXIT_UNUSABLE;
    }
    for (const std::string& g : chosen) steps.push_back(read_step(file.get(), "/history/" + g));
    const std::string status = io::h5::string_attribute(file.get(), "/", "status").value_or("");
    if (status != "completed")
      std::cerr << "xpl history: note: " << escape_control(file_name) << " has status '"
                << escape_control(status) << "': its history ends where the run stopped\n";
  } catch (const io::h5::FormatError& e) {
    std::cerr << "xpl history: " << escape_control(file_name) << ": " << escape_control(e.what())
              << "; " << e.expected() << "\n";
    return EXIT_UNUSABLE;
  } catch (const io::h5::Error& e) {
    std::cerr << "xpl history: " << escape_control(file_name) << ": " << escape_control(e.what())
              << "\n";
    return EXIT_UNUSABLE;
  }
  if (csv.empty()) {
    write_csv(std::cout, steps);
    return std::cout ? 0 : 4;
  }
  std::ofstream out(csv);
  write_csv(out, steps);
  out.close();
  if (!out) {
    std::cerr << "xpl history: cannot write " << csv << "\n";
    return 4;
  }
  return 0;
}

}  // namespace xpl::apps
