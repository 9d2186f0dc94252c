// Multi-class Poisson tiles (issue 26): every class keeps its own spacing and every pair of
// classes its packing radii (plus exclusions) in every configuration of every tile set, the tight
// radius never crosses a corner, each class fills its share up to the borders, variants stay in
// their class, and edge objects sit across edges, the same in every tile with that edge.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <string>
#include <tuple>

#include "generator/point_metrics.h"
#include "generator/poisson_tiles.h"
#include "generator/tiling.h"

namespace wangscape {
namespace {

// A meadow-like set: grass (most points), flowers kept a little off the boulders, a few boulders.
PoissonFillOptions meadow_options(std::uint64_t seed, int points_per_tile = 24, bool boulders_on_edges = false) {
  PoissonFillOptions o;
  o.points_per_tile = points_per_tile;
  o.darts_per_visit = 2000;
  o.seed = seed;
  o.relax_rounds = seed % 3 == 0 ? 8 : 0;  // relaxation keeps every class's distances too
  PoissonClass grass{.share = 0.7, .variants = 4, .exclusion = {}};
  PoissonClass flower{.share = 0.25, .variants = 3, .exclusion = {0.0, 0.0, 0.05}};
  PoissonClass boulder{
      .share = 0.05, .packing_radius = 0.09, .variants = 2, .edge_objects = boulders_on_edges, .exclusion = {}};
  o.classes = {grass, flower, boulder};
  return o;
}

// Float positions: a pair may fall short of a double bound by the rounding of its coordinates.
constexpr double kFloatSlack = 1e-6;

const std::vector<std::string> kSets = {"cohen8", "cohen12", "corner-2", "complete-edge-2", "cohen8-corners"};

TEST(PoissonClasses, EveryClassPairKeepsItsDistanceInEveryConfiguration) {
  for (const std::string& name : kSets)
    for (std::uint64_t seed = 1; seed <= 6; ++seed) {
      SCOPED_TRACE(name + " seed " + std::to_string(seed));
      const PoissonFillOptions options = meadow_options(seed, 24, seed % 2 == 0);
      const FilledTileSet filled = fill_poisson_tiles(builtin_tileset(name), options);
      ASSERT_EQ(filled.classes.size(), 3u);
      // The distances the options ask for (class_fill_distances), not the fill's own report of them.
      const std::vector<double> required = class_fill_distances(options), least = class_min_distances(filled);
      ASSERT_EQ(least.size(), 9u);
      for (std::size_t a = 0; a < 3; ++a)
        for (std::size_t b = 0; b < 3; ++b)
          EXPECT_GE(least[a * 3 + b], required[a * 3 + b] - kFloatSlack) << a << " " << b;
      // The radii the fill reports come from the distances it measured: they are at least the ones
      // asked for (the boulders' 0.09), so the distances above are the options', not only the output's.
      EXPECT_GE(filled.classes[2].packing, 0.09 * (1 - 1e-5));
      // The union is Poisson at the total density: the default packing radius is the one class's.
      EXPECT_GE(filled.classes[0].spacing, 2.0 * filled.classes[0].packing);
      // A real tiling agrees with the configurations.
      TilingOptions tiling_options;
      tiling_options.seed = seed + 40;
      const Tiling tiling = make_tiling(filled.set, 16, 16, tiling_options);
      int close = 0;
      for (int j = 0; j < tiling.height; ++j)
        for (int i = 0; i < tiling.width; ++i)
          for (int dj = -1; dj <= 1; ++dj)
            for (int di = -1; di <= 1; ++di) {
              if (i + di < 0 || j + dj < 0 || i + di >= tiling.width || j + dj >= tiling.height) continue;
              for (const TilePoint& p : filled.tiles[tiling.at(i, j)])
                for (const TilePoint& q : filled.tiles[tiling.at(i + di, j + dj)]) {
                  if (di == 0 && dj == 0 && p.id == q.id) continue;
                  const double d = std::hypot(double(q.x) + di - p.x, double(q.y) + dj - p.y);
                  if (d < required[p.species * 3u + q.species] - kFloatSlack) ++close;
                }
            }
      EXPECT_EQ(close, 0);
    }
}

TEST(PoissonClasses, TightRadiusNeverCrossesACornerOfAPlainEdgeTile) {
  for (const std::string name : {"cohen8", "cohen12", "complete-edge-2"})
    for (std::uint64_t seed = 1; seed <= 4; ++seed) {
      const FilledTileSet filled = fill_poisson_tiles(builtin_tileset(name), meadow_options(seed));
      for (const auto& tile : filled.tiles)
        for (const TilePoint& p : tile) {
          const double tight = filled.classes[p.species].tight;
          ASSERT_GT(tight, 0.0);
          for (double cx : {0.0, 1.0})
            for (double cy : {0.0, 1.0})
              EXPECT_GE(std::hypot(p.x - cx, p.y - cy), tight * (1 - 1e-6)) << name << " class " << int(p.species);
        }
    }
}

// Per class: mean points per tile over the target, and edge / corner density over the interior
// in 48 x 48 tilings (zones one own spacing wide), over fill seeds 1..seeds.
struct ClassFill {
  double fill = 0, edge = 0, corner = 0;
};
std::vector<ClassFill> class_fill(const std::string& name, int seeds) {
  std::vector<ClassFill> out(3);
  for (int s = 1; s <= seeds; ++s) {
    const PoissonFillOptions options = meadow_options(static_cast<std::uint64_t>(s), 40);
    const FilledTileSet filled = fill_poisson_tiles(builtin_tileset(name), options);
    TilingOptions tiling_options;
    tiling_options.seed = 100 + static_cast<std::uint64_t>(s);
    const Tiling tiling = make_tiling(filled.set, 48, 48, tiling_options);
    for (std::size_t c = 0; c < 3; ++c) {
      std::vector<float> x, y;
      for (int j = 0; j < tiling.height; ++j)
        for (int i = 0; i < tiling.width; ++i)
          for (const TilePoint& p : filled.tiles[tiling.at(i, j)])
            if (p.species == c) {
              x.push_back(static_cast<float>(i + p.x));
              y.push_back(static_cast<float>(j + p.y));
            }
      PointMetricsOptions metrics;
      metrics.area = {0, 0, double(tiling.width), double(tiling.height)};
      metrics.packing_diameter = filled.classes[c].spacing;
      metrics.zone_width = std::min(filled.classes[c].spacing, 0.3);
      metrics.spectrum = false;
      const PointMetrics m = measure_points(x, y, metrics);
      const double target = options.points_per_tile * options.classes[c].share;
      out[c].fill += double(x.size()) / (tiling.width * tiling.height) / target / seeds;
      out[c].edge += m.edge_density_ratio / seeds;
      out[c].corner += m.corner_density_ratio / seeds;
      EXPECT_EQ(m.close_pairs, 0u) << name << " class " << c;
    }
  }
  return out;
}

TEST(PoissonClasses, EveryClassFillsItsShareUpToTheTileBorders) {
  for (const std::string name : {"cohen8", "corner-2"}) {
    const std::vector<ClassFill> fill = class_fill(name, 6);
    for (std::size_t c = 0; c < 3; ++c) {
      std::printf("%s class %zu: fill %.3f edge %.3f corner %.3f\n", name.c_str(), c, fill[c].fill, fill[c].edge,
                  fill[c].corner);
      EXPECT_GT(fill[c].fill, 0.85) << name << " class " << c;
      EXPECT_LT(fill[c].fill, 1.05) << name << " class " << c;
      // Two boulders a tile: their zones hold too few for a ratio. The others within 0.3 (measured
      // 0.82..1.26; with the classes taken in turn at each tile visit, cohen8's flowers had 0.48
      // in the corners).
      if (c == 2) continue;
      EXPECT_NEAR(fill[c].edge, 1.0, 0.3) << name << " class " << c;
      EXPECT_NEAR(fill[c].corner, 1.0, 0.3) << name << " class " << c;
    }
  }
}

TEST(PoissonClasses, VariantsAndAttributesFollowTheirClass) {
  const PoissonFillOptions options = meadow_options(3);
  const FilledTileSet filled = fill_poisson_tiles(builtin_tileset("cohen8"), options);
  EXPECT_EQ(filled.variants, 9);
  EXPECT_EQ(class_variant_range(filled, 0), std::pair(0, 4));
  EXPECT_EQ(class_variant_range(filled, 1), std::pair(4, 3));
  EXPECT_EQ(class_variant_range(filled, 2), std::pair(7, 2));
  std::set<int> seen_species;
  for (const auto& tile : filled.tiles)
    for (const TilePoint& p : tile) {
      seen_species.insert(p.species);
      const auto [first, count] = class_variant_range(filled, p.species);
      EXPECT_GE(p.variant, first);
      EXPECT_LT(p.variant, first + count);
    }
  EXPECT_EQ(seen_species.size(), 3u);
}

TEST(PoissonClasses, OneExplicitClassIsTheSingleClassFill) {
  for (const std::string name : {"cohen8", "corner-2"}) {
    PoissonFillOptions options;
    options.points_per_tile = 12;
    options.relax_rounds = 4;
    const FilledTileSet plain = fill_poisson_tiles(builtin_tileset(name), options);
    options.classes = {PoissonClass{.share = 3.0, .variants = options.variants, .exclusion = {}}};
    const FilledTileSet one = fill_poisson_tiles(builtin_tileset(name), options);
    EXPECT_EQ(plain.tiles, one.tiles) << name;
    ASSERT_EQ(plain.classes.size(), 1u);
    EXPECT_EQ(class_variant_range(plain, 0), std::pair(0, options.variants));
  }
}

// The sides of a tile as (side, edge color, end-corner colors): tiles with equal keys on a side
// hold the same edge objects across it.
using SideKey = std::tuple<int, int, int, int>;
SideKey side_key(const Tile& t, int side) {
  switch (side) {
    case 0:
      return {0, t.s(), t.sw(), t.se()};
    case 1:
      return {1, t.n(), t.nw(), t.ne()};
    case 2:
      return {2, t.w(), t.sw(), t.nw()};
    default:
      return {3, t.e(), t.se(), t.ne()};
  }
}

TEST(PoissonClasses, EdgeObjectsCrossAnEdgeNeverACornerAndAreTheSameInEveryTileWithThatEdge) {
  std::size_t compared = 0, objects = 0;
  for (const std::string name : {"cohen8", "corner-2", "complete-edge-2"})
    for (std::uint64_t seed = 1; seed <= 4; ++seed) {
      SCOPED_TRACE(name + " seed " + std::to_string(seed));
      const FilledTileSet filled = fill_poisson_tiles(builtin_tileset(name), meadow_options(seed, 24, true));
      ASSERT_TRUE(filled.classes[2].edge_objects);
      const double tight = filled.classes[2].tight;
      std::map<SideKey, std::vector<std::tuple<std::uint32_t, float, float>>> by_side;
      for (std::size_t t = 0; t < filled.tiles.size(); ++t) {
        std::array<std::vector<std::tuple<std::uint32_t, float, float>>, 4> crossing;
        for (const TilePoint& p : filled.tiles[t]) {
          if (p.species != 2) continue;
          ++objects;
          const double to_side[4] = {p.y, 1.0 - p.y, p.x, 1.0 - p.x};
          int sides = 0;
          for (int side = 0; side < 4; ++side)
            if (to_side[side] < tight) ++sides, crossing[static_cast<std::size_t>(side)].push_back({p.id, p.x, p.y});
          EXPECT_EQ(sides, 1) << "an edge object crosses exactly one edge";
          for (double cx : {0.0, 1.0})
            for (double cy : {0.0, 1.0}) EXPECT_GE(std::hypot(p.x - cx, p.y - cy), tight * (1 - 1e-6));
        }
        for (int side = 0; side < 4; ++side) {
          auto [it, inserted] = by_side.emplace(side_key(filled.set.tiles[t], side), crossing[std::size_t(side)]);
          if (inserted) continue;
          EXPECT_EQ(it->second, crossing[std::size_t(side)]) << "tile " << t << " side " << side;
          ++compared;
        }
      }
    }
  EXPECT_GT(objects, 100u);
  EXPECT_GT(compared, 100u);
}

TEST(PoissonClasses, RelaxationRaisesEveryClassDistanceByOneFactor) {
  double mean_gain = 0;
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    PoissonFillOptions options = meadow_options(seed, 40);
    options.relax_rounds = 0;
    const FilledTileSet darts = fill_poisson_tiles(builtin_tileset("cohen8"), options);
    options.relax_rounds = 8;
    const FilledTileSet relaxed = fill_poisson_tiles(builtin_tileset("cohen8"), options);
    const double gain = relaxed.classes[0].packing / darts.classes[0].packing;
    EXPECT_GE(relaxed.classes[2].packing, 0.09 * (1 - 1e-5));  // the boulders' radius asked for
    const std::vector<double> required = class_fill_distances(options), least = class_min_distances(relaxed);
    for (std::size_t a = 0; a < 3; ++a)
      for (std::size_t b = 0; b < 3; ++b)
        EXPECT_GE(least[a * 3 + b], required[a * 3 + b] - kFloatSlack) << a << " " << b;
    std::printf("seed %d: relaxation raised every distance by %.3f\n", int(seed), gain);
    mean_gain += gain / 4;
  }
  // Measured 1.06-1.13 (mean 1.11); before relaxation took several classes, 1.
  EXPECT_GT(mean_gain, 1.05);
}

TEST(PoissonClasses, RejectsBadClasses) {
  PoissonFillOptions options = meadow_options(1);
  options.classes[1].share = 0;
  EXPECT_THROW(fill_poisson_tiles(builtin_tileset("cohen8"), options), Error);
  options = meadow_options(1);
  options.classes[2].packing_radius = 0.6;
  EXPECT_THROW(fill_poisson_tiles(builtin_tileset("cohen8"), options), Error);
  options = meadow_options(1);
  options.classes[0].exclusion = {0, 0, 0, 0};  // more than one per class
  EXPECT_THROW(fill_poisson_tiles(builtin_tileset("cohen8"), options), Error);
}

}  // namespace
}  // namespace wangscape
