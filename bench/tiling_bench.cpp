// Tiles per second for 10,000 x 10,000-tile tilings (Shade 2002 made tilings "ten thousand tiles
// on a side"). Streamed row by row, so memory stays O(row): the sink only folds each row into a
// checksum so the work cannot be optimised away. Then the time of one hashed tile_at without
// identical neighbours.
#include <benchmark/benchmark.h>

#include <cstdint>

#include "generator/tiling.h"

namespace {

using wangscape::TilingAlgorithm;

constexpr int kSide = 10'000;

void run(benchmark::State& state, const char* set_name, TilingAlgorithm algorithm) {
  const wangscape::TileSet set = wangscape::builtin_tileset(set_name);
  wangscape::TilingOptions options;
  options.algorithm = algorithm;
  for (auto _ : state) {
    std::uint64_t checksum = 0;
    wangscape::stream_tiling(set, kSide, kSide, options, [&](int, std::span<const std::uint16_t> row) {
      checksum += row.front() + row.back() + row[row.size() / 2];
    });
    benchmark::DoNotOptimize(checksum);
    ++options.seed;
  }
  state.SetItemsProcessed(state.iterations() * std::int64_t{kSide} * kSide);
  state.SetLabel("tiles/s = items_per_second");
}

void BM_ScanlineCohen8(benchmark::State& state) { run(state, "cohen8", TilingAlgorithm::scanline); }
void BM_ScanlineCohen18(benchmark::State& state) { run(state, "cohen18", TilingAlgorithm::scanline); }
void BM_BottomLeftCohen8(benchmark::State& state) { run(state, "cohen8", TilingAlgorithm::bottom_left); }
void BM_HashCompleteEdge2(benchmark::State& state) { run(state, "complete-edge-2", TilingAlgorithm::hash); }
void BM_HashCorner2(benchmark::State& state) { run(state, "corner-2", TilingAlgorithm::hash); }
// Culik's aperiodic 13 tiles, one row at a time from a real in 128-bit fixed point.
void BM_AperiodicCulik13(benchmark::State& state) { run(state, "culik13", TilingAlgorithm::aperiodic); }

// The whole tiling in memory (2 bytes per tile): what `wangscape tiling` does.
void BM_MakeTilingHashCompleteEdge2(benchmark::State& state) {
  const wangscape::TileSet set = wangscape::builtin_tileset("complete-edge-2");
  wangscape::TilingOptions options;
  options.algorithm = TilingAlgorithm::hash;
  for (auto _ : state) benchmark::DoNotOptimize(wangscape::make_tiling(set, kSide, kSide, options).tiles.data());
  state.SetItemsProcessed(state.iterations() * std::int64_t{kSide} * kSide);
}

// Random access with forbid_identical_neighbours: one HashedTiling::tile_at repairs the colors of a
// patch around its tile (the margin in generator/tiling_hashed.cpp), so this is the cost of that patch.
void tile_at_without_identical_neighbours(benchmark::State& state, const char* set_name) {
  const wangscape::HashedTiling hashed(wangscape::builtin_tileset(set_name), 1, true);
  std::int64_t i = -1'000'003;
  for (auto _ : state) {
    benchmark::DoNotOptimize(hashed.tile_at(i, 7 * i));
    i += 7919;  // a fresh place each call
  }
  state.SetItemsProcessed(state.iterations());
}
void BM_TileAtForbidCompleteEdge2(benchmark::State& state) {
  tile_at_without_identical_neighbours(state, "complete-edge-2");
}
void BM_TileAtForbidCorner2(benchmark::State& state) { tile_at_without_identical_neighbours(state, "corner-2"); }

BENCHMARK(BM_ScanlineCohen8)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ScanlineCohen18)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_BottomLeftCohen8)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_HashCompleteEdge2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_HashCorner2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_AperiodicCulik13)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_MakeTilingHashCompleteEdge2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_TileAtForbidCompleteEdge2)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_TileAtForbidCorner2)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
