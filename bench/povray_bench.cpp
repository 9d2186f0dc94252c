// POV-Ray export speed: a million flowers streamed into instances.inc (goal >= 2 M instances/s),
// and the bytes each instance costs. POV-Ray's own parse/render time and memory for 100 k and
// 1 M instances: bench/povray_render_bench.sh.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <numbers>
#include <sstream>

#include "exporters/povray_writer.h"
#include "templates/sunflower.h"

namespace wangscape {
namespace {

// `count` instances on a jittered grid, in batches of 64 k as placement streams them.
std::vector<InstanceBatch> make_batches(std::size_t count) {
  std::vector<InstanceBatch> batches;
  constexpr std::size_t kBatch = 1 << 16;
  std::uint64_t state = 12345;
  const auto next = [&] {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return float(state >> 40) / float(1 << 24);
  };
  const auto side = static_cast<std::size_t>(std::sqrt(double(count))) + 1;
  for (std::size_t i = 0; i < count; ++i) {
    if (i % kBatch == 0) batches.emplace_back();
    const float x = float(i % side) * 0.9f + next() * 0.5f, y = float(i / side) * 0.9f + next() * 0.5f;
    batches.back().push_back(x - 450.0f, y - 450.0f, 1100.0f + next() * 30.0f, next() * float(2 * std::numbers::pi),
                             0.9f + 0.2f * next(), std::uint16_t(i % 11), std::uint32_t(i % 8));
  }
  return batches;
}

// The whole folder (scene.pov, ini, models.inc with 11 small sunflowers, instances.inc), as
// `wangscape build` writes it, minus placement.
void BM_PovrayExportScene(benchmark::State& state) {
  const auto count = static_cast<std::size_t>(state.range(0));
  const auto batches = make_batches(count);
  Scene scene;
  for (const auto& model : make_sunflower_variants({11, 1, 400})) scene.models.push_back(model.mesh);
  scene.instances = [&](const std::function<void(const InstanceBatch&)>& sink) {
    for (const auto& b : batches) sink(b);
  };
  const auto dir = std::filesystem::temp_directory_path() / ("wangscape_povray_bench_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  PovrayExportStats stats;
  for (auto _ : state) stats = write_povray_scene(scene, dir, {});
  std::filesystem::remove_all(dir);
  state.counters["instances/s"] = benchmark::Counter(double(count), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["bytes/instance"] = double(stats.instance_bytes) / double(count);
}
BENCHMARK(BM_PovrayExportScene)->Arg(1'000'000)->Unit(benchmark::kMillisecond)->UseRealTime();

// The formatting loop alone, into memory.
void BM_PovrayInstanceFormatting(benchmark::State& state) {
  const auto count = static_cast<std::size_t>(state.range(0));
  const auto batches = make_batches(count);
  std::vector<std::string> model_names;  // the 11 variants make_batches uses
  for (int v = 0; v < 11; ++v) model_names.push_back("Sunflower_" + std::to_string(v));
  std::uint64_t bytes = 0;
  for (auto _ : state) {
    std::ostringstream out;
    PovrayInstanceWriter writer(out, model_names);
    for (const auto& b : batches) writer.write(b);
    writer.flush();
    bytes = writer.bytes();
  }
  state.counters["instances/s"] = benchmark::Counter(double(count), benchmark::Counter::kIsIterationInvariantRate);
  state.counters["bytes/instance"] = double(bytes) / double(count);
}
BENCHMARK(BM_PovrayInstanceFormatting)->Arg(1'000'000)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace wangscape

BENCHMARK_MAIN();
