// The view in motion (renders/view/frame_cache.h) on the default scene, along four paths of
// bench/paths/ (issue 37's three, and a sideways step):
//  - 0, walk.json: 8 s at head height through the field at 1.4 m/s, the gaze turning up to about
//    60 degrees a second;
//  - 1, walk_then_still.json: the same walk, then 2 s standing still;
//  - 2, flight.json: 8 s 25 m above the field at 10 m/s, looking ahead and down;
//  - 3, side_step.json: 2 s of a sideways step at 1.4 m/s past the flowers of the close-up,
//    1-2 m away (they come in at the right edge).
// BM_CachedPath/PATH/W/H: one iteration plays the whole path at 60 frames/s (play_view_path) through a FrameCache
// with its default budget (the frames `wangscape view --path P --fps 60` draws), the first frame
// cold. Counters: the median, 95th percentile and slowest frame (ms), the 95th percentile over
// the median, the mean share of the pixels traced anew, of those probed at the edge the camera
// steps toward and of the holes reprojection left (before tracing), the median of the warm frames' phases
// (reprojecting, choosing, tracing, resolving; ms), the cold frames, and the process CPU
// seconds per frame (all threads: getrusage). Quality along the same paths: `wangscape view DIR
// --path P --fps 60 --compare-every K --json` (docs/viewer-design.md, "The sample cache").
// BM_CachedPath/PATH/W/H/0 draws every frame whole instead (LdiRenderer::render, the default
// engine): the frames before the cache.
// BM_WarmStep/W/H: the cost of a warm frame's passes, steadier than a path's medians on a busy
// machine: two cameras of the walk 1/60 s apart (frames 120 and 121) drawn in turn, so that each
// frame is the same small move; the minimum and median of each phase over 120 frames.
#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <algorithm>
#include <array>
#include <vector>

#include "bench/default_view_world.h"
#include "renders/view/frame_cache.h"
#include "renders/view/view_frames.h"
#include "scene/view_path.h"

namespace {

using namespace wangscape;
using namespace wangscape::bench;

constexpr const char* kPaths[] = {"walk.json", "walk_then_still.json", "flight.json", "side_step.json"};

double process_cpu_seconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return double(usage.ru_utime.tv_sec + usage.ru_stime.tv_sec) +
         double(usage.ru_utime.tv_usec + usage.ru_stime.tv_usec) / 1e6;
}

double at(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[std::min(v.size() - 1, std::size_t(q * double(v.size())))];
}

void BM_CachedPath(benchmark::State& state) {
  const auto world = default_world();
  const std::filesystem::path file =
      std::filesystem::path(WANGSCAPE_SOURCE_DIR) / "bench/paths" / kPaths[state.range(0)];
  const ViewPath path = read_view_path(file);
  PathPlayback playback;
  playback.width = int(state.range(1));
  playback.height = int(state.range(2));
  playback.fov_degrees = world->scene().camera.fov_degrees;
  playback.fps = kDefaultViewFps;
  playback.cached = state.range(3) != 0;
  for (auto _ : state) {
    std::vector<double> frame_ms;
    std::array<std::vector<double>, 4> phases;
    double fresh = 0, cold = 0, probes = 0, holes = 0;
    const double cpu_start = process_cpu_seconds();
    play_view_path(world, path, file, playback, [&](const PathFrame& frame) {
      frame_ms.push_back(frame.frame_ms);
      fresh += frame.fresh_share;
      if (!frame.cached) return;
      cold += frame.cached->cold;
      probes += double(frame.cached->probes) / double(frame.cached->pixels);
      holes += double(frame.cached->holes) / double(frame.cached->pixels);
      if (!frame.cached->cold)
        for (std::size_t p = 0; p < phases.size(); ++p) phases[p].push_back(frame.cached->phase_ms[p]);
    });
    const double frames = double(frame_ms.size());
    state.counters["cpu_s_per_frame"] = (process_cpu_seconds() - cpu_start) / frames;
    state.counters["median_ms"] = at(frame_ms, 0.5);
    state.counters["p95_ms"] = at(frame_ms, 0.95);
    state.counters["max_ms"] = at(frame_ms, 1.0);
    state.counters["p95_over_median"] = at(frame_ms, 0.95) / at(frame_ms, 0.5);
    state.counters["fresh_share"] = fresh / frames;
    state.counters["cold_frames"] = cold;
    state.counters["probe_share"] = probes / frames;
    state.counters["hole_share"] = holes / frames;
    state.counters["frames"] = frames;
    const char* names[4] = {"reproject_ms", "choose_ms", "trace_ms", "resolve_ms"};
    for (std::size_t p = 0; p < phases.size(); ++p) state.counters[names[p]] = at(phases[p], 0.5);
  }
}

void paths(benchmark::internal::Benchmark* b) {
  for (int path = 0; path < 4; ++path)
    for (const auto& [w, h] : {std::pair{640, 360}, std::pair{1280, 720}}) {
      b->Args({path, w, h, 1});
      if (path != 1) b->Args({path, w, h, 0});
    }
}
BENCHMARK(BM_CachedPath)->Apply(paths)->Iterations(1)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_WarmStep(benchmark::State& state) {
  const auto world = default_world();
  const std::filesystem::path file = std::filesystem::path(WANGSCAPE_SOURCE_DIR) / "bench/paths" / kPaths[0];
  const ViewPath path = read_view_path(file);
  const GroundHeightAt ground = [&](double e, double n) { return world->scene().field->ground.height(e, n); };
  const double fov = world->scene().camera.fov_degrees, start = path.keys.front().time;
  const Camera cameras[2] = {camera_along(path, start + 120.0 / kDefaultViewFps, fov, ground, file),
                             camera_along(path, start + 121.0 / kDefaultViewFps, fov, ground, file)};
  LdiRenderer renderer(world, int(state.range(0)), int(state.range(1)));
  FrameCache cache(renderer);
  renderer.apply(ViewSettings{});                            // the view's defaults, as play_view_path draws
  for (int f = 0; f < 8; ++f) cache.render(cameras[f % 2]);  // cold, then warm
  for (auto _ : state) {
    std::vector<double> frame_ms;
    std::array<std::vector<double>, 4> phases;
    double cold = 0, fresh = 0;
    for (int f = 0; f < 120; ++f) {
      const CachedFrameStats& stats = cache.render(cameras[f % 2]);
      cold += stats.cold;
      fresh += stats.fresh_share();
      frame_ms.push_back(stats.frame_ms);
      for (std::size_t p = 0; p < phases.size(); ++p) phases[p].push_back(stats.phase_ms[p]);
    }
    state.counters["cold_frames"] = cold;
    state.counters["fresh_share"] = fresh / 120;
    state.counters["min_ms"] = at(frame_ms, 0);
    state.counters["median_ms"] = at(frame_ms, 0.5);
    const char* names[4] = {"reproject", "choose", "trace", "resolve"};
    for (std::size_t p = 0; p < phases.size(); ++p) {
      state.counters[std::string(names[p]) + "_min_ms"] = at(phases[p], 0);
      state.counters[std::string(names[p]) + "_median_ms"] = at(phases[p], 0.5);
    }
  }
}
BENCHMARK(BM_WarmStep)
    ->Args({640, 360})
    ->Args({1280, 720})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

// A camera holding still (the walk's camera at frame 120): 120 still frames after a cold and a
// warm one, the phases' medians and the fresh samples a frame traces (the convergence's pace).
void BM_StillFrames(benchmark::State& state) {
  const auto world = default_world();
  const std::filesystem::path file = std::filesystem::path(WANGSCAPE_SOURCE_DIR) / "bench/paths" / kPaths[0];
  const ViewPath path = read_view_path(file);
  const GroundHeightAt ground = [&](double e, double n) { return world->scene().field->ground.height(e, n); };
  const double fov = world->scene().camera.fov_degrees, start = path.keys.front().time;
  const Camera camera = camera_along(path, start + 120.0 / kDefaultViewFps, fov, ground, file);
  LdiRenderer renderer(world, int(state.range(0)), int(state.range(1)));
  renderer.apply(ViewSettings{});
  for (auto _ : state) {
    FrameCache cache(renderer);
    cache.render(camera);  // cold
    std::vector<double> frame_ms;
    std::array<std::vector<double>, 4> phases;
    double fresh = 0;
    for (int f = 0; f < 120; ++f) {
      const CachedFrameStats& stats = cache.render(camera);
      fresh += double(stats.fresh);
      frame_ms.push_back(stats.frame_ms);
      for (std::size_t p = 0; p < phases.size(); ++p) phases[p].push_back(stats.phase_ms[p]);
    }
    state.counters["fresh_per_frame"] = fresh / 120;
    state.counters["median_ms"] = at(frame_ms, 0.5);
    state.counters["max_ms"] = at(frame_ms, 1.0);
    const char* names[4] = {"reproject", "choose", "trace", "resolve"};
    for (std::size_t p = 0; p < phases.size(); ++p) state.counters[std::string(names[p]) + "_ms"] = at(phases[p], 0.5);
  }
}
BENCHMARK(BM_StillFrames)
    ->Args({640, 360})
    ->Args({1280, 720})
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
