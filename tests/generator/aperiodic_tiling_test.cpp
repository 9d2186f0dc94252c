// Culik's 13 tiles and the aperiodic algorithm that lays them.
#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <random>
#include <string>

#include "generator/tiling.h"
#include "tests/generator/test_support.h"

namespace wangscape {
namespace {

using testing::error_of;

Tiling culik_tiling(int width, int height, std::uint64_t seed, std::int64_t origin_i = 0, std::int64_t origin_j = 0) {
  TilingOptions options;
  options.algorithm = TilingAlgorithm::aperiodic;
  options.seed = seed;
  options.origin_i = origin_i;
  options.origin_j = origin_j;
  return make_tiling(builtin_tileset("culik13"), width, height, options);
}

// The first offset (di, dj) in the half plane dj > 0 or (dj = 0, di > 0), |di|, dj <= max_offset,
// at which the whole window repeats itself, or nothing.
std::optional<std::pair<int, int>> period_within(const Tiling& tiling, int max_offset) {
  for (int dj = 0; dj <= max_offset; ++dj)
    for (int di = -max_offset; di <= max_offset; ++di) {
      if (dj == 0 && di <= 0) continue;
      bool repeats = true;
      for (int lj = 0; lj + dj < tiling.height && repeats; ++lj)
        for (int li = std::max(0, -di); li < tiling.width && li + di < tiling.width && repeats; ++li)
          repeats = tiling.at(li, lj) == tiling.at(li + di, lj + dj);
      if (repeats) return std::pair{di, dj};
    }
  return std::nullopt;
}

TEST(Culik13, ThirteenTilesAndEachMultipliesItsSouthEdgeIntoItsNorthEdge) {
  const TileSet set = builtin_tileset("culik13");
  ASSERT_EQ(set.size(), std::size_t{kCulikTiles});
  EXPECT_EQ(set.horizontal_colors, 4);
  EXPECT_EQ(set.vertical_colors, 5);
  int tripling = 0;
  for (const Tile& t : set.tiles) {
    // Colors back to numbers (tileset.h): digit 3 is a 0; carries 0, 1, 2 are 0, -1, -2 (times 3)
    // and 3, 4 are 0, 1/2 (times 1/2). Doubled, so halving tiles stay whole: q S + W = N + E.
    const auto digit = [](int c) { return c == 3 ? 0 : c; };
    const bool triples = t.w() <= 2;
    ASSERT_EQ(triples, t.e() <= 2) << "a tile mixes the two multipliers' carries";
    if (triples) {
      ++tripling;
      EXPECT_EQ(3 * digit(t.s()) - t.w(), digit(t.n()) - t.e());
      EXPECT_NE(t.s(), 3) << "a tripling row never reads the halving rows' 0";
    } else {
      EXPECT_EQ(digit(t.s()) + (t.w() - 3), 2 * digit(t.n()) + (t.e() - 3));
      EXPECT_NE(t.s(), 0) << "a halving row reads its 0 as color 3";
    }
  }
  EXPECT_EQ(tripling, 6);  // Culik: 6 tiles multiply by 3, 7 by 1/2
}

TEST(Culik13, ValidAtAThousandSquareUsingEveryTileAndNeverRepeating) {
  const TileSet set = builtin_tileset("culik13");
  for (const std::uint64_t seed : {1u, 2u, 3u}) {
    const Tiling tiling = culik_tiling(1000, 1000, seed, -500, 17);
    ASSERT_NO_THROW(check_tiling(set, tiling)) << "seed " << seed;
    std::vector<int> count(set.size());
    for (const std::uint16_t t : tiling.tiles) ++count[t];
    for (std::size_t t = 0; t < set.size(); ++t) EXPECT_GT(count[t], 0) << "seed " << seed << " tile " << t;
    // Exact: for every offset up to 32 tiles some tile differs from the one at that offset.
    const auto period = period_within(tiling, 32);
    EXPECT_FALSE(period) << "seed " << seed << " repeats at " << period->first << ", " << period->second;
  }
}

TEST(Culik13, PeriodCheckFindsThePeriodOfAPeriodicTiling) {
  // The check above can fail: a window that repeats every 3 tiles east and every 2 north.
  Tiling tiling{40, 30, 0, 0, std::vector<std::uint16_t>(40 * 30)};
  for (int lj = 0; lj < 30; ++lj)
    for (int li = 0; li < 40; ++li) tiling.tiles[static_cast<std::size_t>(lj * 40 + li)] = (li % 3) + 3 * (lj % 2);
  const auto period = period_within(tiling, 8);
  ASSERT_TRUE(period);
  EXPECT_EQ(*period, std::pair(3, 0));
}

TEST(Culik13, ValidOverManySeedsSizesAndOrigins) {
  const TileSet set = builtin_tileset("culik13");
  std::mt19937_64 draw(7);
  for (std::uint64_t seed = 1; seed <= 300; ++seed) {
    const int width = 1 + static_cast<int>(draw() % 60), height = 1 + static_cast<int>(draw() % 60);
    // Near zero, far out and at the edges of the addressable plane (+-2^60).
    const std::int64_t far = kMaxTileCoordinate - width;
    const std::int64_t origins[] = {0, -static_cast<std::int64_t>(draw() % 5000), far, -kMaxTileCoordinate,
                                    static_cast<std::int64_t>(draw() >> 4) - (std::int64_t{1} << 59)};
    const std::int64_t origin_i = origins[seed % 5];
    const Tiling tiling = culik_tiling(width, height, seed, origin_i, -static_cast<std::int64_t>(seed));
    ASSERT_NO_THROW(check_tiling(set, tiling)) << "seed " << seed << " origin " << origin_i;
  }
}

TEST(Culik13, WindowsSideBySideWithOneSeedContinueOneTiling) {
  for (const std::int64_t origin : {std::int64_t{-40}, std::int64_t{1} << 58, -(std::int64_t{1} << 60)}) {
    const Tiling wide = culik_tiling(60, 25, 11, origin);
    const Tiling part = culik_tiling(17, 25, 11, origin + 29);
    for (int lj = 0; lj < 25; ++lj)
      for (int li = 0; li < 17; ++li) ASSERT_EQ(part.at(li, lj), wide.at(li + 29, lj)) << "origin " << origin;
  }
}

TEST(Culik13, SeedsGiveDifferentTilingsTheSameSeedTheSameOneAndRowsStreamAlike) {
  EXPECT_NE(culik_tiling(64, 64, 5).tiles, culik_tiling(64, 64, 6).tiles);
  EXPECT_EQ(culik_tiling(64, 64, 5).tiles, culik_tiling(64, 64, 5).tiles);
  const TileSet set = builtin_tileset("culik13");
  TilingOptions options;
  options.algorithm = TilingAlgorithm::aperiodic;
  options.seed = 5;
  std::vector<std::uint16_t> streamed(64 * 64);
  std::vector<int> order;
  stream_tiling(set, 64, 64, options, [&](int local_j, std::span<const std::uint16_t> row) {
    order.push_back(local_j);
    std::copy(row.begin(), row.end(), streamed.begin() + local_j * 64);
  });
  EXPECT_EQ(streamed, culik_tiling(64, 64, 5).tiles);
  EXPECT_EQ(order.front(), 0);  // south to north
  EXPECT_EQ(order.back(), 63);
}

TEST(Culik13, AUserFileWithTheSameTilesInAnotherOrderIsLaidToo) {
  std::vector<Tile> tiles = builtin_tileset("culik13").tiles;
  std::reverse(tiles.begin(), tiles.end());
  const TileSet set = make_tileset("mine", tiles, "mine.json");
  TilingOptions options;
  options.algorithm = TilingAlgorithm::aperiodic;
  EXPECT_NO_THROW(check_tiling(set, make_tiling(set, 50, 50, options)));
}

TEST(Culik13Errors, EachAlgorithmRefusesWhatItCannotLay) {
  const TileSet culik = builtin_tileset("culik13");
  TilingOptions options;
  for (const TilingAlgorithm algorithm :
       {TilingAlgorithm::scanline, TilingAlgorithm::bottom_left, TilingAlgorithm::hash}) {
    options.algorithm = algorithm;
    EXPECT_EQ(error_of([&] { make_tiling(culik, 8, 8, options); }),
              "tile set 'culik13': Culik's aperiodic set cannot be laid by the " + std::string(to_string(algorithm)) +
                  " algorithm (some neighbours have no tile between them); expected the aperiodic algorithm");
  }
  options.algorithm = TilingAlgorithm::aperiodic;
  EXPECT_EQ(error_of([&] { make_tiling(builtin_tileset("cohen8"), 8, 8, options); }),
            "tile set 'cohen8': the aperiodic algorithm tiles only Culik's 13-tile set (culik13); expected that set, "
            "or the scanline, bottom-left or hash algorithm for this one");
  std::vector<Tile> twelve = culik.tiles;
  twelve.pop_back();
  EXPECT_NE(error_of([&] {
              make_tiling(make_tileset("x", twelve, "x.json"), 8, 8, options);
            }).find("tile set 'x.json': the aperiodic algorithm tiles only"),
            std::string::npos);
  options.forbid_identical_neighbours = true;
  EXPECT_EQ(error_of([&] { make_tiling(culik, 8, 8, options); }),
            "tile set 'culik13': the aperiodic algorithm cannot forbid identical neighbours (Culik's construction "
            "fixes every tile)");
  EXPECT_EQ(parse_tiling_algorithm("aperiodic"), TilingAlgorithm::aperiodic);
}

}  // namespace
}  // namespace wangscape
