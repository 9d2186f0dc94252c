#include "exporters/texture_tile_files.h"

#include <string>
#include <system_error>

#include "core/atomic_file.h"
#include "exporters/image_io.h"
#include "scene/tileset_file.h"

namespace wangscape {

namespace {

void make_folder(const std::filesystem::path& dir) {
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error) throw Error("cannot create folder '" + dir.string() + "': " + error.message());
}

// The tile entries: file name plus the tile's colors, in set order.
Json tile_entries(const TileSet& set, const std::string& prefix) {
  Json tiles = Json::array();
  for (std::size_t t = 0; t < set.size(); ++t) {
    Json entry;
    entry["file"] = prefix + std::to_string(t) + ".png";
    add_tile_colors(entry, set, set.tiles[t]);
    tiles.push_back(std::move(entry));
  }
  return tiles;
}

}  // namespace

void write_noise_tile_files(const std::filesystem::path& dir, const NoiseTileSet& tiles, int pixels,
                            NoisePattern pattern) {
  make_folder(dir);
  for (std::uint32_t t = 0; t < tiles.size(); ++t)
    write_image_gray16(dir / ("noise_tile_" + std::to_string(t) + ".png"),
                       rasterize_noise_tile(tiles, t, pixels, pattern));
  const bool is_signed = pattern == NoisePattern::noise || pattern == NoisePattern::fbm;
  Json doc;
  doc["kind"] = "noise";
  doc["set"] = tileset_to_json(tiles.set());
  doc["lattice"] = tiles.lattice();
  doc["octaves"] = tiles.levels();
  doc["seed"] = tiles.seed();
  doc["pattern"] = to_string(pattern);
  doc["pixels"] = pixels;
  doc["gray"] = {{"min", is_signed ? -1 : 0}, {"max", 1}};
  doc["tiles"] = tile_entries(tiles.set(), "noise_tile_");
  write_file_atomically(dir / "noise_tiles.json", doc.dump(2) + "\n");
}

void write_texture_tile_files(const std::filesystem::path& dir, const TextureTileSet& tiles) {
  make_folder(dir);
  for (std::size_t t = 0; t < tiles.tiles.size(); ++t)
    write_image(dir / ("texture_tile_" + std::to_string(t) + ".png"), tiles.tiles[t].image);
  Json doc;
  doc["kind"] = "texture";
  doc["set"] = tileset_to_json(tiles.set);
  doc["tile_size"] = tiles.tile_size;
  doc["marks"] = tiles.marks;
  doc["total_error"] = tiles.total_error();
  Json windows = Json::array();
  for (const TextureWindow& w : tiles.windows) windows.push_back({{"exemplar", w.exemplar}, {"x", w.x}, {"y", w.y}});
  doc["windows"] = std::move(windows);
  Json entries = tile_entries(tiles.set, "texture_tile_");
  for (std::size_t t = 0; t < tiles.tiles.size(); ++t) entries[t]["error"] = tiles.tiles[t].error;
  doc["tiles"] = std::move(entries);
  write_file_atomically(dir / "texture_tiles.json", doc.dump(2) + "\n");
}

}  // namespace wangscape
