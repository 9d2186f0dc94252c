// Runs the real Blender headless on a Blender export (exporters/blender_export.h): enables
// the Wangscape add-on from the export's zip, imports the manifest, saves DIR/scene.blend and
// renders with Cycles on the CPU (denoising off) to DIR/render_blender.png. Blender's output
// is kept in DIR/blender.log; the .blend and the image appear atomically.
#pragma once

#include <filesystem>
#include <functional>
#include <string>

#include "core/error.h"

namespace wangscape {

struct BlenderRenderOptions {
  int width = 0, height = 0;  // pixels; 0 = as the manifest says
  int samples = 0;            // Cycles samples; 0 = as the manifest says
  int threads = 0;            // 0 = as the manifest says (all cores when it says 0)
  std::string image_name = "render_blender.png";
  bool save_blend = true;  // DIR/scene.blend, or blend_path
  std::filesystem::path blend_path;
  // Frames: the cameras of every frame of a path in a JSON file, {"fps": F, "cameras": [[E, N,
  // H, target E, N, H], ...] (ENU m, frame k's at k), "render": [k, ...]}. The camera is
  // keyframed at every frame of the .blend saved; the frames in "render" are rendered with
  // Cycles in the same Blender run, each into `frames_dir` (an existing folder) and once
  // complete handed to on_frame(k, file), which moves it away; no still is written.
  std::filesystem::path cameras_file, frames_dir;
  std::filesystem::path log;  // Blender's output; empty: DIR/blender.log
  std::function<void(int frame, const std::filesystem::path& file)> on_frame;
  // The Blender program: a name looked up in PATH or a path. Empty = $WANGSCAPE_BLENDER,
  // else "blender".
  std::string executable;
};

struct BlenderRenderResult {
  std::filesystem::path image;     // DIR/render_blender.png (empty for frames)
  std::filesystem::path blend;     // DIR/scene.blend (empty when not saved)
  std::filesystem::path log;       // DIR/blender.log (or the log asked)
  std::filesystem::path manifest;  // the manifest imported
  double seconds = 0;              // wall-clock time of the Blender run (start, import, render)
};

// The manifest render_blender uses for DIR: DIR/blender/manifest.json, else
// DIR/manifest.json; empty when neither exists.
std::filesystem::path find_blender_manifest(const std::filesystem::path& dir);

// Renders the Blender export found in DIR. Throws Error when there is no manifest,
// when Blender is not installed (naming the program looked for), or when it fails (quoting
// the last lines of DIR/blender.log). No partial image or .blend is left behind.
BlenderRenderResult render_blender(const std::filesystem::path& dir, const BlenderRenderOptions& options = {});

// The Blender program render_blender would run, resolved through PATH; empty when none.
std::filesystem::path find_blender(const std::string& executable = {});

}  // namespace wangscape
