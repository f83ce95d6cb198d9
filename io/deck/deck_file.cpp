#include "io/deck/deck_file.hpp"

#include <cstring>
#include <fstream>
#include <new>
#include <vector>

namespace xpl::io {

namespace {

/// Bytes read at a time: the line lengths are checked chunk by chunk.
constexpr std::size_t CHUNK_BYTES = std::size_t{1} << 20;

std::string kind_of(std::filesystem::file_type type) {
  switch (type) {
    case std::filesystem::file_type::directory:
      return "a directory";
    case std::filesystem::file_type::character:
    case std::filesystem::file_type::block:
      return "a device";
    case std::filesystem::file_type::fifo:
      return "a pipe";
    case std::filesystem::file_type::socket:
      return "a socket";
    default:
      return "not a regular file";
  }
}

}  // namespace

DeckFileError read_deck_file(const std::filesystem::path& path, std::string& content) {
  content.clear();
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(path, error);
  if (error || status.type() == std::filesystem::file_type::not_found)
    return {"cannot open the file", "expected an existing, readable file"};
  if (status.type() != std::filesystem::file_type::regular)
    return {"is " + kind_of(status.type()), "expected a regular file holding deck text"};
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  if (!error && size > MAX_DECK_BYTES)
    return {"is " + std::to_string(size) + " bytes, more than the limit of " +
                std::to_string(MAX_DECK_BYTES) + " bytes (2 GiB)",
            "expected a deck of at most 2 GiB"};
  std::ifstream in(path, std::ios::binary);
  if (!in) return {"cannot open the file", "expected an existing, readable file"};
  // One allocation of the file's size: the pages are only touched as they are filled, so a
  // file refused after its first chunk costs only that chunk.
  try {
    if (!error) content.reserve(static_cast<std::size_t>(size));
  } catch (const std::bad_alloc&) {  // NOLINT(bugprone-empty-catch): grow as it is read
  }
  std::vector<char> chunk(CHUNK_BYTES);
  std::size_t line_length = 0;
  long long line = 1;
  while (in) {
    in.read(chunk.data(), static_cast<std::streamsize>(chunk.size()));
    const auto count = static_cast<std::size_t>(in.gcount());
    if (count == 0) break;
    const char* p = chunk.data();
    const char* end = p + count;
    while (p < end) {
      const void* found = std::memchr(p, '\n', static_cast<std::size_t>(end - p));
      const char* stop = found != nullptr ? static_cast<const char*>(found) : end;
      line_length += static_cast<std::size_t>(stop - p);
      if (line_length > MAX_LINE_CHARS)
        return {"line longer than " + std::to_string(MAX_LINE_CHARS) + " characters",
                "expected deck lines of at most 1 MiB (Abaqus allows 256 characters; continue "
                "long data lines on the next line after a trailing comma)",
                static_cast<int>(line)};
      if (found == nullptr) break;
      ++line;
      line_length = 0;
      p = stop + 1;
    }
    if (content.size() + count > MAX_DECK_BYTES)  // the file grew while it was read
      return {"is more than the limit of " + std::to_string(MAX_DECK_BYTES) + " bytes (2 GiB)",
              "expected a deck of at most 2 GiB"};
    content.append(chunk.data(), count);
  }
  if (in.bad()) return {"could not be read to its end", "expected a readable file"};
  return {};
}

}  // namespace xpl::io
