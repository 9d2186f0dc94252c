// What `build`, `render` and `demo` share: a build or a render with the CLI's progress and
// messages (stages and bars on stderr only when it is a terminal; the line of what was written
// unless --quiet).
#pragma once

#include <array>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "cli/command.h"
#include "cli/progress.h"
#include "renders/ldi/ldi_scene.h"
#include "scene/scene_file.h"

namespace wangscape::cli {

// The LDI build's stages and a progress bar on a terminal (cmd_ldi.cpp); `progress` holds the
// bar and must outlive the build.
LdiSceneObserver ldi_terminal_observer(const GlobalOptions& global, std::unique_ptr<Progress>& progress);

// Builds `config` into `out_dir` (cmd_build.cpp); says what it wrote unless --quiet or not
// `say_written` (demo says it once, for the image).
void run_build(const SceneConfig& config, const std::filesystem::path& out_dir, const GlobalOptions& global,
               bool say_written = true);

struct RenderRequest {
  std::string engine = "povray";
  int width = 0, height = 0;                             // 0 = as the scene says
  std::string out;                                       // embree: the image (default DIR/render_embree.png)
  int spp = 0;                                           // embree: samples per pixel (0 = from the scene)
  std::string path, frames;                              // --path FILE --frames FOLDER: an animation along the path
  std::optional<double> fps;                             // of the path (default 24)
  long long first_frame = 0, frame_count = 0;            // a part of the path (0 frames: to its end)
  std::optional<std::array<double, 3>> camera, look_at;  // another camera (E,N[,H]; E,N,H)
  std::optional<double> fov;                             // embree, povray: another field of view (degrees)
  std::optional<std::array<double, 2>> sun;              // embree, povray: another sun (azimuth, elevation)
};
// Renders a built folder into DIR/render.png (cmd_render.cpp).
void run_render(const std::filesystem::path& dir, const RenderRequest& request, const GlobalOptions& global);

}  // namespace wangscape::cli
