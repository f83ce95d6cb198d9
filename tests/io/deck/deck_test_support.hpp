#pragma once
/// \file Helpers shared by the deck reader tests: a small valid deck and error capture.

#include <string>
#include <vector>

#include "common/error.hpp"
#include "io/deck/deck_reader.hpp"

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

/// Model data of a flat plate of two S4R elements 11, 12 in z = 0 (nodes 1..6, x in [0, 2],
/// y in [0, 1]; normals along +z), a material ALU and a 2 mm shell section: no step.
inline std::string shell_plate_model() {
  return "*NODE, NSET=PLATE_NODES\n"
         "1, 0, 0, 0\n"
         "2, 1, 0, 0\n"
         "3, 2, 0, 0\n"
         "4, 0, 1, 0\n"
         "5, 1, 1, 0\n"
         "6, 2, 1, 0\n"
         "*ELEMENT, TYPE=S4R, ELSET=PLATE\n"
         "11, 1, 2, 5, 4\n"
         "12, 2, 3, 6, 5\n"
         "*MATERIAL, NAME=ALU\n"
         "*DENSITY\n"
         "2700.\n"
         "*ELASTIC\n"
         "7e10, 0.33\n"
         "*SHELL SECTION, ELSET=PLATE, MATERIAL=ALU\n"
         "0.002\n";
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

/// The expected message prefix `file:LINE: *KEYWORD: ` for `needle`'s line in `deck`.
inline std::string at(const std::string& deck, const std::string& needle,
                      const std::string& keyword, const std::string& file_name = "t.inp") {
  return file_name + ":" + std::to_string(line_of(deck, needle)) + ": " + keyword + ": ";
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

/// Whether one of the messages is exactly `message`.
inline bool has_message(const std::vector<std::string>& messages, const std::string& message) {
  for (const std::string& m : messages)
    if (m == message) return true;
  return false;
}

/// Whether some message starts with `prefix` and contains `text`.
inline bool has_error(const std::vector<std::string>& messages, const std::string& prefix,
                      const std::string& text = "") {
  for (const std::string& m : messages)
    if (m.rfind(prefix, 0) == 0 && m.find(text) != std::string::npos) return true;
  return false;
}

}  // namespace xpl::test
