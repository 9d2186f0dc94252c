// A flythrough's path file (docs/viewer.md, "A path file"): keyframes of time, eye and look-at
// point, each given in ENU meters either with an absolute height or with a height above the
// ground, and the camera at any time along a Catmull-Rom spline through them. Read defensively
// (core/text_file.h): size, nesting, counts and every number are checked before use. The one
// evaluation of a path for every renderer: the view's frames (renders/view/view_frames.h) and
// `wangscape render --path` (renders/render_path.h) take frame k's camera from camera_at_frame,
// and name its file path_frame_name(k).
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "scene/scene.h"

namespace wangscape {

inline constexpr std::uintmax_t kMaxPathFileBytes = 16u << 20;  // about 200,000 keyframes as written
inline constexpr std::size_t kMaxPathKeyframes = 100000;
inline constexpr double kMaxPathSeconds = 3600;
inline constexpr int kMaxPathFrames = 100000;         // an hour at 24 frames/s is 86,401
inline constexpr double kMaxPathCoordinate = 1e7;     // meters east or north of the scene's origin
inline constexpr double kMinPathHeight = -12000;      // below the deepest ground on Earth
inline constexpr double kMaxPathHeight = 100000;      // meters, absolute or above the ground
inline constexpr double kMinPathLookSideways = 1e-3;  // meters between a keyframe's eye and look_at (E, N)

struct PathKeyframe {
  double time = 0;
  // E, N and the height: absolute, or above the ground when the path says so (ViewPath).
  std::array<double, 3> position{}, look_at{};
};

struct ViewPath {
  std::vector<PathKeyframe> keys;  // at least two, times ascending
  bool position_above_ground = false;
  bool look_at_above_ground = false;

  double duration() const { return keys.back().time - keys.front().time; }
  // Frames at `fps` from the first key time to the last, both included.
  long long frame_count(double fps) const;
};

// Parses a path file's text; `file` names it in errors (Error: file, "keyframes[3].position",
// what was expected).
ViewPath parse_view_path(std::string_view text, const std::filesystem::path& file);
// Reads and parses a path file (a regular file of at most kMaxPathFileBytes).
ViewPath read_view_path(const std::filesystem::path& file);
// The path as JSON text, readable by parse_view_path (a walk recorded in the window).
std::string view_path_json(const ViewPath& path);

// The ground height at E, N (nullopt: no ground there).
using GroundHeightAt = std::function<std::optional<double>(double east, double north)>;

// The camera at `time` (clamped to the path's times), with the horizontal field of view
// `fov_degrees`: E, N and the height of the eye and of the point looked at interpolated by the
// spline; a height above the ground is added to the ground under the interpolated point, so
// the spline is taken over the ground. Throws Error naming `file` and the time when such a
// point has no ground under it.
Camera camera_along(const ViewPath& path, double time, double fov_degrees, const GroundHeightAt& ground,
                    const std::filesystem::path& file);

// The path's frames at `fps` (ViewPath::frame_count). Throws Error naming `file` when they are
// more than kMaxPathFrames; the message asks to lower `rate` (what sets the frame rate) or to cut
// the path in parts.
long long path_frame_count(const ViewPath& path, double fps, const std::filesystem::path& file,
                           std::string_view rate = "the frame rate");

// Frame k's camera at `fps`: camera_along at the first key's time plus k / fps seconds.
Camera camera_at_frame(const ViewPath& path, long long frame, double fps, double fov_degrees,
                       const GroundHeightAt& ground, const std::filesystem::path& file);

// The file of frame k in a folder of a path's frames: "frame-00042.png" (five digits, as many as
// kMaxPathFrames needs); kPathFramePattern is the same for ffmpeg's -i.
std::string path_frame_name(long long frame);
inline constexpr const char* kPathFramePattern = "frame-%05d.png";

}  // namespace wangscape
