#include "renders/render_folder.h"

#include <fmt/format.h>

#include <algorithm>

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

}  // namespace

FolderRenderResult render_scene_folder(const std::filesystem::path& dir, const FolderRenderRequest& request) {
  if (request.engine == RenderEngine::embree) return render_embree(dir, request);
  if (!request.out.empty() || request.samples_per_pixel != 0)
    throw Error("render: --out and --spp are for --engine embree; " + std::string(to_string(request.engine)) +
                " writes its image into the folder and takes its samples from the scene");
  if (request.engine == RenderEngine::blender) {
    BlenderRenderOptions options;
    options.width = request.width;
    options.height = request.height;
    const auto result = render_blender(dir, options);
    return {result.image, result.log, result.blend, result.seconds, {}};
  }
  PovrayRenderOptions options;
  options.width = request.width;
  options.height = request.height;
  options.on_progress = request.on_progress;
  const auto result = render_povray(dir, options);
  return {result.image, result.log, {}, result.seconds, {}};
}

}  // namespace wangscape
