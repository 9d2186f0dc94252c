// Filled tile sets (tile colors + Poisson-disk points) as JSON; the schema is
// docs/filled-tileset-format.md. The color keys are tileset_json's, so a filled set is also a
// plain tile-set document (readers that only want colors ignore the rest).
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "generator/poisson_tiles.h"
#include "scene/tileset_file.h"

namespace wangscape {

Json filled_tileset_to_json(const FilledTileSet& filled);

// Throws Error "filled tile set '<source>': tile 3 point 5: ..." naming what is wrong.
FilledTileSet filled_tileset_from_json(const Json& document, std::string_view source);

// Top-level keys one per line, each tile's colors on one line, then one point per line.
std::string format_filled_tileset_json(const Json& document);

void write_filled_tileset_json(const std::filesystem::path& path, const FilledTileSet& filled);
FilledTileSet read_filled_tileset_json(const std::filesystem::path& path);

}  // namespace wangscape
