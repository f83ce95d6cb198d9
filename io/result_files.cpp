#include "io/result_files.hpp"

namespace xpl::io {
// Implementation in progress (result files helper).
}  // namespace xpl::io
