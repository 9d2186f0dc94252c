#include "renders/ldi/ldi_scene.h"

#include <span>
#include <utility>

#include "folder/pack_light.h"
#include "renders/trace/field_sky.h"
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

// The levels of a scene's pack (as build_ldi_pack derives them).
LdiLevels pack_levels(const SceneLdiInputs& inputs, const LdiBuildOptions& options) {
  return ldi_levels(options.view, options.tile_size, ldi_prism_top(inputs.filled, inputs.models));
}
}  // namespace

LdiBuildReport build_scene_ldi_pack(const Scene& scene, const std::filesystem::path& out, LdiBuildOptions options,
                                    const LdiSceneObserver& observer) {
  const LdiPackLight light = pack_light_record(options.shading, scene.sun);  // before the sun is applied
  const SceneLdiInputs inputs = scene_ldi_inputs(scene, options);
  if (observer.progress) options.progress = observer.progress;
  if (observer.stage)
    observer.stage("sampling " + std::to_string(inputs.filled.tiles.size()) + " tiles x " +
                   std::to_string(options.view.levels) + " levels x " + std::to_string(options.view.directions) +
                   " directions into " + out.string());
  LdiPackInfo info = ldi_pack_info(inputs.filled, inputs.models, options);
  info.light = light;
  return build_ldi_pack(inputs.filled, inputs.models, options, pack_levels(inputs, options), info, out);
}

std::vector<LdiImage> build_scene_tile_ldis(const Scene& scene, LdiBuildOptions options, std::size_t tile,
                                            const LdiLevels& levels) {
  const SceneLdiInputs inputs = scene_ldi_inputs(scene, options);
  return build_tile_ldis(inputs.filled, inputs.models, options, tile, levels);
}

TileGroundLight bake_scene_ground_light(const Scene& scene, const ShadingSettings& shading, std::uint32_t resolution) {
  LdiBuildOptions options;
  options.shading = shading;
  const SceneLdiInputs inputs = scene_ldi_inputs(scene, options);
  return bake_tile_ground_light(inputs.filled, inputs.models, options, resolution);
}

std::uint32_t steep_resolution(const LdiPackInfo& pack) {
  return pack.resolutions[pack.levels - std::min(pack.levels, kSteepLevels)];
}

LdiPackInfo steep_pack_info(const LdiPackInfo& pack) {
  LdiPackInfo steep = pack;
  steep.levels = std::uint32_t(kSteepElevations.size());
  steep.resolutions.assign(kSteepElevations.size(), steep_resolution(pack));
  steep.level_distances.assign(kSteepElevations.size(), pack.level_distances.back());
  steep.elevations.assign(kSteepElevations.rbegin(), kSteepElevations.rend());  // steep_pack_level()
  return steep;
}

namespace {
// The steep sets as levels of a build, and the options they are sampled with: the tiles' pack's
// head height as the pack holds it (a float), so that a folder's steep pack and the view's own
// sampling give the same bytes.
LdiLevels steep_levels(const LdiPackInfo& steep) {
  LdiLevels levels;
  levels.prism_top = steep.prism_top;
  for (std::uint32_t k = 0; k < steep.levels; ++k) {
    levels.resolutions.push_back(steep.resolutions[k]);
    levels.distances.push_back(steep.level_distances[k]);
    levels.elevations.push_back(steep.elevations[k]);
  }
  return levels;
}

LdiBuildOptions steep_options(const LdiPackInfo& steep, const ShadingSettings& shading) {
  LdiBuildOptions options;
  options.shading = shading;
  options.view.head_height = steep.head_height;
  options.view.directions = int(steep.directions);
  return options;
}
}  // namespace

std::vector<LdiImage> build_scene_steep_ldis(const Scene& scene, const LdiPackInfo& pack,
                                             const ShadingSettings& shading, std::size_t tile) {
  const LdiPackInfo steep = steep_pack_info(pack);
  return build_scene_tile_ldis(scene, steep_options(steep, shading), tile, steep_levels(steep));
}

void build_scene_ldi_packs(const Scene& scene, const FolderFiles& files, const LdiBuildOptions& options,
                           const LdiSceneObserver& observer) {
  const std::filesystem::path pack_file = files.pack(), steep_file = files.steep_pack();
  LdiBuildOptions tiles_options = options;
  const SceneLdiInputs inputs = scene_ldi_inputs(scene, tiles_options);
  LdiPackInfo pack = ldi_pack_info(inputs.filled, inputs.models, tiles_options);
  pack.light = pack_light_record(options.shading, scene.sun);
  const LdiPackInfo steep = steep_pack_info(pack);
  // With fewer levels than kSteepLevels the steep sets take the finest level's resolution: six
  // sets of it (156 MB for a 16 x 24 m field of two levels) would outweigh the tiles' pack, and
  // the view samples them if it ever looks down. Written only when at most twice the tiles' (the
  // default scene's seven levels: a fifth of them, 19 MB).
  const auto pixels = [](const LdiPackInfo& info) {
    double sum = 0;
    for (const std::uint32_t r : info.resolutions) sum += double(r) * double(r);
    return sum;
  };
  const bool with_steep = pixels(steep) <= 2 * pixels(pack);
  // One progress over both packs: the steep sets' LDIs and rays follow the tiles'.
  const std::uint64_t tiles_total = std::uint64_t(pack.tiles) * pack.levels * pack.directions;
  const std::uint64_t total =
      tiles_total + (with_steep ? std::uint64_t(steep.tiles) * steep.levels * steep.directions : 0);
  const auto report = [&](std::uint64_t before, std::uint64_t rays_before) {
    return [&observer, &total, before, rays_before](std::uint64_t done, std::uint64_t, std::uint64_t rays) {
      if (observer.progress) observer.progress(before + done, total, rays_before + rays);
    };
  };
  if (observer.stage)
    observer.stage(
        "sampling " + std::to_string(pack.tiles) + " tiles x " + std::to_string(pack.levels) + " levels x " +
        std::to_string(pack.directions) + " directions into " + pack_file.string() +
        (with_steep ? ", and " + std::to_string(steep.levels) + " steep sets into " + steep_file.string() : ""));
  tiles_options.progress = report(0, 0);
  const LdiBuildReport tiles =
      build_ldi_pack(inputs.filled, inputs.models, tiles_options, pack_levels(inputs, tiles_options), pack, pack_file);
  if (!with_steep) return;
  LdiBuildOptions steep_build = steep_options(steep, tiles_options.shading);  // (the sun already applied)
  steep_build.tile_size = tiles_options.tile_size;
  steep_build.progress = report(tiles_total, tiles.primary_rays + tiles.secondary_rays);
  build_ldi_pack(inputs.filled, inputs.models, steep_build, steep_levels(steep), steep, steep_file);
}

LdiBuildOptions ldi_options(const SceneConfig& config) {
  LdiBuildOptions options;
  options.view.head_height = config.ldi.head_height;
  options.view.levels = config.ldi.levels;
  options.view.directions = config.ldi.directions;
  options.shading = scene_file_light(config);
  return options;
}

FolderStage ldi_folder_stage(const LdiBuildOptions& options, const LdiSceneObserver& observer) {
  return [options, observer](FolderBuild& build) {
    build_scene_ldi_packs(build.scene, build.staging, options, observer);
    if (observer.stage) observer.stage("estimating the flowers' share of the sky");
    write_sky_shares(build.staging.sky_shares(),
                     bake_field_sky(build.scene, with_sun(options.shading, build.scene.sun)));
    // The view's bake, with its inputs (the light before the sun, as the pack records it).
    if (observer.stage) observer.stage("baking the light the plants leave on the ground");
    write_ground_light(build.staging.ground_light(),
                       bake_scene_ground_light(build.scene, options.shading, kGroundLightResolution));
  };
}

}  // namespace wangscape
