#include "io/deck/deck_reader.hpp"

#include <utility>

#include "io/deck/deck_file.hpp"
#include "io/deck/deck_handlers.hpp"
#include "io/deck/deck_keywords.hpp"
#include "io/deck/deck_lines.hpp"
#include "io/deck/deck_units.hpp"
#include "io/deck/model_checks.hpp"

namespace xpl::io {

namespace {

/// Reads the deck text and builds the Model. The blocks (views into `text` and the storage)
/// are released before the Model is completed, and so is `owned_text` (the text, if the
/// caller does not need it any more): the peak is then the reader state's.
Model build_model(std::string_view text, const std::string& file_name, ModelChecks checks,
                  std::string* owned_text = nullptr) {
  InputErrors errors;
  DeckState deck(errors, file_name);
  {
    DeckStorage storage;
    const std::vector<DeckBlock> blocks = read_deck_blocks(text, file_name, storage, errors);
    read_blocks(deck, blocks);
    read_directives(storage.directives, deck.model, errors);
  }
  if (owned_text != nullptr) std::string().swap(*owned_text);
  Model model = finish(deck);
  settle_units(model);
  // The whole-model checks need a complete model, so they run only on an otherwise clean deck.
  if (checks != ModelChecks::Skip && errors.empty()) {
    for (const std::string& message : unsupported_features(model)) errors.add_plain(message);
    for (const std::string& message : unimplemented_kernels(model)) {
      if (checks == ModelChecks::Run)
        errors.add_plain(message);
      else
        model.deck_messages.push_back({true, message + " (xpl run refuses this model)"});
    }
  }
  errors.throw_if_any();
  return model;
}

}  // namespace

Model read_deck(const std::filesystem::path& path, ModelChecks checks) {
  std::string content;
  const DeckFileError refused = read_deck_file(path, content);
  if (!refused.ok()) {
    InputErrors errors;
    errors.add_plain(refused.line > 0 ? path.string() + ":" + std::to_string(refused.line) + ": " +
                                            refused.problem + "; " + refused.expected
                                      : path.string() + ": the deck " + refused.problem + "; " +
                                            refused.expected);
    errors.throw_if_any();
  }
  return build_model(content, path.string(), checks, &content);
}

Model read_deck_text(const std::string& text, const std::string& file_name, ModelChecks checks) {
  return build_model(text, file_name, checks);
}

}  // namespace xpl::io
