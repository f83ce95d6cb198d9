#pragma once
/// \file The models of `xpl bench` (bench.cpp) as deck text built in memory: the same decks,
/// character for character, as the generators of benchmarks/ write (make_block.py,
/// make_plate_benchmark.py, make_contact_benchmark.py) for the same arguments, so that a
/// figure of `xpl bench` and one of the scripts measure the same model.
/// tests/apps/check_bench.py compares the two.

#include <string>
#include <vector>

namespace xpl::apps {

/// One benchmark model: its name, what it is, and its size.
struct BenchModel {
  std::string name;         ///< hex, shell, contact, plastic-hex, plastic-shell
  std::string description;  ///< one line for the table's legend
  int n = 0;                ///< elements per edge (hex, plate), per side of a contact block
  int m = 0;                ///< contact: element layers of each block; else unused
  int increments = 0;       ///< about this many increments run
  /// The equivalent generator call (for the legend and the documentation).
  std::string script() const;
  /// The deck text.
  std::string deck() const;
};

/// The standard models: the sizes of a full benchmark (each run a few seconds on a 2-core
/// machine) or, `quick`, tiny ones that only show that everything runs.
std::vector<BenchModel> bench_models(bool quick);

}  // namespace xpl::apps
