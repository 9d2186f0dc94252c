#include "renders/ldi/ldi_scene.h"

#include <utility>

#include "scene/scene.h"

namespace wangscape {

LdiBuildReport build_scene_ldi_pack(const SceneConfig& config, const std::filesystem::path& out,
                                    LdiBuildOptions options, const LdiSceneObserver& observer) {
  const Scene scene = make_scene(config, observer.stage);
  if (!scene.field || scene.models.empty())
    throw Error(config.source, "", "the scene has no field of flowers to sample into LDIs");
  return build_scene_ldi_pack(scene, out, std::move(options), observer);
}

LdiBuildReport build_scene_ldi_pack(const Scene& scene, const std::filesystem::path& out, LdiBuildOptions options,
                                    const LdiSceneObserver& observer) {
  if (!scene.field || scene.models.empty())
    throw Error("scene '" + scene.name + "': no field of flowers to sample into LDIs");
  const SceneField& field = *scene.field;
  FilledTileSet filled = field.filled;
  for (auto& points : filled.tiles)  // the yaw placement gives each instance
    for (TilePoint& p : points) p.yaw = field.yaw_of(p.yaw);
  options.tile_size = field.placement.tile_size;
  options.shading = with_sun(options.shading, scene.sun);
  if (observer.progress) options.progress = observer.progress;
  if (observer.stage)
    observer.stage("sampling " + std::to_string(filled.tiles.size()) + " tiles x " +
                   std::to_string(options.view.levels) + " levels x " + std::to_string(options.view.directions) +
                   " directions into " + out.string());
  // The LDIs are per tile at their own levels of detail: the full models, never the proxies
  // camera-aware export appends.
  if (field.proxy_offset == 0) return build_ldi_pack(filled, scene.models, options, out);
  const std::vector<Mesh> full(scene.models.begin(), scene.models.begin() + std::ptrdiff_t(field.proxy_offset));
  return build_ldi_pack(filled, full, options, out);
}

LdiBuildOptions ldi_options(const SceneConfig& config) {
  LdiBuildOptions options;
  options.view.head_height = config.ldi.head_height;
  options.view.levels = config.ldi.levels;
  options.view.directions = config.ldi.directions;
  options.shading.ao_rays = config.ldi.sky_rays;
  return options;
}

}  // namespace wangscape
