// Poisson-disk tiles: the distance bound holds in real tilings of every built-in set, replicas
// are one point, the fill is deterministic on any thread count, and relaxation raises rho.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include "generator/point_metrics.h"
#include "generator/poisson_tiles.h"
#include "generator/tiling.h"

namespace wangscape {
namespace {

// Small fills: few points per tile keep the whole suite fast and still cross every border.
PoissonFillOptions small_options(std::uint64_t seed, int relax_rounds = 0) {
  PoissonFillOptions o;
  o.points_per_tile = 6;
  o.darts_per_visit = 1000;
  o.seed = seed;
  o.relax_rounds = relax_rounds;
  return o;
}

// Pairs of point instances closer than `diameter` in `tiling`, in double precision from the
// tile-local positions (no float rounding of world coordinates).
int close_pairs_in_tiling(const FilledTileSet& filled, const Tiling& tiling, double diameter) {
  int close = 0;
  for (int j = 0; j < tiling.height; ++j)
    for (int i = 0; i < tiling.width; ++i)
      for (int dj = 0; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) {
          if (dj == 0 && di < 0) continue;  // each neighbouring pair of tiles once
          const int a = i + di, b = j + dj;
          if (a < 0 || b >= tiling.height || a >= tiling.width) continue;
          const auto& own = filled.tiles[tiling.at(i, j)];
          const auto& other = filled.tiles[tiling.at(a, b)];
          for (std::size_t p = 0; p < own.size(); ++p)
            for (std::size_t q = (di == 0 && dj == 0) ? p + 1 : 0; q < other.size(); ++q) {
              const double dx = double(other[q].x) + di - own[p].x, dy = double(other[q].y) + dj - own[p].y;
              if (std::hypot(dx, dy) < diameter) ++close;
            }
        }
  return close;
}

bool is_complete(const TileSet& set) {
  try {
    HashedTiling probe(set, 1);
    return true;
  } catch (const Error&) {
    return false;
  }
}

TEST(PoissonTiles, NoPairCloserThanPackingDiameterInAnyTilingOfEveryBuiltinSet) {
  for (const std::string& name : builtin_tileset_names()) {
    const TileSet set = builtin_tileset(name);
    const bool complete = is_complete(set);
    for (std::uint64_t seed = 1; seed <= 6; ++seed) {
      SCOPED_TRACE(name + " seed " + std::to_string(seed));
      const FilledTileSet filled = fill_poisson_tiles(set, small_options(seed, seed % 2 == 0 ? 8 : 0));
      const double diameter = 2.0 * filled.radius_packing;
      ASSERT_GT(diameter, 0.0);
      EXPECT_GE(min_distance_over_configurations(filled), diameter);
      for (std::uint64_t tiling_seed = 1; tiling_seed <= 2; ++tiling_seed) {
        TilingOptions options;
        options.seed = tiling_seed * 31 + seed;
        if (name == "culik13") options.algorithm = TilingAlgorithm::aperiodic;  // its only algorithm
        const Tiling swept = make_tiling(set, 32, 32, options);
        EXPECT_EQ(close_pairs_in_tiling(filled, swept, diameter), 0) << to_string(options.algorithm);
        if (complete) {
          options.algorithm = TilingAlgorithm::hash;
          options.origin_i = -1000 * static_cast<std::int64_t>(tiling_seed);
          const Tiling hashed = make_tiling(set, 32, 32, options);
          EXPECT_EQ(close_pairs_in_tiling(filled, hashed, diameter), 0) << "hash";
        }
      }
    }
  }
}

TEST(PoissonTiles, ReplicatedPointsAreIdenticalEverywhere) {
  for (const std::string name : {"cohen8", "owen12", "corner-2", "cohen8-corners"}) {
    SCOPED_TRACE(name);
    const PoissonFillOptions options = small_options(5, 6);
    const FilledTileSet filled = fill_poisson_tiles(builtin_tileset(name), options);
    std::map<std::uint32_t, TilePoint> first_seen;
    int replicated = 0;
    for (const auto& tile : filled.tiles)
      for (const TilePoint& p : tile) {
        const PointAttributes a =
            point_attributes(options.seed, p.id, options.variants, options.min_scale, options.max_scale);
        EXPECT_EQ(p.variant, a.variant);
        EXPECT_EQ(p.yaw, a.yaw);
        EXPECT_EQ(p.scale, a.scale);
        auto [it, inserted] = first_seen.emplace(p.id, p);
        if (inserted) continue;
        ++replicated;
        EXPECT_EQ(it->second, p) << "point " << p.id;
      }
    EXPECT_GT(replicated, 0) << "strips shared by color must replicate points";
  }
}

TEST(PoissonTiles, TilesSharingAnEdgeColorShareTheEdgeStrip) {
  // Points within half the shared width of the south edge (away from the corners) are strip
  // points: every tile with the same south color holds the same ones (Shade 2002's replication).
  std::size_t compared = 0;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    PoissonFillOptions options;
    options.seed = seed;
    const FilledTileSet filled = fill_poisson_tiles(builtin_tileset("cohen8"), options);
    const double band = 0.5 * filled.shared_width;
    std::map<int, std::vector<std::uint32_t>> strip_by_color;
    for (std::size_t t = 0; t < filled.tiles.size(); ++t) {
      std::vector<std::uint32_t> ids;
      for (const TilePoint& p : filled.tiles[t])
        if (p.y < band && p.x > filled.shared_width && p.x < 1 - filled.shared_width) ids.push_back(p.id);
      auto [it, inserted] = strip_by_color.emplace(filled.set.tiles[t].s(), ids);
      if (!inserted) {
        EXPECT_EQ(it->second, ids) << "seed " << seed << " tile " << t;
        compared += ids.size();
      }
    }
  }
  EXPECT_GT(compared, 0u) << "no strip points to compare";
}

std::string fill_bytes(const TileSet& set, const PoissonFillOptions& options) {
  const FilledTileSet filled = fill_poisson_tiles(set, options);
  std::string bytes;
  auto put = [&bytes](const auto& value) { bytes.append(reinterpret_cast<const char*>(&value), sizeof(value)); };
  for (const auto& tile : filled.tiles)
    for (const TilePoint& p : tile) {
      put(p.x), put(p.y), put(p.yaw), put(p.scale), put(p.variant), put(p.id);
    }
  put(filled.radius_packing);
  return bytes;
}

TEST(PoissonTiles, SameSeedSameBytesOnOneAndTwoThreads) {
  for (const std::string name : {"cohen8", "corner-2"}) {
    PoissonFillOptions options;
    options.points_per_tile = 12;
    options.relax_rounds = 10;
    options.seed = 42;
    std::string one, two;
    {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
      one = fill_bytes(builtin_tileset(name), options);
    }
    {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
      two = fill_bytes(builtin_tileset(name), options);
    }
    EXPECT_EQ(one, two) << name;
    options.seed = 43;
    EXPECT_NE(one, fill_bytes(builtin_tileset(name), options)) << name << ": the seed must matter";
  }
}

TEST(PoissonTiles, RelaxationRaisesRhoAndStopsBeforeALattice) {
  for (const std::string name : {"cohen8", "corner-2", "cohen12"}) {
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      SCOPED_TRACE(name + " seed " + std::to_string(seed));
      PoissonFillOptions options;
      options.seed = seed;
      PoissonFillReport darts, relaxed;
      const FilledTileSet a = fill_poisson_tiles(builtin_tileset(name), options, &darts);
      options.relax_rounds = 60;
      const FilledTileSet b = fill_poisson_tiles(builtin_tileset(name), options, &relaxed);
      const double spacing = hexagonal_spacing(1.0, options.points_per_tile);
      EXPECT_GT(a.radius_packing * 2 / spacing, 0.70);
      EXPECT_GT(b.radius_packing, a.radius_packing * 1.08) << "relaxation must raise rho, not just move points";
      EXPECT_GE(relaxed.nn_spread, options.min_nn_spread);
      EXPECT_GT(relaxed.relax_rounds_run, 0);
    }
  }
}

TEST(PoissonTiles, TightRadiusNeverCrossesACornerOfAPlainEdgeTile) {
  const FilledTileSet filled = fill_poisson_tiles(builtin_tileset("cohen18"), small_options(9, 5));
  ASSERT_GT(filled.radius_tight, 0.0);
  for (const auto& tile : filled.tiles)
    for (const TilePoint& p : tile)
      for (double cx : {0.0, 1.0})
        for (double cy : {0.0, 1.0}) EXPECT_GE(std::hypot(p.x - cx, p.y - cy), filled.radius_tight * (1 - 1e-6));
}

TEST(PoissonTiles, TilesReachTheirTargetCount) {
  PoissonFillOptions options;
  options.points_per_tile = 20;
  const FilledTileSet filled = fill_poisson_tiles(builtin_tileset("cohen8"), options);
  for (const auto& tile : filled.tiles) {
    EXPECT_GE(tile.size(), 16u);
    EXPECT_LE(tile.size(), 24u);
  }
}

// Mean edge and corner densities over the interior's (point_metrics, zones one packing diameter
// wide) of 32 x 32 scanline tilings of `name` filled with 20 points per tile, over fill seeds
// 1..seeds: one seed's figures scatter by about 0.1 (8 tiles of 20 points), the mean does not.
std::pair<double, double> mean_edge_corner_density(const std::string& name, int relax_rounds, int seeds) {
  double edge = 0, corner = 0;
  for (int s = 1; s <= seeds; ++s) {
    PoissonFillOptions options;
    options.seed = static_cast<std::uint64_t>(s);
    options.relax_rounds = relax_rounds;
    const FilledTileSet filled = fill_poisson_tiles(builtin_tileset(name), options);
    TilingOptions tiling_options;
    tiling_options.seed = 100 + static_cast<std::uint64_t>(s);
    const Tiling tiling = make_tiling(filled.set, 32, 32, tiling_options);
    std::vector<float> x, y;
    for (int j = 0; j < tiling.height; ++j)
      for (int i = 0; i < tiling.width; ++i)
        for (const TilePoint& p : filled.tiles[tiling.at(i, j)]) {
          x.push_back(static_cast<float>(i + p.x));
          y.push_back(static_cast<float>(j + p.y));
        }
    PointMetricsOptions metrics;
    metrics.area = {0, 0, double(tiling.width), double(tiling.height)};
    metrics.packing_diameter = 2 * filled.radius_packing;
    metrics.spectrum = false;
    const PointMetrics m = measure_points(x, y, metrics);
    edge += m.edge_density_ratio / seeds;
    corner += m.corner_density_ratio / seeds;
  }
  return {edge, corner};
}

TEST(PoissonTiles, EdgeAndCornerDensitiesMatchTheInteriorInPlainEdgeSets) {
  // The issue-3 goal (within 5 % of the interior after relaxation), for cohen8; darts alone and
  // the 12-tile set within 7 %. Before the strip quotas and wider strips: cohen8 0.95 / 0.93
  // after relaxation (edge / corner), so the band can fail.
  const auto [edge, corner] = mean_edge_corner_density("cohen8", 100, 16);
  EXPECT_NEAR(edge, 1.0, 0.05);
  EXPECT_NEAR(corner, 1.0, 0.05);
  const auto [dart_edge, dart_corner] = mean_edge_corner_density("cohen8", 0, 16);
  EXPECT_NEAR(dart_edge, 1.0, 0.07);
  EXPECT_NEAR(dart_corner, 1.0, 0.07);
  const auto [edge12, corner12] = mean_edge_corner_density("cohen12", 100, 8);
  EXPECT_NEAR(edge12, 1.0, 0.07);
  EXPECT_NEAR(corner12, 1.0, 0.07);
  std::printf("cohen8 relaxed edge %.3f corner %.3f, darts %.3f %.3f; cohen12 relaxed %.3f %.3f\n", edge, corner,
              dart_edge, dart_corner, edge12, corner12);
}

TEST(PoissonTiles, RejectsBadOptions) {
  PoissonFillOptions options;
  options.points_per_tile = 0;
  EXPECT_THROW(fill_poisson_tiles(builtin_tileset("cohen8"), options), Error);
  options.points_per_tile = 20;
  options.dart_rho = 1.5;
  EXPECT_THROW(fill_poisson_tiles(builtin_tileset("cohen8"), options), Error);
}

TEST(TileAdjacency, EdgeNeighboursShareTheEdgeAndDiagonalsCompleteABlock) {
  const TileSet set = builtin_tileset("cohen8");
  const TileAdjacency adjacency(set);
  for (std::size_t t = 0; t < set.tiles.size(); ++t) {
    for (std::uint16_t u : adjacency.neighbours(t, 1, 0)) EXPECT_EQ(set.tiles[t].e(), set.tiles[u].w());
    for (std::uint16_t u : adjacency.neighbours(t, 0, -1)) EXPECT_EQ(set.tiles[t].s(), set.tiles[u].n());
    // cohen8 holds every pair of adjacent edge colors, so any tile can sit across a corner.
    EXPECT_EQ(adjacency.neighbours(t, 1, 1).size(), set.tiles.size());
  }
}

}  // namespace
}  // namespace wangscape
