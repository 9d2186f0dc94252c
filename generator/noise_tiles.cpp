#include "generator/noise_tiles.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <bit>
#include <cstring>
#include <string>

#include "core/hash.h"

namespace wangscape {

namespace {

// What a border or interior gradient is keyed by; salts keep the kinds apart.
enum class Part : std::uint64_t { corner = 1, horizontal_edge, vertical_edge, interior };

std::uint8_t gradient_index(std::uint64_t seed, int level, Part part, std::uint64_t key, int position) {
  std::uint64_t h = mix64(seed ^ (static_cast<std::uint64_t>(part) << 56));
  h = mix64(h ^ static_cast<std::uint64_t>(level));
  h = mix64(h ^ key);
  return static_cast<std::uint8_t>(mix64(h ^ static_cast<std::uint64_t>(position)) >> 56);
}

constexpr std::array<const char*, 5> kPatternNames = {"noise", "fbm", "turbulence", "marble", "wood"};

}  // namespace

const char* to_string(NoisePattern pattern) { return kPatternNames[static_cast<std::size_t>(pattern)]; }

NoisePattern parse_noise_pattern(const char* text) {
  for (std::size_t k = 0; k < kPatternNames.size(); ++k)
    if (std::strcmp(text, kPatternNames[k]) == 0) return static_cast<NoisePattern>(k);
  throw Error(std::string("unknown noise pattern '") + text + "'; expected noise, fbm, turbulence, marble or wood");
}

NoiseTileSet::NoiseTileSet(const TileSet& set, const NoiseTileOptions& options)
    : set_(set), lattice_(options.lattice), seed_(options.seed) {
  const std::string where = "noise tiles of " + set.describe();
  if (set.tiles.empty()) throw Error(where + ": no tiles");
  if (lattice_ < 4 || lattice_ > 4096 || !std::has_single_bit(static_cast<unsigned>(lattice_)))
    throw Error(where + ": lattice " + std::to_string(lattice_) + "; expected a power of two in 4..4096");
  const int max_levels = std::countr_zero(static_cast<unsigned>(lattice_)) - 1;  // down to 4 x 4 cells
  if (options.octaves < 0 || options.octaves > max_levels)
    throw Error(where + ": " + std::to_string(options.octaves) + " octaves; a lattice of " + std::to_string(lattice_) +
                " holds 1.." + std::to_string(max_levels) + " (0 = all)");
  levels_ = options.octaves == 0 ? max_levels : options.octaves;

  for (std::size_t k = 0; k < table_.size(); ++k) {
    const double angle = 2 * std::numbers::pi * (static_cast<double>(k) + 0.5) / static_cast<double>(table_.size());
    // The value from a hash of k, so a point's value does not follow its gradient's angle.
    const double unit = static_cast<double>(mix64(k) >> 11) / static_cast<double>(std::uint64_t{1} << 53);
    table_[k] = {static_cast<float>(std::cos(angle)), static_cast<float>(std::sin(angle)),
                 kPointValue * static_cast<float>(2 * unit - 1)};
  }
  float weights = 0, w = 1;
  for (int level = 0; level < levels_; ++level, w *= 0.5f) {
    level_offset_[static_cast<std::size_t>(level)] = tile_stride_;
    const auto side = static_cast<std::size_t>(cells(level) + 1);
    tile_stride_ += side * side;
    weights += w;
  }
  norm_ = 1 / weights;

  // Edge keys: (edge color, end corner, end corner); absent colors count as 0, so plain edge
  // sets share one corner gradient and corner sets get corner_colors^2 edge keys.
  const std::uint64_t corners = static_cast<std::uint64_t>(std::max(1, set.corner_colors));
  const auto color = [](int c) { return static_cast<std::uint64_t>(c < 0 ? 0 : c); };
  const auto edge_key = [&](int edge, int first_corner, int second_corner) {
    return (color(edge) * corners + color(first_corner)) * corners + color(second_corner);
  };
  points_.assign(tile_stride_ * set.size(), 0);
  for (std::size_t t = 0; t < set.size(); ++t) {
    const Tile& tile = set.tiles[t];
    for (int level = 0; level < levels_; ++level) {
      const int n = cells(level);
      std::uint8_t* p = &points_[t * tile_stride_ + level_offset_[static_cast<std::size_t>(level)]];
      const auto at = [&](int px, int py) -> std::uint8_t& {
        return p[static_cast<std::size_t>(py) * static_cast<std::size_t>(n + 1) + static_cast<std::size_t>(px)];
      };
      for (int py = 1; py < n; ++py)
        for (int px = 1; px < n; ++px) at(px, py) = gradient_index(seed_, level, Part::interior, t, py * (n + 1) + px);
      // Horizontal edges run west to east, vertical edges south to north.
      for (int k = 1; k < n; ++k) {
        at(k, 0) = gradient_index(seed_, level, Part::horizontal_edge, edge_key(tile.s(), tile.sw(), tile.se()), k);
        at(k, n) = gradient_index(seed_, level, Part::horizontal_edge, edge_key(tile.n(), tile.nw(), tile.ne()), k);
        at(0, k) = gradient_index(seed_, level, Part::vertical_edge, edge_key(tile.w(), tile.sw(), tile.nw()), k);
        at(n, k) = gradient_index(seed_, level, Part::vertical_edge, edge_key(tile.e(), tile.se(), tile.ne()), k);
      }
      at(0, 0) = gradient_index(seed_, level, Part::corner, color(tile.sw()), 0);
      at(n, 0) = gradient_index(seed_, level, Part::corner, color(tile.se()), 0);
      at(0, n) = gradient_index(seed_, level, Part::corner, color(tile.nw()), 0);
      at(n, n) = gradient_index(seed_, level, Part::corner, color(tile.ne()), 0);
    }
  }
}

NoiseField make_noise_field(const TileSet& set, const NoiseTileOptions& options, std::uint64_t tiling_seed,
                            double tile_size) {
  if (!(tile_size > 0))
    throw Error("noise field of " + set.describe() + ": tile size " + std::to_string(tile_size) + "; expected > 0");
  return NoiseField(NoiseTileSet(set, options), HashedTiling(set, tiling_seed), tile_size);
}

std::uint16_t noise_to_gray16(NoisePattern pattern, float value) {
  const bool is_signed = pattern == NoisePattern::noise || pattern == NoisePattern::fbm;
  const float unit = is_signed ? 0.5f * (value + 1) : value;
  return static_cast<std::uint16_t>(std::lround(std::clamp(unit, 0.f, 1.f) * 65535.f));
}

ImageGray16 rasterize_noise_tile(const NoiseTileSet& tiles, std::uint32_t tile, int pixels, NoisePattern pattern) {
  if (pixels < 1 || pixels > 16384)
    throw Error("noise tile raster: " + std::to_string(pixels) + " pixels; expected 1..16384");
  if (tile >= tiles.size())
    throw Error("noise tile raster: tile " + std::to_string(tile) + " of a set of " + std::to_string(tiles.size()));
  if (pattern == NoisePattern::marble || pattern == NoisePattern::wood)
    throw Error(std::string("noise tile raster: pattern '") + to_string(pattern) +
                "' needs a tiling; expected noise, fbm or turbulence");
  ImageGray16 image(pixels, pixels);
  tbb::parallel_for(0, pixels, [&](int row) {
    const float v = 1 - (static_cast<float>(row) + 0.5f) / static_cast<float>(pixels);
    for (int col = 0; col < pixels; ++col) {
      const float u = (static_cast<float>(col) + 0.5f) / static_cast<float>(pixels);
      const float value = pattern == NoisePattern::noise
                              ? tiles.sample(tile, 0, u, v).value
                              : tiles.fractal(tile, u, v, pattern == NoisePattern::turbulence);
      image.set(col, row, noise_to_gray16(pattern, value));
    }
  });
  return image;
}

ImageGray16 render_noise_preview(const NoiseField& field, NoisePattern pattern, int width, int height,
                                 double pixel_size, double x0, double y0) {
  if (width < 1 || height < 1 || static_cast<std::int64_t>(width) * height > (std::int64_t{1} << 28))
    throw Error("noise preview: " + std::to_string(width) + " x " + std::to_string(height) +
                " pixels; expected a positive size of at most 2^28 pixels");
  if (!(pixel_size > 0)) throw Error("noise preview: pixel size " + std::to_string(pixel_size) + "; expected > 0");
  ImageGray16 image(width, height);
  tbb::parallel_for(tbb::blocked_range<int>(0, height, 8), [&](const tbb::blocked_range<int>& rows) {
    for (int row = rows.begin(); row < rows.end(); ++row) {
      const double y = y0 + (height - row - 0.5) * pixel_size;
      for (int col = 0; col < width; ++col)
        image.set(col, row, noise_to_gray16(pattern, field.pattern(pattern, x0 + (col + 0.5) * pixel_size, y)));
    }
  });
  return image;
}

}  // namespace wangscape
