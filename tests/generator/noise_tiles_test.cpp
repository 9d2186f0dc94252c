#include "generator/noise_tiles.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>
#include <string>

#include "generator/tiling_stats.h"
#include "tests/generator/noise_reference.h"
#include "tests/generator/test_support.h"

namespace wangscape {
namespace {

using testing::error_of;
using testing::LatticePointAt;
using testing::reference_noise;

// Float precision for a noise value (|value| <= 1) and for its gradient on an n-cell lattice
// (per tile side, so of order n).
constexpr float kValueTolerance = 2e-6f;
float gradient_tolerance(int cells) { return 4e-6f * static_cast<float>(cells); }

struct Case {
  const char* set;
  TilingAlgorithm algorithm;
};
// Shared corner gradient (cohen8), corner-coded edges (cohen8-corners), complete sets under
// scanline and hash, corner colors (corner-2: Maung 2012's corner method).
constexpr Case kCases[] = {{"cohen8", TilingAlgorithm::scanline},
                           {"cohen18", TilingAlgorithm::bottom_left},
                           {"cohen8-corners", TilingAlgorithm::scanline},
                           {"complete-edge-2", TilingAlgorithm::hash},
                           {"complete-edge-3", TilingAlgorithm::scanline},
                           {"corner-2", TilingAlgorithm::hash},
                           {"corner-3", TilingAlgorithm::hash}};

void expect_same(const NoiseSample& a, const NoiseSample& b, int cells, const std::string& where) {
  ASSERT_NEAR(a.value, b.value, kValueTolerance) << where;
  ASSERT_NEAR(a.du, b.du, gradient_tolerance(cells)) << where;
  ASSERT_NEAR(a.dv, b.dv, gradient_tolerance(cells)) << where;
}

TEST(NoiseTiles, ValueAndGradientAgreeAcrossEveryEdgeOfManyTilings) {
  for (const Case& c : kCases) {
    const TileSet set = builtin_tileset(c.set);
    for (std::uint64_t seed = 1; seed <= 8; ++seed) {
      NoiseTileOptions options;
      options.lattice = 16;
      options.seed = seed * 31;
      const NoiseTileSet tiles(set, options);
      TilingOptions tiling_options;
      tiling_options.algorithm = c.algorithm;
      tiling_options.seed = seed;
      tiling_options.origin_i = -3;
      const Tiling tiling = make_tiling(set, 9, 7, tiling_options);
      for (int level = 0; level < tiles.levels(); ++level)
        for (int j = 0; j < tiling.height; ++j)
          for (int i = 0; i < tiling.width; ++i)
            for (int k = 0; k <= 40; ++k) {
              const float along = static_cast<float>(k) / 40.f;
              const std::string where = std::string(c.set) + " seed " + std::to_string(seed) + " level " +
                                        std::to_string(level) + " tile (" + std::to_string(i) + ", " +
                                        std::to_string(j) + ") at " + std::to_string(along);
              const std::uint32_t here = tiling.at(i, j);
              if (i + 1 < tiling.width)
                expect_same(tiles.sample(here, level, 1, along), tiles.sample(tiling.at(i + 1, j), level, 0, along),
                            tiles.cells(level), where + " east");
              if (j + 1 < tiling.height)
                expect_same(tiles.sample(here, level, along, 1), tiles.sample(tiling.at(i, j + 1), level, along, 0),
                            tiles.cells(level), where + " north");
            }
    }
  }
}

TEST(NoiseTiles, TilesWhoseEdgesDifferDisagreeThere) {
  // The check above is not vacuous: across an edge whose colors differ, the noise jumps.
  const TileSet set = builtin_tileset("complete-edge-2");
  const NoiseTileSet tiles(set, {});
  std::uint32_t east0 = 0, west1 = 0;
  for (std::uint32_t t = 0; t < set.size(); ++t) {
    if (set.tiles[t].e() == 0) east0 = t;
    if (set.tiles[t].w() == 1) west1 = t;
  }
  float largest = 0;
  for (int k = 1; k < 40; ++k) {
    const float v = static_cast<float>(k) / 40.f;
    largest = std::max(largest, std::abs(tiles.sample(east0, 0, 1, v).value - tiles.sample(west1, 0, 0, v).value));
  }
  EXPECT_GT(largest, 0.1f);
}

TEST(NoiseTiles, TheHashedFieldIsContinuousAcrossTileEdgesInWorldCoordinates) {
  const NoiseField field = make_noise_field(builtin_tileset("corner-2"), {}, 9, 2.5);
  for (int i = -20; i <= 20; ++i)
    for (int k = 0; k < 10; ++k) {
      const double x = i * 2.5, y = -7.3 + 1.37 * k;
      const double h = 1e-9;
      EXPECT_NEAR(field.fbm(x - h, y), field.fbm(x + h, y), 1e-5) << "x " << x << " y " << y;
      EXPECT_NEAR(field.turbulence(y, x - h), field.turbulence(y, x + h), 1e-5) << "x " << y << " y " << x;
    }
}

TEST(NoiseTiles, TheGradientIsTheDerivativeOfTheValue) {
  const NoiseField field = make_noise_field(builtin_tileset("complete-edge-2"), {}, 3, 4.0);
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> coordinate(-40, 40);
  for (int k = 0; k < 500; ++k) {
    const double x = coordinate(rng), y = coordinate(rng), h = 1e-3;
    for (int level = 0; level < field.tiles().levels(); ++level) {
      const NoiseSample s = field.noise(x, y, level);
      const double du = (field.noise(x + h, y, level).value - field.noise(x - h, y, level).value) / (2 * h);
      const double dv = (field.noise(x, y + h, level).value - field.noise(x, y - h, level).value) / (2 * h);
      EXPECT_NEAR(s.du, du, 2e-2 * std::max(1.0, std::abs(du))) << x << ", " << y << " level " << level;
      EXPECT_NEAR(s.dv, dv, 2e-2 * std::max(1.0, std::abs(dv))) << x << ", " << y << " level " << level;
    }
  }
}

std::int64_t floor_div(std::int64_t a, std::int64_t b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

TEST(NoiseTiles, TurbulenceMipsAgreeWithADirectEvaluation) {
  const TileSet set = builtin_tileset("complete-edge-2");
  NoiseTileOptions options;
  options.lattice = 32;  // 4 levels: 32, 16, 8, 4 cells per tile
  options.seed = 11;
  const double tile_size = 3.0;
  const NoiseField field = make_noise_field(set, options, 21, tile_size);
  const NoiseTileSet& tiles = field.tiles();
  ASSERT_EQ(tiles.levels(), 4);

  // One global gradient lattice per level, read from whichever tile holds the point; a point
  // on a border is held by up to four tiles, which must agree.
  const auto global_gradient = [&](int level) {
    return [&, level](std::int64_t px, std::int64_t py) {
      const int n = tiles.cells(level);
      const std::int64_t i = floor_div(px, n), j = floor_div(py, n);
      const auto lx = static_cast<int>(px - i * n), ly = static_cast<int>(py - j * n);
      const std::uint32_t tile = field.lookup().tile_at(i, j);
      const std::array<float, 2> g = tiles.gradient(tile, level, lx, ly);
      const float value = tiles.point_value(tile, level, lx, ly);
      if (lx == 0) {
        EXPECT_EQ(g, tiles.gradient(field.lookup().tile_at(i - 1, j), level, n, ly));
        EXPECT_EQ(value, tiles.point_value(field.lookup().tile_at(i - 1, j), level, n, ly));
      }
      if (ly == 0) {
        EXPECT_EQ(g, tiles.gradient(field.lookup().tile_at(i, j - 1), level, lx, n));
        EXPECT_EQ(value, tiles.point_value(field.lookup().tile_at(i, j - 1), level, lx, n));
      }
      return std::array<float, 3>{g[0], g[1], value};
    };
  };
  const auto octave = [&](double x, double y, int level) {
    const double scale = tiles.cells(level) / tile_size;
    return reference_noise(x * scale, y * scale, global_gradient(level));
  };
  // The documented sum: octave k at t = t0 + k reads level L-1-t, linear in t between levels.
  const auto reference = [&](double x, double y, bool absolute, double t0) {
    const int levels = tiles.levels();
    double sum = 0, weights = 0, w = 1;
    for (int k = 0; k < levels; ++k, w *= 0.5) {
      weights += w;
      const double t = t0 + k;
      const int whole = static_cast<int>(std::floor(t));
      const double frac = t - whole;
      if (whole >= levels) continue;
      const double a = octave(x, y, levels - 1 - whole);
      const double b = whole + 1 < levels ? octave(x, y, levels - 2 - whole) : 0.0;
      const double n = a + frac * (b - a);
      sum += w * (absolute ? std::abs(n) : n);
    }
    return sum / weights;
  };

  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> coordinate(-30, 30);
  for (int k = 0; k < 400; ++k) {
    const double x = coordinate(rng), y = coordinate(rng);
    for (int level = 0; level < tiles.levels(); ++level)
      ASSERT_NEAR(field.noise(x, y, level).value, octave(x, y, level), 2e-5) << x << ", " << y << " level " << level;
    for (const double t0 : {0.0, 0.5, 1.25, 2.7, 3.5}) {
      const auto t = static_cast<float>(t0);
      ASSERT_NEAR(field.turbulence(x, y, t), reference(x, y, true, t0), 2e-5) << x << ", " << y << " t " << t0;
      ASSERT_NEAR(field.fbm(x, y, t), reference(x, y, false, t0), 2e-5) << x << ", " << y << " t " << t0;
    }
  }
}

TEST(NoiseTiles, VaryingFrequencyIsContinuousInLog2Frequency) {
  const NoiseField field = make_noise_field(builtin_tileset("corner-2"), {.lattice = 64}, 4, 1.0);
  for (int k = 0; k < 200; ++k) {
    const double x = 0.137 * k, y = -0.071 * k;
    for (float t = 0.f; t < 5.f; t += 0.25f) {
      const float h = 1e-4f;
      EXPECT_NEAR(field.turbulence(x, y, t - h), field.turbulence(x, y, t + h), 1e-3) << x << ", " << y << " t " << t;
    }
  }
}

// Values sampled on a grid, quantised into 8 bands, as a Tiling so tiling_stats scores them.
Tiling quantised_field(const std::function<double(double, double)>& value, int side) {
  Tiling grid;
  grid.width = grid.height = side;
  for (int j = 0; j < side; ++j)
    for (int i = 0; i < side; ++i) {
      const double v = value(i + 0.31, j + 0.57);
      grid.tiles.push_back(static_cast<std::uint16_t>(std::clamp(static_cast<int>((v + 1) * 4), 0, 7)));
    }
  return grid;
}

TEST(NoiseTiles, ALargeTilingIsNoMorePeriodicThanUntiledNoise) {
  // One sample per lattice cell (lattice 16, tile size 16), 256 x 256 samples = 16 x 16 tiles.
  const auto score = [](const auto& value) { return periodicity_score(quantised_field(value, 256)); };
  const TileSet one = make_tileset("one", {Tile::edges(0, 0, 0, 0)}, "one");
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const LatticePointAt hashed = testing::untiled_lattice(seed);
    const double untiled = score([&](double x, double y) { return reference_noise(x, y, hashed); }).score;
    // Three corner colors (9 edge keys) or four edge colors: at the level of untiled noise.
    for (const char* name : {"corner-3", "complete-edge-4"}) {
      const NoiseField tiled = make_noise_field(builtin_tileset(name), {.seed = seed}, seed, 16.0);
      const double tiled_score = score([&](double x, double y) { return tiled.noise(x, y).value; }).score;
      EXPECT_LT(tiled_score, untiled + 0.03) << name << " seed " << seed;
    }
    // Two edge colors and one shared corner gradient repeat border gradients more often: a
    // weak peak at whole-tile offsets, far below repetition.
    const NoiseField two = make_noise_field(builtin_tileset("complete-edge-2"), {.seed = seed}, seed, 16.0);
    EXPECT_LT(score([&](double x, double y) { return two.noise(x, y).value; }).score, 0.2) << "seed " << seed;
    // The score does see repetition: one tile repeated scores ~1 at its period.
    const NoiseField periodic = make_noise_field(one, {.seed = seed}, seed, 16.0);
    const PeriodicityPeak repeating = score([&](double x, double y) { return periodic.noise(x, y).value; });
    EXPECT_GT(repeating.score, 0.95) << "seed " << seed;
    EXPECT_EQ(repeating.di % 16, 0);
    EXPECT_EQ(repeating.dj % 16, 0);
  }
}

TEST(NoiseTiles, RastersSampleThePatternAtPixelCentres) {
  const NoiseField field = make_noise_field(builtin_tileset("complete-edge-2"), {.lattice = 32}, 2, 8.0);
  const ImageGray16 tile = rasterize_noise_tile(field.tiles(), 5, 64, NoisePattern::turbulence);
  ASSERT_EQ(tile.width, 64);
  EXPECT_EQ(tile.at(10, 3),
            noise_to_gray16(NoisePattern::turbulence, field.tiles().fractal(5, 10.5f / 64.f, 1 - 3.5f / 64.f, true)));
  const ImageGray16 preview = render_noise_preview(field, NoisePattern::marble, 80, 60, 0.5, -10, 4);
  EXPECT_EQ(preview.at(7, 59), noise_to_gray16(NoisePattern::marble, field.marble(-10 + 7.5 * 0.5, 4 + 0.25)));
  std::uint16_t lo = 65535, hi = 0;
  for (const std::uint16_t p : preview.pixels) lo = std::min(lo, p), hi = std::max(hi, p);
  EXPECT_GT(hi - lo, 30000);  // marble spans its range
}

TEST(NoiseTiles, OptionsOutOfRangeAreNamed) {
  const TileSet set = builtin_tileset("cohen8");
  EXPECT_NE(error_of([&] { NoiseTileSet(set, {.lattice = 24}); }).find("lattice 24; expected a power of two"),
            std::string::npos);
  EXPECT_NE(error_of([&] { NoiseTileSet(set, {.lattice = 16, .octaves = 4}); }).find("holds 1..3"), std::string::npos);
  EXPECT_NE(error_of([&] { make_noise_field(set, {}, 1, 1.0); }).find("needs a complete set"), std::string::npos);
  EXPECT_NE(error_of([] { parse_noise_pattern("plasma"); }).find("'plasma'"), std::string::npos);
}

}  // namespace
}  // namespace wangscape
