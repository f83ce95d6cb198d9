#pragma once
/// \file Checks of a whole, otherwise valid Model that the deck reader runs after building it:
/// features it reads but the time loop does not run yet, and rigid bodies sharing a node.

#include <string>
#include <vector>

#include "solver/model.hpp"

namespace xpl::io {

/// Features the deck reader accepts but the time loop does not run yet, one message per
/// keyword occurrence (`file:LINE: *KEYWORD: problem; expectation`), and nodes in two rigid
/// bodies. read_deck reports them as deck errors, so such a model is refused before anything
/// is written rather than partly ignored. `model` must be complete (no deck errors).
std::vector<std::string> unsupported_features(const Model& model);

}  // namespace xpl::io
