// The LDI build of a scene file: the scene's filled tile set (set, points per tile, seed,
// relaxation), its models (variants, triangle budget, scale), the field's facing applied to the
// points' yaw as placement applies it, its tile size and its sun; the view, sky rays and the
// rest come from the caller's options. What `wangscape ldi build` runs.
#pragma once

#include <filesystem>
#include <functional>
#include <string>

#include "renders/ldi/ldi_build.h"
#include "scene/scene.h"
#include "scene/scene_file.h"

namespace wangscape {

struct LdiSceneObserver {
  std::function<void(const std::string& message)> stage;  // assembling the scene, building
  // LDIs done / total and rays traced so far (worker threads, one call at a time).
  std::function<void(std::uint64_t done, std::uint64_t total, std::uint64_t rays)> progress;
};

// The options the scene file's [ldi] section gives (head height, levels, directions, sky rays).
LdiBuildOptions ldi_options(const SceneConfig& config);

// Builds the pack of `config` to `out` (atomically). options.tile_size, the sun's direction and
// its strength (a scale of shading.sun_color) are taken from the scene. Throws Error naming the
// scene file when it has no field of flowers.
LdiBuildReport build_scene_ldi_pack(const SceneConfig& config, const std::filesystem::path& out,
                                    LdiBuildOptions options, const LdiSceneObserver& observer = {});
// The same from a scene already assembled (`wangscape build` makes it once for every export).
LdiBuildReport build_scene_ldi_pack(const Scene& scene, const std::filesystem::path& out, LdiBuildOptions options,
                                    const LdiSceneObserver& observer = {});

// The LDIs of one tile of the scene's set at levels of the caller's (the view's steep set), with
// the same inputs as the scene's pack (its points' yaw, tile size, sun, full models).
std::vector<LdiImage> build_scene_tile_ldis(const Scene& scene, LdiBuildOptions options, std::size_t tile,
                                            const LdiLevels& levels);

}  // namespace wangscape
