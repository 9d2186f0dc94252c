// `wangscape view` without a window: offline frames, frame statistics, path playback and the
// comparison with the Embree reference, on top of the renderer of renders/view/ldi_renderer.h.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <optional>

#include "core/error.h"
#include "core/number_text.h"
#include "core/run_cleanup.h"
#include "core/vecmath.h"
#include "exporters/image_io.h"
#include "renders/external/child_process.h"
#include "renders/trace/embree_reference.h"
#include "renders/trace/image_compare.h"
#include "renders/view/view_frames.h"
#include "renders/view/view_path.h"

namespace wangscape {

namespace fs = std::filesystem;

namespace {

// Removes what a path playback wrote if it does not finish: the frames folder when this run made
// it, else this run's frames.
class FramesCleanup {
 public:
  explicit FramesCleanup(const fs::path& dir) : dir_(dir), made_(!fs::exists(dir)) {
    if (made_) register_temporary(dir_);
  }
  FramesCleanup(const FramesCleanup&) = delete;
  FramesCleanup& operator=(const FramesCleanup&) = delete;
  void wrote(const fs::path& file) { written_.push_back(file); }
  void keep() {
    if (made_) unregister_temporary(dir_);
    made_ = false;
    written_.clear();
  }
  ~FramesCleanup() {
    std::error_code ec;
    if (made_) {
      fs::remove_all(dir_, ec);
      unregister_temporary(dir_);
    }
    for (const fs::path& file : written_) fs::remove(file, ec);
  }

 private:
  fs::path dir_;
  bool made_;
  std::vector<fs::path> written_;
};

void play_path(const std::shared_ptr<const ViewWorld>& world, const ViewRequest& request, const ViewPath& path,
               int width, int height, double fov) {
  const double fps = request.path_fps;
  const long long frames = path.frame_count(fps);
  if (frames > kMaxPathFrames)
    throw Error(request.path, "",
                "lasts " + number_text(path.duration()) + " s: " + std::to_string(frames) + " frames at " +
                    number_text(fps) + " frames/s; at most " + std::to_string(kMaxPathFrames) +
                    " are rendered (lower --fps or cut the path in parts)");
  const GroundHeightAt ground = [&](double e, double n) { return world->scene().field->ground.height(e, n); };
  for (double t : {path.keys.front().time, path.keys.back().time}) camera_along(path, t, ground, request.path);

  std::error_code ec;
  FramesCleanup cleanup(request.frames_dir);
  fs::create_directories(request.frames_dir, ec);
  if (!fs::is_directory(request.frames_dir, ec)) throw Error(request.frames_dir, "", "cannot make the frames folder");
  LdiRenderer renderer(world, width, height);
  renderer.apply(request.settings);
  const auto start = std::chrono::steady_clock::now();
  for (long long k = 0; k < frames; ++k) {
    const PathCamera at = camera_along(path, path.keys.front().time + double(k) / fps, ground, request.path);
    renderer.render(ViewCamera{at.position, at.look_at, fov});
    char name[32];
    std::snprintf(name, sizeof name, "frame-%05lld.png", k);
    write_image(request.frames_dir / name, renderer.image());
    cleanup.wrote(request.frames_dir / name);
    if (!request.quiet && isatty(2)) {
      const double spent = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::fprintf(stderr, "\rwangscape: frame %lld / %lld, about %.0f s left ", k + 1, frames,
                   spent / double(k + 1) * double(frames - k - 1));
    }
  }
  if (!request.quiet && isatty(2)) std::fprintf(stderr, "\n");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const fs::path ffmpeg = find_program("ffmpeg");
  if (!ffmpeg.empty()) {
    const fs::path movie = request.frames_dir / "path.mp4", log = request.frames_dir / "ffmpeg.log";
    const ChildExit exit = run_logged({ffmpeg.string(), "-y", "-loglevel", "error", "-framerate", number_text(fps),
                                       "-i", (request.frames_dir / "frame-%05d.png").string(), "-pix_fmt", "yuv420p",
                                       "-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2", movie.string()},
                                      log);
    if (!exit.exited || exit.status != 0) throw Error(movie, "", "ffmpeg " + exit.describe() + last_log_lines(log, 3));
    fs::remove(log, ec);
  }
  cleanup.keep();
  if (!request.quiet)
    std::fprintf(stderr, "wangscape: wrote %lld frames of %dx%d to %s%s in %.1f s\n", frames, width, height,
                 request.frames_dir.string().c_str(),
                 ffmpeg.empty() ? " (no ffmpeg on PATH: PNG frames only)" : " and path.mp4", seconds);
}

// --compare: the same camera ray traced by the Embree reference (the truth, and the exact
// geometry at one sample per pixel), and the figures.
void print_comparison(const ViewWorld& world, const LdiRenderer& renderer, const ViewCamera& camera,
                      const ViewRequest& request, const ViewFrameStats& frame) {
  const ViewComparison v = compare_with_reference(world, renderer, camera, request.truth_samples);
  const ImageComparison& c = v.comparison;
  const ImageComparison& e = v.exact;
  if (!request.diff.empty()) write_image(request.diff, c.difference);
  if (!request.truth_out.empty()) write_image(request.truth_out, v.truth);
  if (!request.side_by_side.empty()) write_image(request.side_by_side, side_by_side(renderer.image(), v.truth));
  if (request.json)
    std::printf(
        "{\"psnr_db\": %s, \"ssim\": %s, \"hole_share\": %s, \"holes\": %llu, \"reference_seconds\": %s, "
        "\"truth_samples\": %d, \"exact_psnr_db\": %s, \"exact_ssim\": %s, \"exact_hole_share\": %s, "
        "\"psnr_gap_db\": %s, \"ssim_gap\": %s, \"exact_seconds\": %s, \"samples\": %d, \"frame_ms\": %s}\n",
        number_text(c.psnr_db).c_str(), number_text(c.ssim).c_str(), number_text(c.holes.share).c_str(),
        static_cast<unsigned long long>(c.holes.holes), number_text(v.reference.seconds).c_str(),
        v.reference.samples_per_pixel, number_text(e.psnr_db).c_str(), number_text(e.ssim).c_str(),
        number_text(e.holes.share).c_str(), number_text(e.psnr_db - c.psnr_db).c_str(),
        number_text(e.ssim - c.ssim).c_str(), number_text(v.one_sample.seconds).c_str(), renderer.samples(),
        number_text(frame.frame_ms).c_str());
  else
    std::printf(
        "PSNR: %.2f dB (the exact geometry at %d sample(s) per pixel: %.2f dB, a gap of %.2f dB)\n"
        "SSIM: %.4f (exact: %.4f, a gap of %.4f)\n"
        "holes: %.4f %% of the pixels (%llu; %.4f %% of the truth's covered)\n"
        "truth: %d samples per pixel, %.2f s%s%s; exact image: %.2f s; the frame: %.1f ms\n",
        c.psnr_db, renderer.samples(), e.psnr_db, e.psnr_db - c.psnr_db, c.ssim, e.ssim, e.ssim - c.ssim,
        100 * c.holes.share, static_cast<unsigned long long>(c.holes.holes), 100 * c.holes.share_of_covered,
        v.reference.samples_per_pixel, v.reference.seconds, request.truth_out.empty() ? "" : ", saved to ",
        request.truth_out.string().c_str(), v.one_sample.seconds, frame.frame_ms);
  if (!request.quiet)
    for (const auto& [file, what] :
         {std::pair{request.truth_out, "the reference"},
          std::pair{request.side_by_side, "the frame beside the reference"}, std::pair{request.diff, "the difference"}})
      if (!file.empty()) std::fprintf(stderr, "wangscape: wrote %s to %s\n", what, file.string().c_str());
}

}  // namespace

ViewComparison compare_with_reference(const ViewWorld& world, const LdiRenderer& renderer, const ViewCamera& camera,
                                      int samples_per_pixel) {
  ReferenceOptions options;
  options.camera = Camera{camera.position, camera.target, camera.fov_degrees};
  options.width = renderer.width();
  options.height = renderer.height();
  options.samples_per_pixel = samples_per_pixel;
  options.shading = world.shading();
  const ReferenceImage truth = render_reference(world.scene(), options);
  options.samples_per_pixel = renderer.samples();
  const ReferenceImage one_sample = render_reference(world.scene(), options);
  const CoverageMask truth_mask = coverage_mask(truth.coverage, renderer.width(), renderer.height());
  CoverageMask view_mask{renderer.width(), renderer.height(), {}};
  view_mask.covered.resize(std::size_t(renderer.width()) * std::size_t(renderer.height()));
  for (int y = 0; y < renderer.height(); ++y)
    for (int x = 0; x < renderer.width(); ++x)
      view_mask.covered[std::size_t(y) * std::size_t(renderer.width()) + std::size_t(x)] = !renderer.sky_at(x, y);
  const CoverageMask one_sample_mask = coverage_mask(one_sample.coverage, renderer.width(), renderer.height());
  return {compare_images(renderer.image(), truth.image, &view_mask, &truth_mask),
          compare_images(one_sample.image, truth.image, &one_sample_mask, &truth_mask), truth.stats, one_sample.stats,
          truth.image};
}

ViewCamera view_camera(const ViewWorld& world, const ViewRequest& request) {
  ViewCamera camera;
  const Camera& scene = world.scene().camera;
  camera.position = scene.position;
  camera.target = scene.target;
  camera.fov_degrees = request.fov_degrees.value_or(scene.fov_degrees);
  check_field_of_view(camera.fov_degrees, "--fov");
  if (request.camera) {
    camera.position = *request.camera;
    if (std::isnan(camera.position[2])) {
      const auto h = world.scene().field->ground.height(camera.position[0], camera.position[1]);
      if (!h)
        throw Error("--camera " + number_text(camera.position[0]) + "," + number_text(camera.position[1]) +
                    ": not over the ground; give the height too (E,N,H)");
      camera.position[2] = *h + world.pack().info().head_height;
    }
  }
  if (request.look_at) camera.target = *request.look_at;
  if (std::hypot(camera.target[0] - camera.position[0], camera.target[1] - camera.position[1]) < 1e-6)
    throw Error("--look-at: must lie sideways of the camera (not straight above, below or at it)");
  return camera;
}

ViewFrameStats measure_view(LdiRenderer& renderer, const ViewCamera& camera, int frames) {
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

std::string view_stats_json(const ViewFrameStats& stats) {
  std::string levels;
  for (std::uint64_t n : stats.levels) levels += (levels.empty() ? "" : ", ") + std::to_string(n);
  const double fps = stats.frame_ms > 0 ? 1000.0 / stats.frame_ms : 0;
  return "{\"frame_ms\": " + number_text(stats.frame_ms) + ", \"fps\": " + number_text(fps) +
         ", \"depth_pixels\": " + std::to_string(stats.depth_pixels) +
         ", \"tiles\": {\"drawn\": " + std::to_string(stats.tiles_drawn) +
         ", \"culled\": " + std::to_string(stats.tiles_culled) + ", \"steep\": " + std::to_string(stats.steep_tiles) +
         "}, \"levels\": [" + levels + "], \"ray_cast\": " + (stats.ray_cast ? "true" : "false") + "}";
}

void check_view_request(const ViewRequest& request) {
  if ((request.width != 0 || request.height != 0) &&
      (request.width < 1 || request.height < 1 || request.width > 16384 || request.height > 16384))
    throw Error("--size " + std::to_string(request.width) + "x" + std::to_string(request.height) +
                ": expected WIDTHxHEIGHT, each 1 .. 16384 pixels");
  if (request.fov_degrees) check_field_of_view(*request.fov_degrees, "--fov");
  if (!request.path.empty() && request.frames_dir.empty()) throw Error("--path: needs --frames OUTDIR");
  if (!(request.path_fps > 0 && request.path_fps <= 240)) throw Error("--fps: expected 0 .. 240 frames per second");
  if (request.repeat < 0 || request.repeat > 100000) throw Error("--repeat: expected 0 .. 100000 frames");
  if (!(request.settings.detail >= kMinViewDetail && request.settings.detail <= kMaxViewDetail))
    throw Error("--detail " + number_text(request.settings.detail) + ": expected " + number_text(kMinViewDetail) +
                " .. " + number_text(kMaxViewDetail) + " (1: the pack's levels at their own distances)");
  if (!request.diff.empty() && !request.compare) throw Error("--diff: needs --compare");
  if (!(request.settings.near_field >= 0 && request.settings.near_field <= kMaxNearField))
    throw Error("--near " + number_text(request.settings.near_field) + ": expected 0 .. " + number_text(kMaxNearField) +
                " meters (0: LDIs everywhere)");
  if (request.settings.samples < 1 || request.settings.samples > kMaxViewSamples)
    throw Error("--spp " + std::to_string(request.settings.samples) + ": expected 1 .. " +
                std::to_string(kMaxViewSamples) + " samples per pixel");
  if (request.truth_samples < 1 || request.truth_samples > kMaxReferenceSamples)
    throw Error("--truth-spp " + std::to_string(request.truth_samples) + ": expected 1 .. " +
                std::to_string(kMaxReferenceSamples) + " samples per pixel");
  if (!request.truth_out.empty() && !request.compare) throw Error("--reference: needs --compare");
  if (!request.side_by_side.empty() && !request.compare) throw Error("--side-by-side: needs --compare");
}

bool wants_window(const ViewRequest& request) {
  return request.out.empty() && request.path.empty() && !request.stats && !request.compare;
}

std::shared_ptr<const ViewWorld> load_view_world(const ViewRequest& request) {
  return ViewWorld::load(request.dir, [&](const std::string& message) {
    if (!request.quiet) std::fprintf(stderr, "wangscape: %s\n", message.c_str());
  });
}

int run_view_frames(const std::shared_ptr<const ViewWorld>& world, const ViewRequest& request, const ViewPath* path) {
  const ViewCamera camera = view_camera(*world, request);
  const int width = request.width ? request.width : world->scene().render.width;
  const int height = request.height ? request.height : world->scene().render.height;

  if (!request.path.empty()) {
    play_path(world, request, path ? *path : read_view_path(request.path), width, height, camera.fov_degrees);
    return 0;
  }
  LdiRenderer renderer(world, width, height);
  renderer.apply(request.settings);
  const ViewFrameStats stats =
      request.stats ? measure_view(renderer, camera, request.repeat ? request.repeat : 200) : renderer.render(camera);
  if (!request.out.empty()) {
    write_image(request.out, renderer.image());
    if (!request.quiet)
      std::fprintf(stderr, "wangscape: wrote the frame (%dx%d) to %s\n", width, height, request.out.string().c_str());
  }
  if (request.compare) {
    print_comparison(*world, renderer, camera, request, stats);
    return 0;
  }
  if (request.stats) {
    if (request.json) {
      std::printf("%s\n", view_stats_json(stats).c_str());
    } else {
      std::printf("eye: %.2f %.2f %.2f (ENU m), looking at %.2f %.2f %.2f, fov %.1f degrees, %dx%d\n",
                  camera.position[0], camera.position[1], camera.position[2], camera.target[0], camera.target[1],
                  camera.target[2], camera.fov_degrees, width, height);
      std::printf("frame: %.2f ms (%.1f frames/s, median of %d)\n", stats.frame_ms,
                  stats.frame_ms > 0 ? 1000 / stats.frame_ms : 0.0, request.repeat ? request.repeat : 200);
      std::printf("of it: tiles %.2f ms, LDIs %.2f ms, terrain %.2f ms, near field %.2f ms, sky and resolve %.2f ms\n",
                  stats.phase_ms[0], stats.phase_ms[1], stats.phase_ms[2], stats.phase_ms[3], stats.phase_ms[4]);
      if (stats.ray_cast) std::printf("drawn by: rays (the whole frame ray cast, --engine)\n");
      std::printf("near field: %llu tiles, %llu rays; %llu LDI tiles behind it not drawn\n",
                  static_cast<unsigned long long>(stats.near_tiles), static_cast<unsigned long long>(stats.near_rays),
                  static_cast<unsigned long long>(stats.tiles_occluded));
      std::printf("depth pixels: %llu (%.1f M/s)\n", static_cast<unsigned long long>(stats.depth_pixels),
                  stats.frame_ms > 0 ? double(stats.depth_pixels) / stats.frame_ms / 1e3 : 0.0);
      std::printf("terrain: %llu triangles, %llu pixels tested\n",
                  static_cast<unsigned long long>(stats.terrain_triangles),
                  static_cast<unsigned long long>(stats.terrain_pixels));
      std::printf("tiles: %llu drawn (%llu from the steep sets, seen from above), %llu culled\n",
                  static_cast<unsigned long long>(stats.tiles_drawn),
                  static_cast<unsigned long long>(stats.steep_tiles),
                  static_cast<unsigned long long>(stats.tiles_culled));
      std::string levels;
      for (std::uint64_t n : stats.levels) levels += (levels.empty() ? "" : ", ") + std::to_string(n);
      std::printf("tiles per level (last: far field): %s\n", levels.c_str());
    }
  }
  return 0;
}

}  // namespace wangscape
