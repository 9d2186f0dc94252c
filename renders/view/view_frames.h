// The view's frames without a window, as typed calls: the camera a view starts from, a path
// played frame by frame, the median statistics of one camera and a frame against the Embree
// reference (renders/trace/embree_reference.h). Prints nothing and names no flag: the program
// (`wangscape view`, cli/cmd_view.cpp) checks its flags, prints the figures and progress and
// writes the files; the window, the benches and the tests drive the same calls.
#pragma once

#include <array>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string_view>
#include <utility>

#include "renders/trace/embree_reference.h"
#include "renders/trace/image_compare.h"
#include "renders/view/frame_cache.h"
#include "renders/view/ldi_renderer.h"
#include "scene/view_path.h"

namespace wangscape {

// The truth of a comparison: the Embree reference at 64 samples per pixel (40 dB from 256, so
// converged for a comparison of one-sample frames; docs/viewer-design.md).
inline constexpr int kDefaultTruthSamples = 64;
inline constexpr double kDefaultPathFps = 24;

// The engines by the names users write, for the command line's choices.
inline constexpr std::array<std::pair<ViewEngine, std::string_view>, 3> kViewEngineNames{
    {{ViewEngine::automatic, "auto"}, {ViewEngine::ldi, "ldi"}, {ViewEngine::embree, "embree"}}};

// ---- the camera ------------------------------------------------------------------------------

// What a view changes of the scene's own camera: each part given replaces the scene's.
struct CameraChoice {
  std::optional<std::array<double, 3>> position;  // E, N, H (ENU m); H NaN: head height above the ground
  std::optional<std::array<double, 3>> look_at;   // E, N, H (ENU m)
  std::optional<double> fov_degrees;              // horizontal
};

// True when `target` lies sideways of `eye` (not straight above, below or at it), as a camera
// needs: its right vector is horizontal.
bool looks_sideways(const std::array<double, 3>& eye, const std::array<double, 3>& target);

// The scene's camera with `choice` applied; an eye without a height stands at the pack's head
// height above the ground. Throws Error for a field of view outside (0, 179] degrees, an eye
// without a height that is not over the ground, or a point looked at that is not sideways of
// the eye.
Camera view_camera(const ViewWorld& world, const CameraChoice& choice);

// ---- a path, frame by frame ------------------------------------------------------------------

// How a path is played (play_view_path).
struct PathPlayback {
  int width = 640, height = 360;  // pixels
  double fov_degrees = 60;        // horizontal, every frame's
  // Frames per second along the path; each cached frame traces anew what a frame at this rate
  // has time for (FrameBudget::fps; kMinViewFps .. kMaxViewFps).
  double fps = kDefaultPathFps;
  bool cached = true;                        // each frame from the previous frame's samples (FrameCache)
  int compare_every = 0;                     // compare frames 0, K, 2K, ... with the truth (0: none)
  int truth_samples = kDefaultTruthSamples;  // the truth's samples per pixel
  ViewSettings settings;
};

struct ViewComparison;

// One frame of a path as it is played. What it points to lives until the callback returns.
struct PathFrame {
  long long index = 0;  // 0 .. count - 1
  long long count = 0;  // the path's frames
  Camera camera;
  const ImageRgb8* image = nullptr;
  double frame_ms = 0;
  double fresh_share = 1;                      // of the pixels, those traced anew (1: drawn whole)
  const CachedFrameStats* cached = nullptr;    // the cache's figures (null: drawn whole)
  const ViewComparison* comparison = nullptr;  // the frames compare_every picks: against the truth
};

// Plays `path` (read from `file`, which errors name): checks its frame count and that its first
// and last cameras are over the ground before the first frame, then draws every frame in order
// and hands it to `on_frame`, on the calling thread. Throws Error for a camera of the path that
// is not over the ground (the file and the time) or settings the renderer refuses; whatever
// `on_frame` throws ends the playback.
void play_view_path(const std::shared_ptr<const ViewWorld>& world, const ViewPath& path,
                    const std::filesystem::path& file, const PathPlayback& playback,
                    const std::function<void(const PathFrame&)>& on_frame);

// ---- statistics and the truth ----------------------------------------------------------------

// Median frame statistics over `frames` renders of one camera.
ViewFrameStats measure_view(LdiRenderer& renderer, const Camera& camera, int frames);

// The renderer's last frame (drawn from `camera`) against the truth, the Embree reference of the
// same camera and size ray traced with the light the pack was shaded with at `samples_per_pixel`
// (0: the scene's): PSNR, SSIM, holes (sky in the frame where the truth has geometry) and the
// difference image. Also the exact geometry at the renderer's samples per pixel (the reference at
// 1 sample, or N at N samples per pixel) against the same truth: what any frame of that many
// samples can reach, so the gap is the view's own.
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

}  // namespace wangscape
