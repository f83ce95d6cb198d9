#include "io/deck_reader.hpp"

namespace xpl::io {
// Implementation in progress (deck reader helper).
}  // namespace xpl::io
