// Noise tiles and texture tiles as files (docs/texture-tiles.md): one PNG per tile (16-bit grey
// for noise, 8-bit RGB for textures) plus a JSON description naming each tile's file and colors.
// Every file is written atomically; a failed write throws Error naming the file.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "exporters/image_io.h"
#include "generator/image.h"
#include "generator/noise_tiles.h"
#include "generator/texture_tiles.h"

namespace wangscape {

// DIR/noise_tile_<k>.png (pixels x pixels, `pattern`: noise, fbm or turbulence) for every tile
// and DIR/noise_tiles.json:
//   {"kind": "noise", "set": {tile-set JSON}, "lattice", "octaves", "seed", "pattern", "pixels",
//    "gray": {"min": -1 or 0, "max": 1}, "tiles": [{"file": "noise_tile_0.png", "n": 0, ...}, ...]}
// DIR is staged beside it and replaces it whole (core/staged_folder.h): it must be missing, empty
// or an earlier folder of the same tiles, and a failed write leaves it as it was.
void write_noise_tile_files(const std::filesystem::path& dir, const NoiseTileSet& tiles, int pixels,
                            NoisePattern pattern = NoisePattern::fbm);

// DIR/texture_tile_<k>.png for every tile and DIR/texture_tiles.json:
//   {"kind": "texture", "set": {tile-set JSON}, "tile_size", "marks", "total_error",
//    "windows": [{"exemplar", "x", "y"}, ...],
//    "tiles": [{"file": "texture_tile_0.png", "error": 123, "n": 0, ...}, ...]}
// DIR is staged beside it and replaces it whole (core/staged_folder.h): it must be missing, empty
// or an earlier folder of the same tiles, and a failed write leaves it as it was.
void write_texture_tile_files(const std::filesystem::path& dir, const TextureTileSet& tiles);

// `wangscape noise tiles` and `wangscape texture tiles`: make a set's tiles, write them to
// `out` as above and, with a preview size, a preview_size stochastic tiling of them (preview_size
// is "WxH", at most 16384 each) into `preview`. Return a one-line summary. Throw Error
// naming the value at fault (the preview size, the set, an exemplar file).
struct NoiseTilesJob {
  std::string set = "corner-3";
  NoiseTileOptions options;
  int pixels = 128;  // per tile side in the tile files
  // The preview's pattern (none given: turbulence) and the tile files' (none given: fbm); the
  // tiles hold noise, fbm or turbulence, so with marble or wood (patterns of the whole tiling) fbm.
  std::optional<NoisePattern> pattern;
  std::filesystem::path out;
  std::string preview_size;  // "WxH"; empty = no preview
  std::filesystem::path preview;
};
std::string run_tiles_job(const NoiseTilesJob& job);

struct TextureTilesJob {
  std::string set = "cohen8";
  std::vector<std::string> exemplars;  // image files, or shipped names (meadow, pumice)
  TextureTileOptions options;
  std::filesystem::path out;
  std::string preview_size;
  std::filesystem::path preview;
};
std::string run_tiles_job(const TextureTilesJob& job);

}  // namespace wangscape
