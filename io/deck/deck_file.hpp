#pragma once
/// \file Reading a deck or included file into memory, within limits: only regular files (a
/// directory, a device such as /dev/zero or a pipe is refused), at most MAX_DECK_BYTES, no
/// physical line longer than MAX_LINE_CHARS (found while reading, so a 2 GB line is refused
/// after its first MiB, not after taking the machine's memory).

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

namespace xpl::io {

/// Largest deck or included file, bytes (2 GiB − 1: every line number fits an int). Decks of
/// 10^7 elements take about 1 GB of text.
inline constexpr std::uintmax_t MAX_DECK_BYTES = (std::uintmax_t{1} << 31) - 1;
/// Longest physical line, characters. Abaqus allows 256; generated decks sometimes put a
/// whole set on one line, so xpl allows far more.
inline constexpr std::size_t MAX_LINE_CHARS = std::size_t{1} << 20;

/// Why a file could not be read: `problem` empty when it was read.
struct DeckFileError {
  std::string problem;   ///< "is a directory", "line longer than ..."
  std::string expected;  ///< what would have been accepted
  int line = 0;          ///< the offending line (1-based), 0 when it concerns the whole file
  bool ok() const { return problem.empty(); }
};

/// Reads the regular file `path` into `content` (replaced). On a refusal `content` holds at
/// most what was read before it.
DeckFileError read_deck_file(const std::filesystem::path& path, std::string& content);

}  // namespace xpl::io
