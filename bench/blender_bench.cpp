// Blender-side figures, measured with the real Blender (times inside Blender, without its
// ~1.5 s start): the add-on's import of 100 k and 1 M instances (geometry-nodes instancing,
// goal <= 5 s for 1 M), a Cycles render at 320x240, and for comparison the same field as one
// glTF node per flower imported by Blender's glTF importer at 10 k and 30 k flowers. Also the
// C++ export times. Each Blender case runs once (Iterations(1)); counters carry the details.
#include <benchmark/benchmark.h>

#include <fstream>
#include <map>
#include <sstream>

#include "exporters/blender_export.h"
#include "exporters/gltf_writer.h"
#include "renders/external/blender_render.h"
#include "renders/external/child_process.h"
#include "tests/blender/test_scene.h"

namespace wangscape {
namespace {

const std::filesystem::path kScratch = std::filesystem::temp_directory_path() / "wangscape_blender_bench";

// A field of `instances` flowers with about 16 flowers per square meter.
Scene bench_scene(std::uint64_t instances) {
  const float size = std::max(20.0f, float(std::sqrt(double(instances) / 16.0)));
  Scene scene = testing::make_test_scene(instances, 128, size, 65536);
  scene.render.width = 320;
  scene.render.height = 240;
  return scene;
}

// Runs blender_bench.py in Blender; returns its "bench: name value" lines.
std::map<std::string, double> run_blender(const std::vector<std::string>& script_args, benchmark::State& state) {
  const auto log = kScratch / "bench.log";
  std::filesystem::remove(log);
  std::vector<std::string> argv = {find_blender().string(),
                                   "-b",
                                   "--factory-startup",
                                   "--python-exit-code",
                                   "1",
                                   "--python",
                                   std::string(WANGSCAPE_SOURCE_DIR) + "/bench/blender_bench.py",
                                   "--"};
  argv.insert(argv.end(), script_args.begin(), script_args.end());
  const ChildExit exit = run_logged(argv, log);
  if (!exit.exited || exit.status != 0) {
    state.SkipWithError(("blender " + exit.describe() + ":" + last_log_lines(log, 10)).c_str());
    return {};
  }
  std::map<std::string, double> values;
  std::ifstream in(log);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("bench: ", 0) != 0) continue;
    std::istringstream fields(line.substr(7));
    std::string name;
    double value = 0;
    fields >> name >> value;
    values[name] = value;
  }
  state.counters["blender_process_s"] = exit.seconds;
  return values;
}

void BM_AddonImport(benchmark::State& state) {
  const auto count = std::uint64_t(state.range(0));
  const auto folder = kScratch / ("addon_" + std::to_string(count));
  std::filesystem::remove_all(folder);
  export_blender(bench_scene(count), folder);
  for (auto _ : state) {
    const auto values =
        run_blender({"addon", (folder / "wangscape_import.zip").string(), (folder / "manifest.json").string()}, state);
    if (values.empty()) return;
    state.SetIterationTime(values.at("import"));
    state.counters["instances"] = values.at("instances");
    state.counters["python_count_instances_s"] = values.at("count_instances");
  }
}
BENCHMARK(BM_AddonImport)->Arg(100'000)->Arg(1'000'000)->Iterations(1)->UseManualTime()->Unit(benchmark::kSecond);

void BM_CyclesRender320x240(benchmark::State& state) {
  const auto count = std::uint64_t(state.range(0));
  const auto folder = kScratch / ("cycles_" + std::to_string(count));
  std::filesystem::remove_all(folder);
  export_blender(bench_scene(count), folder);
  for (auto _ : state) {
    const auto values = run_blender(
        {"render", (folder / "wangscape_import.zip").string(), (folder / "manifest.json").string(), "320", "240"},
        state);
    if (values.empty()) return;
    state.SetIterationTime(values.at("render"));
    state.counters["samples"] = values.at("samples");
    state.counters["import_s"] = values.at("import");
  }
}
BENCHMARK(BM_CyclesRender320x240)->Arg(100'000)->Iterations(1)->UseManualTime()->Unit(benchmark::kSecond);

void BM_GltfNodePerFlowerImport(benchmark::State& state) {
  const auto count = std::uint64_t(state.range(0));
  const auto path = kScratch / ("nodes_" + std::to_string(count) + ".glb");
  GltfOptions options;
  options.instancing = GltfInstancing::node_per_instance;
  write_gltf(bench_scene(count), path, options);
  for (auto _ : state) {
    const auto values = run_blender({"gltf", path.string()}, state);
    if (values.empty()) return;
    state.SetIterationTime(values.at("import"));
    state.counters["objects"] = values.at("objects");
  }
}
BENCHMARK(BM_GltfNodePerFlowerImport)
    ->Arg(10'000)
    ->Arg(30'000)
    ->Iterations(1)
    ->UseManualTime()
    ->Unit(benchmark::kSecond);

// The C++ side: writing the arrays and the .glb for 1 M instances.
void BM_ExportBlenderArrays(benchmark::State& state) {
  const Scene scene = bench_scene(std::uint64_t(state.range(0)));
  for (auto _ : state) export_blender(scene, kScratch / "export_arrays");
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_ExportBlenderArrays)->Arg(1'000'000)->Unit(benchmark::kMillisecond);

void BM_ExportGltfInstanced(benchmark::State& state) {
  const Scene scene = bench_scene(std::uint64_t(state.range(0)));
  for (auto _ : state) write_gltf(scene, kScratch / "export.glb");
  state.SetItemsProcessed(state.iterations() * state.range(0));
}
BENCHMARK(BM_ExportGltfInstanced)->Arg(1'000'000)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace wangscape

int main(int argc, char** argv) {
  std::filesystem::create_directories(wangscape::kScratch);
  if (wangscape::find_blender().empty()) {
    std::fprintf(stderr, "blender_bench: the real blender is required (apt install blender)\n");
    return 1;
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
