// The tiles' plan alone (renders/view/tile_plan.h, issue 36): a pure function of the world, the
// camera and the settings, checked without drawing a frame.
#include "renders/view/tile_plan.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>

#include "tests/renders/view_test_world.h"

namespace wangscape {
namespace {

using view_test::field;
using view_test::looking;
using view_test::tiny_world;

ViewProjection projection(const Camera& camera) { return ViewProjection::of(camera, 160, 90); }

// At head height looking north across the field: the tiles behind the eye are culled, the near
// field's tiles are not warped, the rest are warped back to front with their level growing with
// their distance, and a mask leaves its tiles out.
TEST(TilePlan, HeadHeightNorthwardBackToFrontLevelsByDistance) {
  const ViewWorld& world = *field();
  const Camera camera = looking(0, -2, 1.7, 0, 10, 1.0);
  TilePlan plan;
  plan_tiles(world, projection(camera), {1.0, 3.0, nullptr}, plan);
  const ViewWorld::Tiles& tiles = world.tiles();
  ASSERT_EQ(plan.flags.size(), tiles.size());
  EXPECT_GT(plan.culled, 0u);
  EXPECT_GT(plan.near, 0u);
  EXPECT_EQ(plan.drawn + plan.culled, tiles.size());
  for (std::size_t t = 0; t < tiles.size(); ++t) {
    const bool behind = tiles.y0[t] + world.tile_size() < -2.5;
    EXPECT_TRUE(!behind || !(plan.flags[t] & TilePlan::kInView)) << t;
  }
  ASSERT_FALSE(plan.order.empty());
  for (std::size_t k = 0; k < plan.order.size(); ++k) {
    const std::uint32_t t = plan.order[k];
    EXPECT_TRUE(plan.flags[t] & TilePlan::kInView);
    EXPECT_FALSE(plan.flags[t] & TilePlan::kNear);
    EXPECT_GE(plan.distance[t], 3.0f);
    if (k > 0) {
      const std::uint32_t before = plan.order[k - 1];
      EXPECT_GE(plan.distance[before], plan.distance[t]);  // back to front
      EXPECT_GE(plan.level_a[before], plan.level_a[t]);    // farther: the same level or coarser
    }
  }
  EXPECT_FALSE(plan.any_steep);  // from head height, the pack's own LDIs
  // A mask keeping one tile of those warped.
  std::vector<std::uint8_t> mask(tiles.size(), 0);
  const std::uint32_t kept = plan.order.front();
  mask[kept] = 1;
  TilePlan masked;
  plan_tiles(world, projection(camera), {1.0, 3.0, &mask}, masked);
  EXPECT_EQ(masked.order, std::vector<std::uint32_t>{kept});
  EXPECT_EQ(masked.drawn, plan.drawn);  // counted all the same
}

// From above, the steep sets stand in; the plan is the same on one thread and on two.
TEST(TilePlan, FromAboveTheSteepSetsTheSameOnAnyThreadCount) {
  static const auto world = tiny_world("[-40.0, -8.0, 40.0, 120.0]", "plan_above", "300.0");
  const ViewProjection view = projection(looking(0, -10, 20, 0, 40, 1.0, 60));
  TilePlan two;
  plan_tiles(*world, view, {}, two);
  EXPECT_TRUE(two.any_steep);
  EXPECT_GT(two.steep_tiles, two.drawn / 2);
  TilePlan one;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    plan_tiles(*world, view, {}, one);
  }
  EXPECT_EQ(one.order, two.order);
  EXPECT_EQ(one.level_a, two.level_a);
  EXPECT_EQ(one.steep, two.steep);
  EXPECT_EQ(one.dir_a, two.dir_a);
  EXPECT_EQ(one.flags, two.flags);
}

}  // namespace
}  // namespace wangscape
