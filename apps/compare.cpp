// `xpl compare REF.h5 NEW.h5`: regression comparison of two result files (io/results/
// result_compare.hpp), as a text report or as JSON for CI systems.

#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "common/error.hpp"
#include "io/result_tools/compare_values.hpp"
#include "io/result_tools/result_compare.hpp"
#include "subcommands.hpp"

namespace xpl::apps {

namespace {

constexpr int EXIT_DIFFERS = 1;
constexpr int EXIT_UNUSABLE = 2;

constexpr const char* COMPARE_USAGE =
    "usage: xpl compare REF.h5 NEW.h5 [--rtol R] [--atol A] [--ftol F] [--history]\n"
    "                   [--fields U,S,...] [--frames last|all] [--json]\n";

/// `xpl compare --help`: the synopsis and what the options mean.
constexpr const char* COMPARE_HELP =
    "\n"
    "Compares two result files for a regression test: a value passes when\n"
    "  |new - ref| <= A + R |ref| + F max|ref of the dataset|   (all 0 by default: bitwise)\n"
    "Compared: the mesh coordinates, the overclosure tables, every history series of every\n"
    "step on REF's times (NEW interpolated linearly) and the fields of the last frame;\n"
    "nodes and elements are matched by deck id.\n"
    "  --rtol R, --atol A, --ftol F  relative, absolute and fraction-of-largest tolerances\n"
    "  --history          compare the history only (with --fields: and those fields)\n"
    "  --fields U,S,...   compare these fields only (with --history: and the history)\n"
    "  --frames last|all  the last frame (default) or every frame, paired in order\n"
    "  --json             the report as JSON on stdout\n"
    "Exit codes: 0 every value within the tolerance, 1 something differs, 2 unusable input\n"
    "  (missing, not HDF5, other mesh, failed or truncated run) or a usage error.\n";

/// A number argument; false (after a message) if it is not a finite number ≥ 0.
bool parse_tolerance(const std::string& option, const std::string& text, double& value) {
  std::istringstream in(text);
  in >> value;
  if (in.fail() || !in.eof() || !std::isfinite(value) || value < 0.0) {
    std::cerr << "xpl compare: " << option << ": '" << text << "' is not a number >= 0\n"
              << COMPARE_USAGE;
    return false;
  }
  return true;
}

std::string describe(const io::CompareValue& v) {
  std::string text = v.where.empty() ? "" : v.where + " ";
  if (!std::isnan(v.time)) text += "at t = " + io::format_number(v.time) + " s ";
  return text + "ref " + io::format_number(v.reference) + ", new " + io::format_number(v.value) +
         ", |diff| " + io::format_number(v.difference);
}

/// `text` as printed: names and messages from a file may hold control characters, which
/// must not reach the terminal raw (escaped as --import and the logs do).
std::string shown(const std::string& text) {
  return escape_control(text);
}

void print_text(const io::CompareReport& report, const io::CompareOptions& options,
                const std::string& ref, const std::string& cand) {
  std::printf(
      "xpl compare: %s (REF) vs %s (NEW): pass when |new - ref| <= %s + %s |ref| + %s max|ref|\n",
      shown(ref).c_str(), shown(cand).c_str(), io::format_number(options.atol).c_str(),
      io::format_number(options.rtol).c_str(), io::format_number(options.ftol).c_str());
  long failed = 0;
  for (const io::DatasetComparison& d : report.datasets) {
    const std::string name = shown(d.name);
    if (!d.problem.empty()) {
      std::printf("FAIL %s: %s\n", name.c_str(), shown(d.problem).c_str());
    } else if (d.failed > 0) {
      std::printf("FAIL %s: %ld of %ld values differ; worst %s > tolerance %s\n", name.c_str(),
                  d.failed, d.compared, shown(describe(d.worst)).c_str(),
                  io::format_number(d.worst.tolerance).c_str());
    } else if (d.has_largest) {
      std::printf("pass %s: %ld values; largest %s\n", name.c_str(), d.compared,
                  shown(describe(d.largest)).c_str());
    } else {
      std::printf("pass %s: empty in both\n", name.c_str());
    }
    failed += d.passed() ? 0 : 1;
  }
  for (const std::string& note : report.notes) std::printf("note: %s\n", shown(note).c_str());
  std::printf("xpl compare: %s: %ld of %zu datasets differ\n", failed > 0 ? "DIFFERENT" : "PASSED",
              failed, report.datasets.size());
}

}  // namespace

int compare_main(const std::vector<std::string>& args) {
  io::CompareOptions options;
  std::vector<std::string> files;
  bool json = false, history = false, fields = false;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& w = args[i];
    if (w == "--help" || w == "-h") {
      std::cout << COMPARE_USAGE << COMPARE_HELP;
      return 0;
    }
    const auto value = [&]() -> const std::string* {
      if (i + 1 >= args.size()) {
        std::cerr << "xpl compare: " << w << " needs a value\n" << COMPARE_USAGE;
        return nullptr;
      }
      return &args[++i];
    };
    if (w == "--rtol" || w == "--atol" || w == "--ftol") {
      const std::string* v = value();
      double& tolerance = w == "--rtol"   ? options.rtol
                          : w == "--atol" ? options.atol
                                          : options.ftol;
      if (!v || !parse_tolerance(w, *v, tolerance)) return EXIT_UNUSABLE;
    } else if (w == "--history") {
      history = true;
    } else if (w == "--fields") {
      const std::string* v = value();
      if (!v) return EXIT_UNUSABLE;
      fields = true;
      std::stringstream list(*v);
      for (std::string name; std::getline(list, name, ',');)
        if (!name.empty()) options.names.push_back(name);
    } else if (w == "--frames") {
      const std::string* v = value();
      if (!v) return EXIT_UNUSABLE;
      if (*v != "last" && *v != "all") {
        std::cerr << "xpl compare: --frames: '" << *v << "': expected last or all\n";
        return EXIT_UNUSABLE;
      }
      options.all_frames = *v == "all";
    } else if (w == "--json") {
      json = true;
    } else if (!w.empty() && w[0] == '-') {
      std::cerr << "xpl compare: unknown option '" << w << "'\n" << COMPARE_USAGE;
      return EXIT_UNUSABLE;
    } else {
      files.push_back(w);
    }
  }
  if (files.size() != 2) {
    std::cerr << "xpl compare: expected two result files (REF.h5 NEW.h5), got " << files.size()
              << "\n"
              << COMPARE_USAGE;
    return EXIT_UNUSABLE;
  }
  // --history and --fields select; without either, everything is compared.
  if (history || fields) {
    options.history = history;
    options.fields = fields;
    options.tables = false;
  }
  try {
    const io::CompareReport report = io::compare_results(files[0], files[1], options);
    if (json)
      std::cout << report.json(options, files[0], files[1]).text();
    else
      print_text(report, options, files[0], files[1]);
    return report.passed() ? 0 : EXIT_DIFFERS;
  } catch (const io::UnusableInput& e) {
    std::cerr << "xpl compare: cannot compare: " << shown(e.what()) << "\n";
    if (json) {
      io::JsonValue out = io::JsonValue::object();
      out.set("reference", files[0]);
      out.set("new", files[1]);
      out.set("passed", false);
      out.set("unusable", e.what());
      std::cout << out.text();
    }
    return EXIT_UNUSABLE;
  }
}

}  // namespace xpl::apps
