#include "exporters/texture_tile_files.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <string>
#include <system_error>

#include "core/atomic_file.h"
#include "core/json_text.h"
#include "core/staged_folder.h"
#include "exporters/image_io.h"
#include "scene/ground_look.h"
#include "scene/tileset_file.h"

namespace wangscape {

namespace {

constexpr const char* kNoiseTilesFile = "noise_tiles.json";
constexpr const char* kTextureTilesFile = "texture_tiles.json";

// Throws Error naming `dir` unless it is missing, empty or an earlier folder of these tiles (it
// holds `json_name`): the folder is replaced whole, so nothing else may be in it.
void check_tile_folder_target(const std::filesystem::path& dir, const char* json_name) {
  std::error_code ec;
  if (!std::filesystem::exists(dir, ec)) return;
  if (!std::filesystem::is_directory(dir, ec)) throw Error(dir, "", "exists and is not a folder");
  if (std::filesystem::is_empty(dir, ec) || std::filesystem::is_regular_file(dir / json_name, ec)) return;
  throw Error(dir, "",
              std::string("exists and is not a folder of tiles (it has no ") + json_name +
                  "); give a new or empty folder, or an earlier run's");
}

// A folder of tiles written whole or not at all (core/staged_folder.h): `write` fills the
// staging folder, which then replaces `dir`; a failed write leaves `dir` as it was, or none. Its
// errors name a file where it was to be, not under the staging folder's name.
template <class Write>
void write_tile_folder(const std::filesystem::path& dir, const char* json_name, Write&& write) {
  check_tile_folder_target(dir, json_name);
  StagedFolder staged(dir);
  try {
    write(staged.path());
  } catch (const Error& e) {
    std::string message = e.what();
    const std::string staging = staged.path().string(), target = staged.target().string();
    for (auto at = message.find(staging); at != std::string::npos; at = message.find(staging, at + target.size()))
      message.replace(at, staging.size(), target);
    throw Error(message);
  }
  staged.publish();
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

// "WxH" of a --preview, each 1..16384.
std::array<int, 2> parse_preview_size(const std::string& text) {
  int w = 0, h = 0;
  char tail = 0;
  if (std::sscanf(text.c_str(), "%dx%d%c", &w, &h, &tail) != 2 || w < 1 || h < 1 || w > 16384 || h > 16384)
    throw Error("--preview '" + text + "' must be WIDTHxHEIGHT in pixels, each 1..16384 (e.g. 1024x512)");
  return {w, h};
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A finite tiling of `set` covering w x h pixels at `tile` pixels per tile (any set, any algorithm).
Tiling preview_tiling(const TileSet& set, int w, int h, int tile, std::uint64_t seed) {
  TilingOptions options;
  options.seed = seed;
  return make_tiling(set, (w + tile - 1) / tile, (h + tile - 1) / tile, options);
}

// Writes the tile files after the preview was written; when they fail, the preview goes too.
template <class Write>
void write_tiles_after_preview(const std::filesystem::path& preview, bool no_preview, Write&& write) {
  try {
    write();
  } catch (...) {
    std::error_code ignored;
    if (!no_preview) std::filesystem::remove(preview, ignored);
    throw;
  }
}

// The files of write_noise_tile_files into `dir`.
void fill_noise_tile_folder(const std::filesystem::path& dir, const NoiseTileSet& tiles, int pixels,
                            NoisePattern pattern) {
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
  write_file_atomically(dir / kNoiseTilesFile, json_text(doc, 2) + "\n");
}

// The files of write_texture_tile_files into `dir`.
void fill_texture_tile_folder(const std::filesystem::path& dir, const TextureTileSet& tiles) {
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
  write_file_atomically(dir / kTextureTilesFile, json_text(doc, 2) + "\n");
}

}  // namespace

std::string run_tiles_job(const NoiseTilesJob& job) {
  const auto start = std::chrono::steady_clock::now();
  const std::array<int, 2> size =
      job.preview_size.empty() ? std::array<int, 2>{} : parse_preview_size(job.preview_size);
  check_tile_folder_target(job.out, kNoiseTilesFile);  // before the work
  const NoiseTileSet tiles(load_tileset(job.set), job.options);
  // The preview first: a preview that cannot be written leaves no tiles folder behind.
  if (!job.preview_size.empty()) {
    // The pattern over the set's own tiling, one tile per `pixels` pixels: a window of a scanline
    // tiling, or for marble and wood, whose second layer reads tiles 7 away (beyond any window:
    // there it drew plain stripes in whole tiles), the unbounded hashed tiling of a complete set.
    const NoisePattern pattern = job.pattern.value_or(NoisePattern::turbulence);
    const double pixel = 1.0 / job.pixels;
    ImageGray16 image(size[0], size[1]);
    if (pattern == NoisePattern::marble || pattern == NoisePattern::wood) {
      try {
        image = render_noise_preview(make_noise_field(tiles.set(), job.options, job.options.seed, 1.0), pattern,
                                     size[0], size[1], pixel);
      } catch (const Error& e) {
        throw Error(std::string("--pattern ") + to_string(pattern) + ": " + e.what() +
                    " (marble and wood are drawn over the unbounded tiling of a complete set: complete-edge-K, "
                    "corner-K)");
      }
    } else {
      const WindowNoise field(
          tiles, WindowTiles{preview_tiling(tiles.set(), size[0], size[1], job.pixels, job.options.seed)}, 1.0);
      for (int y = 0; y < size[1]; ++y)
        for (int x = 0; x < size[0]; ++x)
          image.set(x, y,
                    noise_to_gray16(pattern, field.pattern(pattern, (x + 0.5) * pixel, (size[1] - y - 0.5) * pixel)));
    }
    write_image_gray16(job.preview, image);
  }
  // The tiles hold noise, fbm or turbulence; marble and wood are patterns of the whole tiling.
  NoisePattern in_tiles = NoisePattern::fbm;
  if (job.pattern && *job.pattern != NoisePattern::marble && *job.pattern != NoisePattern::wood)
    in_tiles = *job.pattern;
  write_tiles_after_preview(job.preview, job.preview_size.empty(),
                            [&] { write_noise_tile_files(job.out, tiles, job.pixels, in_tiles); });
  char line[256];
  std::snprintf(line, sizeof line, "%s: %zu noise tiles, lattice %d, %d octaves, %.3f s", tiles.set().name.c_str(),
                tiles.size(), tiles.lattice(), tiles.levels(), seconds_since(start));
  return line;
}

std::string run_tiles_job(const TextureTilesJob& job) {
  const auto start = std::chrono::steady_clock::now();
  const std::array<int, 2> size =
      job.preview_size.empty() ? std::array<int, 2>{} : parse_preview_size(job.preview_size);
  check_tile_folder_target(job.out, kTextureTilesFile);  // before the work
  std::vector<ImageRgb8> exemplars;
  for (const auto& name : job.exemplars) {
    const auto shipped = shipped_exemplar(name);
    exemplars.push_back(read_image(shipped.empty() ? std::filesystem::path(name) : shipped));
  }
  TextureTileReport report;
  const TextureTileSet tiles = make_texture_tiles(load_tileset(job.set), exemplars, job.options, &report);
  if (!job.preview_size.empty()) {  // first, as above
    const ImageRgb8 all =
        draw_texture_tiling(tiles, preview_tiling(tiles.set, size[0], size[1], tiles.tile_size, job.options.seed));
    ImageRgb8 image(size[0], size[1]);
    for (int y = 0; y < size[1]; ++y)
      std::copy_n(&all.pixels[all.offset(0, y)], std::size_t(size[0]) * 3, &image.pixels[image.offset(0, y)]);
    write_image(job.preview, image);
  }
  write_tiles_after_preview(job.preview, job.preview_size.empty(), [&] { write_texture_tile_files(job.out, tiles); });
  char line[256];
  std::snprintf(line, sizeof line, "%s: %zu texture tiles of %d px, quilting error %llu (search %llu -> %llu), %.3f s",
                tiles.set.name.c_str(), tiles.tiles.size(), tiles.tile_size,
                static_cast<unsigned long long>(tiles.total_error()),
                static_cast<unsigned long long>(report.initial_cost),
                static_cast<unsigned long long>(report.final_cost), seconds_since(start));
  return line;
}

void write_noise_tile_files(const std::filesystem::path& dir, const NoiseTileSet& tiles, int pixels,
                            NoisePattern pattern) {
  write_tile_folder(dir, kNoiseTilesFile, [&](const std::filesystem::path& staging) {
    fill_noise_tile_folder(staging, tiles, pixels, pattern);
  });
}

void write_texture_tile_files(const std::filesystem::path& dir, const TextureTileSet& tiles) {
  write_tile_folder(dir, kTextureTilesFile,
                    [&](const std::filesystem::path& staging) { fill_texture_tile_folder(staging, tiles); });
}

}  // namespace wangscape
