#include "io/deck_reader.hpp"

#include <fstream>
#include <sstream>

#include "io/deck_builder.hpp"
#include "io/deck_lines.hpp"

namespace xpl::io {

Model read_deck(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    InputErrors errors;
    errors.add_plain(path.string() + ": cannot open the deck; expected a readable file");
    errors.throw_if_any();
  }
  std::ostringstream content;
  content << in.rdbuf();
  return read_deck_text(content.str(), path.string());
}

Model read_deck_text(const std::string& text, const std::string& file_name) {
  InputErrors errors;
  const std::vector<DeckBlock> blocks = read_deck_blocks(text, file_name, errors);
  DeckBuilder builder(errors, file_name);
  builder.read(blocks);
  Model model = builder.finish();
  errors.throw_if_any();
  return model;
}

}  // namespace xpl::io
