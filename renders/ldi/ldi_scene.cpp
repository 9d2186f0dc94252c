#include "renders/ldi/ldi_scene.h"

#include <span>
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

namespace {
// What the LDIs of a scene are sampled from: its filled set with the yaw placement gives each
// instance, and the full models (never the proxies camera-aware export appends: the LDIs are per
// tile at their own levels of detail).
struct SceneLdiInputs {
  FilledTileSet filled;
  std::span<const Mesh> models;
};

SceneLdiInputs scene_ldi_inputs(const Scene& scene, LdiBuildOptions& options) {
  if (!scene.field || scene.models.empty())
    throw Error("scene '" + scene.name + "': no field of flowers to sample into LDIs");
  const SceneField& field = *scene.field;
  SceneLdiInputs inputs{field.filled, scene.models};
  for (auto& points : inputs.filled.tiles)
    for (TilePoint& p : points) p.yaw = field.yaw_of(p.yaw);
  if (field.proxy_offset != 0) inputs.models = inputs.models.first(field.proxy_offset);
  options.tile_size = field.placement.tile_size;
  options.shading = with_sun(options.shading, scene.sun);
  return inputs;
}
}  // namespace

LdiBuildReport build_scene_ldi_pack(const Scene& scene, const std::filesystem::path& out, LdiBuildOptions options,
                                    const LdiSceneObserver& observer) {
  const SceneLdiInputs inputs = scene_ldi_inputs(scene, options);
  if (observer.progress) options.progress = observer.progress;
  if (observer.stage)
    observer.stage("sampling " + std::to_string(inputs.filled.tiles.size()) + " tiles x " +
                   std::to_string(options.view.levels) + " levels x " + std::to_string(options.view.directions) +
                   " directions into " + out.string());
  return build_ldi_pack(inputs.filled, inputs.models, options, out);
}

std::vector<LdiImage> build_scene_tile_ldis(const Scene& scene, LdiBuildOptions options, std::size_t tile,
                                            const LdiLevels& levels) {
  const SceneLdiInputs inputs = scene_ldi_inputs(scene, options);
  return build_tile_ldis(inputs.filled, inputs.models, options, tile, levels);
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
