// The real-time LDI view on the default scene (its field on Mount St. Helens, the pack built once
// per run into a temporary file: about 25 s), from three cameras at 640 x 360 and 1280 x 720:
//  - camera 0, the scene's own: at the field's northern edge, looking south across it;
//  - camera 1, in the field: 300 m inside, at head height, looking the same way;
//  - camera 2, above the field: 25 m up, looking down into it.
// BM_ViewFrame/CAMERA/W/H: one LdiRenderer::render per iteration. Counters: fps, depth pixels
//   per second (M), the tiles drawn and the median milliseconds of each phase (tiles, LDIs,
//   terrain, resolve), which say what limits the frame.
// BM_ViewAgainstReference/CAMERA/W/H: one Embree reference frame of the same view (the scene's
//   4 samples per pixel, the pack's light); counters: its seconds, the LDI frame's (median of
//   20), their ratio, PSNR (dB), SSIM and the share of hole pixels.
// bench/view_bench.sh runs the same views through `wangscape view --stats`.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>

#include "renders/ldi/ldi_scene.h"
#include "renders/view/view_frames.h"
#include "scene/scene.h"
#include "scene/scene_file.h"

namespace {

using namespace wangscape;

std::shared_ptr<const ViewWorld> default_world() {
  static const std::shared_ptr<const ViewWorld> world = [] {
    const SceneConfig config = default_scene_config();
    Scene scene = make_scene(config);
    const std::filesystem::path pack =
        std::filesystem::temp_directory_path() / ("wangscape-view-bench-" + std::to_string(::getpid()) + ".ldi");
    build_scene_ldi_pack(scene, pack, ldi_options(config));
    auto made = std::make_shared<const ViewWorld>(std::move(scene), pack, ldi_options(config).shading);
    std::filesystem::remove(pack);  // the pack stays mapped
    return made;
  }();
  return world;
}

ViewCamera bench_camera(const ViewWorld& world, int which) {
  const double head = std::numeric_limits<double>::quiet_NaN();  // head height above the ground
  ViewRequest request;
  if (which == 1) {
    request.camera = {0, 6300, head};
    request.look_at = {0, 1200, 1500};
  } else if (which == 2) {
    request.camera = {0, 6640, 1150};
    request.look_at = {0, 6450, 1125};
  }
  return view_camera(world, request);
}

void BM_ViewFrame(benchmark::State& state) {
  const auto world = default_world();
  LdiRenderer renderer(world, int(state.range(1)), int(state.range(2)));
  const ViewCamera camera = bench_camera(*world, int(state.range(0)));
  std::uint64_t depth_pixels = 0, tiles = 0;
  std::array<std::vector<double>, 4> phases;
  for (auto _ : state) {
    const ViewFrameStats& s = renderer.render(camera);
    depth_pixels += s.depth_pixels;
    tiles = s.tiles_drawn;
    for (std::size_t p = 0; p < 4; ++p) phases[p].push_back(s.phase_ms[p]);
  }
  state.counters["fps"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["Mdepth_px_per_s"] = benchmark::Counter(double(depth_pixels) / 1e6, benchmark::Counter::kIsRate);
  state.counters["tiles_drawn"] = double(tiles);
  const char* names[4] = {"tiles_ms", "ldis_ms", "terrain_ms", "resolve_ms"};
  for (std::size_t p = 0; p < 4; ++p) {
    auto& v = phases[p];
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
    state.counters[names[p]] = v.empty() ? 0.0 : v[v.size() / 2];
  }
}

void BM_ViewAgainstReference(benchmark::State& state) {
  const auto world = default_world();
  LdiRenderer renderer(world, int(state.range(1)), int(state.range(2)));
  const ViewCamera camera = bench_camera(*world, int(state.range(0)));
  for (auto _ : state) {
    const double frame_ms = measure_view(renderer, camera, 20).frame_ms;
    renderer.render(camera);
    const ViewComparison v = compare_with_reference(*world, renderer, camera, 0);
    state.counters["reference_s"] = v.reference.seconds;
    state.counters["ldi_frame_s"] = frame_ms / 1e3;
    state.counters["speedup"] = v.reference.seconds / (frame_ms / 1e3);
    state.counters["psnr_db"] = v.comparison.psnr_db;
    state.counters["ssim"] = v.comparison.ssim;
    state.counters["hole_share"] = v.comparison.holes.share;
  }
}

void views(benchmark::internal::Benchmark* b) {
  for (int camera = 0; camera < 3; ++camera) {
    b->Args({camera, 640, 360});
    b->Args({camera, 1280, 720});
  }
  b->ArgNames({"camera", "width", "height"});
}

BENCHMARK(BM_ViewFrame)->Apply(views)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_ViewAgainstReference)->Apply(views)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);

}  // namespace

BENCHMARK_MAIN();
