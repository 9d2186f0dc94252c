// `wangscape view` without a window: offline frames, frame statistics, path playback and the
// comparison with the Embree reference, on top of the renderer of renders/view/ldi_renderer.h.
#include <tbb/global_control.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <optional>

#include "core/error.h"
#include "core/memory_budget.h"
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
  const double fps = request.fps.value_or(kDefaultPathFps);
  const long long frames = path.frame_count(fps);
  if (frames > kMaxPathFrames)
    throw Error(request.path, "",
                "lasts " + number_text(path.duration()) + " s: " + std::to_string(frames) + " frames at " +
                    number_text(fps) + " frames/s; at most " + std::to_string(kMaxPathFrames) +
                    " are rendered (lower --fps or cut the path in parts)");
  const GroundHeightAt ground = [&](double e, double n) { return world->scene().field->ground.height(e, n); };
  for (double t : {path.keys.front().time, path.keys.back().time}) camera_along(path, t, fov, ground, request.path);

  std::error_code ec;
  const bool writes = !request.frames_dir.empty();
  std::optional<FramesCleanup> cleanup;
  if (writes) {
    cleanup.emplace(request.frames_dir);
    fs::create_directories(request.frames_dir, ec);
    if (!fs::is_directory(request.frames_dir, ec)) throw Error(request.frames_dir, "", "cannot make the frames folder");
  }
  LdiRenderer renderer(world, width, height);
  renderer.apply(request.settings);
  // Each frame from the previous frame's samples, with the budget of a frame at the path's rate:
  // the frames the window draws at that rate.
  FrameBudget budget;
  budget.fps = std::clamp(fps, kMinViewFps, kMaxViewFps);
  FrameCache cache(renderer, budget);
  std::vector<double> frame_ms;
  double fresh_share = 0;
  const auto start = std::chrono::steady_clock::now();
  for (long long k = 0; k < frames; ++k) {
    const Camera camera = camera_along(path, path.keys.front().time + double(k) / fps, fov, ground, request.path);
    const ImageRgb8* image = &renderer.image();
    if (request.cached) {
      const CachedFrameStats& stats = cache.render(camera);
      frame_ms.push_back(stats.frame_ms);
      fresh_share += stats.fresh_share();
      image = &cache.image();
    } else {
      frame_ms.push_back(renderer.render(camera).frame_ms);
      fresh_share += 1;
    }
    if (request.compare_every > 0 && k % request.compare_every == 0) {
      const ViewComparison v = compare_with_reference(
          *world, *image,
          [&](int x, int y) { return request.cached ? std::isinf(cache.depth_at(x, y)) : renderer.sky_at(x, y); },
          camera, request.truth_samples, 1);
      std::printf("{\"frame\": %lld, \"frame_ms\": %s, %s}\n", k, number_text(frame_ms.back()).c_str(),
                  comparison_json_members(v, 1).c_str());
      std::fflush(stdout);
      if (writes) {  // the truth beside the frame it was compared with
        char name[32];
        std::snprintf(name, sizeof name, "truth-%05lld.png", k);
        write_image(request.frames_dir / name, v.truth);
        cleanup->wrote(request.frames_dir / name);
      }
    }
    if (writes) {
      char name[32];
      std::snprintf(name, sizeof name, "frame-%05lld.png", k);
      write_image(request.frames_dir / name, *image);
      cleanup->wrote(request.frames_dir / name);
    }
    if (!request.quiet && isatty(2)) {
      const double spent = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      std::fprintf(stderr, "\rwangscape: frame %lld / %lld, about %.0f s left ", k + 1, frames,
                   spent / double(k + 1) * double(frames - k - 1));
    }
  }
  if (!request.quiet && isatty(2)) std::fprintf(stderr, "\n");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (request.stats) {
    std::vector<double> sorted = frame_ms;
    std::sort(sorted.begin(), sorted.end());
    const auto at = [&](double q) {
      return sorted[std::min(sorted.size() - 1, std::size_t(q * double(sorted.size())))];
    };
    if (request.json)
      std::printf(
          "{\"frame_ms\": %s, \"frame_ms_p95\": %s, \"frame_ms_max\": %s, \"fresh_share\": %s, \"frames\": %lld}\n",
          number_text(at(0.5)).c_str(), number_text(at(0.95)).c_str(), number_text(sorted.back()).c_str(),
          number_text(fresh_share / double(frames)).c_str(), frames);
    else
      std::printf(
          "%lld frames of %dx%d at %s frames/s: median %.2f ms, 95th percentile %.2f ms, max %.2f ms; "
          "traced anew: %.1f %% of the pixels a frame\n",
          frames, width, height, number_text(fps).c_str(), at(0.5), at(0.95), sorted.back(),
          100 * fresh_share / double(frames));
  }
  if (!writes) return;
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
  cleanup->keep();
  if (!request.quiet)
    std::fprintf(stderr, "wangscape: wrote %lld frames of %dx%d to %s%s in %.1f s\n", frames, width, height,
                 request.frames_dir.string().c_str(),
                 ffmpeg.empty() ? " (no ffmpeg on PATH: PNG frames only)" : " and path.mp4", seconds);
}

// --compare: the same camera ray traced by the Embree reference (the truth, and the exact
// geometry at one sample per pixel), and the figures.
void print_comparison(const ViewWorld& world, const LdiRenderer& renderer, const Camera& camera,
                      const ViewRequest& request, const ViewFrameStats& frame) {
  const ViewComparison v = compare_with_reference(world, renderer, camera, request.truth_samples);
  const ImageComparison& c = v.comparison;
  const ImageComparison& e = v.exact;
  if (!request.diff.empty()) write_image(request.diff, c.difference);
  if (!request.truth_out.empty()) write_image(request.truth_out, v.truth);
  if (!request.side_by_side.empty()) write_image(request.side_by_side, side_by_side(renderer.image(), v.truth));
  if (request.json)
    std::printf("{%s, \"frame_ms\": %s}\n", comparison_json_members(v, renderer.samples()).c_str(),
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

std::string comparison_json_members(const ViewComparison& v, int frame_samples) {
  const ImageComparison& c = v.comparison;
  const ImageComparison& e = v.exact;
  return "\"psnr_db\": " + number_text(c.psnr_db) + ", \"ssim\": " + number_text(c.ssim) +
         ", \"hole_share\": " + number_text(c.holes.share) + ", \"holes\": " + std::to_string(c.holes.holes) +
         ", \"reference_seconds\": " + number_text(v.reference.seconds) +
         ", \"truth_samples\": " + std::to_string(v.reference.samples_per_pixel) +
         ", \"exact_psnr_db\": " + number_text(e.psnr_db) + ", \"exact_ssim\": " + number_text(e.ssim) +
         ", \"exact_hole_share\": " + number_text(e.holes.share) +
         ", \"psnr_gap_db\": " + number_text(e.psnr_db - c.psnr_db) +
         ", \"ssim_gap\": " + number_text(e.ssim - c.ssim) +
         ", \"exact_seconds\": " + number_text(v.one_sample.seconds) +
         ", \"samples\": " + std::to_string(frame_samples);
}

Camera view_camera(const ViewWorld& world, const ViewRequest& request) {
  Camera camera;
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
  if (!request.path.empty() && request.frames_dir.empty() && !request.stats && request.compare_every == 0)
    throw Error("--path: needs --frames OUTDIR (or --stats, or --compare-every K)");
  if (request.compare_every < 0) throw Error("--compare-every: expected a number of frames, 1 or more");
  if (request.compare_every > 0 && request.path.empty()) throw Error("--compare-every: needs --path FILE");
  if (request.fps && !(*request.fps >= kMinViewFps && *request.fps <= kMaxViewFps))
    throw Error("--fps " + number_text(*request.fps) + ": expected " + number_text(kMinViewFps) + " .. " +
                number_text(kMaxViewFps) + " frames per second");
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

void check_view_memory(const ViewRequest& request, int width, int height, bool window) {
  // Bytes a pixel, as measured (peak resident memory at 1024 x 1024 and 2048 x 2048 pixels, the
  // small template's folder, issue 41): the image (3) and the z-buffer (8), and a z-buffer of
  // each thread for the LDIs' splats (8 each); the sums of --spp N (12); the sample cache of a
  // path or the window (64: two 24-byte samples, the key, need, fresh and lattice bytes); the
  // truth, the exact image, their masks and SSIM's planes of --compare (about 120).
  const auto threads =
      double(std::max<std::size_t>(1, tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism)));
  const bool cached = window || (!request.path.empty() && request.cached);
  const bool compares = request.compare || request.compare_every > 0;
  const double per_pixel =
      11 + 8 * threads + (request.settings.samples > 1 ? 12 : 0) + (cached ? 64 : 0) + (compares ? 120 : 0);
  const double pixels = double(width) * double(height);
  const std::string size = std::to_string(width) + "x" + std::to_string(height);
  const std::string what =
      (request.width ? "--size " + size : "the scene's image size " + size + " ([image] width, height)") +
      ": frames of " + fixed_text(pixels, 0) + " pixels at about " + fixed_text(per_pixel, 0) + " bytes a pixel (" +
      fixed_text(threads, 0) + " threads" + (cached ? ", the sample cache" : "") +
      (compares ? ", the comparison" : "") + ")";
  if (const auto excess = memory_estimate_excess(what, pixels * per_pixel))
    throw Error(*excess + "; lower --size" + (threads > 1 ? " or --threads" : ""));
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
  const Camera camera = view_camera(*world, request);
  const int width = request.width ? request.width : world->scene().render.width;
  const int height = request.height ? request.height : world->scene().render.height;
  check_view_memory(request, width, height);

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
