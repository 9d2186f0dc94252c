// The view's frames without a window (renders/view/view_frames.h): the camera, path playback,
// statistics and the comparison with the Embree reference, on top of the renderer of
// renders/view/ldi_renderer.h and the sample cache of renders/view/frame_cache.h.
#include "renders/view/view_frames.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/number_text.h"
#include "core/vecmath.h"
#include "renders/trace/embree_reference.h"
#include "renders/trace/image_compare.h"
#include "scene/view_path.h"

namespace wangscape {

bool looks_sideways(const std::array<double, 3>& eye, const std::array<double, 3>& target) {
  return std::hypot(target[0] - eye[0], target[1] - eye[1]) >= 1e-6;
}

Camera view_camera(const ViewWorld& world, const CameraChoice& choice) {
  Camera camera;
  const Camera& scene = world.scene().camera;
  camera.position = scene.position;
  camera.target = scene.target;
  camera.fov_degrees = choice.fov_degrees.value_or(scene.fov_degrees);
  check_field_of_view(camera.fov_degrees, "field of view");
  if (choice.position) {
    camera.position = *choice.position;
    if (std::isnan(camera.position[2])) {
      const auto h = world.scene().field->ground.height(camera.position[0], camera.position[1]);
      if (!h)
        throw Error("eye at " + number_text(camera.position[0]) + "," + number_text(camera.position[1]) +
                    ": not over the ground; give its height too (E,N,H)");
      camera.position[2] = *h + world.pack().info().head_height;
    }
  }
  if (choice.look_at) camera.target = *choice.look_at;
  if (!looks_sideways(camera.position, camera.target))
    throw Error("the point looked at must lie sideways of the eye (not straight above, below or at it)");
  return camera;
}

void play_view_path(const std::shared_ptr<const ViewWorld>& world, const ViewPath& path,
                    const std::filesystem::path& file, const PathPlayback& playback,
                    const std::function<void(const PathFrame&)>& on_frame) {
  const double fps = playback.fps;
  const long long frames = path_frame_count(path, fps, file);
  const GroundHeightAt ground = [&](double e, double n) { return world->scene().field->ground.height(e, n); };
  const auto camera_at = [&](long long k) { return camera_at_frame(path, k, fps, playback.fov_degrees, ground, file); };
  // A path whose ends leave the ground is refused before the first frame.
  for (double t : {path.keys.front().time, path.keys.back().time})
    camera_along(path, t, playback.fov_degrees, ground, file);

  LdiRenderer renderer(world, playback.width, playback.height);
  renderer.apply(playback.settings);
  // Each frame from the previous frame's samples, with the budget of a frame at the path's rate:
  // the frames the window draws at that rate.
  FrameBudget budget;
  budget.fps = std::clamp(fps, kMinViewFps, kMaxViewFps);
  FrameCache cache(renderer, budget);
  for (long long k = 0; k < frames; ++k) {
    PathFrame frame;
    frame.index = k;
    frame.count = frames;
    frame.camera = camera_at(k);
    if (playback.cached) {
      frame.cached = &cache.render(frame.camera);
      frame.frame_ms = frame.cached->frame_ms;
      frame.fresh_share = frame.cached->fresh_share();
      frame.image = &cache.image();
    } else {
      frame.frame_ms = renderer.render(frame.camera).frame_ms;
      frame.image = &renderer.image();
    }
    std::optional<ViewComparison> comparison;
    if (playback.compare_every > 0 && k % playback.compare_every == 0) {
      comparison = compare_with_reference(
          *world, *frame.image,
          [&](int x, int y) { return playback.cached ? std::isinf(cache.depth_at(x, y)) : renderer.sky_at(x, y); },
          frame.camera, playback.truth_samples, 1);
      frame.comparison = &*comparison;
    }
    on_frame(frame);
  }
}

ViewFrameStats measure_view(LdiRenderer& renderer, const Camera& camera, int frames) {
  // The frame time and each phase's: medians of their own.
  std::array<std::vector<double>, 6> times;
  ViewFrameStats stats;
  for (int k = 0; k < std::max(frames, 1); ++k) {
    stats = renderer.render(camera);
    times[0].push_back(stats.frame_ms);
    for (std::size_t p = 0; p < stats.phase_ms.size(); ++p) times[p + 1].push_back(stats.phase_ms[p]);
  }
  const auto median = [](std::vector<double>& v) {
    std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  stats.frame_ms = median(times[0]);
  for (std::size_t p = 0; p < stats.phase_ms.size(); ++p) stats.phase_ms[p] = median(times[p + 1]);
  return stats;
}

ViewComparison compare_with_reference(const ViewWorld& world, const LdiRenderer& renderer, const Camera& camera,
                                      int samples_per_pixel) {
  return compare_with_reference(
      world, renderer.image(), [&](int x, int y) { return renderer.sky_at(x, y); }, camera, samples_per_pixel,
      renderer.samples());
}

ViewComparison compare_with_reference(const ViewWorld& world, const ImageRgb8& frame,
                                      const std::function<bool(int, int)>& sky_at, const Camera& camera,
                                      int samples_per_pixel, int frame_samples) {
  ReferenceOptions options;
  options.camera = camera;
  options.width = frame.width;
  options.height = frame.height;
  options.samples_per_pixel = samples_per_pixel;
  options.shading = world.shading();
  const ReferenceImage truth = render_reference(world.scene(), options);
  options.samples_per_pixel = frame_samples;
  const ReferenceImage one_sample = render_reference(world.scene(), options);
  const CoverageMask truth_mask = coverage_mask(truth.coverage, frame.width, frame.height);
  CoverageMask view_mask{frame.width, frame.height, {}};
  view_mask.covered.resize(std::size_t(frame.width) * std::size_t(frame.height));
  for (int y = 0; y < frame.height; ++y)
    for (int x = 0; x < frame.width; ++x)
      view_mask.covered[std::size_t(y) * std::size_t(frame.width) + std::size_t(x)] = !sky_at(x, y);
  const CoverageMask one_sample_mask = coverage_mask(one_sample.coverage, frame.width, frame.height);
  return {compare_images(frame, truth.image, &view_mask, &truth_mask),
          compare_images(one_sample.image, truth.image, &one_sample_mask, &truth_mask), truth.stats, one_sample.stats,
          truth.image};
}

}  // namespace wangscape
