#include "renders/render_folder.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "core/atomic_file.h"
#include "core/error.h"
#include "exporters/folder_state.h"
#include "exporters/image_io.h"
#include "exporters/scene_folder.h"
#include "renders/external/blender_render.h"
#include "renders/external/povray_render.h"
#include "renders/ldi/ldi_scene.h"
#include "renders/trace/embree_reference.h"

namespace wangscape {

namespace {

FolderRenderResult render_embree(const std::filesystem::path& dir, const FolderRenderRequest& request) {
  const SceneConfig config = load_scene_folder_config(dir);
  const Scene scene = make_folder_scene(dir, config);
  ReferenceOptions options;
  options.width = request.width;
  options.height = request.height;
  options.samples_per_pixel = request.samples_per_pixel;
  options.shading = ldi_options(config).shading;  // the light the folder's LDI pack is shaded with
  options.progress = request.on_progress;
  const ReferenceImage result = render_reference(scene, options);
  const std::filesystem::path image = request.out.empty() ? dir / kEmbreeRenderImage : request.out;
  write_image(image, result.image);
  const ReferenceStats& s = result.stats;
  const double rays = double(s.primary_rays + s.secondary_rays);
  const std::string summary =
      fmt::format("{} x {}, {} samples per pixel, {} flowers, build {:.1f} s, trace {:.1f} s, {:.1f} M rays/s",
                  result.image.width, result.image.height, s.samples_per_pixel, s.instances, s.build_seconds,
                  s.render_seconds, rays / 1e6 / std::max(1e-9, s.render_seconds));
  return {image, {}, {}, s.seconds, summary};
}

// One side given: the other keeps the scene's aspect ratio (160 wide of a 640 x 360 scene: 90
// high), at least one pixel.
FolderRenderRequest with_aspect_kept(const std::filesystem::path& dir, FolderRenderRequest request) {
  if ((request.width > 0) == (request.height > 0)) return request;
  const ImageConfig scene = load_scene_folder_config(dir).image;
  if (request.width > 0)
    request.height = std::max(1, int(std::lround(double(request.width) * scene.height / scene.width)));
  else
    request.width = std::max(1, int(std::lround(double(request.height) * scene.width / scene.height)));
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

FolderRenderResult render_scene_folder(const std::filesystem::path& dir, const FolderRenderRequest& asked) {
  const FolderRenderRequest request = with_aspect_kept(dir, asked);
  if (request.engine == RenderEngine::embree) return render_embree(dir, request);
  if (request.samples_per_pixel != 0)
    throw Error("render: --spp is for --engine embree; " + std::string(to_string(request.engine)) +
                " takes its samples from the scene (its antialias)");
  if (request.engine == RenderEngine::blender) {
    BlenderRenderOptions options;
    options.width = request.width;
    options.height = request.height;
    const auto result = render_blender(dir, options);
    return copied_to_out({result.image, result.log, result.blend, result.seconds, {}}, request.out);
  }
  PovrayRenderOptions options;
  options.width = request.width;
  options.height = request.height;
  options.on_progress = request.on_progress;
  const auto result = render_povray(dir, options);
  return copied_to_out({result.image, result.log, {}, result.seconds, {}}, request.out);
}

}  // namespace wangscape
