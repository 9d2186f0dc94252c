#include "renders/render_folder.h"

#include "core/error.h"
#include "renders/blender_render.h"
#include "renders/povray_render.h"

namespace wangscape {

FolderRenderResult render_scene_folder(const std::filesystem::path& dir, const FolderRenderRequest& request) {
  if (request.engine == "blender") {
    BlenderRenderOptions options;
    options.width = request.width;
    options.height = request.height;
    const auto result = render_blender(dir, options);
    return {result.image, result.log, result.blend, result.seconds};
  }
  if (request.engine != "povray")
    throw Error("render: engine '" + request.engine + "' is not available in this wangscape (known: povray, blender)");
  PovrayRenderOptions options;
  options.width = request.width;
  options.height = request.height;
  options.on_progress = request.on_progress;
  const auto result = render_povray(dir, options);
  return {result.image, result.log, {}, result.seconds};
}

}  // namespace wangscape
