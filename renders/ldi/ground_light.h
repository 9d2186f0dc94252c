// The light a tile's plants leave on the ground under them. The view's terrain is a mesh with no
// plants on it, so nothing shadowed it: seen from above, the ground between the plants was lit as
// open ground where the ray-traced truth has it half in the leaves' shadow (docs/viewer-design.md,
// "Looking down"). Per tile of the set, in the 3 x 3 context its LDIs are shaded in, over a grid
// of texels on the tile's ground: the sun's share (the open fraction of shadow rays toward the
// sun) and the sky's (open_sky_share, as shade() lights the ground), each the mean of four points
// in the texel; then each level halves the last, down to one texel a tile.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <vector>

#include "renders/ldi/ldi_build.h"

namespace wangscape {

class TileGroundLight {
 public:
  // Shares of the open ground's light, of 255.
  struct Texel {
    std::uint8_t sun = 255, sky = 255;
    friend bool operator==(const Texel&, const Texel&) = default;
  };
  TileGroundLight() = default;
  // All texels open. `resolution`: a power of two, 1 .. 1024.
  TileGroundLight(std::size_t tiles, std::uint32_t resolution);

  bool empty() const { return texels_.empty(); }
  std::size_t tiles() const { return tiles_; }
  std::uint32_t resolution() const { return resolution_; }  // texels across a tile at level 0
  int levels() const { return levels_; }                    // level k: resolution >> k across
  // Texel (i, j) of `level` (i east, j north, from the tile's south-west corner).
  const Texel& at(std::size_t tile, int level, std::uint32_t i, std::uint32_t j) const {
    return texels_[index(tile, level, i, j)];
  }
  Texel& at(std::size_t tile, int level, std::uint32_t i, std::uint32_t j) { return texels_[index(tile, level, i, j)]; }
  // A tile's texels of `level`, rows from the south, texels from the west.
  std::span<const Texel> texels(std::size_t tile, int level) const {
    return {&texels_[index(tile, level, 0, 0)], level_texels(level)};
  }
  std::span<Texel> texels(std::size_t tile, int level) {
    return {&texels_[index(tile, level, 0, 0)], level_texels(level)};
  }
  // The sun's and the sky's shares (0 .. 1) at (u, v) in the tile (0 .. 1 east and north),
  // bilinear in the level whose texels are as large as `footprint` (level-0 texels a screen pixel
  // covers), clamped at the tile's sides.
  std::array<float, 2> shares(std::size_t tile, float u, float v, float footprint) const {
    int level = 0;
    if (footprint > 1) level = std::min(levels_ - 1, std::ilogb(footprint) + 1);
    const std::uint32_t n = resolution_ >> level;
    const float x = std::clamp(u * float(n) - 0.5f, 0.0f, float(n - 1)),
                y = std::clamp(v * float(n) - 0.5f, 0.0f, float(n - 1));
    const auto i = std::uint32_t(x), j = std::uint32_t(y);
    const std::uint32_t i1 = std::min(i + 1, n - 1), j1 = std::min(j + 1, n - 1);
    const float ax = x - float(i), ay = y - float(j);
    const Texel &a = at(tile, level, i, j), &b = at(tile, level, i1, j), &c = at(tile, level, i, j1),
                &d = at(tile, level, i1, j1);
    const auto mix = [&](std::uint8_t p, std::uint8_t q, std::uint8_t r, std::uint8_t s) {
      const float low = float(p) + (float(q) - float(p)) * ax, high = float(r) + (float(s) - float(r)) * ax;
      return (low + (high - low) * ay) * (1.0f / 255);
    };
    return {mix(a.sun, b.sun, c.sun, d.sun), mix(a.sky, b.sky, c.sky, d.sky)};
  }
  // Levels 1 .. levels() - 1 of every tile, each texel the mean of the four below it.
  void make_levels();
  bool operator==(const TileGroundLight&) const = default;

 private:
  std::size_t level_texels(int level) const { return std::size_t(resolution_ >> level) * (resolution_ >> level); }
  std::size_t index(std::size_t tile, int level, std::uint32_t i, std::uint32_t j) const {
    return tile * tile_texels_ + level_offsets_[std::size_t(level)] + std::size_t(j) * (resolution_ >> level) + i;
  }
  std::size_t tiles_ = 0, tile_texels_ = 0;
  std::uint32_t resolution_ = 0;
  int levels_ = 0;
  std::vector<std::size_t> level_offsets_;
  std::vector<Texel> texels_;
};

// The ground light of every tile of `filled` with `models` (options: the tile size, the light with
// its sun, the sky rays, the context choice and the seed, as the LDIs are shaded) at `resolution`
// texels across a tile. Deterministic: the same bytes on any thread count. Throws Error for bad
// inputs (as build_tile_ldis) or an Embree error.
TileGroundLight bake_tile_ground_light(const FilledTileSet& filled, std::span<const Mesh> models,
                                       const LdiBuildOptions& options, std::uint32_t resolution);

// The texels across a tile of the ground light the view shades its terrain with, and that
// `wangscape build` bakes into a scene folder for it.
inline constexpr std::uint32_t kGroundLightResolution = 64;

// The light in a file of its own (a scene folder's ground light, docs/scene-folder.md):
// "WSCGLT\r\n", u32 version 1, u32 resolution, u32 tiles, then per tile its level 0 (rows from the
// south, texels from the west), two bytes a texel (sun, sky: shares of 255), little endian. The
// coarser levels are not kept: make_levels() makes them again, the same bytes as the bake's.
// Written atomically; read back only as `tiles` tiles of `resolution` texels (the view's set and
// resolution), a file of exactly their size: else an Error naming the file and what was expected.
void write_ground_light(const std::filesystem::path& path, const TileGroundLight& light);
TileGroundLight read_ground_light(const std::filesystem::path& path, std::size_t tiles, std::uint32_t resolution);

}  // namespace wangscape
