// Placement: instances land in the tile the tiling puts there, stand on the ground, follow the
// filters, stream in batches, and do not depend on the window or the thread count.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <map>
#include <tuple>

#include "generator/placement.h"

namespace wangscape {
namespace {

const FilledTileSet& filled_set(const std::string& name) {
  static std::map<std::string, FilledTileSet> cache;
  auto it = cache.find(name);
  if (it == cache.end()) {
    PoissonFillOptions options;
    options.points_per_tile = 10;
    options.seed = 3;
    it = cache.emplace(name, fill_poisson_tiles(builtin_tileset(name), options)).first;
  }
  return it->second;
}

using Instance = std::tuple<float, float, float, float, float, std::uint16_t, std::uint32_t>;

std::vector<Instance> collect(const InstanceBatch& b) {
  std::vector<Instance> out;
  for (std::size_t k = 0; k < b.size(); ++k)
    out.emplace_back(b.x[k], b.y[k], b.z[k], b.yaw[k], b.scale[k], b.variant[k], b.tile[k]);
  return out;
}

TEST(Placement, InstancesMatchTheTilingAndStandOnTheGround) {
  const FilledTileSet& filled = filled_set("cohen8");
  const FlatGround ground{{-10, -6, 30, 26}, 3.5};
  PlacementOptions options;
  options.tile_size = 4;
  options.seed = 11;
  options.batch_points = 100;  // several batches
  std::vector<Instance> all;
  std::size_t batches = 0;
  const PlacementStats stats = place_instances(filled, ground, options, [&](const InstanceBatch& b) {
    ++batches;
    const auto got = collect(b);
    all.insert(all.end(), got.begin(), got.end());
  });
  EXPECT_GT(batches, 1u);
  EXPECT_EQ(stats.points, all.size());
  EXPECT_EQ(stats.tiles, 11u * 9u);  // [-12, 32) x [-8, 28) in 4 m tiles

  TilingOptions tiling_options;
  tiling_options.seed = 11;
  tiling_options.origin_i = -3;
  tiling_options.origin_j = -2;
  const Tiling tiling = make_tiling(filled.set, 11, 9, tiling_options);
  std::size_t expected = 0;
  for (int j = 0; j < 9; ++j)
    for (int i = 0; i < 11; ++i)
      for (const TilePoint& p : filled.tiles[tiling.at(i, j)]) {
        const double x = (i - 3 + p.x) * 4.0, y = (j - 2 + p.y) * 4.0;
        if (ground.area.contains(x, y)) ++expected;
      }
  EXPECT_EQ(all.size(), expected);
  for (const auto& [x, y, z, yaw, scale, variant, tile] : all) {
    EXPECT_EQ(z, 3.5f);
    EXPECT_TRUE(ground.area.contains(x, y));
    const int i = static_cast<int>(std::floor(x / 4.0)) + 3, j = static_cast<int>(std::floor(y / 4.0)) + 2;
    EXPECT_EQ(tile, tiling.at(i, j));
    EXPECT_LT(variant, filled.variants);
  }
}

TEST(Placement, HashedTilesCoverTheSameGroundInEveryWindow) {
  const FilledTileSet& filled = filled_set("complete-edge-2");
  PlacementOptions options;
  options.algorithm = TilingAlgorithm::hash;
  options.tile_size = 2;
  auto run = [&](Extent area) {
    std::map<std::pair<float, float>, Instance> by_position;
    place_instances(filled, FlatGround{area, 0.0}, options, [&](const InstanceBatch& b) {
      for (const Instance& inst : collect(b)) by_position[{std::get<0>(inst), std::get<1>(inst)}] = inst;
    });
    return by_position;
  };
  const auto big = run({-20, -20, 20, 20});
  const auto small = run({-6, 2, 10, 14});
  ASSERT_FALSE(small.empty());
  for (const auto& [pos, inst] : small) {
    auto it = big.find(pos);
    ASSERT_NE(it, big.end());
    EXPECT_EQ(it->second, inst);
  }
}

// With no identical neighbours, a hashed placement lays the tiles `tiling --algorithm hash
// --no-identical-neighbours` gives there (it laid the plain hashed tiles, neighbours alike), in a
// window of the area as in the whole.
TEST(Placement, HashedTilesWithoutIdenticalNeighboursAreTheTilingsInEveryWindow) {
  const FilledTileSet& filled = filled_set("complete-edge-2");
  PlacementOptions options;
  options.algorithm = TilingAlgorithm::hash;
  options.forbid_identical_neighbours = true;
  options.tile_size = 2;
  options.seed = 7;
  TilingOptions tiling_options;
  tiling_options.algorithm = TilingAlgorithm::hash;
  tiling_options.forbid_identical_neighbours = true;
  tiling_options.seed = 7;
  tiling_options.origin_i = -10;
  tiling_options.origin_j = -10;
  const Tiling tiling = make_tiling(filled.set, 20, 20, tiling_options);
  for (const Extent window : {Extent{-20, -20, 20, 20}, Extent{-6, 2, 10, 14}}) {
    options.window = window;
    std::size_t placed = 0;
    place_instances(filled, FlatGround{{-20, -20, 20, 20}, 0.0}, options, [&](const InstanceBatch& b) {
      for (const auto& [x, y, z, yaw, scale, variant, tile] : collect(b)) {
        const int i = static_cast<int>(std::floor(x / 2.0)) + 10, j = static_cast<int>(std::floor(y / 2.0)) + 10;
        EXPECT_EQ(tile, tiling.at(i, j)) << "at tile (" << i - 10 << ", " << j - 10 << ")";
        ++placed;
      }
    });
    EXPECT_GT(placed, 100u);
  }
  for (int j = 0; j < 20; ++j)
    for (int i = 0; i + 1 < 20; ++i) {
      EXPECT_NE(tiling.at(i, j), tiling.at(i + 1, j));
      EXPECT_NE(tiling.at(j, i), tiling.at(j, i + 1));
    }
}

TEST(Placement, TileAndPointFiltersDropWhatTheyReject) {
  const FilledTileSet& filled = filled_set("cohen8");
  const FlatGround ground{{0, 0, 40, 40}, 1.0};
  PlacementOptions options;
  options.tile_size = 4;
  std::size_t total = 0, filtered = 0;
  place_instances(filled, ground, options, [&](const InstanceBatch& b) { total += b.size(); });
  const PlacementStats stats = place_instances(
      filled, ground, options,
      [&](const InstanceBatch& b) {
        filtered += b.size();
        for (std::size_t k = 0; k < b.size(); ++k) {
          EXPECT_FALSE(b.x[k] >= 8 && b.x[k] < 12) << "tile column 2 was rejected";
          EXPECT_LT(b.y[k], 30.0f) << "points above y = 30 were rejected";
        }
      },
      [](const TileCell& cell) { return cell.i != 2; }, [](double, double y, double) { return y < 30.0; });
  EXPECT_EQ(stats.tiles_kept, 90u);
  EXPECT_LT(filtered, total);
  EXPECT_GT(filtered, total / 2);
}

TEST(Placement, SameBytesOnOneAndTwoThreads) {
  const FilledTileSet& filled = filled_set("cohen8");
  const FlatGround ground{{0, 0, 200, 120}, 0.0};
  PlacementOptions options;
  options.tile_size = 4;
  options.batch_points = 500;
  auto run = [&] {
    std::vector<Instance> all;
    place_instances(filled, ground, options, [&](const InstanceBatch& b) {
      const auto got = collect(b);
      all.insert(all.end(), got.begin(), got.end());
    });
    return all;
  };
  std::vector<Instance> one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = run();
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    two = run();
  }
  EXPECT_EQ(one, two);
}

TEST(Placement, RejectsANonPositiveTileSize) {
  PlacementOptions options;
  options.tile_size = 0;
  EXPECT_THROW(place_instances(filled_set("cohen8"), FlatGround{{0, 0, 1, 1}, 0}, options, [](const InstanceBatch&) {}),
               Error);
}

}  // namespace
}  // namespace wangscape
