// Terrain figures (issue 4): loading SainteHelens.dem (goal < 0.5 s), height lookups,
// scatter over it with a height lookup per instance (goal >= 20 M instances/s), and the
// peak memory of a 100 M-instance streamed scatter (goal < 1 GB).
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <random>

#include "generator/placement.h"
#include "generator/poisson_tiles.h"
#include "terrain/mask.h"
#include "terrain/terrain.h"

namespace {

using namespace wangscape;

const std::filesystem::path kDem = std::filesystem::path(WANGSCAPE_SOURCE_DIR) / "data" / "SainteHelens.dem";

const Terrain& helens() {
  static const Terrain terrain = Terrain::load(kDem);
  return terrain;
}

const FilledTileSet& sunflower_tiles() {
  static const FilledTileSet filled = [] {
    PoissonFillOptions options;
    options.points_per_tile = 20;
    options.seed = 7;
    return fill_poisson_tiles(builtin_tileset("complete-edge-2"), options);
  }();
  return filled;
}

double peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_maxrss) / 1024.0;  // Linux: kilobytes
}

void BM_LoadSainteHelens(benchmark::State& state) {
  (void)Terrain::load(kDem);  // GDAL and PROJ start-up, once
  for (auto _ : state) {
    Terrain terrain = Terrain::load(kDem);
    benchmark::DoNotOptimize(terrain.extent());
  }
}
BENCHMARK(BM_LoadSainteHelens)->Unit(benchmark::kMillisecond);

void BM_HeightLookup(benchmark::State& state) {
  const Terrain& terrain = helens();
  const Extent e = terrain.extent();
  std::vector<double> xs(1 << 16), ys(1 << 16);
  std::mt19937 rng(1);
  for (std::size_t k = 0; k < xs.size(); ++k) {
    xs[k] = std::uniform_real_distribution<double>(e.min_x, e.max_x)(rng);
    ys[k] = std::uniform_real_distribution<double>(e.min_y, e.max_y)(rng);
  }
  double sum = 0;
  for (auto _ : state) {
    for (std::size_t k = 0; k < xs.size(); ++k) sum += terrain.height(xs[k], ys[k]).value_or(0.0);
    benchmark::DoNotOptimize(sum);
  }
  state.SetItemsProcessed(std::int64_t(state.iterations()) * std::int64_t(xs.size()));
}
BENCHMARK(BM_HeightLookup);

// Scatter over a window of the terrain, z from the DEM, below a 1500 m threshold when
// state.range(0) is 1 (the tile table and the point compare of Shade 2002).
void BM_ScatterWithHeight(benchmark::State& state) {
  const Terrain& terrain = helens();
  const FilledTileSet& filled = sunflower_tiles();
  const Terrain& ground = terrain;
  const bool threshold = state.range(0) != 0;
  const TerrainFilter filter(terrain, {.max_height_m = threshold ? std::optional(1500.0) : std::nullopt,
                                       .min_height_m = {},
                                       .max_slope_deg = {},
                                       .mask_image = {},
                                       .masks = {}});
  PlacementOptions options;
  options.tile_size = 4.0;
  options.algorithm = TilingAlgorithm::hash;
  options.area = Extent{-2000, -2000, 2000, 2000};  // 16 km^2, about 20 M instances unfiltered
  std::uint64_t instances = 0, tiles = 0;
  for (auto _ : state) {
    double checksum = 0;
    const auto sink = [&](const InstanceBatch& batch) { checksum += batch.z.front(); };
    PlacementStats stats;
    if (threshold)
      stats = place_instances(
          filled, ground, options, sink, [&](const TileCell& cell) { return filter.tile_passes(cell.bounds); },
          KeepAllPoints{});
    else
      stats = place_instances(filled, ground, options, sink);
    instances += stats.points;
    tiles += stats.tiles;
    benchmark::DoNotOptimize(checksum);
  }
  state.SetItemsProcessed(std::int64_t(instances));
  state.counters["instances_per_run"] = double(instances) / double(state.iterations());
  state.counters["tiles_per_second"] = benchmark::Counter(double(tiles), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ScatterWithHeight)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

// The same scatter over a flat plane: what placement costs without a DEM (for comparison).
void BM_ScatterFlatReference(benchmark::State& state) {
  const FilledTileSet& filled = sunflower_tiles();
  PlacementOptions options;
  options.tile_size = 4.0;
  options.algorithm = TilingAlgorithm::hash;
  const Extent window{-2000, -2000, 2000, 2000};
  options.area = window;
  std::uint64_t instances = 0;
  for (auto _ : state) {
    double checksum = 0;
    const auto stats = place_instances(filled, FlatGround{window, 100.0}, options,
                                       [&](const InstanceBatch& batch) { checksum += batch.z.front(); });
    instances += stats.points;
    benchmark::DoNotOptimize(checksum);
  }
  state.SetItemsProcessed(std::int64_t(instances));
}
BENCHMARK(BM_ScatterFlatReference)->Unit(benchmark::kMillisecond)->UseRealTime();

// 100 M instances streamed over the DEM: nothing holds them, so memory stays bounded.
void BM_Scatter100MPeakMemory(benchmark::State& state) {
  const Terrain& terrain = helens();
  const FilledTileSet& filled = sunflower_tiles();
  const Terrain& ground = terrain;
  PlacementOptions options;
  options.tile_size = 4.0;
  options.algorithm = TilingAlgorithm::hash;
  // 20 points per 16 m^2 tile: 100 M instances need 80 km^2 of ground with data.
  options.area = Extent{-4400, -4800, 4400, 4800};
  const double before = peak_rss_mb();
  std::uint64_t instances = 0;
  for (auto _ : state) {
    double checksum = 0;
    const auto stats =
        place_instances(filled, ground, options, [&](const InstanceBatch& batch) { checksum += batch.z.back(); });
    instances += stats.points;
    benchmark::DoNotOptimize(checksum);
  }
  state.SetItemsProcessed(std::int64_t(instances));
  state.counters["instances"] = double(instances) / double(state.iterations());
  state.counters["peak_rss_MB"] = peak_rss_mb();
  state.counters["peak_rss_before_MB"] = before;
}
BENCHMARK(BM_Scatter100MPeakMemory)->Iterations(1)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
