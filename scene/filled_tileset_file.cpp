#include "scene/filled_tileset_file.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include "core/atomic_file.h"
#include "core/json_text.h"

namespace wangscape {

namespace {

constexpr const char* kFormat = "wangscape-filled-tileset";
constexpr int kVersion = 1;

std::string where(std::string_view source) { return "filled tile set '" + std::string(source) + "'"; }

const Json& required(const Json& object, const char* key, const std::string& at, const char* expected) {
  const auto it = object.find(key);
  if (it == object.end()) throw Error(at + ": missing key \"" + key + "\"; expected " + expected);
  return *it;
}

bool in_range(double v, double lo, double hi, bool hi_open) { return v >= lo && (hi_open ? v < hi : v <= hi); }

std::string expected_range(double lo, double hi, bool hi_open) {
  return "expected a number in [" + std::to_string(lo) + ", " + std::to_string(hi) + (hi_open ? ")" : "]");
}

double number_in(const Json& value, const std::string& at, const char* key, double lo, double hi, bool hi_open) {
  if (!value.is_number() || !in_range(value.get<double>(), lo, hi, hi_open))
    throw Error(at + ": \"" + key + "\" is " + json_text(value) + "; " + expected_range(lo, hi, hi_open));
  return value.get<double>();
}

// Point values are kept as floats: the range holds for the float kept, not only for the text
// (x = 0.99999999 is 1.0f, which the writer would write and the reader then refuse).
float float_in(const Json& value, const std::string& at, const char* key, double lo, double hi, bool hi_open) {
  const auto kept = static_cast<float>(number_in(value, at, key, lo, hi, hi_open));
  if (!in_range(kept, lo, hi, hi_open))
    throw Error(at + ": \"" + key + "\" is " + json_text(value) + ", " + json_text(Json(kept)) + " as a float; " +
                expected_range(lo, hi, hi_open));
  return kept;
}

std::uint64_t integer_in(const Json& value, const std::string& at, const char* key, std::uint64_t hi) {
  if (!value.is_number_unsigned() && !(value.is_number_integer() && value.get<std::int64_t>() >= 0))
    throw Error(at + ": \"" + key + "\" is " + json_text(value) + "; expected a non-negative integer");
  const auto v = value.get<std::uint64_t>();
  if (v > hi) throw Error(at + ": \"" + key + "\" is " + json_text(value) + "; expected at most " + std::to_string(hi));
  return v;
}

}  // namespace

Json filled_tileset_to_json(const FilledTileSet& filled) {
  Json document = tileset_to_json(filled.set);
  Json tiles = std::move(document["tiles"]);
  document.erase("tiles");
  document["format"] = kFormat;
  document["version"] = kVersion;
  document["seed"] = filled.seed;
  document["radius_packing"] = filled.radius_packing;
  document["radius_tight"] = filled.radius_tight;
  document["shared_width"] = filled.shared_width;
  document["variants"] = filled.variants;
  // Several classes (species): each one's radii and variants (one class needs none: the above).
  if (filled.classes.size() > 1) {
    Json classes = Json::array();
    for (std::size_t c = 0; c < filled.classes.size(); ++c) {
      const auto& radii = filled.classes[c];
      const auto [first, count] = class_variant_range(filled, int(c));
      classes.push_back({{"packing", radii.packing},
                         {"tight", radii.tight},
                         {"edge_objects", radii.edge_objects},
                         {"spacing", radii.spacing},
                         {"first_variant", first},
                         {"variants", count}});
    }
    document["classes"] = std::move(classes);
  }
  for (std::size_t t = 0; t < filled.tiles.size(); ++t) {
    Json points = Json::array();
    for (const TilePoint& p : filled.tiles[t]) {
      // Floats widen to doubles exactly, and the shortest double that reads back is written.
      Json point;
      point["id"] = p.id;
      point["x"] = static_cast<double>(p.x);
      point["y"] = static_cast<double>(p.y);
      point["variant"] = p.variant;
      point["yaw"] = static_cast<double>(p.yaw);
      point["scale"] = static_cast<double>(p.scale);
      point["rank"] = static_cast<double>(p.rank);
      if (filled.classes.size() > 1) point["species"] = p.species;
      points.push_back(std::move(point));
    }
    tiles[t]["points"] = std::move(points);
  }
  document["tiles"] = std::move(tiles);
  return document;
}

FilledTileSet filled_tileset_from_json(const Json& document, std::string_view source) {
  FilledTileSet filled;
  filled.set = tileset_from_json(document, source);  // colors, with tileset_json's checks
  const std::string at = where(source);
  const Json& format = required(document, "format", at, "\"wangscape-filled-tileset\"");
  if (format != kFormat)
    throw Error(at + ": \"format\" is " + json_text(format) + "; expected \"" + kFormat +
                "\" (write one with `wangscape tileset --per-tile N --out FILE`)");
  if (const auto v = integer_in(required(document, "version", at, "1"), at, "version", 1000); v != kVersion)
    throw Error(at + ": version " + std::to_string(v) + "; this wangscape reads version " + std::to_string(kVersion));
  filled.seed = integer_in(required(document, "seed", at, "an integer"), at, "seed", UINT64_MAX);
  filled.radius_packing =
      number_in(required(document, "radius_packing", at, "a number"), at, "radius_packing", 1e-9, 0.5, false);
  filled.radius_tight =
      number_in(required(document, "radius_tight", at, "a number"), at, "radius_tight", 0.0, 0.5, false);
  filled.shared_width =
      number_in(required(document, "shared_width", at, "a number"), at, "shared_width", 0.0, 0.5, false);
  filled.variants =
      static_cast<int>(integer_in(required(document, "variants", at, "an integer"), at, "variants", 65535));
  if (filled.variants < 1) throw Error(at + ": \"variants\" is 0; expected at least 1");

  if (const auto it = document.find("classes"); it != document.end()) {
    if (!it->is_array() || it->size() < 2 || it->size() > 255)
      throw Error(at + ": \"classes\" is " + json_text(*it) + "; expected an array of 2 to 255 classes");
    for (std::size_t c = 0; c < it->size(); ++c) {
      const std::string class_at = at + ": class " + std::to_string(c);
      const Json& k = (*it)[c];
      if (!k.is_object()) throw Error(class_at + " is " + json_text(k) + "; expected an object");
      FilledTileSet::ClassRadii radii;
      radii.packing = number_in(required(k, "packing", class_at, "a number"), class_at, "packing", 0.0, 0.5, false);
      radii.tight = number_in(required(k, "tight", class_at, "a number"), class_at, "tight", 0.0, 0.5, false);
      radii.spacing = number_in(required(k, "spacing", class_at, "a number"), class_at, "spacing", 0.0, 1.0, false);
      const Json& edge = required(k, "edge_objects", class_at, "true or false");
      if (!edge.is_boolean())
        throw Error(class_at + ": \"edge_objects\" is " + json_text(edge) + "; expected true or false");
      radii.edge_objects = edge.get<bool>();
      const auto first = integer_in(required(k, "first_variant", class_at, "an integer"), class_at, "first_variant",
                                    std::uint64_t(filled.variants - 1));
      const auto count = integer_in(required(k, "variants", class_at, "an integer"), class_at, "variants",
                                    std::uint64_t(filled.variants) - first);
      if (count < 1) throw Error(class_at + ": \"variants\" is 0; expected at least 1");
      filled.classes.push_back(radii);
      filled.class_variants.emplace_back(int(first), int(count));
    }
  }
  const std::uint64_t last_species = filled.classes.empty() ? 0 : filled.classes.size() - 1;

  const Json& tiles = document["tiles"];
  filled.tiles.resize(tiles.size());
  for (std::size_t t = 0; t < tiles.size(); ++t) {
    const std::string tile_at = at + ": tile " + std::to_string(t);
    const Json& points = required(tiles[t], "points", tile_at, "an array of points");
    if (!points.is_array()) throw Error(tile_at + ": \"points\" is " + json_text(points) + "; expected an array");
    for (std::size_t k = 0; k < points.size(); ++k) {
      const std::string point_at = tile_at + " point " + std::to_string(k);
      const Json& p = points[k];
      if (!p.is_object()) throw Error(point_at + " is " + json_text(p) + "; expected an object");
      TilePoint tp;
      tp.id =
          static_cast<std::uint32_t>(integer_in(required(p, "id", point_at, "an integer"), point_at, "id", UINT32_MAX));
      tp.x = float_in(required(p, "x", point_at, "a number"), point_at, "x", 0.0, 1.0, true);
      tp.y = float_in(required(p, "y", point_at, "a number"), point_at, "y", 0.0, 1.0, true);
      tp.variant = static_cast<std::uint16_t>(integer_in(required(p, "variant", point_at, "an integer"), point_at,
                                                         "variant", static_cast<std::uint64_t>(filled.variants - 1)));
      tp.yaw = float_in(required(p, "yaw", point_at, "a number"), point_at, "yaw", -7.0, 7.0, false);
      tp.scale = float_in(required(p, "scale", point_at, "a number"), point_at, "scale", 1e-6, 1e6, false);
      // Both optional: files written before classes and ranks hold one class, every point rank 0.
      if (const auto rank = p.find("rank"); rank != p.end())
        tp.rank = float_in(*rank, point_at, "rank", 0.0, 1.0, true);
      if (const auto species = p.find("species"); species != p.end())
        tp.species = static_cast<std::uint8_t>(integer_in(*species, point_at, "species", last_species));
      filled.tiles[t].push_back(tp);
    }
  }
  return filled;
}

std::string format_filled_tileset_json(const Json& document) {
  // A tile's colors on its first line, then one point per line.
  return format_tileset_json(document, [](const Json& tile) {
    Json colors = tile;
    colors.erase("points");
    std::string text = json_text(colors);
    text.pop_back();  // the closing brace: the points follow
    text += ", \"points\": [";
    const Json& points = tile.contains("points") ? tile["points"] : Json::array();
    for (std::size_t k = 0; k < points.size(); ++k) text += (k ? ",\n      " : "\n      ") + json_text(points[k]);
    return text + (points.empty() ? "]}" : "\n    ]}");
  });
}

void write_filled_tileset_json(const std::filesystem::path& path, const FilledTileSet& filled) {
  write_file_atomically(path, format_filled_tileset_json(filled_tileset_to_json(filled)));
}

FilledTileSet read_filled_tileset_json(const std::filesystem::path& path) {
  return filled_tileset_from_json(read_json_file(path, "filled tile set"), path.string());
}

}  // namespace wangscape
