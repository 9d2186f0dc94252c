// Placement of a multi-class set (issue 26): the point filter sees each point's class and
// progressive rank, and interior variation draws each instance's variant inside its class.
#include <gtest/gtest.h>

#include <map>

#include "generator/placement.h"

namespace wangscape {
namespace {

FilledTileSet meadow() {
  PoissonFillOptions options;
  options.points_per_tile = 30;
  options.seed = 4;
  options.classes = {PoissonClass{.share = 0.7, .variants = 4, .exclusion = {}},
                     PoissonClass{.share = 0.3, .variants = 3, .exclusion = {}}};
  return fill_poisson_tiles(builtin_tileset("cohen8"), options);
}

// The class of each instance, from its variant (-1: none).
int class_of(const FilledTileSet& filled, int variant) { return class_of_variant(filled, variant).value_or(-1); }

TEST(PlacementClasses, ThePointFilterSeesClassAndRank) {
  const FilledTileSet filled = meadow();
  const FlatGround ground{{0, 0, 80, 80}, 0.0};
  PlacementOptions options;
  options.tile_size = 4;
  std::map<int, std::size_t> all, kept;
  place_instances(filled, ground, options, [&](const InstanceBatch& b) {
    for (std::size_t k = 0; k < b.size(); ++k) ++all[class_of(filled, b.variant[k])];
  });
  // Class 0 thinned to a quarter by rank, class 1 kept whole.
  place_instances(
      filled, ground, options,
      [&](const InstanceBatch& b) {
        for (std::size_t k = 0; k < b.size(); ++k) ++kept[class_of(filled, b.variant[k])];
      },
      KeepAllTiles{},
      [](double, double, double, std::uint8_t species, float rank) { return species == 1 || rank < 0.25f; });
  ASSERT_GT(all[0], 1000u);
  EXPECT_EQ(kept[1], all[1]);
  EXPECT_NEAR(double(kept[0]) / double(all[0]), 0.25, 0.03);
  EXPECT_EQ(all.count(-1), 0u);
}

TEST(PlacementClasses, InteriorVariationDrawsInsideTheClass) {
  const FilledTileSet filled = meadow();
  const FlatGround ground{{0, 0, 80, 80}, 0.0};
  PlacementOptions options;
  options.tile_size = 4;
  options.world_attributes =
      PlacementOptions::WorldAttributes{.seed = 5, .variants = 7, .min_scale = 1, .max_scale = 1};
  std::size_t placed = 0;
  std::map<std::uint16_t, std::size_t> by_variant;
  place_instances(filled, ground, options, [&](const InstanceBatch& b) {
    for (std::size_t k = 0; k < b.size(); ++k) ++by_variant[b.variant[k]], ++placed;
  });
  // Both classes' instances, every variant of each used, none outside 0..6.
  EXPECT_GT(placed, 1000u);
  EXPECT_EQ(by_variant.size(), 7u);
  EXPECT_LT(by_variant.rbegin()->first, 7);
  // Each point keeps its class under interior variation: the class counts match the plain placement's.
  std::map<int, std::size_t> placed_classes;
  for (const auto& [variant, n] : by_variant) placed_classes[class_of(filled, variant)] += n;
  std::size_t without = 0;
  std::map<int, std::size_t> plain_classes;
  options.world_attributes.reset();
  place_instances(filled, ground, options, [&](const InstanceBatch& b) {
    for (std::size_t k = 0; k < b.size(); ++k) ++plain_classes[class_of(filled, b.variant[k])], ++without;
  });
  EXPECT_EQ(without, placed);
  EXPECT_EQ(placed_classes, plain_classes);
}

}  // namespace
}  // namespace wangscape
