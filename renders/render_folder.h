// One entry point for rendering a scene folder with any engine the folder was built for, so the
// program and batch runs choose engines by name.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

namespace wangscape {

struct FolderRenderRequest {
  std::string engine = "povray";  // povray or blender
  int width = 0, height = 0;      // 0 = as the scene says
  // POV-Ray only: pixels done of the total, now and then.
  std::function<void(std::uint64_t done, std::uint64_t total)> on_progress;
};

struct FolderRenderResult {
  std::filesystem::path image, log;
  std::filesystem::path blend;  // Blender: the .blend saved beside the image
  double seconds = 0;
};

// Renders DIR with the requested engine. Throws Error naming an unknown engine (and the known
// ones), a folder without that engine's export, or the renderer's own failure.
FolderRenderResult render_scene_folder(const std::filesystem::path& dir, const FolderRenderRequest& request);

}  // namespace wangscape
