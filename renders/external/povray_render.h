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
  // A .pov file in DIR rendered instead of scene.ini's Input_File_Name (the folder's scene with
  // other cameras, exporters/povray_writer.h's povray_scene_with_cameras).
  std::string input_file;
  // An animation: frames > 0 renders frame_number 0 .. frames - 1 in one POV-Ray run (+KFI0
  // +KFF<frames - 1>; POV-Ray parses the scene again for each frame, in the same process). Each
  // frame is written into `frames_dir` (an existing, empty folder) and, once complete, handed to
  // on_frame(k, file), which moves it away; the still image is then not written.
  int frames = 0;
  std::filesystem::path frames_dir;
  std::function<void(int frame, const std::filesystem::path& file)> on_frame;
};

struct PovrayRenderResult {
  std::filesystem::path image;  // DIR/render.png (empty for an animation)
  std::filesystem::path log;    // DIR/povray.log
  double seconds = 0;           // wall-clock time of the POV-Ray run
};

// Renders DIR/scene.ini. Throws Error when the folder has no scene.ini, when POV-Ray
// is not installed (naming the program looked for), or when it fails (quoting the last lines
// of its log). The log is kept as DIR/povray.log in every case; no partial image is left (of an
// animation: the frames completed before the failure have been handed to on_frame).
PovrayRenderResult render_povray(const std::filesystem::path& dir, const PovrayRenderOptions& options = {});

// The POV-Ray program that render_povray would run, resolved through PATH; empty when none.
std::filesystem::path find_povray(const std::string& executable = {});

}  // namespace wangscape
