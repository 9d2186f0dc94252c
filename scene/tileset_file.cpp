#include "scene/tileset_file.h"

#include <algorithm>
#include <fstream>
#include <sstream>

#include "core/atomic_file.h"
#include "core/json_text.h"
#include "core/text_file.h"

namespace wangscape {

namespace {

constexpr std::array<const char*, 4> kEdgeKeys = {"n", "e", "s", "w"};
constexpr std::array<const char*, 4> kCornerKeys = {"ne", "se", "sw", "nw"};
constexpr int kMaxColor = 63;  // make_tileset's limit

std::string where(std::string_view source) { return "tile set '" + std::string(source) + "'"; }

bool is_known_tile_key(const std::string& key) {
  return std::find(kEdgeKeys.begin(), kEdgeKeys.end(), key) != kEdgeKeys.end() ||
         std::find(kCornerKeys.begin(), kCornerKeys.end(), key) != kCornerKeys.end() ||
         std::find(kTileContentKeys.begin(), kTileContentKeys.end(), key) != kTileContentKeys.end();
}

}  // namespace

void add_tile_colors(Json& object, const TileSet& set, const Tile& tile) {
  if (set.has_edges) {
    object["n"] = tile.n();
    object["e"] = tile.e();
    object["s"] = tile.s();
    object["w"] = tile.w();
  }
  if (set.has_corners) {
    object["ne"] = tile.ne();
    object["se"] = tile.se();
    object["sw"] = tile.sw();
    object["nw"] = tile.nw();
  }
}

Tile tile_colors_from_json(const Json& object, std::string_view source, std::size_t index, bool edges, bool corners) {
  const std::string at = where(source) + ": tile " + std::to_string(index);
  if (!object.is_object()) throw Error(at + " is " + std::string(object.type_name()) + "; expected an object");
  for (const auto& [key, value] : object.items())
    if (!is_known_tile_key(key))
      throw Error(
          at + ": unknown key '" + key +
          "'; expected n, e, s, w (edges), ne, se, sw, nw (corners), points, radius_packing, radius_tight, seed");
  const auto color = [&](const char* key, const char* kind) {
    const auto it = object.find(key);
    if (it == object.end()) throw Error(at + ": missing key '" + key + "'; every tile of " + kind);
    if (!it->is_number_integer() || it->get<std::int64_t>() < 0 || it->get<std::int64_t>() > kMaxColor)
      throw Error(at + ": key '" + key + "' is " + it->dump() + "; expected an integer 0.." +
                  std::to_string(kMaxColor));
    return static_cast<int>(it->get<std::int64_t>());
  };
  Tile tile;
  const char* edge_kind = corners ? "this set needs n, e, s, w, ne, se, sw, nw" : "an edge set needs n, e, s, w";
  if (edges)
    tile = Tile::edges(color("n", edge_kind), color("e", edge_kind), color("s", edge_kind), color("w", edge_kind));
  if (corners) {
    const char* kind = edges ? edge_kind : "a corner set needs ne, se, sw, nw";
    tile.colors[kNE] = static_cast<std::int8_t>(color("ne", kind));
    tile.colors[kSE] = static_cast<std::int8_t>(color("se", kind));
    tile.colors[kSW] = static_cast<std::int8_t>(color("sw", kind));
    tile.colors[kNW] = static_cast<std::int8_t>(color("nw", kind));
  }
  // Keys of the other kind are an error: a corner set's tile with "n" is almost surely a mistake.
  if (!edges)
    for (const char* key : kEdgeKeys)
      if (object.contains(key))
        throw Error(at + ": key '" + key + "' in a corner set; corner tiles use ne, se, sw, nw");
  if (!corners)
    for (const char* key : kCornerKeys)
      if (object.contains(key))
        throw Error(at + ": key '" + key + "' but tile 0 has no corner colors; every tile must color the same parts");
  return tile;
}

Json tileset_to_json(const TileSet& set) {
  Json document;
  document["name"] = set.name;
  document["kind"] = set.kind == TileKind::edge ? "edge" : "corner";
  Json tiles = Json::array();
  for (const Tile& tile : set.tiles) {
    Json object = Json::object();
    add_tile_colors(object, set, tile);
    tiles.push_back(std::move(object));
  }
  document["tiles"] = std::move(tiles);
  return document;
}

TileSet tileset_from_json(const Json& document, std::string_view source) {
  if (!document.is_object())
    throw Error(where(source) + ": the document is " + std::string(document.type_name()) +
                "; expected an object with \"tiles\"");
  std::string name = std::filesystem::path(std::string(source)).stem().string();
  if (const auto it = document.find("name"); it != document.end()) {
    if (!it->is_string()) throw Error(where(source) + ": \"name\" is " + it->dump() + "; expected a string");
    name = it->get<std::string>();
  }
  const auto tiles = document.find("tiles");
  if (tiles == document.end()) throw Error(where(source) + ": missing key \"tiles\"; expected an array of tiles");
  if (!tiles->is_array() || tiles->empty())
    throw Error(where(source) + ": \"tiles\" is " + (tiles->is_array() ? std::string("empty") : tiles->dump()) +
                "; expected a non-empty array of tiles");
  const Json& first = tiles->front();
  bool edges = first.is_object() && first.contains("n");
  bool corners = first.is_object() && first.contains("ne");
  if (const auto kind = document.find("kind"); kind != document.end()) {
    if (*kind == "edge") {
      edges = true;
    } else if (*kind == "corner") {
      if (edges) throw Error(where(source) + ": tile 0: key 'n' in a corner set; corner tiles use ne, se, sw, nw");
      corners = true;
    } else {
      throw Error(where(source) + ": \"kind\" is " + kind->dump() + "; expected \"edge\" or \"corner\"");
    }
  } else if (!edges && !corners) {
    edges = true;  // reports the missing edge keys of tile 0
  }
  std::vector<Tile> parsed;
  parsed.reserve(tiles->size());
  for (std::size_t i = 0; i < tiles->size(); ++i)
    parsed.push_back(tile_colors_from_json((*tiles)[i], source, i, edges, corners));
  return make_tileset(std::move(name), std::move(parsed), source);
}

std::string format_tileset_json(const Json& document) {
  return format_tileset_json(document, [](const Json& tile) { return json_text(tile); });
}

std::string format_tileset_json(const Json& document, const std::function<std::string(const Json& tile)>& format_tile) {
  std::string text = "{\n";
  bool first_key = true;
  for (const auto& [key, value] : document.items()) {
    text += first_key ? "  " : ",\n  ";
    first_key = false;
    text += json_text(Json(key)) + ": ";
    if (key == "tiles" && value.is_array()) {
      text += "[";
      for (std::size_t i = 0; i < value.size(); ++i) text += (i ? ",\n    " : "\n    ") + format_tile(value[i]);
      text += value.empty() ? "]" : "\n  ]";
    } else {
      text += json_text(value);
    }
  }
  return text + "\n}\n";
}

Json read_json_file(const std::filesystem::path& path, std::string_view what) {
  const std::string at = std::string(what) + " '" + path.string() + "'";
  const std::string text = read_text_file(path, kMaxJsonFileBytes, what);
  check_nesting(text, path, kMaxNesting);  // nlohmann's parser and dump() recurse
  try {
    return Json::parse(text);
  } catch (const Json::exception& e) {
    throw Error(at + ": not valid JSON: " + json_error_text(e));  // where and what, without nlohmann's id
  }
}

TileSet read_tileset_json(const std::filesystem::path& path) {
  return tileset_from_json(read_json_file(path, "tile set"), path.string());
}

void write_tileset_json(const std::filesystem::path& path, const TileSet& set) {
  write_file_atomically(path, format_tileset_json(tileset_to_json(set)));
}

TileSet load_tileset(std::string_view name_or_file) {
  if (is_builtin_tileset(name_or_file)) return builtin_tileset(name_or_file);
  const std::filesystem::path path{std::string(name_or_file)};
  if (path.extension() == ".json" || std::filesystem::exists(path)) return read_tileset_json(path);
  return builtin_tileset(name_or_file);  // throws: unknown set, listing the built-in names
}

}  // namespace wangscape
