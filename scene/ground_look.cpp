#include "scene/ground_look.h"
#include "core/vecmath.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

#include "scene/scene_ground.h"
#include "terrain/mask.h"

namespace wangscape {

namespace {

// A three-stop sRGB ramp over [0, 1].
using Ramp = std::array<std::array<float, 3>, 3>;

constexpr float c(int v) { return static_cast<float>(v) / 255.f; }
constexpr Ramp kMeadow{{{c(44), c(56), c(22)}, {c(72), c(86), c(34)}, {c(112), c(100), c(58)}}};
constexpr Ramp kPumice{{{c(118), c(108), c(94)}, {c(166), c(156), c(138)}, {c(206), c(198), c(182)}}};
constexpr Ramp kRock{{{c(52), c(48), c(45)}, {c(88), c(82), c(75)}, {c(128), c(120), c(108)}}};
constexpr Ramp kSnow{{{c(208), c(214), c(226)}, {c(234), c(238), c(245)}, {c(250), c(251), c(253)}}};

GroundColor ramp(const Ramp& r, float t) {
  t = std::clamp(t, 0.f, 1.f) * 2;
  const int k = t < 1 ? 0 : 1;
  const float f = t - static_cast<float>(k);
  const auto& a = r[static_cast<std::size_t>(k)];
  const auto& b = r[static_cast<std::size_t>(k + 1)];
  return {a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1]), a[2] + f * (b[2] - a[2])};
}

GroundColor mix(const GroundColor& a, const GroundColor& b, float w) {
  return {a.r + w * (b.r - a.r), a.g + w * (b.g - a.g), a.b + w * (b.b - a.b)};
}

float luminance(float r, float g, float b) { return 0.2126f * r + 0.7152f * g + 0.0722f * b; }

// Turbulence of a tiling is mostly within [0, 0.5]: stretch it over the ramp.
constexpr float kTurbulenceGain = 2.2f;

}  // namespace

GroundLook::GroundLook(const GroundConfig& config, const std::vector<ImageRgb8>& exemplars, HeightAt height_at)
    : config_(config),
      noise_(make_noise_field(builtin_tileset("corner-3"), {.lattice = config.noise_lattice, .seed = config.seed},
                              config.seed, config.noise_scale)) {
  if (config.look == "materials") return;
  TextureTileOptions options;
  options.tile_size = config.texture_pixels;
  options.seed = config.seed;
  // corner-2 is complete (hashed, unbounded) and its random corner marks switch between two
  // exemplars; corner-4 leaves one bit of each corner color to the terrain (texture_tile).
  const bool by_height = config.exemplar2_above.has_value();
  if (by_height && !height_at) throw Error("ground.exemplar2_above needs the terrain's heights");
  height_at_ = std::move(height_at);
  const TileSet set = builtin_tileset(by_height ? "corner-4" : "corner-2");
  // corner-4 has 256 tiles to corner-2's 16: one search round instead of three (the default
  // scene's build: 5.8 CPU-s with three, 4.9 with one, 3.1 with corner-2).
  if (by_height) options.rounds = 1;
  texture_ = make_texture_tiles(set, exemplars, options);
  texture_tiling_.emplace(set, config.seed);
  double sum = 0;
  std::size_t count = 0;
  for (const auto& tile : texture_->tiles)
    for (std::size_t p = 0; p < tile.image.pixels.size(); p += 3, ++count)
      sum += luminance(c(tile.image.pixels[p]), c(tile.image.pixels[p + 1]), c(tile.image.pixels[p + 2]));
  texture_mean_luminance_ = count ? std::max(1e-3f, static_cast<float>(sum / static_cast<double>(count))) : 1.f;
}

GroundColor GroundLook::materials_at(double x, double y, double height, double slope_degrees) const {
  // One fbm layer bends every band border; each material reads turbulence from its own
  // tiles of the same tiling (offsets of whole tiles), so the materials do not share a pattern.
  const double tile = noise_.tile_size();
  const float wobble = noise_.fbm(x + 11 * tile, y - 5 * tile);
  const double h = height + 1.5 * wobble * config_.height_blend;
  const double s = slope_degrees + 1.5 * wobble * config_.slope_blend;
  const float w_pumice =
      smoothstep(config_.pumice_above - config_.height_blend, config_.pumice_above + config_.height_blend, h);
  const float w_snow =
      smoothstep(config_.snow_above - config_.height_blend, config_.snow_above + config_.height_blend, h);
  const float w_rock =
      smoothstep(config_.rock_slope - config_.slope_blend, config_.rock_slope + config_.slope_blend, s);
  const auto layer = [&](const Ramp& r, double offset_tiles) {
    return ramp(r, kTurbulenceGain * noise_.turbulence(x + offset_tiles * tile, y + 3 * offset_tiles * tile));
  };
  GroundColor color = w_pumice < 1 ? layer(kMeadow, 0) : GroundColor{};
  if (w_pumice > 0) color = mix(color, layer(kPumice, 17), w_pumice);
  if (w_snow > 0) color = mix(color, layer(kSnow, 29), w_snow);
  if (w_rock > 0) color = mix(color, layer(kRock, 43), w_rock);
  return color;
}

GroundColor GroundLook::texture_at(double x, double y) const {
  // Bilinear between texel centres of the unbounded tiling; a texel's tile is found per texel,
  // so the filter crosses tile borders like any other texel border.
  const int n = texture_->tile_size;
  const double tx = x / config_.texture_scale * n - 0.5, ty = y / config_.texture_scale * n - 0.5;
  const double fx = std::floor(tx), fy = std::floor(ty);
  // The four texels mostly share a tile: look it up once (with marks from the terrain, that is
  // four height lookups).
  std::int64_t cached_i = std::numeric_limits<std::int64_t>::min(), cached_j = cached_i;
  std::uint32_t cached_tile = 0;
  const auto texel = [&](std::int64_t ix, std::int64_t iy) {
    const std::int64_t i = ix >= 0 ? ix / n : (ix - n + 1) / n, j = iy >= 0 ? iy / n : (iy - n + 1) / n;
    if (i != cached_i || j != cached_j) cached_tile = texture_tile(cached_i = i, cached_j = j);
    const auto& image = texture_->tiles[cached_tile].image;
    const int px = static_cast<int>(ix - i * n), py = n - 1 - static_cast<int>(iy - j * n);  // north at the top
    const std::size_t o = image.offset(px, py);
    return GroundColor{c(image.pixels[o]), c(image.pixels[o + 1]), c(image.pixels[o + 2])};
  };
  const auto ix = static_cast<std::int64_t>(fx), iy = static_cast<std::int64_t>(fy);
  const auto wx = static_cast<float>(tx - fx), wy = static_cast<float>(ty - fy);
  return mix(mix(texel(ix, iy), texel(ix + 1, iy), wx), mix(texel(ix, iy + 1), texel(ix + 1, iy + 1), wx), wy);
}

std::uint32_t GroundLook::texture_tile(std::int64_t i, std::int64_t j) const {
  if (!config_.exemplar2_above) return texture_tiling_->tile_at(i, j);
  const double above = *config_.exemplar2_above;
  const auto corner = [&](std::int64_t vx, std::int64_t vy) {
    const auto height =
        height_at_(static_cast<double>(vx) * config_.texture_scale, static_cast<double>(vy) * config_.texture_scale);
    const std::uint32_t mark = height && *height > above ? 1 : 0;  // mark m reads exemplar m mod 2
    return 2 * texture_tiling_->corner_at(vx, vy, 2) + mark;
  };
  std::array<std::uint32_t, kSlotCount> colors{};
  colors[kSW] = corner(i, j);
  colors[kSE] = corner(i + 1, j);
  colors[kNE] = corner(i + 1, j + 1);
  colors[kNW] = corner(i, j + 1);
  return texture_tiling_->tile_with_colors(colors);
}

GroundColor GroundLook::color_at(double x, double y, double height, double slope_degrees) const {
  if (!texture_) return materials_at(x, y, height, slope_degrees);
  const GroundColor texture = texture_at(x, y);
  if (config_.look == "texture") return texture;
  // Texture detail over the materials: their color scaled by the texture's relative brightness.
  const float detail = luminance(texture.r, texture.g, texture.b) / texture_mean_luminance_;
  const float gain = 1 + static_cast<float>(config_.texture_strength) * (detail - 1);
  const GroundColor base = materials_at(x, y, height, slope_degrees);
  return {base.r * gain, base.g * gain, base.b * gain};
}

std::filesystem::path shipped_exemplar(const std::string& name) {
  if (name.find('/') != std::string::npos || name.find('.') != std::string::npos) return {};
  const std::filesystem::path file = data_root() / "templates/exemplars" / (name + ".png");
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec))
    throw Error("'" + name + "' is no shipped exemplar (shipped: meadow, pumice) and no image file");
  return file;
}

std::vector<ImageRgb8> load_ground_exemplars(const SceneConfig& config) {
  std::vector<ImageRgb8> images;
  if (!config.ground || config.ground->look == "materials") return images;
  const std::pair<const char*, const std::string*> keys[] = {{"exemplar", &config.ground->exemplar},
                                                             {"exemplar2", &config.ground->exemplar2}};
  for (const auto& [key, value] : keys) {
    const std::string& name = *value;
    if (name.empty()) continue;
    try {
      const std::filesystem::path shipped = shipped_exemplar(name);
      RgbRaster raster = read_rgb_raster(shipped.empty() ? std::filesystem::path(name) : shipped);
      ImageRgb8 image;
      image.width = raster.width;
      image.height = raster.height;
      image.pixels = std::move(raster.pixels);
      images.push_back(std::move(image));
    } catch (const Error& e) {
      throw config.error_at(std::string("ground.") + key, e.message());
    }
  }
  return images;
}

GroundBake bake_ground(const GroundLook& look, const SceneGround& ground, int pixels) {
  GroundBake bake;
  bake.extent = ground.extent();
  const double longer = std::max(bake.extent.width(), bake.extent.height());
  const double pixel = longer / std::max(1, pixels);
  const int w = std::max(1, static_cast<int>(std::lround(bake.extent.width() / pixel)));
  const int h = std::max(1, static_cast<int>(std::lround(bake.extent.height() / pixel)));
  bake.image = ImageRgb8(w, h);
  const double dx = bake.extent.width() / w, dy = bake.extent.height() / h;
  tbb::parallel_for(0, h, [&](int row) {
    const double y = bake.extent.max_y - (row + 0.5) * dy;
    for (int col = 0; col < w; ++col) {
      const double x = bake.extent.min_x + (col + 0.5) * dx;
      const GroundColor color =
          look.color_at(x, y, ground.height(x, y).value_or(0), ground.slope_degrees(x, y).value_or(0));
      const auto byte = [](float v) { return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.f, 1.f) * 255)); };
      bake.image.set(col, row, {byte(color.r), byte(color.g), byte(color.b)});
    }
  });
  return bake;
}

}  // namespace wangscape
