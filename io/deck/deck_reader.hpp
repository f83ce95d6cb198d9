#pragma once
/// \file Reads an Abaqus-format deck (the xpl subset) into a Model.

#include <filesystem>
#include <string>

#include "solver/model.hpp"

namespace xpl::io {

/// Reads a deck file, following *INCLUDE relative to the including file. Deck ids are mapped
/// to contiguous internal indices here, once. Throws InputError listing every problem of the
/// deck (`file:LINE: *KEYWORD: what is wrong; what is expected`), never a partial Model.
Model read_deck(const std::filesystem::path& path);

/// Same as read_deck, from text in memory; `file_name` is used in messages, its directory
/// for *INCLUDE, and its stem as the job name.
Model read_deck_text(const std::string& text, const std::string& file_name);

}  // namespace xpl::io
