// Placement over a real DEM (generator's place_instances over a Terrain, which is a Ground):
// every instance stands on the ground, below the threshold; fair edges follow the contour;
// a hashed tiling of a sub-area equals the same part of the whole.
#include <gtest/gtest.h>

#include <algorithm>
#include <tuple>

#include "generator/placement.h"
#include "generator/poisson_tiles.h"
#include "terrain/mask.h"
#include "terrain_test_support.h"

namespace wangscape {
namespace {

const Terrain& helens() {
  static const Terrain terrain = Terrain::load(test::saint_helens());
  return terrain;
}

const FilledTileSet& tiles() {
  static const FilledTileSet filled = [] {
    PoissonFillOptions options;
    options.points_per_tile = 6;
    options.seed = 3;
    return fill_poisson_tiles(builtin_tileset("complete-edge-2"), options);
  }();
  return filled;
}

using Instance = std::tuple<float, float, float, std::uint16_t, std::uint32_t>;

std::vector<Instance> scatter(const Extent& area, double tile_size, const TerrainFilter& filter, bool fair) {
  PlacementOptions options;
  options.tile_size = tile_size;
  options.algorithm = TilingAlgorithm::hash;
  options.seed = 42;
  options.area = area;
  options.batch_points = 5000;  // several batches
  std::vector<Instance> out;
  place_instances(
      tiles(), helens(), options,
      [&](const InstanceBatch& b) {
        for (std::size_t k = 0; k < b.size(); ++k) out.emplace_back(b.x[k], b.y[k], b.z[k], b.variant[k], b.tile[k]);
      },
      [&](const TileCell& cell) { return fair ? filter.tile_may_pass(cell.bounds) : filter.tile_passes(cell.bounds); },
      [&](double x, double y, double z) { return !fair || filter.point_passes(x, y, z); });
  return out;
}

const Extent kWindow{-2000, -2500, 1500, 1000};

TEST(PlacementOnDem, EveryInstanceStandsOnTheGroundBelowTheThreshold) {
  const TerrainFilter filter(
      helens(), {.max_height_m = 1500.0, .min_height_m = {}, .max_slope_deg = {}, .mask_image = {}, .masks = {}});
  for (const bool fair : {false, true}) {
    const auto instances = scatter(kWindow, 8.0, filter, fair);
    ASSERT_GT(instances.size(), 1000u);
    for (const auto& [x, y, z, variant, tile] : instances) {
      const auto ground = helens().height(x, y);
      ASSERT_TRUE(ground.has_value()) << x << ", " << y;
      ASSERT_NEAR(z, *ground, 0.01) << x << ", " << y;  // z from the double position, checked at the float one
      ASSERT_LE(z, 1500.0f);
    }
  }
}

// scatter's estimate (issue 24): the tiles of the DEM's extent times the mean points per tile
// times the share of cells that pass comes within 15 % of the count placed, with and without
// fair edges, and a lower limit gives a smaller share.
TEST(PlacementOnDem, ThePassingShareEstimatesTheCountAfterTheMasks) {
  const TerrainFilter filter(
      helens(), {.max_height_m = 1500.0, .min_height_m = {}, .max_slope_deg = {}, .mask_image = {}, .masks = {}});
  const TerrainFilter lower(
      helens(), {.max_height_m = 1000.0, .min_height_m = {}, .max_slope_deg = {}, .mask_image = {}, .masks = {}});
  const Extent whole = helens().extent();
  const double tile_size = 30.0;
  const TileRange range = tile_range(whole, tile_size);
  std::size_t points = 0;
  for (const auto& tile : tiles().tiles) points += tile.size();
  const double mean = double(points) / double(tiles().tiles.size());
  for (const bool fair : {false, true}) {
    const double share = filter.passing_share(fair);
    ASSERT_GT(share, 0.0);
    ASSERT_LT(share, 1.0);
    EXPECT_LT(lower.passing_share(fair), share);
    const double estimate = double(range.width()) * range.height() * mean * share;
    const double placed = double(scatter(whole, tile_size, filter, fair).size());
    EXPECT_NEAR(placed / estimate, 1.0, 0.15) << (fair ? "fair edges" : "whole tiles");
  }
}

TEST(PlacementOnDem, FairEdgesKeepEveryStrictFlowerAndFollowTheContour) {
  const TerrainFilter filter(
      helens(), {.max_height_m = 1500.0, .min_height_m = {}, .max_slope_deg = {}, .mask_image = {}, .masks = {}});
  auto strict = scatter(kWindow, 8.0, filter, false);
  auto fair = scatter(kWindow, 8.0, filter, true);
  EXPECT_GT(fair.size(), strict.size());  // partial tiles along the contour are kept
  std::sort(strict.begin(), strict.end());
  std::sort(fair.begin(), fair.end());
  EXPECT_TRUE(std::includes(fair.begin(), fair.end(), strict.begin(), strict.end()));
  // Near the contour, fair-edge flowers stand higher than any strict one can get close to.
  float strict_top = 0, fair_top = 0;
  for (const auto& i : strict) strict_top = std::max(strict_top, std::get<2>(i));
  for (const auto& i : fair) fair_top = std::max(fair_top, std::get<2>(i));
  EXPECT_GT(fair_top, strict_top);
  EXPECT_GT(fair_top, 1499.0f);
}

TEST(PlacementOnDem, HashedSubAreaEqualsThatPartOfTheWhole) {
  const TerrainFilter filter(
      helens(), {.max_height_m = 1800.0, .min_height_m = {}, .max_slope_deg = 35.0, .mask_image = {}, .masks = {}});
  const double s = 8.0;
  for (const bool fair : {false, true}) {
    auto whole = scatter(kWindow, s, filter, fair);
    ASSERT_GT(whole.size(), 1000u);
    // A sub-window around a flower of the whole run, with edges inside tiles: the tiles it
    // touches are whole tiles of the big run.
    // (The window must stay inside kWindow's tiles: pick a flower 500 m inside it.)
    const auto inner = std::find_if(whole.begin() + std::ptrdiff_t(whole.size() / 2), whole.end(), [](const auto& i) {
      return std::get<0>(i) > kWindow.min_x + 500 && std::get<0>(i) < kWindow.max_x - 500 &&
             std::get<1>(i) > kWindow.min_y + 500 && std::get<1>(i) < kWindow.max_y - 500;
    });
    ASSERT_NE(inner, whole.end());
    const float cx = std::get<0>(*inner), cy = std::get<1>(*inner);
    const Extent sub{cx - 403.3, cy - 297.1, cx + 305.25, cy + 401.9};
    auto part = scatter(sub, s, filter, fair);
    ASSERT_FALSE(part.empty());
    const TileRange r = tile_range(sub, s);
    std::vector<Instance> expected;
    for (const auto& i : whole) {
      const auto ti = std::int64_t(std::floor(std::get<0>(i) / s)), tj = std::int64_t(std::floor(std::get<1>(i) / s));
      if (ti >= r.i0 && ti < r.i1 && tj >= r.j0 && tj < r.j1) expected.push_back(i);
    }
    std::sort(expected.begin(), expected.end());
    std::sort(part.begin(), part.end());
    EXPECT_EQ(part, expected);
  }
}

TEST(PlacementOnDem, NodataIsNeverPlanted) {
  // The quadrangle's no-data corners: a window over the north-west corner of the raster.
  const TerrainFilter filter(
      helens(), {.max_height_m = {}, .min_height_m = {}, .max_slope_deg = {}, .mask_image = {}, .masks = {}});
  const Extent e = helens().extent();
  const Extent corner{e.min_x, e.max_y - 600, e.min_x + 600, e.max_y};
  for (const bool fair : {false, true})
    for (const auto& [x, y, z, variant, tile] : scatter(corner, 4.0, filter, fair))
      ASSERT_TRUE(helens().height(x, y).has_value());
}

}  // namespace
}  // namespace wangscape
