// `wangscape render DIR --path FILE --frames FRAMES`: a path file (scene/view_path.h, the one the
// view plays and records) rendered frame by frame by any engine the folder was built for. Frame k
// is the view's frame k: the same camera (camera_at_frame: the same keyframes, spline and heights
// above the ground), the same file name (FRAMES/frame-NNNNN.png, path_frame_name). POV-Ray renders
// every frame in one run through its animation clock, Blender in one run from one .blend whose
// camera is keyframed at every frame, the Embree reference frame by frame over one build of the
// scene. Frames already in FRAMES and complete are not rendered again; each frame appears whole
// (rendered under a temporary name, then renamed). Prints nothing.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <vector>

#include "renders/external/render_engine.h"
#include "scene/scene.h"
#include "scene/view_path.h"

namespace wangscape {

inline constexpr double kMinPathRenderFps = 1, kMaxPathRenderFps = 240;  // the view's range
inline constexpr double kDefaultPathRenderFps = 24;

struct PathRenderRequest {
  RenderEngine engine = RenderEngine::povray;
  std::filesystem::path path;    // the path file
  std::filesystem::path frames;  // the folder of frames, made when missing
  double fps = kDefaultPathRenderFps;
  int width = 0, height = 0;  // pixels; 0: the scene's (one side given: the other keeps its aspect)
  int samples = 0;            // embree: samples per pixel; blender: Cycles samples; 0: the scene's
  // A part of the path: frame_count frames from first_frame (0: to the end), rendered with the
  // whole path's cameras (a batch splits a path so, each part a task); the movie is made only
  // when the request covers every frame.
  long long first_frame = 0, frame_count = 0;
  // A frame done of the total: `rendered` false when it was already there, complete.
  std::function<void(long long frame, long long total, bool rendered)> on_frame;
};

struct PathRenderResult {
  long long frames = 0, rendered = 0, skipped = 0;  // of the requested part
  int width = 0, height = 0;
  std::filesystem::path movie;  // FRAMES/path.mp4; empty without ffmpeg on PATH
  std::filesystem::path blend;  // Blender: FRAMES/path.blend, the camera keyframed
  std::filesystem::path log;    // the renderer's log (POV-Ray, Blender)
  double seconds = 0;           // the whole call
};

// The cameras of `path`'s frames at `fps` over the scene of folder DIR (its ground for heights
// above the ground, its camera's field of view): frame k's at k. `file` names the path in errors.
std::vector<Camera> path_cameras(const Scene& scene, const ViewPath& path, double fps,
                                 const std::filesystem::path& file);

// Renders `request.path` over DIR into request.frames, then path.mp4 when ffmpeg is on PATH.
// Throws Error, before any frame, for a path file that cannot be read, a frame rate outside
// kMinPathRenderFps .. kMaxPathRenderFps, a part outside the path's frames, a folder without that
// engine's export, a frames folder that cannot be made or written; and the renderer's failure (the frames completed
// before it stay, for a later run to skip).
PathRenderResult render_path(const std::filesystem::path& dir, const PathRenderRequest& request);

// True when `file` is a whole PNG image (its signature, header and closing chunk) of `width` x
// `height` pixels: what a frame left by an earlier run must be to be skipped.
bool complete_png(const std::filesystem::path& file, int width, int height);

}  // namespace wangscape
