#include "renders/ldi/ground_light.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.h"
#include "core/hash.h"
#include "renders/ldi/tile_context.h"

namespace wangscape {

TileGroundLight::TileGroundLight(std::size_t tiles, std::uint32_t resolution) : tiles_(tiles), resolution_(resolution) {
  if (resolution < 1 || resolution > 1024 || (resolution & (resolution - 1)) != 0)
    throw Error("ground light: " + std::to_string(resolution) +
                " texels across a tile; expected a power of two 1 .. 1024");
  for (std::uint32_t r = resolution; r >= 1; r /= 2) {
    level_offsets_.push_back(tile_texels_);
    tile_texels_ += std::size_t(r) * r;
    ++levels_;
  }
  texels_.assign(tiles_ * tile_texels_, Texel{});
}

void TileGroundLight::make_levels() {
  for (std::size_t t = 0; t < tiles_; ++t)
    for (int level = 1; level < levels_; ++level) {
      const std::uint32_t n = resolution_ >> level;
      for (std::uint32_t j = 0; j < n; ++j)
        for (std::uint32_t i = 0; i < n; ++i) {
          unsigned sun = 0, sky = 0;
          for (std::uint32_t k = 0; k < 4; ++k) {
            const Texel& below = at(t, level - 1, 2 * i + (k & 1), 2 * j + (k >> 1));
            sun += below.sun;
            sky += below.sky;
          }
          at(t, level, i, j) = {std::uint8_t((sun + 2) / 4), std::uint8_t((sky + 2) / 4)};
        }
    }
}

TileGroundLight bake_tile_ground_light(const FilledTileSet& filled, std::span<const Mesh> models,
                                       const LdiBuildOptions& options, std::uint32_t resolution) {
  TileGroundLight out(filled.tiles.size(), resolution);
  EmbreeDevice device;
  // The plants as instances of one scene per model: a flattened context took 0.2 s a tile to build.
  const std::vector<EmbreeScene> occluders = model_scenes(device, models, nullptr);
  const float texel = float(options.tile_size / resolution);
  // Four points in each texel, a 2 x 2 grid: the shares are their means.
  constexpr float kPoints[4][2] = {{0.25f, 0.25f}, {0.75f, 0.25f}, {0.25f, 0.75f}, {0.75f, 0.75f}};
  for (std::size_t t = 0; t < filled.tiles.size(); ++t) {
    const EmbreeScene scene = tile_context_scene(device, occluders, filled, models, options, t);
    tbb::parallel_for(
        tbb::blocked_range<std::uint32_t>(0, resolution), [&](const tbb::blocked_range<std::uint32_t>& rows) {
          for (std::uint32_t j = rows.begin(); j != rows.end(); ++j)
            for (std::uint32_t i = 0; i < resolution; ++i) {
              float sun = 0, sky = 0;
              for (int k = 0; k < 4; ++k) {
                SurfaceSample ground;
                ground.position = {(float(i) + kPoints[k][0]) * texel, (float(j) + kPoints[k][1]) * texel, 0};
                ground.normal = {0, 0, 1};
                int rays = 0;
                // (The open ground's sun share is the normal's cos: the share of it here is 0 or 1.)
                sun += shadowed_sun_share(scene.get(), options.shading, ground, &rays) > 0 ? 1.0f : 0.0f;
                const std::uint64_t random = mix64(mix64(mix64(options.seed ^ 0x67726f756e64ull) ^ t) ^
                                                   (std::uint64_t(j) << 32 | std::uint64_t(i) << 2 | std::uint64_t(k)));
                sky += open_sky_share(scene.get(), options.shading, ground.position, ground.normal, random);
              }
              out.at(t, 0, i, j) = {std::uint8_t(std::lround(sun / 4 * 255)), std::uint8_t(std::lround(sky / 4 * 255))};
            }
        });
    device.check("tracing the ground light of tile " + std::to_string(t));
  }
  out.make_levels();
  return out;
}

}  // namespace wangscape
