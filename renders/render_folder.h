// One entry point for rendering a scene folder with any engine the folder was built for, so the
// program and batch runs choose engines by name.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include "renders/external/render_engine.h"
#include "scene/scene_file.h"

namespace wangscape {

struct FolderRenderRequest {
  RenderEngine engine = RenderEngine::povray;
  int width = 0, height = 0;  // 0 = as the scene says
  // Embree only: the image (default DIR/render_embree.png) and samples per pixel (0 = the
  // scene's antialias setting squared). Other engines refuse them.
  std::filesystem::path out;
  int samples_per_pixel = 0;
  // POV-Ray and Embree: pixels done of the total, now and then.
  std::function<void(std::uint64_t done, std::uint64_t total)> on_progress;
  // Another camera than the scene's, without building the folder again: each part given replaces
  // the scene camera's. The eye E, N, H (ENU m; H NaN: the [ldi] head height above the ground),
  // the point looked at E, N, H.
  std::optional<std::array<double, 3>> eye, look_at;
  // Embree and POV-Ray: another horizontal field of view (degrees, in (0, 180)) and another sun
  // (its azimuth and elevation, degrees, as [sun] has them); the scene's strength and colour stay.
  std::optional<double> fov_degrees;
  std::optional<std::array<double, 2>> sun_degrees;
};

struct FolderRenderResult {
  std::filesystem::path image, log;
  std::filesystem::path blend;  // Blender: the .blend saved beside the image
  double seconds = 0;
  std::string summary;  // Embree: size, samples, flowers, build and trace seconds, rays per second
};

// The image `wangscape render DIR --engine embree` writes unless told otherwise.
inline constexpr const char* kEmbreeRenderImage = "render_embree.png";

// Renders DIR with the requested engine. Embree renders the folder's Scene (SceneFolder::open,
// folder/scene_folder.h) with the light its LDI pack was shaded with, so it needs no export of
// its own. Throws Error naming a folder without that engine's export, or the
// renderer's own failure; with another camera, Error for an eye without a height that is not
// over the ground or a point looked at that is not sideways of the eye.
// The image size of a render of DIR asked as `width` x `height`: 0 x 0 the scene's; one side
// given, the other keeps the scene's aspect ratio (at least one pixel).
std::array<int, 2> folder_image_size(const SceneConfig& config, int width, int height);

FolderRenderResult render_scene_folder(const std::filesystem::path& dir, const FolderRenderRequest& request);

}  // namespace wangscape
