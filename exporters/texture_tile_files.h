// Noise tiles and texture tiles as files (docs/texture-tiles.md): one PNG per tile (16-bit grey
// for noise, 8-bit RGB for textures) plus a JSON description naming each tile's file and colors.
// Every file is written atomically; a failed write throws Error naming the file.
#pragma once

#include <filesystem>

#include "exporters/image_io.h"
#include "generator/image.h"
#include "generator/noise_tiles.h"
#include "generator/texture_tiles.h"

namespace wangscape {

// DIR/noise_tile_<k>.png (pixels x pixels, `pattern`: noise, fbm or turbulence) for every tile
// and DIR/noise_tiles.json:
//   {"kind": "noise", "set": {tile-set JSON}, "lattice", "octaves", "seed", "pattern", "pixels",
//    "gray": {"min": -1 or 0, "max": 1}, "tiles": [{"file": "noise_tile_0.png", "n": 0, ...}, ...]}
// Creates DIR if needed.
void write_noise_tile_files(const std::filesystem::path& dir, const NoiseTileSet& tiles, int pixels,
                            NoisePattern pattern = NoisePattern::fbm);

// DIR/texture_tile_<k>.png for every tile and DIR/texture_tiles.json:
//   {"kind": "texture", "set": {tile-set JSON}, "tile_size", "marks", "total_error",
//    "windows": [{"exemplar", "x", "y"}, ...],
//    "tiles": [{"file": "texture_tile_0.png", "error": 123, "n": 0, ...}, ...]}
// Creates DIR if needed.
void write_texture_tile_files(const std::filesystem::path& dir, const TextureTileSet& tiles);

}  // namespace wangscape
