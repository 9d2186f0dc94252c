#include "generator/tiling_stats.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace wangscape {
namespace {

// A tiling repeating a `period_i` x `period_j` block of a stochastic one (edges need not match).
Tiling repeat_block(const Tiling& source, int period_i, int period_j, int width, int height) {
  Tiling tiling;
  tiling.width = width;
  tiling.height = height;
  for (int j = 0; j < height; ++j)
    for (int i = 0; i < width; ++i) tiling.tiles.push_back(source.at(i % period_i, j % period_j));
  return tiling;
}

TEST(TilingStats, PeriodicTilingsScoreHighAndStochasticOnesLow) {
  const TileSet set = builtin_tileset("cohen8");
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    TilingOptions options;
    options.seed = seed;
    const Tiling stochastic = make_tiling(set, 128, 128, options);
    const PeriodicityPeak low = periodicity_score(stochastic);
    EXPECT_LT(low.score, 0.15) << "seed " << seed;

    const int period_i = 3 + static_cast<int>(seed % 5), period_j = 2 + static_cast<int>(seed % 7);
    const Tiling periodic = repeat_block(stochastic, period_i, period_j, 128, 128);
    const PeriodicityPeak high = periodicity_score(periodic);
    EXPECT_GT(high.score, 0.95) << "seed " << seed;
    // The peak sits on a lattice vector of the period.
    EXPECT_EQ(high.di % period_i, 0);
    EXPECT_EQ(high.dj % period_j, 0);
  }
}

TEST(TilingStats, AValidPeriodicTilingOfACompleteSetScoresHigh) {
  // Columns alternating (N,E,S,W) = (0,1,0,0) and (0,0,0,1): valid, period 2.
  const TileSet set = builtin_tileset("complete-edge-2");
  const auto index_of = [&](const Tile& t) {
    return static_cast<std::uint16_t>(std::find(set.tiles.begin(), set.tiles.end(), t) - set.tiles.begin());
  };
  Tiling tiling;
  tiling.width = 40;
  tiling.height = 30;
  for (int j = 0; j < 30; ++j)
    for (int i = 0; i < 40; ++i)
      tiling.tiles.push_back(i % 2 ? index_of(Tile::edges(0, 0, 0, 1)) : index_of(Tile::edges(0, 1, 0, 0)));
  const TilingStats stats = compute_tiling_stats(set, tiling);
  EXPECT_TRUE(stats.valid) << stats.invalid_reason;
  EXPECT_GT(stats.periodicity, 0.99);
  EXPECT_DOUBLE_EQ(stats.identical_neighbour_rate, (30.0 * 39 * 0 + 29.0 * 40) / (30.0 * 39 + 29.0 * 40));
}

TEST(TilingStats, FrequenciesValidityAndIdenticalNeighbours) {
  const TileSet set = builtin_tileset("cohen8");
  TilingOptions options;
  options.forbid_identical_neighbours = true;
  const Tiling tiling = make_tiling(set, 50, 40, options);
  TilingStats stats = compute_tiling_stats(set, tiling);
  EXPECT_TRUE(stats.valid);
  EXPECT_EQ(stats.identical_neighbour_rate, 0.0);
  std::uint64_t total = 0;
  for (const std::uint64_t f : stats.frequencies) {
    EXPECT_GT(f, 50u);  // 2000 tiles over 8: none starved
    total += f;
  }
  EXPECT_EQ(total, 2000u);

  options.forbid_identical_neighbours = false;
  stats = compute_tiling_stats(set, make_tiling(set, 200, 200, options));
  // Each tile has 2 candidates, one of which may be the western neighbour: about 1/8 of pairs.
  EXPECT_GT(stats.identical_neighbour_rate, 0.05);
  EXPECT_LT(stats.identical_neighbour_rate, 0.25);

  Tiling broken = tiling;
  const int east = set.tiles[tiling.at(0, 0)].e();
  broken.tiles[1] = static_cast<std::uint16_t>(
      std::find_if(set.tiles.begin(), set.tiles.end(), [&](const Tile& t) { return t.w() != east; }) -
      set.tiles.begin());
  stats = compute_tiling_stats(set, broken);
  EXPECT_FALSE(stats.valid);
  EXPECT_NE(stats.invalid_reason.find("tile (0, 0) has E="), std::string::npos) << stats.invalid_reason;
}

}  // namespace
}  // namespace wangscape
