// Generation time of the sunflower models: the 11 default variants at a preview and a
// close-up triangle budget, and loading a close-up back from binary PLY through Assimp.
#include <benchmark/benchmark.h>

#include <cstdint>
#include <span>
#include <sstream>

#include "templates/mesh_io.h"
#include "templates/sunflower.h"

namespace {

void BM_SunflowerVariants(benchmark::State& state) {
  const wangscape::SunflowerOptions options{11, 1, std::size_t(state.range(0))};
  std::size_t triangles = 0;
  for (auto _ : state) {
    const auto models = wangscape::make_sunflower_variants(options);
    triangles = 0;
    for (const auto& model : models) triangles += model.mesh.triangle_count();
    benchmark::DoNotOptimize(triangles);
  }
  state.counters["triangles"] = double(triangles);
  state.counters["triangles_per_s"] =
      benchmark::Counter(double(triangles) * double(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_SunflowerVariants)->Arg(500)->Arg(35000)->Unit(benchmark::kMillisecond);

void BM_ReadPlyCloseUp(benchmark::State& state) {
  std::ostringstream out(std::ios::binary);
  wangscape::write_ply(out, wangscape::make_sunflower(1, 0, 35000).mesh);
  const std::string bytes = out.str();
  for (auto _ : state) {
    benchmark::DoNotOptimize(wangscape::read_model(
        std::span(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()), ".ply", "bench.ply"));
  }
  state.SetBytesProcessed(std::int64_t(bytes.size()) * state.iterations());
}
BENCHMARK(BM_ReadPlyCloseUp)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
