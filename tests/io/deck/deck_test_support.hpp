#pragma once
/// \file Helpers shared by the deck reader tests: a small valid deck and error capture.

#include <string>
#include <vector>

#include "common/error.hpp"
#include "io/deck_reader.hpp"

namespace xpl::test {

/// Model data of two unit bricks side by side (x in [0, 2]) with sparse ids 1000001..12 and
/// elements 5000001, 5000002, a material and a section: no step.
inline std::string two_brick_model() {
  return "*NODE, NSET=ALLN\n"
         "1000001, 0, 0, 0\n"
         "1000002, 1, 0, 0\n"
         "1000003, 1, 1, 0\n"
         "1000004, 0, 1, 0\n"
         "1000005, 2, 0, 0\n"
         "1000006, 2, 1, 0\n"
         "1000007, 0, 0, 1\n"
         "1000008, 1, 0, 1\n"
         "1000009, 1, 1, 1\n"
         "1000010, 0, 1, 1\n"
         "1000011, 2, 0, 1\n"
         "1000012, 2, 1, 1\n"
         "*ELEMENT, TYPE=C3D8R, ELSET=BRICKS\n"
         "5000001, 1000001, 1000002, 1000003, 1000004, 1000007, 1000008, 1000009, 1000010\n"
         "5000002, 1000002, 1000005, 1000006, 1000003, 1000008, 1000011, 1000012, 1000009\n"
         "*MATERIAL, NAME=STEEL\n"
         "*DENSITY\n"
         "7800.\n"
         "*ELASTIC\n"
         "2.1e11, 0.3\n"
         "*SOLID SECTION, ELSET=BRICKS, MATERIAL=STEEL\n";
}

/// A minimal valid step.
inline std::string simple_step() {
  return "*STEP\n"
         "*DYNAMIC, EXPLICIT\n"
         ", 1e-3\n"
         "*END STEP\n";
}

/// 1-based number of the first line of `deck` containing `needle` (0 if none).
inline int line_of(const std::string& deck, const std::string& needle) {
  const std::size_t at = deck.find(needle);
  if (at == std::string::npos) return 0;
  int line = 1;
  for (std::size_t i = 0; i < at; ++i)
    if (deck[i] == '\n') ++line;
  return line;
}

/// The messages of the InputError thrown by reading `deck`; empty if it reads fine.
inline std::vector<std::string> deck_errors(const std::string& deck,
                                            const std::string& file_name = "t.inp") {
  try {
    io::read_deck_text(deck, file_name);
  } catch (const InputError& e) {
    return e.messages();
  }
  return {};
}

/// Whether some message starts with `prefix` and contains `text`.
inline bool has_error(const std::vector<std::string>& messages, const std::string& prefix,
                      const std::string& text = "") {
  for (const std::string& m : messages)
    if (m.rfind(prefix, 0) == 0 && m.find(text) != std::string::npos) return true;
  return false;
}

}  // namespace xpl::test
