// The batch file (TOML, docs/batch-file.md): a base scene plus what varies (DEMs, viewpoints
// chosen from the terrain, sun times, engines, image size), and its expansion into tasks, one
// still each. Expansion loads every ground once (SceneGround) and checks every input, so a
// batch naming a missing DEM fails here, before any task runs.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "renders/external/render_engine.h"
#include "scene/scene.h"
#include "scene/scene_file.h"
#include "scene/view_path.h"

namespace wangscape {

// Limits of a batch (docs/limits.md), checked before anything is allocated for them.
inline constexpr std::uintmax_t kMaxBatchFileBytes = 1 << 20;  // the batch file, as a scene file
inline constexpr int kMaxBatchTasks = 100000;                  // stills of one batch (plan.json ~80 MB)
inline constexpr int kMaxBatchSuns = 10000;                    // suns of [sun] from/to/step_minutes
inline constexpr int kMaxBatchRetries = 100;                   // batch run --retries (Slurm resubmissions)
inline constexpr double kMaxSunStepMinutes = 1e9;              // [sun] step_minutes (about 1,900 years)
inline constexpr double kMaxEyeHeight = 20000;                 // viewpoints' eye_height, meters above ground
inline constexpr double kMaxGroundHeight = 12000;              // |min_height| of summits, meters

// How [[viewpoints]] choose cameras: at flowers, on summits, over a grid, along a path.
enum class ViewpointKind { flowers, summits, grid, path };

// "flowers", "summits", "grid", "path": as a batch file writes them.
std::string_view to_string(ViewpointKind kind);
// The kind `name` names, or nothing (the batch file's reader names the line at fault).
std::optional<ViewpointKind> find_viewpoint_kind(std::string_view name);

// [[viewpoints]]: how cameras are chosen from the ground (ENU meters, heights above ground).
struct ViewpointRule {
  ViewpointKind kind = ViewpointKind::flowers;
  int count = 2;                                   // flowers: cameras; summits: at most this many
  double eye_height = 1.7;                         // meters above the ground
  double min_height = 0;                           // summits: meters, only summits at least this high
  std::array<int, 2> grid{2, 2};                   // grid: columns x rows over the field
  std::vector<std::array<double, 2>> path_enu;     // path: [east, north] meters
  std::vector<std::array<double, 2>> path_latlon;  // path: [latitude, longitude] WGS 84 degrees
  double fov = 0;                                  // degrees; 0 = the scene's
  int line = 0;                                    // where it was written, for messages
};

// [[paths]]: an animation along a path file (the view's, docs/viewer.md), rendered by every engine
// of the batch over every DEM with the scene's own sun, its frames split into tasks of
// frames_per_task each (over the pool or a Slurm array) and made into path.mp4 once all are done.
inline constexpr double kMinBatchPathFps = 1, kMaxBatchPathFps = 240;  // render --path's range
struct BatchPath {
  std::filesystem::path file;  // the path file
  ViewPath path;               // read when the batch file is
  double fps = 24;
  int frames_per_task = 24;
  long long frames = 0;  // at fps
  int line = 0;
};

// A task's part of a path: frames first .. first + count - 1 of `total`, into the output's
// paths/FOLDER/ (shared by the parts of one path, engine and DEM).
struct BatchFrames {
  std::filesystem::path file;  // the path file
  double fps = 24;
  long long first = 0, count = 0, total = 0;
  std::string folder;  // "1-walk-povray": the [[paths]] entry, the file's stem, the engine (and DEM)
};

// One sun: a time (at the scene's origin) or fixed angles.
struct BatchSun {
  std::optional<std::int64_t> time_unix;  // seconds since 1970 UTC
  std::string label;                      // as written ("2024-07-15T09:00:00-07:00", "az 135 el 35")
  double azimuth = 135, elevation = 35;   // compass degrees; set from the time by expansion
};

struct BatchConfig {
  std::filesystem::path source;             // the batch file, or "<example batch>"
  SceneConfig scene;                        // the base scene
  std::vector<std::filesystem::path> dems;  // empty = the scene's own terrain
  int dems_line = 0;                        // line of `dems`, for messages
  std::vector<ViewpointRule> viewpoints;
  std::vector<BatchPath> paths;
  std::vector<BatchSun> suns;                               // empty = the scene's sun
  std::vector<RenderEngine> engines{RenderEngine::povray};  // povray, blender or embree
  int width = 0, height = 0;                                // 0 = the scene's
};

// One still, or one part of a path's frames: everything a worker needs, resolved (no ground
// lookups at run time).
struct BatchTask {
  int index = 0;
  std::string id;                             // "0007"
  std::filesystem::path dem;                  // empty = flat ground
  std::string scene_key;                      // hash of what the scene folder depends on (shared folders)
  std::string viewpoint;                      // "flowers 2/4", "summit 1", "path 3" ...
  Camera camera;                              // ENU meters
  std::array<double, 2> camera_latlon{0, 0};  // WGS 84 degrees of the camera
  BatchSun sun;
  RenderEngine engine = RenderEngine::povray;  // povray, blender or embree
  int width = 0, height = 0;
  std::string input_hash;  // scene key + camera + sun + engine + size: skip when unchanged
  // A part of a path's frames instead of a still (the camera: its first frame's); its still is
  // that first frame, for the gallery.
  std::optional<BatchFrames> frames;
};

// Parses a batch file; relative paths resolve against its folder. Throws Error
// "<file>:<line>: <what>" for unknown keys, wrong types and bad values.
BatchConfig parse_batch_config(std::string_view toml_text, const std::filesystem::path& source,
                               const std::filesystem::path& base_dir);
BatchConfig load_batch_config(const std::filesystem::path& file);

// The tasks a batch expands to, in a fixed order (DEM, viewpoint, sun, engine). Throws Error
// naming the batch file when a DEM is missing, a time is night, or no viewpoint fits.
std::vector<BatchTask> expand_batch(const BatchConfig& config);

// The scene a task renders: the base scene over the task's DEM, with its camera, sun and size.
SceneConfig task_scene_config(const SceneConfig& base, const BatchTask& task);

// A task's id: its index with at least 4 digits ("0007"); the name of its still, record and log.
std::string batch_task_id(int index);

// 16 hex digits of a 64-bit FNV-1a hash (input hashes, scene keys).
std::string hash_hex(std::string_view text);

// The small example batch (templates/batches/example.toml) over the embedded default scene.
std::string_view example_batch_text();

}  // namespace wangscape
