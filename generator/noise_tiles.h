// Perlin-noise Wang tiles (Maung 2012): tiles that hold only lattice gradients, so the noise is
// evaluated on the fly at any point of an unbounded tiling and no image is ever stored.
//
// A tile covers an n x n cell lattice ((n + 1)^2 gradients, n a power of two). The gradients on
// the tile's border belong to the border: an edge's n - 1 inner gradients are keyed by the edge
// color and the colors of its two end corners, a corner's gradient by its corner color (one
// shared gradient for every corner when the set has no corner colors). Perlin noise on a lattice
// line depends only on the gradients on that line, so two tiles that agree on an edge key agree
// in value and in gradient all along that edge: seamless by construction (Maung 2012, section III).
//
// Every lattice point carries a value besides its gradient (value-gradient noise): plain
// gradient noise is zero at every lattice point, and the zero lines of its turbulence run through
// them, so the lattice shows as straight creases along the axes (issue 23: the command's preview
// held 1.26 times as much spectral energy along the axes as along the diagonals; 1.10 with point
// values; docs/texture-tiles.md).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include "generator/image.h"
#include "generator/tileset.h"
#include "generator/tiling.h"

namespace wangscape {

struct NoiseTileOptions {
  // Lattice cells per tile side at the finest level (level 0): a power of two, 4..4096.
  int lattice = 16;
  // Mip levels (octaves): at most log2(lattice) - 1 (the coarsest has 4 x 4 cells); 0 = all.
  int octaves = 0;
  std::uint64_t seed = 1;
};

// Noise value (in [-1, 1]) and its gradient. The gradient is per tile side for tile-local
// evaluation (NoiseTileSet) and per world unit for world evaluation (TiledNoise).
struct NoiseSample {
  float value = 0, du = 0, dv = 0;
};

// What a raster or a renderer samples. noise: the finest level alone, in [-1, 1]; fbm: the
// signed 1/f sum, in [-1, 1]; turbulence: the sum of |octaves|, in [0, 1]; marble, wood: [0, 1].
enum class NoisePattern : std::uint8_t { noise, fbm, turbulence, marble, wood };

// "noise", "fbm", "turbulence", "marble", "wood"; parse throws Error naming the value.
const char* to_string(NoisePattern pattern);
NoisePattern parse_noise_pattern(const char* text);

// The gradients of every tile of a set at every mip level. Built once; every method is const,
// thread-safe and allocation-free.
class NoiseTileSet {
 public:
  // Throws Error naming the set or the option out of range.
  NoiseTileSet(const TileSet& set, const NoiseTileOptions& options);

  const TileSet& set() const { return set_; }
  std::size_t size() const { return set_.size(); }
  int lattice() const { return lattice_; }
  int levels() const { return levels_; }
  int cells(int level) const { return lattice_ >> level; }
  std::uint64_t seed() const { return seed_; }

  // Gradient (unit vector) at lattice point (px, py), 0 <= px, py <= cells(level), px east, py north.
  std::array<float, 2> gradient(std::uint32_t tile, int level, int px, int py) const {
    const LatticePoint& p = table_[lattice_point(tile, level, px, py)];
    return {p.gx, p.gy};
  }
  // The point's value, in [-kPointValue, kPointValue] (before the scale to [-1, 1]: kValueScale).
  float point_value(std::uint32_t tile, int level, int px, int py) const {
    return table_[lattice_point(tile, level, px, py)].value;
  }
  // Lattice point values are uniform in [-kPointValue, kPointValue]. Untiled turbulence of this
  // kind has an axis-to-diagonal energy ratio of 1.24 with 0, 1.05 with 0.4 and 1.18 with 0.7
  // (the value noise's own creases come back; docs/texture-tiles.md).
  static constexpr float kPointValue = 0.4f;
  // Gradient noise with unit gradients stays within +-sqrt(1/2), the interpolated point values
  // within +-kPointValue: this scale maps their sum to [-1, 1].
  static constexpr float kValueScale = 1 / (std::numbers::sqrt2_v<float> / 2 + kPointValue);

  // Perlin noise (quintic fade) of `tile` at `level` at tile-local (u, v) in [0, 1]^2.
  NoiseSample sample(std::uint32_t tile, int level, float u, float v) const;

  // Sum over octaves k = 0..levels-1 of 2^-k * octave(log2_frequency + k), normalised by
  // sum 2^-k; |octave| when `absolute` (turbulence). octave(t), t = log2 of the frequency over
  // the coarsest level's, reads level levels-1-t, interpolated linearly in t between the two
  // levels around it (Maung 2012, section VI); octaves above the finest level fade out over one
  // octave, t < 0 is clamped to 0. With log2_frequency = 0 this is plain fbm / turbulence.
  float fractal(std::uint32_t tile, float u, float v, bool absolute, float log2_frequency = 0) const;

 private:
  std::uint8_t lattice_point(std::uint32_t tile, int level, int px, int py) const {
    return points_[tile * tile_stride_ + level_offset_[static_cast<std::size_t>(level)] +
                   static_cast<std::size_t>(py) * static_cast<std::size_t>(cells(level) + 1) +
                   static_cast<std::size_t>(px)];
  }

  TileSet set_;
  int lattice_ = 0, levels_ = 0;
  std::uint64_t seed_ = 0;
  float norm_ = 1;  // 1 / sum of the octave weights
  struct LatticePoint {
    float gx = 0, gy = 0, value = 0;
  };
  std::array<LatticePoint, 256> table_{};
  std::array<std::size_t, 16> level_offset_{};
  std::size_t tile_stride_ = 0;
  std::vector<std::uint8_t> points_;  // per tile, per level, rows south to north: table indices
};

struct MarbleParams {
  float stripes = 1.5f;    // stripes per tile side, across the x + y diagonal
  float distortion = 1.f;  // phase shift (turns) per unit of turbulence difference
};

struct WoodParams {
  float rings = 5.f;   // rings per tile side along y
  float grain = 0.4f;  // ring displacement (tile sides) by the coarsest octave
};

// A finite tiling (make_tiling's window) as a tile lookup; tiles outside the window clamp to it.
struct WindowTiles {
  Tiling tiling;
  std::uint32_t tile_at(std::int64_t i, std::int64_t j) const {
    const std::int64_t li = std::clamp<std::int64_t>(i - tiling.origin_i, 0, tiling.width - 1);
    const std::int64_t lj = std::clamp<std::int64_t>(j - tiling.origin_j, 0, tiling.height - 1);
    return tiling.at(static_cast<int>(li), static_cast<int>(lj));
  }
};

// Noise over a tiling: Lookup is anything with `std::uint32_t tile_at(int64 i, int64 j) const`
// (HashedTiling: unbounded, O(1); WindowTiles: a finite window). Every method is const,
// thread-safe, allocation-free and non-virtual: what renderers call per sample.
template <class Lookup>
class TiledNoise {
 public:
  // tile_size: world units per tile side (> 0).
  TiledNoise(NoiseTileSet tiles, Lookup lookup, double tile_size)
      : tiles_(std::move(tiles)), lookup_(std::move(lookup)), tile_size_(tile_size) {}

  const NoiseTileSet& tiles() const { return tiles_; }
  const Lookup& lookup() const { return lookup_; }
  double tile_size() const { return tile_size_; }

  struct Location {
    std::int64_t i = 0, j = 0;
    std::uint32_t tile = 0;
    float u = 0, v = 0;
  };
  Location locate(double x, double y) const {
    const double s = x / tile_size_, t = y / tile_size_;
    const double fi = std::floor(s), fj = std::floor(t);
    Location at;
    at.i = static_cast<std::int64_t>(fi);
    at.j = static_cast<std::int64_t>(fj);
    at.tile = lookup_.tile_at(at.i, at.j);
    at.u = static_cast<float>(s - fi);
    at.v = static_cast<float>(t - fj);
    return at;
  }

  // One level's noise; the gradient per world unit.
  NoiseSample noise(double x, double y, int level = 0) const {
    const Location at = locate(x, y);
    NoiseSample s = tiles_.sample(at.tile, level, at.u, at.v);
    const auto scale = static_cast<float>(1.0 / tile_size_);
    s.du *= scale;
    s.dv *= scale;
    return s;
  }
  float fbm(double x, double y, float log2_frequency = 0) const {
    const Location at = locate(x, y);
    return tiles_.fractal(at.tile, at.u, at.v, false, log2_frequency);
  }
  float turbulence(double x, double y, float log2_frequency = 0) const {
    const Location at = locate(x, y);
    return tiles_.fractal(at.tile, at.u, at.v, true, log2_frequency);
  }
  // Maung 2012, section X: stripes bent by the difference of two turbulence layers read from
  // different tiles of the tiling (offset by whole tiles).
  float marble(double x, double y, const MarbleParams& p = {}) const {
    const double offset = kLayerOffsetTiles * tile_size_;
    const double t = turbulence(x, y) - turbulence(x + offset, y - offset);
    const double phase = p.stripes * (x + y) / tile_size_ + p.distortion * t;
    return static_cast<float>(0.5 + 0.5 * std::sin(2 * std::numbers::pi * phase));
  }
  // Maung 2012, section XI: three layers; rings bent by the coarsest octave, a middle octave for
  // color variation, the finest for a sanded grain.
  float wood(double x, double y, const WoodParams& p = {}) const {
    const Location at = locate(x, y);
    const int coarse = tiles_.levels() - 1, middle = coarse / 2;
    const float bend = tiles_.sample(at.tile, coarse, at.u, at.v).value;
    const double rings = p.rings * (y / tile_size_ + p.grain * bend);
    const double profile = 0.5 + 0.5 * std::sin(2 * std::numbers::pi * rings);
    const float variation = tiles_.sample(at.tile, middle, at.u, at.v).value;
    const float sanded = tiles_.sample(at.tile, 0, at.u, at.v).value;
    return static_cast<float>(0.7 * profile + 0.2 * (0.5 + 0.5 * variation) + 0.1 * (0.5 + 0.5 * sanded));
  }
  float pattern(NoisePattern kind, double x, double y) const {
    switch (kind) {
      case NoisePattern::noise:
        return noise(x, y).value;
      case NoisePattern::fbm:
        return fbm(x, y);
      case NoisePattern::turbulence:
        return turbulence(x, y);
      case NoisePattern::marble:
        return marble(x, y);
      case NoisePattern::wood:
        return wood(x, y);
    }
    return 0;
  }

 private:
  static constexpr double kLayerOffsetTiles = 7;
  NoiseTileSet tiles_;
  Lookup lookup_;
  double tile_size_ = 1;
};

// Noise over the unbounded hashed tiling of a complete set (complete-edge-K, corner-K).
using NoiseField = TiledNoise<HashedTiling>;
// Noise over one finite tiling (any algorithm).
using WindowNoise = TiledNoise<WindowTiles>;

// Throws Error (from NoiseTileSet or HashedTiling) when the set is not complete or an
// option is out of range; tile_size must be > 0.
NoiseField make_noise_field(const TileSet& set, const NoiseTileOptions& options, std::uint64_t tiling_seed,
                            double tile_size);

// 16-bit grey value of a pattern value: [-1, 1] for noise and fbm, [0, 1] for the others.
std::uint16_t noise_to_gray16(NoisePattern pattern, float value);

// One tile, pixels x pixels, sampled at pixel centres, north at the top: noise, fbm or
// turbulence (marble and wood need the tiling). Tiles laid by any valid tiling join seamlessly.
ImageGray16 rasterize_noise_tile(const NoiseTileSet& tiles, std::uint32_t tile, int pixels,
                                 NoisePattern pattern = NoisePattern::fbm);

// A width x height preview of `field` with pixel_size world units per pixel, its south-west
// corner at world (x0, y0), north at the top. Rows in parallel (TBB); same bytes on any thread count.
ImageGray16 render_noise_preview(const NoiseField& field, NoisePattern pattern, int width, int height,
                                 double pixel_size, double x0 = 0, double y0 = 0);

// ---------------------------------------------------------------------------------------------
// Per-sample kernels, inline so renderers' loops can inline them.

inline NoiseSample NoiseTileSet::sample(std::uint32_t tile, int level, float u, float v) const {
  const int n = cells(level);
  const float gx = u * static_cast<float>(n), gy = v * static_cast<float>(n);
  const int cx = std::clamp(static_cast<int>(std::floor(gx)), 0, n - 1);
  const int cy = std::clamp(static_cast<int>(std::floor(gy)), 0, n - 1);
  const float fx = gx - static_cast<float>(cx), fy = gy - static_cast<float>(cy);
  const std::uint8_t* row =
      &points_[tile * tile_stride_ + level_offset_[static_cast<std::size_t>(level)] +
               static_cast<std::size_t>(cy) * static_cast<std::size_t>(n + 1) + static_cast<std::size_t>(cx)];
  const LatticePoint& g00 = table_[row[0]];
  const LatticePoint& g10 = table_[row[1]];
  const LatticePoint& g01 = table_[row[n + 1]];
  const LatticePoint& g11 = table_[row[n + 2]];
  // Each corner's ramp: its value plus its gradient times the offset from it.
  const float n00 = g00.value + g00.gx * fx + g00.gy * fy;
  const float n10 = g10.value + g10.gx * (fx - 1) + g10.gy * fy;
  const float n01 = g01.value + g01.gx * fx + g01.gy * (fy - 1);
  const float n11 = g11.value + g11.gx * (fx - 1) + g11.gy * (fy - 1);
  const auto fade = [](float t) { return t * t * t * (t * (t * 6 - 15) + 10); };
  const auto dfade = [](float t) { return 30 * t * t * (t - 1) * (t - 1); };
  const float sx = fade(fx), sy = fade(fy), dsx = dfade(fx), dsy = dfade(fy);
  const float a = n00 + sx * (n10 - n00), b = n01 + sx * (n11 - n01);
  const float dax = g00.gx + sx * (g10.gx - g00.gx) + dsx * (n10 - n00);
  const float dbx = g01.gx + sx * (g11.gx - g01.gx) + dsx * (n11 - n01);
  const float day = g00.gy + sx * (g10.gy - g00.gy), dby = g01.gy + sx * (g11.gy - g01.gy);
  const float per_side = kValueScale * static_cast<float>(n);
  return {kValueScale * (a + sy * (b - a)), per_side * (dax + sy * (dbx - dax)),
          per_side * (day + sy * (dby - day) + dsy * (b - a))};
}

inline float NoiseTileSet::fractal(std::uint32_t tile, float u, float v, bool absolute, float log2_frequency) const {
  const float t0 = std::max(0.f, log2_frequency);
  const int whole = static_cast<int>(t0);
  const float frac = t0 - static_cast<float>(whole);
  float sum = 0, weight = 1;
  for (int k = 0; k < levels_ && whole + k < levels_; ++k, weight *= 0.5f) {
    const int level = levels_ - 1 - (whole + k);
    float n = sample(tile, level, u, v).value;
    if (frac > 0) {
      const float next = level > 0 ? sample(tile, level - 1, u, v).value : 0.f;
      n += frac * (next - n);
    }
    sum += weight * (absolute ? std::abs(n) : n);
  }
  return sum * norm_;
}

}  // namespace wangscape
