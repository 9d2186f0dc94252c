// Masks (height threshold, slope, painted image) and the terrain mesh.
#include <gtest/gtest.h>

#include <random>

#include "terrain/mask.h"
#include "terrain/terrain_mesh.h"
#include "terrain_test_support.h"

namespace wangscape {
namespace {

const Terrain& helens() {
  static const Terrain terrain = Terrain::load(test::saint_helens());
  return terrain;
}

Extent random_tile(const Extent& e, double size, std::mt19937& rng) {
  const double x = std::uniform_real_distribution<double>(e.min_x - size, e.max_x)(rng);
  const double y = std::uniform_real_distribution<double>(e.min_y - size, e.max_y)(rng);
  return {x, y, x + size, y + size};
}

TEST(Mask, PassingTilesLieWhollyBelowTheThresholdAndFlatEnough) {
  const Terrain& terrain = helens();
  const TerrainFilter filter(
      terrain, {.max_height_m = 1500.0, .min_height_m = {}, .max_slope_deg = 25.0, .mask_image = {}, .masks = {}});
  std::mt19937 rng(1);
  int passing = 0, maybe = 0;
  for (int k = 0; k < 4000; ++k) {
    const double size = k % 2 ? 4.0 : 60.0;
    const Extent tile = random_tile(terrain.extent(), size, rng);
    const bool passes = filter.tile_passes(tile);
    if (passes) {
      EXPECT_TRUE(filter.tile_may_pass(tile));
    }
    maybe += filter.tile_may_pass(tile);
    if (!passes) continue;
    ++passing;
    for (int p = 0; p < 50; ++p) {
      const double x = std::uniform_real_distribution<double>(tile.min_x, tile.max_x)(rng);
      const double y = std::uniform_real_distribution<double>(tile.min_y, tile.max_y)(rng);
      const auto s = terrain.sample(x, y);
      ASSERT_TRUE(s.has_value());
      ASSERT_LE(s->height, 1500.0);
      ASSERT_LE(s->slope_degrees(), 25.0 + 0.01);  // the center Jacobian: a hair of slack
      ASSERT_TRUE(filter.point_passes(x, y) || s->slope_degrees() > 25.0);
    }
  }
  EXPECT_GT(passing, 200);
  EXPECT_GT(maybe, passing);
}

TEST(Mask, TileTestIsExactNotAStaircaseOfCells) {
  // A 4 m tile whose own ground is below the threshold passes even when a corner of its
  // 30 m DEM cell is above it: the strict border follows the contour at the tile size.
  const Terrain& terrain = helens();
  const TerrainFilter filter(
      terrain, {.max_height_m = 1500.0, .min_height_m = {}, .max_slope_deg = {}, .mask_image = {}, .masks = {}});
  std::mt19937 rng(8);
  int near_contour = 0;
  for (int k = 0; k < 20000 && near_contour < 300; ++k) {
    const Extent tile = random_tile(terrain.extent(), 4.0, rng);
    double highest = -1e9;
    bool data = true;
    for (int a = 0; a <= 8 && data; ++a)
      for (int b = 0; b <= 8 && data; ++b) {
        const auto h = terrain.height(tile.min_x + a * 0.5, tile.min_y + b * 0.5);
        data = h.has_value();
        if (h) highest = std::max(highest, *h);
      }
    if (!data || highest < 1450.0 || highest > 1550.0) continue;  // only tiles near the contour
    ++near_contour;
    if (highest < 1500.0 - 0.05) {
      EXPECT_TRUE(filter.tile_passes(tile)) << "max " << highest;
    }
    if (highest > 1500.0) {
      EXPECT_FALSE(filter.tile_passes(tile)) << "max " << highest;
    }
  }
  EXPECT_GE(near_contour, 300);
}

TEST(Mask, PointTestFollowsTheGround) {
  const Terrain& terrain = helens();
  const TerrainFilter filter(
      terrain, {.max_height_m = 1200.0, .min_height_m = {}, .max_slope_deg = {}, .mask_image = {}, .masks = {}});
  std::mt19937 rng(2);
  const Extent e = terrain.extent();
  int yes = 0, no = 0;
  for (int k = 0; k < 20000; ++k) {
    const double x = std::uniform_real_distribution<double>(e.min_x, e.max_x)(rng);
    const double y = std::uniform_real_distribution<double>(e.min_y, e.max_y)(rng);
    const auto h = terrain.height(x, y);
    EXPECT_EQ(filter.point_passes(x, y), h && *h <= 1200.0);
    (filter.point_passes(x, y) ? yes : no)++;
  }
  EXPECT_GT(yes, 1000);
  EXPECT_GT(no, 1000);
}

TEST(Mask, ThresholdBelowEveryHeightIsExplained) {
  const TerrainFilter filter(
      helens(), {.max_height_m = 500.0, .min_height_m = {}, .max_slope_deg = {}, .mask_image = {}, .masks = {}});
  try {
    filter.check_satisfiable();
    ADD_FAILURE() << "a 500 m threshold is below Mount St. Helens' lowest point (682 m)";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("below every height"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("682"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(
      TerrainFilter(helens(),
                    {.max_height_m = 700.0, .min_height_m = {}, .max_slope_deg = {}, .mask_image = {}, .masks = {}})
          .check_satisfiable());
  EXPECT_THROW(
      TerrainFilter(helens(),
                    {.max_height_m = {}, .min_height_m = {}, .max_slope_deg = 120.0, .mask_image = {}, .masks = {}}),
      Error);
}

TEST(Mask, PaintedMaskWhiteWestBlackEast) {
  const auto dir = test::scratch_dir("mask");
  // 64 x 32 pixels: white in the western half, black in the eastern half.
  test::write_raster(dir / "west.png", "PNG", GDT_Byte, 64, 32, {}, nullptr,
                     [](int col, int) { return col < 32 ? 255.0 : 0.0; });
  const Terrain& terrain = helens();
  const Extent e = terrain.extent();
  const double middle = (e.min_x + e.max_x) / 2;
  const TerrainFilter filter(
      terrain,
      {.max_height_m = {}, .min_height_m = {}, .max_slope_deg = {}, .mask_image = dir / "west.png", .masks = {}});
  ASSERT_NE(filter.mask(), nullptr);
  EXPECT_EQ(filter.mask()->allowed_count(), 32u * 32u);
  std::mt19937 rng(4);
  for (int k = 0; k < 5000; ++k) {
    const double x = std::uniform_real_distribution<double>(e.min_x, e.max_x)(rng);
    const double y = std::uniform_real_distribution<double>(e.min_y, e.max_y)(rng);
    if (std::abs(x - middle) < 1e-6 * e.width()) continue;
    EXPECT_EQ(filter.mask()->allows(x, y), x < middle);
    if (x > middle) {
      EXPECT_FALSE(filter.point_passes(x, y));
    }
    const Extent tile{x - 2, y - 2, x + 2, y + 2};
    if (x > middle + 2) {
      EXPECT_FALSE(filter.tile_passes(tile));
    }
  }
  // An all-black mask is explained, a missing one names the file.
  test::write_raster(dir / "black.png", "PNG", GDT_Byte, 8, 8, {}, nullptr, [](int, int) { return 0.0; });
  EXPECT_THROW(
      TerrainFilter(
          terrain,
          {.max_height_m = {}, .min_height_m = {}, .max_slope_deg = {}, .mask_image = dir / "black.png", .masks = {}})
          .check_satisfiable(),
      Error);
  try {
    TerrainFilter(
        terrain,
        {.max_height_m = {}, .min_height_m = {}, .max_slope_deg = {}, .mask_image = dir / "nothing.png", .masks = {}});
    ADD_FAILURE();
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("nothing.png"), std::string::npos);
  }
}

TEST(TerrainMesh, FullMeshStandsOnTheSamples) {
  const Terrain& terrain = helens();
  const TerrainMesh mesh = make_terrain_mesh(terrain);
  const DemRaster& dem = terrain.dem();
  EXPECT_EQ(mesh.stride, 1);
  EXPECT_EQ(mesh.positions.size(), dem.cell_count() - dem.nodata_count);
  EXPECT_EQ(mesh.normals.size(), mesh.positions.size());
  EXPECT_GT(mesh.triangles.size(), mesh.positions.size());  // about two per vertex
  for (const auto& t : mesh.triangles) {
    const auto &a = mesh.positions[t[0]], &b = mesh.positions[t[1]], &c = mesh.positions[t[2]];
    ASSERT_GT((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]), 0.0f);  // counter-clockwise
  }
  std::mt19937 rng(6);
  for (int k = 0; k < 2000; ++k) {
    const std::size_t v = std::uniform_int_distribution<std::size_t>(0, mesh.positions.size() - 1)(rng);
    const auto& p = mesh.positions[v];
    const auto& n = mesh.normals[v];
    EXPECT_NEAR(n[0] * n[0] + n[1] * n[1] + n[2] * n[2], 1.0f, 1e-5f);
    EXPECT_GT(n[2], 0.0f);
    if (const auto h = terrain.height(p[0], p[1])) {
      EXPECT_NEAR(*h, p[2], 0.05);  // float positions
    }
  }
}

TEST(TerrainMesh, BudgetAndCrop) {
  const Terrain& terrain = helens();
  const TerrainMesh small = make_terrain_mesh(terrain, {.max_vertices = 5000, .crop = {}});
  EXPECT_LE(small.positions.size(), 5000u);
  EXPECT_GT(small.positions.size(), 2000u);
  EXPECT_GT(small.stride, 1);
  const Extent crop{-1000, -500, 1500, 2000};
  const TerrainMesh cropped = make_terrain_mesh(terrain, {.max_vertices = 0, .crop = crop});
  for (const auto& p : cropped.positions) ASSERT_TRUE(crop.contains(p[0], p[1]));
  EXPECT_NEAR(double(cropped.positions.size()), 2500.0 * 2500.0 / (30.0 * 30.0), 200.0);
  EXPECT_THROW(make_terrain_mesh(terrain, {.max_vertices = 0, .crop = Extent{1e6, 1e6, 1e6 + 10, 1e6 + 10}}), Error);
}

}  // namespace
}  // namespace wangscape
