// The real-time view on the default scene (its field on Mount St. Helens, the pack built once per
// run into a temporary file: about 25 s), from four cameras at 640 x 360 and 1280 x 720:
//  - camera 0, the scene's own: at the field's northern edge, looking south across it;
//  - camera 1, in the field: 300 m inside, at head height, looking the same way;
//  - camera 2, above the field: 25 m up, looking down into it;
//  - camera 3, a close-up: 1.5 m east of a flower at head height, looking at it (west).
// Each frame with the near field at the default distance (kDefaultNearField: tiles that close
// ray traced from their real flowers) unless the benchmark's name says near 0 (LDIs only).
// BM_ViewFrame/CAMERA/W/H/NEAR_CM: one LdiRenderer::render per iteration. Counters: fps (wall),
//   process CPU seconds per frame (all threads: getrusage), depth pixels per second (M), the
//   tiles drawn, the near field's tiles and rays, and the median milliseconds of each phase
//   (tiles, LDIs, terrain, near field, resolve), which say what limits the frame.
// BM_ViewAgainstTruth/CAMERA/W/H/NEAR_CM: the frame against the truth (the Embree reference at
//   64 samples per pixel), beside the exact geometry at one sample per pixel: PSNR, SSIM, holes
//   and the gaps (exact minus view).
// BM_ViewRayCast/CAMERA/W/H: the anchor, `view --engine embree`: the same frame ray cast whole
//   (ViewEngine::embree: a primary and a sun-shadow ray per pixel in packets of 16, the
//   near field's shading, both threads), with the counters of BM_ViewFrame.
// BM_ViewRayCastUnshadowed/CAMERA/W/H: the same without the sun-shadow rays (the scene lit with
//   shadows off): one primary ray per pixel and its shading, the floor of any frame whose near
//   field covers the screen (in the field it does at any near field the quality goal allows).
// BM_ViewFrameUnshadowed/CAMERA/W/H/800: BM_ViewFrame without the sun-shadow rays: its near_ms
//   counter is the near field's primary rays and their shading alone.
// BM_RayCastAgainstTruth/CAMERA/640/360: the ray-cast frame against the truth, as above.
// BM_EmbreeOneSample/CAMERA/W/H: the reference renderer at one sample per pixel with the same
//   shading (single rays, both threads): its trace seconds (the scene built once, not counted).
// bench/view_bench.sh runs the same views through `wangscape view --stats`.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <sys/resource.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>

#include "bench/default_view_world.h"
#include "renders/ldi/ldi_scene.h"
#include "renders/view/view_frames.h"
#include "scene/scene.h"
#include "scene/scene_file.h"

namespace {

using namespace wangscape;
using namespace wangscape::bench;

Camera bench_camera(const ViewWorld& world, int which) {
  const double head = std::numeric_limits<double>::quiet_NaN();  // head height above the ground
  CameraChoice choice;
  if (which == 1) {
    choice.position = {0, 6300, head};
    choice.look_at = {0, 1200, 1500};
  } else if (which == 2) {
    choice.position = {0, 6640, 1150};
    choice.look_at = {0, 6450, 1125};
  } else if (which == 3) {
    choice.position = {1.0, 6291.3, 1131.6};
    choice.look_at = {-0.5, 6291.3, 1131.5};
  }
  return view_camera(world, choice);
}

double process_cpu_seconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         double(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec) / 1e6;
}

// Frames of one camera (the LDI view, or the whole frame ray cast) and their counters.
void measure_frames(benchmark::State& state, bool ray_cast, bool shadows = true) {
  const auto world = shadows ? default_world() : default_worlds().unshadowed;
  LdiRenderer renderer(world, int(state.range(1)), int(state.range(2)));
  renderer.set_near_field(ray_cast ? 0 : double(state.range(3)) / 100);
  renderer.set_engine(ray_cast ? ViewEngine::embree : ViewEngine::ldi);
  const Camera camera = bench_camera(*world, int(state.range(0)));
  renderer.render(camera);  // the near field's (or the ray cast's) scene is made on the first frame
  std::uint64_t depth_pixels = 0, tiles = 0, near_tiles = 0, near_rays = 0;
  std::array<std::vector<double>, 5> phases;
  const double cpu_start = process_cpu_seconds();
  for (auto _ : state) {
    const ViewFrameStats& s = renderer.render(camera);
    depth_pixels += s.depth_pixels;
    tiles = s.tiles_drawn;
    near_tiles = s.near_tiles;
    near_rays = s.near_rays;
    for (std::size_t p = 0; p < phases.size(); ++p) phases[p].push_back(s.phase_ms[p]);
  }
  state.counters["cpu_s_per_frame"] = (process_cpu_seconds() - cpu_start) / double(state.iterations());
  state.counters["fps"] = benchmark::Counter(double(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["Mdepth_px_per_s"] = benchmark::Counter(double(depth_pixels) / 1e6, benchmark::Counter::kIsRate);
  state.counters["tiles_drawn"] = double(tiles);
  state.counters["near_tiles"] = double(near_tiles);
  state.counters["near_rays"] = double(near_rays);
  const char* names[5] = {"tiles_ms", "ldis_ms", "terrain_ms", "near_ms", "resolve_ms"};
  for (std::size_t p = 0; p < phases.size(); ++p) {
    auto& v = phases[p];
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
    state.counters[names[p]] = v.empty() ? 0.0 : v[v.size() / 2];
  }
}

void BM_ViewFrame(benchmark::State& state) { measure_frames(state, false); }
void BM_ViewRayCast(benchmark::State& state) { measure_frames(state, true); }
void BM_ViewRayCastUnshadowed(benchmark::State& state) { measure_frames(state, true, false); }
void BM_ViewFrameUnshadowed(benchmark::State& state) { measure_frames(state, false, false); }

void against_truth(benchmark::State& state, bool ray_cast) {
  const auto world = default_world();
  LdiRenderer renderer(world, int(state.range(1)), int(state.range(2)));
  renderer.set_near_field(ray_cast ? 0 : double(state.range(3)) / 100);
  renderer.set_engine(ray_cast ? ViewEngine::embree : ViewEngine::ldi);
  const Camera camera = bench_camera(*world, int(state.range(0)));
  for (auto _ : state) {
    renderer.render(camera);
    const ViewComparison v = compare_with_reference(*world, renderer, camera, kDefaultTruthSamples);
    state.counters["psnr_db"] = v.comparison.psnr_db;
    state.counters["ssim"] = v.comparison.ssim;
    state.counters["hole_share"] = v.comparison.holes.share;
    state.counters["exact_psnr_db"] = v.exact.psnr_db;
    state.counters["exact_ssim"] = v.exact.ssim;
    state.counters["psnr_gap_db"] = v.exact.psnr_db - v.comparison.psnr_db;
    state.counters["ssim_gap"] = v.exact.ssim - v.comparison.ssim;
  }
}

void BM_ViewAgainstTruth(benchmark::State& state) { against_truth(state, false); }
void BM_RayCastAgainstTruth(benchmark::State& state) { against_truth(state, true); }

void BM_EmbreeOneSample(benchmark::State& state) {
  const auto world = default_world();
  const Camera camera = bench_camera(*world, int(state.range(0)));
  ReferenceOptions options;
  options.camera = Camera{camera.position, camera.target, camera.fov_degrees};
  options.width = int(state.range(1));
  options.height = int(state.range(2));
  options.samples_per_pixel = 1;
  options.shading = world->shading();
  options.shading.ao_rays = 0;  // a primary and a sun-shadow ray per pixel, as the near field
  for (auto _ : state) {
    const ReferenceImage r = render_reference(world->scene(), options);
    state.SetIterationTime(r.stats.render_seconds);
    state.counters["trace_s"] = r.stats.render_seconds;
    state.counters["rays"] = double(r.stats.primary_rays + r.stats.secondary_rays);
  }
}

// The walk kept out of the stems (StemClearance, issue 40), once a frame in the window: an eye at
// head height stepping 2.3 cm (1.4 m/s at 60 frames/s) across the default field.
void BM_ClearOfStems(benchmark::State& state) {
  const ViewWorld& world = *default_world();
  Vector3d eye{-20, 6300, 0};
  for (auto _ : state) {
    eye[0] = eye[0] > 20 ? -20 : eye[0] + 0.023;
    eye[2] = world.ground_height(eye[0], eye[1], 0) + 1.7;
    benchmark::DoNotOptimize(world.clear_of_stems(eye));
  }
}
BENCHMARK(BM_ClearOfStems)->Unit(benchmark::kMicrosecond);

void views(benchmark::internal::Benchmark* b) {
  for (int camera = 0; camera < 4; ++camera)
    for (const auto& [w, h] : {std::pair{640, 360}, std::pair{1280, 720}}) {
      b->Args({camera, w, h, std::lround(kDefaultNearField * 100)});
      b->Args({camera, w, h, 0});
    }
  b->ArgNames({"camera", "width", "height", "near_cm"});
}

void near_field_views(benchmark::internal::Benchmark* b) {
  for (int camera = 0; camera < 4; ++camera)
    for (const auto& [w, h] : {std::pair{640, 360}, std::pair{1280, 720}})
      b->Args({camera, w, h, std::lround(kDefaultNearField * 100)});
  b->ArgNames({"camera", "width", "height", "near_cm"});
}

void anchor_views(benchmark::internal::Benchmark* b) {
  for (int camera = 0; camera < 4; ++camera)
    for (const auto& [w, h] : {std::pair{640, 360}, std::pair{1280, 720}}) b->Args({camera, w, h});
  b->ArgNames({"camera", "width", "height"});
}

void small_anchor_views(benchmark::internal::Benchmark* b) {
  for (int camera = 0; camera < 4; ++camera) b->Args({camera, 640, 360});
  b->ArgNames({"camera", "width", "height"});
}

BENCHMARK(BM_ViewFrame)->Apply(views)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_ViewAgainstTruth)->Apply(views)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(1);
BENCHMARK(BM_ViewRayCast)->Apply(anchor_views)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_ViewFrameUnshadowed)->Apply(near_field_views)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_ViewRayCastUnshadowed)->Apply(anchor_views)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_RayCastAgainstTruth)
    ->Apply(small_anchor_views)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->Iterations(1);
BENCHMARK(BM_EmbreeOneSample)->Apply(anchor_views)->Unit(benchmark::kMillisecond)->UseManualTime()->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
