#include "renders/render_folder.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <optional>

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/number_text.h"
#include "core/text_file.h"
#include "exporters/image_io.h"
#include "exporters/povray_writer.h"
#include "folder/scene_folder.h"
#include "renders/external/blender_render.h"
#include "renders/external/povray_render.h"
#include "renders/trace/embree_reference.h"

namespace wangscape {

namespace {

bool other_camera(const FolderRenderRequest& request) { return request.eye || request.look_at || request.fov_degrees; }

// The scene's camera with the parts `request` gives replaced.
Camera chosen_camera(const Scene& scene, const SceneConfig& config, const FolderRenderRequest& request) {
  Camera camera = scene.camera;
  if (request.eye) {
    camera.position = *request.eye;
    if (std::isnan(camera.position[2])) {
      const auto ground =
          scene.field ? scene.field->ground.height(camera.position[0], camera.position[1]) : std::optional<double>();
      if (!ground)
        throw Error("render: eye at " + number_text(camera.position[0]) + "," + number_text(camera.position[1]) +
                    ": not over the ground; give its height too (E,N,H)");
      camera.position[2] = *ground + config.ldi.head_height;
    }
  }
  if (request.look_at) camera.target = *request.look_at;
  if (request.fov_degrees) camera.fov_degrees = *request.fov_degrees;
  if (!(std::hypot(camera.target[0] - camera.position[0], camera.target[1] - camera.position[1]) >= 1e-6))
    throw Error("render: the point looked at must lie sideways of the eye (not straight above, below or at it)");
  return camera;
}

// The scene's sun, or the one `request` asks (its strength and colour kept).
Sun chosen_sun(const Scene& scene, const FolderRenderRequest& request) {
  Sun sun = scene.sun;
  if (request.sun_degrees) {
    sun.azimuth_degrees = (*request.sun_degrees)[0];
    sun.elevation_degrees = (*request.sun_degrees)[1];
  }
  return sun;
}

// Moves a renderer's finished image into place.
void move_image(const std::filesystem::path& from, const std::filesystem::path& to) {
  std::error_code ec;
  std::filesystem::rename(from, to, ec);
  if (ec) throw Error(to, "", "cannot move the rendered image here: " + ec.message());
}

FolderRenderResult render_embree(const SceneFolder& folder, const FolderRenderRequest& request) {
  const SceneConfig& config = folder.config();
  Scene scene = folder.make_scene();
  scene.sun = chosen_sun(scene, request);
  ReferenceOptions options;
  if (other_camera(request)) options.camera = chosen_camera(scene, config, request);
  options.width = request.width;
  options.height = request.height;
  options.samples_per_pixel = request.samples_per_pixel;
  options.shading = folder.light();  // the light the folder's LDI pack is shaded with
  options.progress = request.on_progress;
  const ReferenceImage result = render_reference(scene, options);
  const std::filesystem::path image = request.out.empty() ? folder.files().root() / kEmbreeRenderImage : request.out;
  write_image(image, result.image);
  const ReferenceStats& s = result.stats;
  const double rays = double(s.primary_rays + s.secondary_rays);
  const std::string summary =
      fmt::format("{} x {}, {} samples per pixel, {} flowers, build {:.1f} s, trace {:.1f} s, {:.1f} M rays/s",
                  result.image.width, result.image.height, s.samples_per_pixel, s.instances, s.build_seconds,
                  s.render_seconds, rays / 1e6 / std::max(1e-9, s.render_seconds));
  return {image, {}, {}, s.seconds, summary};
}

// One side given: the other keeps the scene's aspect ratio (folder_image_size).
FolderRenderRequest with_aspect_kept(const SceneConfig& config, FolderRenderRequest request) {
  if ((request.width > 0) == (request.height > 0)) return request;
  const auto [width, height] = folder_image_size(config, request.width, request.height);
  request.width = width;
  request.height = height;
  return request;
}

// POV-Ray and Blender write into the folder; --out is a copy of that image, made atomically.
FolderRenderResult copied_to_out(FolderRenderResult result, const std::filesystem::path& out) {
  if (out.empty()) return result;
  AtomicPath copy(out);
  std::error_code failed;
  std::filesystem::copy_file(result.image, copy.temp_path(), std::filesystem::copy_options::overwrite_existing, failed);
  if (failed) throw Error(out, "", "cannot copy the render " + result.image.string() + ": " + failed.message());
  copy.commit();
  result.image = out;
  return result;
}

}  // namespace

std::array<int, 2> folder_image_size(const SceneConfig& config, int width, int height) {
  if (width > 0 && height > 0) return {width, height};
  const ImageConfig& scene = config.image;
  if (width > 0) return {width, std::max(1, int(std::lround(double(width) * scene.height / scene.width)))};
  if (height > 0) return {std::max(1, int(std::lround(double(height) * scene.width / scene.height))), height};
  return {scene.width, scene.height};
}

FolderRenderResult render_scene_folder(const std::filesystem::path& dir, const FolderRenderRequest& asked) {
  // The folder is opened only where the render needs it: the scene made again for Embree, another
  // camera or POV-Ray's other sun; the scene file for a size given by one side.
  const bool made = asked.engine == RenderEngine::embree || other_camera(asked) ||
                    (asked.sun_degrees && asked.engine == RenderEngine::povray);
  std::optional<SceneFolder> folder;
  if (made || (asked.width > 0) != (asked.height > 0))
    folder.emplace(SceneFolder::open(dir, made ? SceneFolder::Parts::state : SceneFolder::Parts::scene_file));
  const FolderRenderRequest request = folder ? with_aspect_kept(folder->config(), asked) : asked;
  if (request.engine == RenderEngine::embree) return render_embree(*folder, request);
  if (request.samples_per_pixel != 0)
    throw Error("render: --spp is for --engine embree (and blender --path); " + std::string(to_string(request.engine)) +
                " takes its samples from the scene (its antialias)");
  if (request.engine == RenderEngine::blender && (request.fov_degrees || request.sun_degrees))
    throw Error(
        "render: --fov and --sun are for --engine embree and povray; blender renders the folder's export, whose "
        "camera lens and sun were written by the build");
  if (request.engine == RenderEngine::blender) {
    BlenderRenderOptions options;
    options.width = request.width;
    options.height = request.height;
    if (!other_camera(request)) {
      const auto result = render_blender(dir, options);
      return copied_to_out({result.image, result.log, result.blend, result.seconds, {}}, request.out);
    }
    // Another camera: a one-frame run of the frames' script (renders/external/blender_render.h),
    // its frame moved to the still's name.
    const Camera camera = chosen_camera(folder->make_scene(), folder->config(), request);
    AtomicPath work(dir / "blender_camera");  // a folder under a temporary's name, removed when done
    std::filesystem::create_directory(work.temp_path());
    const nlohmann::json spec{{"fps", 1},
                              {"cameras",
                               {{camera.position[0], camera.position[1], camera.position[2], camera.target[0],
                                 camera.target[1], camera.target[2]}}},
                              {"render", {0}}};
    write_file_atomically(work.temp_path() / "cameras.json", spec.dump());
    options.cameras_file = work.temp_path() / "cameras.json";
    options.frames_dir = work.temp_path();
    const std::filesystem::path image = dir / "render_blender.png";
    bool rendered = false;
    options.on_frame = [&](int, const std::filesystem::path& file) {
      move_image(file, image);
      rendered = true;
    };
    BlenderRenderResult result;
    std::error_code ec;
    try {
      result = render_blender(dir, options);
    } catch (...) {
      std::filesystem::remove_all(work.temp_path(), ec);
      throw;
    }
    std::filesystem::remove_all(work.temp_path(), ec);
    if (!rendered) throw Error(image, "", "Blender ended without rendering it; log " + result.log.string());
    return copied_to_out({image, result.log, result.blend, result.seconds, {}}, request.out);
  }
  PovrayRenderOptions options;
  options.width = request.width;
  options.height = request.height;
  options.on_progress = request.on_progress;
  // Another camera or sun: the folder's scene.pov with it, in a temporary .pov beside it.
  AtomicPath pov(dir / "scene_camera.pov");  // never committed: removed when done
  const std::filesystem::path pov_file = FolderFiles(dir).povray_scene();
  if (made && std::filesystem::is_regular_file(pov_file)) {
    const std::string text = read_text_file(pov_file, std::uintmax_t(1) << 30, "POV-Ray scene");
    const Scene scene = folder->make_scene();
    const Camera camera = chosen_camera(scene, folder->config(), request);
    write_file_atomically(pov.temp_path(), request.sun_degrees ? povray_scene_with_camera_and_sun(
                                                                     text, camera, chosen_sun(scene, request), pov_file)
                                                               : povray_scene_with_cameras(text, {camera}, pov_file));
    options.input_file = pov.temp_path().filename().string();
  }
  const auto result = render_povray(dir, options);
  return copied_to_out({result.image, result.log, {}, result.seconds, {}}, request.out);
}

}  // namespace wangscape
