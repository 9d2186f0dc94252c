// Runs the real POV-Ray on a scene folder written by exporters/povray_writer.h: the process
// runs with the folder as its current directory (POV-Ray resolves includes against it), the
// image lands in DIR/render.png atomically, and POV-Ray's messages stay in DIR/povray.log.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

#include "core/error.h"

namespace wangscape {

struct PovrayRenderOptions {
  int width = 0, height = 0;  // pixels; 0 = as scene.ini says
  int threads = 0;            // 0 = as scene.ini says (all cores when it says nothing)
  // Output image name inside the folder (PNG).
  std::string image_name = "render.png";
  // The POV-Ray program: a name looked up in PATH or a path. Empty = $WANGSCAPE_POVRAY,
  // else "povray".
  std::string executable;
  // Called about 5 times a second while rendering with the pixels done and the total
  // (0, 0 while POV-Ray is still parsing).
  std::function<void(std::uint64_t done, std::uint64_t total)> on_progress;
};

struct PovrayRenderResult {
  std::filesystem::path image;  // DIR/render.png
  std::filesystem::path log;    // DIR/povray.log
  double seconds = 0;           // wall-clock time of the POV-Ray run
};

// Renders DIR/scene.ini. Throws Error when the folder has no scene.ini, when POV-Ray
// is not installed (naming the program looked for), or when it fails (quoting the last lines
// of its log). The log is kept as DIR/povray.log in every case; no partial image is left.
PovrayRenderResult render_povray(const std::filesystem::path& dir, const PovrayRenderOptions& options = {});

// The POV-Ray program that render_povray would run, resolved through PATH; empty when none.
std::filesystem::path find_povray(const std::string& executable = {});

}  // namespace wangscape
