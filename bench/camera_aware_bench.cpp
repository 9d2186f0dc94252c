// Placement of the whole St. Helens DEM below 1,200 m (templates/scenes/whole-dem.toml) against
// the camera's far distance: the time of one run of the instance stream (the tile test, the
// masks and the points of the visible tiles), with the visible tiles and the flowers as
// counters. It should follow the visible tiles, not the 8.4 million tiles of the DEM. The
// scene is assembled once per distance, outside the timing (no ground bake). The scene's
// scanline tiling is computed over the whole field on every run (2 bytes a tile, the fixed
// part); the hashed tiling (second argument 1: complete-edge-2) only over the window.
//   build/release/bench/camera_aware_bench --benchmark_min_time=0.5
#include <benchmark/benchmark.h>

#include <string>

#include "scene/scene.h"
#include "scene/scene_file.h"

namespace wangscape {
namespace {

void BM_WholeDemPlacement(benchmark::State& state) {
  SceneConfig config = load_scene_config(std::string(WANGSCAPE_SOURCE_DIR) + "/templates/scenes/whole-dem.toml");
  config.camera_aware.far = static_cast<double>(state.range(0));
  config.camera_aware.far_texture = false;
  config.ground.reset();
  if (state.range(1)) {
    config.tiles.set = "complete-edge-2";
    config.tiles.algorithm = TilingAlgorithm::hash;
  }
  const Scene scene = make_scene(config);
  std::uint64_t flowers = 0;
  for (auto _ : state) {
    flowers = 0;
    scene.instances([&](const InstanceBatch& batch) { flowers += batch.size(); });
  }
  state.counters["visible_tiles"] = double(scene.last_placement->visible_tiles);
  state.counters["flowers"] = double(flowers);
  state.counters["field_tiles"] = double(scene.last_placement->field_tiles);
}
BENCHMARK(BM_WholeDemPlacement)
    ->ArgsProduct({{50, 100, 200, 400, 800}, {0, 1}})
    ->ArgNames({"far", "hash"})
    ->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace wangscape

BENCHMARK_MAIN();
