#include "generator/texture_tiles.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <string>

#include "generator/noise_tiles.h"
#include "tests/generator/test_support.h"

namespace wangscape {
namespace {

using testing::error_of;

// A synthetic exemplar: three fbm layers of a noise field as R, G, B around a base color.
ImageRgb8 synthetic_exemplar(int side, std::uint64_t seed, Rgb8 base) {
  const NoiseField field = make_noise_field(builtin_tileset("corner-3"), {.lattice = 32, .seed = seed}, seed, 48.0);
  ImageRgb8 image(side, side);
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      const auto channel = [&](int c, std::uint8_t b) {
        const float v = field.fbm(x + 1000.0 * c, y);
        return static_cast<std::uint8_t>(std::clamp(static_cast<int>(b + 90 * v), 0, 255));
      };
      image.set(x, y, {channel(0, base.r), channel(1, base.g), channel(2, base.b)});
    }
  return image;
}

const std::vector<ImageRgb8>& meadow() {
  static const std::vector<ImageRgb8> exemplars = {synthetic_exemplar(160, 3, {110, 130, 60})};
  return exemplars;
}
const std::vector<ImageRgb8>& meadow_and_pumice() {
  static const std::vector<ImageRgb8> exemplars = {synthetic_exemplar(160, 3, {110, 130, 60}),
                                                   synthetic_exemplar(160, 4, {170, 160, 150})};
  return exemplars;
}

int square_difference(Rgb8 a, Rgb8 b) {
  return (a.r - b.r) * (a.r - b.r) + (a.g - b.g) * (a.g - b.g) + (a.b - b.b) * (a.b - b.b);
}

// The exemplar color that source code `code` (window * 4 + slot) gives tile pixel (x, y).
Rgb8 through(const TextureTileSet& tiles, std::span<const ImageRgb8> exemplars, std::uint16_t code, int x, int y) {
  const TextureWindow& w = tiles.windows[code / 4u];
  const auto [ex, ey] = texture_source_pixel(tiles.tile_size, w, code % 4, x, y);
  return exemplars[static_cast<std::size_t>(w.exemplar)].at(ex, ey);
}

struct Case {
  const char* set;
  const std::vector<ImageRgb8>& (*exemplars)();
  TilingAlgorithm algorithm;
};
const Case kCases[] = {{"cohen8", meadow, TilingAlgorithm::scanline},
                       {"cohen18", meadow, TilingAlgorithm::scanline},
                       {"cohen8-corners", meadow_and_pumice, TilingAlgorithm::scanline},
                       {"corner-2", meadow_and_pumice, TilingAlgorithm::hash}};

TextureTileOptions small_options(std::uint64_t seed) {
  TextureTileOptions options;
  options.tile_size = 64;
  options.rounds = 1;
  options.candidates = 6;
  options.seed = seed;
  return options;
}

TEST(TextureTiles, EveryPixelIsItsSourceAndTheReportedErrorIsWhatTheCutsLeave) {
  for (const Case& c : kCases) {
    const TextureTileSet tiles = make_texture_tiles(builtin_tileset(c.set), c.exemplars(), small_options(2));
    std::uint64_t total = 0;
    for (std::size_t t = 0; t < tiles.tiles.size(); ++t) {
      const TextureTile& tile = tiles.tiles[t];
      const int size = tiles.tile_size;
      std::uint64_t recomputed = 0;
      for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
          const std::uint16_t here = tile.source[static_cast<std::size_t>(y * size + x)];
          ASSERT_EQ(tile.image.at(x, y), through(tiles, c.exemplars(), here, x, y)) << c.set << " tile " << t;
          for (const auto& [nx, ny] : {std::array<int, 2>{x + 1, y}, std::array<int, 2>{x, y + 1}}) {
            if (nx >= size || ny >= size) continue;
            const std::uint16_t there = tile.source[static_cast<std::size_t>(ny * size + nx)];
            if (there == here) continue;
            // The pixel shows `here`; what `there` would have shown instead, and vice versa.
            recomputed += static_cast<std::uint64_t>(
                square_difference(tile.image.at(x, y), through(tiles, c.exemplars(), there, x, y)) +
                square_difference(tile.image.at(nx, ny), through(tiles, c.exemplars(), here, nx, ny)));
          }
        }
      EXPECT_EQ(tile.error, recomputed) << c.set << " tile " << t;
      total += recomputed;
    }
    EXPECT_GT(total, 0u) << c.set;  // cuts between different samples do leave something
    EXPECT_EQ(tiles.total_error(), total);
  }
}

// Seam cost across one shared edge: each side's pixels against what the other side's source
// continues to across the edge. Corner pixels of vertical edges are skipped (they take the
// horizontal edge's diamond).
std::uint64_t edge_seam(const TextureTileSet& tiles, std::span<const ImageRgb8> exemplars, std::uint32_t west_or_south,
                        std::uint32_t east_or_north, bool vertical_edge) {
  const int size = tiles.tile_size;
  const TextureTile& a = tiles.tiles[west_or_south];
  const TextureTile& b = tiles.tiles[east_or_north];
  std::uint64_t seam = 0;
  for (int k = vertical_edge ? 1 : 0; k < (vertical_edge ? size - 1 : size); ++k) {
    // a's pixel and b's pixel across the edge, each also in the other's coordinates.
    const int ax = vertical_edge ? size - 1 : k, ay = vertical_edge ? k : 0;
    const int bx = vertical_edge ? 0 : k, by = vertical_edge ? k : size - 1;
    const std::uint16_t sa = a.source[static_cast<std::size_t>(ay * size + ax)];
    const std::uint16_t sb = b.source[static_cast<std::size_t>(by * size + bx)];
    const int bx_in_a = vertical_edge ? size : k, by_in_a = vertical_edge ? k : -1;
    const int ax_in_b = vertical_edge ? -1 : k, ay_in_b = vertical_edge ? k : size;
    seam += static_cast<std::uint64_t>(
        square_difference(b.image.at(bx, by), through(tiles, exemplars, sa, bx_in_a, by_in_a)) +
        square_difference(a.image.at(ax, ay), through(tiles, exemplars, sb, ax_in_b, ay_in_b)));
  }
  return seam;
}

TEST(TextureTiles, AlongEverySharedEdgeOfATilingBothSidesComeFromOneDiamond) {
  for (const Case& c : kCases) {
    const TileSet set = builtin_tileset(c.set);
    const TextureTileSet tiles = make_texture_tiles(set, c.exemplars(), small_options(5));
    for (std::uint64_t seed = 1; seed <= 5; ++seed) {
      TilingOptions options;
      options.algorithm = c.algorithm;
      options.seed = seed;
      const Tiling tiling = make_tiling(set, 10, 8, options);
      for (int j = 0; j < tiling.height; ++j)
        for (int i = 0; i < tiling.width; ++i) {
          if (i + 1 < tiling.width) {
            ASSERT_EQ(edge_seam(tiles, c.exemplars(), tiling.at(i, j), tiling.at(i + 1, j), true), 0u)
                << c.set << " seed " << seed << " tile (" << i << ", " << j << ") east";
          }
          if (j + 1 < tiling.height) {  // tiling row j + 1 is north of row j: a's N edge is b's S edge
            ASSERT_EQ(edge_seam(tiles, c.exemplars(), tiling.at(i, j), tiling.at(i, j + 1), false), 0u)
                << c.set << " seed " << seed << " tile (" << i << ", " << j << ") north";
          }
        }
    }
  }
}

TEST(TextureTiles, TilesWhoseEdgesDifferShowASeam) {
  // The check above is not vacuous: two tiles whose E and W colors differ do not continue.
  const TileSet set = builtin_tileset("cohen8");
  const TextureTileSet tiles = make_texture_tiles(set, meadow(), small_options(5));
  for (std::uint32_t a = 0; a < set.size(); ++a)
    for (std::uint32_t b = 0; b < set.size(); ++b)
      if (set.tiles[a].e() != set.tiles[b].w()) {
        EXPECT_GT(edge_seam(tiles, meadow(), a, b, true), 1000u) << a << " | " << b;
      }
}

TEST(TextureTiles, SameSeedSameBytesOnAnyThreadCount) {
  const TileSet set = builtin_tileset("cohen8-corners");
  TextureTileOptions options = small_options(9);
  options.candidates = 8;
  const auto build = [&] { return make_texture_tiles(set, meadow_and_pumice(), options); };
  const TextureTileSet parallel = build();
  TextureTileSet serial;
  {
    const tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    serial = build();
  }
  ASSERT_EQ(parallel.windows, serial.windows);
  for (std::size_t t = 0; t < set.size(); ++t) {
    EXPECT_EQ(parallel.tiles[t].image.pixels, serial.tiles[t].image.pixels) << "tile " << t;
    EXPECT_EQ(parallel.tiles[t].error, serial.tiles[t].error) << "tile " << t;
  }
  options.seed = 10;
  EXPECT_NE(make_texture_tiles(set, meadow_and_pumice(), options).windows, parallel.windows);
}

TEST(TextureTiles, TheSampleSearchLowersTheCutCost) {
  TextureTileOptions options = small_options(4);
  options.rounds = 3;
  options.candidates = 12;
  TextureTileReport report;
  const TextureTileSet tiles = make_texture_tiles(builtin_tileset("cohen8"), meadow(), options, &report);
  EXPECT_LT(report.final_cost, report.initial_cost);
  EXPECT_GT(report.moves_accepted, 0);
  EXPECT_EQ(report.candidates_tried, 3 * 12 * 4);  // 4 windows: 2 N/S colors, 2 E/W colors
  // The tiles' own interiors come after the search and cover the diamonds' cuts in the middle:
  // the search objective is the cost of the diamonds' cuts alone, not the tiles' seam cost.
  EXPECT_GT(tiles.total_error(), 0u);
}

TEST(TextureTiles, MarkedCornersReadTheSecondExemplar) {
  const TileSet set = builtin_tileset("cohen8-corners");
  const TextureTileSet tiles = make_texture_tiles(set, meadow_and_pumice(), small_options(3));
  const int size = tiles.tile_size;
  for (std::size_t t = 0; t < set.size(); ++t) {
    const Tile& tile = set.tiles[t];
    const auto exemplar_at = [&](int x, int y) {
      return tiles.windows[tiles.tiles[t].source[static_cast<std::size_t>(y * size + x)] / 4u].exemplar;
    };
    // Pixels near each corner come from the exemplar of that corner's mark.
    EXPECT_EQ(exemplar_at(size - 3, 2), tile.ne()) << "tile " << t;
    EXPECT_EQ(exemplar_at(size - 3, size - 3), tile.se()) << "tile " << t;
    EXPECT_EQ(exemplar_at(2, size - 3), tile.sw()) << "tile " << t;
    EXPECT_EQ(exemplar_at(2, 2), tile.nw()) << "tile " << t;
  }
}

TEST(TextureTiles, ThePreviewLaysTheTilesNorthUp) {
  const TileSet set = builtin_tileset("cohen8");
  const TextureTileSet tiles = make_texture_tiles(set, meadow(), small_options(1));
  const Tiling tiling = make_tiling(set, 3, 2, {});
  const ImageRgb8 image = draw_texture_tiling(tiles, tiling);
  ASSERT_EQ(image.width, 3 * 64);
  ASSERT_EQ(image.height, 2 * 64);
  EXPECT_EQ(image.at(64 + 5, 7), tiles.tiles[tiling.at(1, 1)].image.at(5, 7));  // row 1 is the top
  EXPECT_EQ(image.at(128 + 9, 64 + 3), tiles.tiles[tiling.at(2, 0)].image.at(9, 3));
}

TEST(TextureTiles, TilesUnder24PixelsHaveNoInteriorAndStillJoin) {
  TextureTileOptions options = small_options(6);
  options.tile_size = 16;
  const TileSet set = builtin_tileset("cohen8");
  const TextureTileSet tiles = make_texture_tiles(set, meadow(), options);
  for (const TextureTile& tile : tiles.tiles)
    for (const std::uint16_t code : tile.source) EXPECT_LT(code / 4u, 4u);  // the 4 diamonds' windows only
  const Tiling tiling = make_tiling(set, 6, 5, {});
  for (int j = 0; j < tiling.height; ++j)
    for (int i = 0; i + 1 < tiling.width; ++i)
      EXPECT_EQ(edge_seam(tiles, meadow(), tiling.at(i, j), tiling.at(i + 1, j), true), 0u);
}

TEST(TextureTiles, BadInputIsNamed) {
  const TileSet set = builtin_tileset("cohen8");
  TextureTileOptions options = small_options(1);
  options.tile_size = 200;
  EXPECT_NE(error_of([&] { make_texture_tiles(set, meadow(), options); }).find("exemplar 1 is 160 x 160 pixels"),
            std::string::npos);
  options.tile_size = 63;
  EXPECT_NE(error_of([&] { make_texture_tiles(set, meadow(), options); }).find("tile size 63"), std::string::npos);
  options.tile_size = 64;
  options.min_separation = 60;
  EXPECT_NE(error_of([&] { make_texture_tiles(set, meadow(), options); }).find("has no room"), std::string::npos);
}

}  // namespace
}  // namespace wangscape
