#pragma once
/// \file The result-file tools of the xpl command line, beside `run` and `check`:
/// `xpl compare` (compare.cpp) and `xpl history` (history.cpp).

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

}  // namespace xpl::apps
