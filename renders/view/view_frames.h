// `wangscape view` without a window: the request's flags, offline frames, statistics, path
// playback and the comparison with the Embree reference (renders/trace/embree_reference.h).
#pragma once

#include <array>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "renders/trace/embree_reference.h"
#include "renders/trace/image_compare.h"
#include "renders/view/frame_cache.h"
#include "renders/view/ldi_renderer.h"
#include "renders/view/view_path.h"

namespace wangscape {

// The truth of a comparison: the Embree reference at 64 samples per pixel (40 dB from 256, so
// converged for a comparison of one-sample frames; docs/viewer.md).
inline constexpr int kDefaultTruthSamples = 64;
inline constexpr double kDefaultPathFps = 24;

struct ViewRequest {
  std::filesystem::path dir;
  std::optional<std::array<double, 3>> camera;   // E, N, H; H absent (NaN) = head height above the ground
  std::optional<std::array<double, 3>> look_at;  // E, N, H
  std::optional<double> fov_degrees;
  int width = 0, height = 0;  // 0 = the scene's image size
  std::filesystem::path out;  // one offline frame
  bool stats = false, json = false;
  int repeat = 0;                            // frames timed for --stats (0: 200)
  std::filesystem::path path;                // keyframes JSON
  std::filesystem::path frames_dir;          // where the path's frames go
  std::optional<double> fps;                 // --path: frames per second (24); the window: the rate it holds (60)
  bool cached = true;                        // --path: each frame from the previous frame's samples (FrameCache)
  int compare_every = 0;                     // --path: compare frames 0, K, 2K, ... with the truth (0: none)
  std::string script;                        // window: scripted input (docs/viewer.md)
  std::filesystem::path record;              // window: where K's keyframes go (empty: path.json)
  bool compare = false;                      // also ray trace the frame with Embree and compare
  std::filesystem::path diff;                // with compare: the difference image
  int truth_samples = kDefaultTruthSamples;  // with compare: the truth's samples per pixel
  std::filesystem::path truth_out;           // with compare: where the truth image goes (empty: none)
  std::filesystem::path side_by_side;        // with compare: the frame beside the truth (empty: none)
  int threads = 0;                           // 0 = all cores
  ViewSettings settings;                     // --detail, --near, --engine, --spp
  bool quiet = false;
};

// The camera of the request: its flags, or the scene's own camera. Throws Error naming the
// flag at fault (--fov outside (0, 179], a camera off the ground without a height, ...).
Camera view_camera(const ViewWorld& world, const ViewRequest& request);

// Refuses a request's flags out of range (sizes, --fov, --fps, --repeat, --detail, --spp) and
// flags that need another (--path without --frames, --diff without --compare), before anything
// is read. Throws Error naming the flag.
void check_view_request(const ViewRequest& request);
// Refuses frames of width x height pixels whose buffers would pass the memory limit
// (core/memory_budget.h), before any is allocated: the estimate names --size (or the scene's
// image size when the request has none), the bytes a pixel and the limit. `window`: the window's
// frames, which keep the sample cache as a path's do.
void check_view_memory(const ViewRequest& request, int width, int height, bool window = false);
// True when the request asks for no file and no figures: the window.
bool wants_window(const ViewRequest& request);
// The folder's world (ViewWorld::load), stages on stderr unless quiet.
std::shared_ptr<const ViewWorld> load_view_world(const ViewRequest& request);
// Offline frame(s), statistics, comparison or path playback, as the request says; prints
// figures to stdout. Returns the exit code (0). Throws Error for bad input.
// `path`: the request's path file already read (read_view_path), or null to read it here.
int run_view_frames(const std::shared_ptr<const ViewWorld>& world, const ViewRequest& request,
                    const ViewPath* path = nullptr);

// The renderer's last frame (drawn from `camera`) against the truth, the Embree reference of the
// same camera and size ray traced with the light the pack was shaded with at `samples_per_pixel`
// (0: the scene's): PSNR, SSIM, holes (sky in the frame where the truth has geometry) and the
// difference image. Also the exact geometry at the renderer's samples per pixel (the reference at
// 1 sample, or N with --spp N) against the same truth: what any frame of that many samples can
// reach, so the gap is the view's own.
struct ViewComparison {
  ImageComparison comparison;  // the renderer's frame against the truth
  ImageComparison exact;       // the exact geometry at the renderer's samples per pixel against the truth
  ReferenceStats reference;    // the truth's figures (its time)
  ReferenceStats one_sample;   // the exact image's (at the renderer's samples per pixel)
  ImageRgb8 truth;             // the truth image itself
};
ViewComparison compare_with_reference(const ViewWorld& world, const LdiRenderer& renderer, const Camera& camera,
                                      int samples_per_pixel);
// The same for any frame of the view: `frame` drawn from `camera` at `frame_samples` samples per
// pixel, `sky_at(x, y)` true where it shows the sky.
ViewComparison compare_with_reference(const ViewWorld& world, const ImageRgb8& frame,
                                      const std::function<bool(int, int)>& sky_at, const Camera& camera,
                                      int samples_per_pixel, int frame_samples);
// The comparison's figures as one JSON object's members (no braces): "psnr_db": ..., ...
std::string comparison_json_members(const ViewComparison& v, int frame_samples);

// Median frame statistics over `frames` renders of one camera.
ViewFrameStats measure_view(LdiRenderer& renderer, const Camera& camera, int frames);
// {"frame_ms": ..., "fps": ..., "depth_pixels": ..., "tiles": {...}, "levels": [...]}
std::string view_stats_json(const ViewFrameStats& stats);

}  // namespace wangscape
