#include "renders/ldi/ground_light.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "core/atomic_file.h"
#include "core/binary_file.h"
#include "core/error.h"
#include "core/hash.h"
#include "renders/ldi/tile_context.h"

namespace wangscape {

namespace {
constexpr char kMagic[8] = {'W', 'S', 'C', 'G', 'L', 'T', '\r', '\n'};
constexpr std::uint32_t kVersion = 1;
constexpr std::uint64_t kHeaderBytes = sizeof kMagic + 3 * 4;  // the magic; the version, resolution and tiles
static_assert(sizeof(TileGroundLight::Texel) == 2, "a texel is its two bytes in the file");
}  // namespace

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

void write_ground_light(const std::filesystem::path& path, const TileGroundLight& light) {
  AtomicFile file(path);
  std::ostream& out = file.stream();
  put_binary_header(out, kMagic, kVersion);
  put_u32(out, light.resolution());
  put_u32(out, std::uint32_t(light.tiles()));
  for (std::size_t t = 0; t < light.tiles(); ++t) {
    const std::span<const TileGroundLight::Texel> texels = light.texels(t, 0);
    out.write(reinterpret_cast<const char*>(texels.data()), std::streamsize(texels.size_bytes()));
  }
  file.commit();
}

TileGroundLight read_ground_light(const std::filesystem::path& path, std::size_t tiles, std::uint32_t resolution) {
  BinaryReader in(path, kMagic, kVersion, "ground light");
  if (const std::uint32_t found = in.u32("the ground light header"); found != resolution)
    in.fail("a resolution of " + std::to_string(found) + " texels across a tile: expected " +
            std::to_string(resolution) + " (rebuild the folder)");
  if (const std::uint32_t found = in.u32("the ground light header"); found != tiles)
    in.fail(std::to_string(found) + " tiles: expected the tile set's " + std::to_string(tiles) +
            " (rebuild the folder)");
  const std::uint64_t bytes = kHeaderBytes + std::uint64_t(tiles) * resolution * resolution * 2;
  if (in.size() != bytes)
    in.fail((in.size() < bytes ? "truncated: " : "longer than its texels: ") + std::to_string(in.size()) +
            " bytes, expected " + std::to_string(bytes) + " (" + std::to_string(tiles) + " tiles of " +
            std::to_string(resolution) + " x " + std::to_string(resolution) + " texels)");
  TileGroundLight light(tiles, resolution);
  for (std::size_t t = 0; t < tiles; ++t) {
    const std::span<TileGroundLight::Texel> texels = light.texels(t, 0);
    in.read(texels.data(), texels.size_bytes(), "tile " + std::to_string(t) + "'s texels");
  }
  light.make_levels();  // (every byte a share of 255: no value to check)
  return light;
}

}  // namespace wangscape
