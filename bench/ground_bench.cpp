// The ground look ([ground], scene/ground_look.h): milliseconds per megapixel to bake it over the
// default scene's DEM (Mount St. Helens), materials alone and with the quilted texture detail,
// and the cost of one color_at call (what the Embree reference and the LDI view will pay).
#include <benchmark/benchmark.h>

#include <chrono>

#include "scene/ground_look.h"
#include "scene/scene_ground.h"

namespace {

using namespace wangscape;

const SceneConfig& default_config() {
  static const SceneConfig config = default_scene_config();
  return config;
}

const SceneGround& helens() {
  static const SceneGround ground = SceneGround::load(default_config().terrain);
  return ground;
}

void run_bake(benchmark::State& state, const char* look) {
  SceneConfig config = default_config();
  config.ground->look = look;
  const GroundLook ground_look(*config.ground, load_ground_exemplars(config));
  const int pixels = static_cast<int>(state.range(0));
  double megapixels = 0, seconds = 0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    const GroundBake bake = bake_ground(ground_look, helens(), pixels);
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    megapixels = bake.image.width * double(bake.image.height) / 1e6;
    benchmark::DoNotOptimize(bake.image.pixels.data());
  }
  // Wall clock (the bake runs rows in parallel), milliseconds per megapixel of the baked image.
  state.counters["megapixels"] = megapixels;
  state.counters["ms_per_megapixel"] = 1e3 * seconds / static_cast<double>(state.iterations()) / megapixels;
}

void BM_BakeMaterials(benchmark::State& state) { run_bake(state, "materials"); }
void BM_BakeBoth(benchmark::State& state) { run_bake(state, "both"); }

void BM_ColorAt(benchmark::State& state) {
  const GroundLook look(*default_config().ground, load_ground_exemplars(default_config()));
  double x = 0;
  for (auto _ : state) {
    x += 1.37;
    benchmark::DoNotOptimize(look.color_at(x, 0.61 * x, 900 + 0.05 * x, 20));
  }
  state.SetItemsProcessed(state.iterations());
}

}  // namespace

BENCHMARK(BM_BakeMaterials)->Arg(1024)->Arg(2048)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_BakeBoth)->Arg(1024)->Arg(2048)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_ColorAt);
BENCHMARK_MAIN();
