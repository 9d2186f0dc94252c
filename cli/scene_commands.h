// What `build`, `render` and `demo` share: the pipeline and the render run with the CLI's
// progress and messages (stderr, only when it is a terminal and --quiet is off).
#pragma once

#include <filesystem>
#include <string>

#include "cli/command.h"
#include "cli/scene_config.h"

namespace wangscape::cli {

// Builds `config` into `out_dir` (cmd_build.cpp).
void run_build(const SceneConfig& config, const std::filesystem::path& out_dir, const GlobalOptions& global);

struct RenderRequest {
  std::string engine = "povray";
  int width = 0, height = 0;  // 0 = as the scene says
};
// Renders a built folder into DIR/render.png (cmd_render.cpp).
void run_render(const std::filesystem::path& dir, const RenderRequest& request, const GlobalOptions& global);

// True when progress and messages go to stderr.
bool chatty(const GlobalOptions& global);

}  // namespace wangscape::cli
