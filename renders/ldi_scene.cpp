#include "renders/ldi_scene.h"

#include <numbers>

#include "scene/scene.h"

namespace wangscape {

LdiBuildReport build_scene_ldi_pack(const SceneConfig& config, const std::filesystem::path& out,
                                    LdiBuildOptions options, const LdiSceneObserver& observer) {
  const Scene scene = make_scene(config, observer.stage);
  if (!scene.field || scene.models.empty())
    throw Error(config.source, "", "the scene has no field of flowers to sample into LDIs");
  const SceneField& field = *scene.field;
  FilledTileSet filled = field.filled;
  if (field.facing_yaw) {
    // The yaw SceneField::place gives an instance (scene/scene.cpp): the facing, spread over
    // +- jitter by the point's own uniform yaw.
    for (auto& points : filled.tiles)
      for (TilePoint& p : points)
        p.yaw = float(*field.facing_yaw + (2 * p.yaw / (2 * std::numbers::pi) - 1) * field.facing_jitter);
  }
  options.tile_size = field.placement.tile_size;
  const auto sun = scene.sun.direction();
  options.shading.sun_direction = {float(sun[0]), float(sun[1]), float(sun[2])};
  for (float& c : options.shading.sun_color) c *= float(scene.sun.strength);
  if (observer.progress) options.progress = observer.progress;
  if (observer.stage)
    observer.stage("sampling " + std::to_string(filled.tiles.size()) + " tiles x " +
                   std::to_string(options.view.levels) + " levels x " + std::to_string(options.view.directions) +
                   " directions into " + out.string());
  return build_ldi_pack(filled, scene.models, options, out);
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
