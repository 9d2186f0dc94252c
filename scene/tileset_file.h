// Tile sets as JSON (docs/tileset-format.md):
//   {"name": "cohen8", "kind": "edge", "tiles": [{"n":0,"e":1,"s":1,"w":0}, ...]}
// Corner sets use keys ne, se, sw, nw; corner-coded edge sets carry both. Tiles may carry
// more keys (points, radius_packing, radius_tight, seed: the tile contents); the color
// functions below read and write only the color keys so other writers can reuse them.
// Uses nlohmann::ordered_json so keys stay in the documented order.
#pragma once

#include <array>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "generator/tileset.h"

namespace wangscape {

using Json = nlohmann::ordered_json;

// Per-tile keys the reader accepts besides the color keys (tile contents, written elsewhere).
inline constexpr std::array<std::string_view, 4> kTileContentKeys = {"points", "radius_packing", "radius_tight",
                                                                     "seed"};

// Adds the tile's color keys (n, e, s, w and/or ne, se, sw, nw, as the set colors them) to `object`.
void add_tile_colors(Json& object, const TileSet& set, const Tile& tile);

// Reads the color keys of tile `index` of the document `source`: edge keys when `edges`,
// corner keys when `corners`. Throws Error "tile set '<source>': tile 3: ..." naming the
// key and what was expected; other keys must be color keys or kTileContentKeys.
Tile tile_colors_from_json(const Json& object, std::string_view source, std::size_t index, bool edges, bool corners);

// {"name", "kind", "tiles": [colors...]}.
Json tileset_to_json(const TileSet& set);

// Parses a document (top-level keys other than name, kind, tiles are ignored). `source` names
// the input in errors. Kind may be omitted: the first tile's keys decide.
TileSet tileset_from_json(const Json& document, std::string_view source);

// One top-level key per line, one tile per line: readable and diff-friendly.
std::string format_tileset_json(const Json& document);

// The same layout with each tile's text produced by `format_tile` (e.g. a tile whose points
// go one per line).
std::string format_tileset_json(const Json& document, const std::function<std::string(const Json& tile)>& format_tile);

// Reads and parses a JSON file; `what` names the kind of document in errors ("tile set").
// Throws Error "<what> '<path>': cannot open the file" or "...: not valid JSON (...)".
Json read_json_file(const std::filesystem::path& path, std::string_view what);

TileSet read_tileset_json(const std::filesystem::path& path);
void write_tileset_json(const std::filesystem::path& path, const TileSet& set);

// `--set NAME|FILE`: a built-in name, or else a JSON file. Throws naming the value when it is
// neither.
TileSet load_tileset(std::string_view name_or_file);

}  // namespace wangscape
