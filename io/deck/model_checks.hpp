#pragma once
/// \file Checks of a whole, otherwise valid Model that the deck reader runs after building it:
/// features it reads but the time loop does not run yet, element kernels that lack a material
/// model, and rigid bodies sharing a node.

#include <string>
#include <vector>

#include "solver/model/model.hpp"

namespace xpl::io {

/// Features the deck reader accepts but the time loop does not run yet, one message per
/// keyword occurrence (`file:LINE: *KEYWORD: problem; expectation`), and nodes in two rigid
/// bodies. read_deck reports them as deck errors, so such a model is refused before anything
/// is written rather than partly ignored. `model` must be complete (no deck errors).
std::vector<std::string> unsupported_features(const Model& model);

/// What a time loop would run wrongly because an element kernel lacks it (one message per
/// material and element type, at the material's keyword line; none in this version: C3D8R
/// and S4R run every material xpl reads, plasticity included). Kept apart from unsupported_features
/// so that a data check can still report the rest of the model (ModelChecks::DataCheck makes these
/// warnings); `xpl run` refuses them like unsupported features. `model` must be complete (no deck
/// errors).
std::vector<std::string> unimplemented_kernels(const Model& model);

}  // namespace xpl::io
