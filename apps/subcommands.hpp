#pragma once
/// \file The commands of the xpl command line beside `run` and `check`: the result-file
/// tools `xpl compare` (compare.cpp) and `xpl history` (history.cpp), and the timing
/// benchmark `xpl bench` (bench.cpp).

#include <string>
#include <vector>

namespace xpl::apps {

/// `xpl compare REF.h5 NEW.h5 [options]`; `args` are the words after "compare". Returns the
/// exit code: 0 every value within the tolerance, 1 something differs, 2 unusable input or
/// a usage error.
int compare_main(const std::vector<std::string>& args);

/// `xpl history JOB.h5 [--step N] [--csv FILE]`; `args` are the words after "history".
/// Returns the exit code: 0 written, 2 unusable input or a usage error.
int history_main(const std::vector<std::string>& args);

/// `xpl bench [--repeat N] [--quick] [--json] [--models LIST] [--deck NAME]`; `args` are the
/// words after "bench". Returns the exit code: 0 done, 2 a usage error, 3 a run failed.
int bench_main(const std::vector<std::string>& args);

}  // namespace xpl::apps
