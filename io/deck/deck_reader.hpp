#pragma once
/// \file Reads an Abaqus-format deck (the xpl subset) into a Model.

#include <filesystem>
#include <string>

#include "solver/model/model.hpp"

namespace xpl::io {

/// Whether read_deck checks the model as a whole once the deck reads without errors.
enum class ModelChecks {
  Run,  ///< refuse what the time loop does not run yet (unsupported_features, model_checks.hpp)
  /// As Run, but what only an element kernel lacks (unimplemented_kernels) becomes a warning
  /// in Model::deck_messages: `xpl check` reports such a model fully, `xpl run` refuses it.
  DataCheck,
  Skip,  ///< only the deck itself: for tests of how such features are read
};

/// Reads a deck file, following *INCLUDE relative to the including file. Deck ids are mapped
/// to contiguous internal indices here, once. Throws InputError listing every problem of the
/// deck (`file:LINE: *KEYWORD: what is wrong; what is expected`), never a partial Model. A deck
/// without such errors is then checked as a whole (`checks`); what that reports is thrown the
/// same way.
Model read_deck(const std::filesystem::path& path, ModelChecks checks = ModelChecks::Run);

/// Same as read_deck, from text in memory; `file_name` is used in messages, its directory
/// for *INCLUDE, and its stem as the job name.
Model read_deck_text(const std::string& text, const std::string& file_name,
                     ModelChecks checks = ModelChecks::Run);

}  // namespace xpl::io
