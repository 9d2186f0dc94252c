// Opening a scene folder, as `wangscape view` and `render --engine embree` do, on the default
// scene (its field on Mount St. Helens with [exports] ldi; the folder is built once per run into
// a temporary folder: about 30 s, mostly the LDI pack):
// BM_OpenViewWorld: ViewWorld::load (the scene file, what the build kept for its readers, the
//   DEM, the models, the pack mapped and checked, the terrain's light and the far field) per
//   iteration. The goal (issue 21): under 1 s.
// BM_OpenFolderScene: SceneFolder::open and make_scene alone (the Scene as the build made it).
// BM_MakeSceneAgain: make_scene from the scene file, as readers did before scene.cache.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>

#include "folder/scene_folder.h"
#include "renders/scene_build.h"
#include "renders/view/view_world.h"
#include "scene/scene_file.h"

namespace {

using namespace wangscape;
namespace fs = std::filesystem;

fs::path built_folder;  // empty until a benchmark asks for it

const fs::path& default_folder() {
  if (built_folder.empty()) {
    SceneConfig config = default_scene_config();
    config.exports.ldi = true;
    built_folder = fs::temp_directory_path() / ("wangscape-open-bench-" + std::to_string(::getpid()));
    build_scene(config, built_folder);
  }
  return built_folder;
}

void BM_OpenViewWorld(benchmark::State& state) {
  const fs::path& dir = default_folder();
  for (auto _ : state) benchmark::DoNotOptimize(ViewWorld::load(dir));
}

void BM_OpenFolderScene(benchmark::State& state) {
  const fs::path& dir = default_folder();
  for (auto _ : state) benchmark::DoNotOptimize(SceneFolder::open(dir).make_scene());
}

void BM_MakeSceneAgain(benchmark::State& state) {
  const SceneConfig config = SceneFolder::open(default_folder(), SceneFolder::Parts::scene_file).config();
  for (auto _ : state) benchmark::DoNotOptimize(make_scene(config));
}

BENCHMARK(BM_OpenViewWorld)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(3);
BENCHMARK(BM_OpenFolderScene)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(3);
BENCHMARK(BM_MakeSceneAgain)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(3);

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  std::error_code ec;
  if (!built_folder.empty()) fs::remove_all(built_folder, ec);
  return 0;
}
