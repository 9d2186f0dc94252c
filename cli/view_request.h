// `wangscape view`'s options as one value (docs/viewer.md, the flags table), filled once by
// cli/cmd_view.cpp, and its checks: every refusal names the flag at fault. The view library
// (renders/view) takes typed values and names no flag; this is where flags meet it.
#pragma once

#include <array>
#include <filesystem>
#include <optional>
#include <string>

#include "renders/view/view_frames.h"

namespace wangscape::cli {

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

// Refuses flags out of range (--camera and --look-at beyond kMaxCameraMeters, sizes, --fov, --fps,
// --repeat, --detail, --near, --spp, --truth-spp) and flags that need another (--path without
// --frames, --diff without --compare), before anything is read. Throws Error naming the flag.
void check_view_request(const ViewRequest& request);

// Refuses frames of width x height pixels whose buffers would pass the memory limit
// (core/memory_budget.h), before any is allocated: the estimate names --size (or the scene's
// image size when the request has none), the bytes a pixel and the limit. `window`: the window's
// frames, which keep the sample cache as a path's do.
void check_view_memory(const ViewRequest& request, int width, int height, bool window = false);

// True when the request asks for no file and no figures: the window.
bool wants_window(const ViewRequest& request);

// The camera the flags ask for over `world` (view_camera): the scene's, with --camera, --look-at
// and --fov in place of its parts. Throws Error naming the flag at fault (--fov outside (0, 179],
// a --camera without a height off the ground, a --look-at straight above or below the eye).
Camera request_camera(const ViewWorld& world, const ViewRequest& request);

}  // namespace wangscape::cli
