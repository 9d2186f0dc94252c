// The LDI build of a scene file: the scene's filled tile set (set, points per tile, seed,
// relaxation), its models (variants, triangle budget, scale), the field's facing applied to the
// points' yaw as placement applies it, its tile size and its sun; the view, sky rays and the
// rest come from the caller's options. What `wangscape ldi build` runs.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>

#include "folder/folder_files.h"
#include "folder/ldi_pack.h"
#include "folder/scene_folder.h"
#include "renders/ldi/ground_light.h"
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

// Builds the pack of `config` to `out` (atomically), recording the light it is shaded with.
// options.tile_size, the sun's direction and its strength (a scale of shading.sun_color) are taken
// from the scene. Throws Error naming the scene file when it has no field of flowers.
LdiBuildReport build_scene_ldi_pack(const SceneConfig& config, const std::filesystem::path& out,
                                    LdiBuildOptions options, const LdiSceneObserver& observer = {});
// The same from a scene already assembled (`wangscape build` makes it once for every export).
LdiBuildReport build_scene_ldi_pack(const Scene& scene, const std::filesystem::path& out, LdiBuildOptions options,
                                    const LdiSceneObserver& observer = {});

// The LDIs of one tile of the scene's set at levels of the caller's (the view's steep set), with
// the same inputs as the scene's pack (its points' yaw, tile size, sun, full models).
std::vector<LdiImage> build_scene_tile_ldis(const Scene& scene, LdiBuildOptions options, std::size_t tile,
                                            const LdiLevels& levels);

// The ground light under each tile's plants (renders/ldi/ground_light.h), with the same inputs as
// the scene's pack and the light `shading` (before the sun is applied), as the pack was shaded.
TileGroundLight bake_scene_ground_light(const Scene& scene, const ShadingSettings& shading, std::uint32_t resolution);

// The steep sets. Seen from above, the pack's LDIs (sampled from head height, a few degrees below
// the horizon) and the one-layer far steps made from them show their columns: a far step holds
// each column's front sample, on the tile's near side, so from higher up every tile shows a band of
// flowers and a gap behind it, rows along the tile grid converging on the vanishing point. A steep
// set is, per (set tile, direction), one LDI sampled at one of kSteepElevations (degrees below the
// horizon); the view draws them for the pack's kSteepLevels coarsest levels, at the resolution of
// the finest of those (steep_resolution), and for finer levels seen far steeper than the pack
// sampled them. The 60-degree set is for views looking down: straight down from 30 m it took SSIM
// 0.27 -> 0.39 against the truth (45, 65 and 85 degrees instead: 0.394). They are a pack of their
// own, one level per set (steep_pack_info), written by `wangscape build` beside the tiles' pack:
// sampled by the view on its first frame from above, they took 6.4 s (the default scene).
inline constexpr std::array<float, 6> kSteepElevations = {6.5f, 9.0f, 13.0f, 19.0f, 30.0f, 60.0f};
inline constexpr std::uint32_t kSteepLevels = 3;
std::uint32_t steep_resolution(const LdiPackInfo& pack);
// The steep sets' pack for the tiles' pack `pack`: its tiles, directions and prism, one level per
// set at steep_resolution, the coarsest level's distance and the set's elevation; the steepest
// first, as a pack's levels descend (steep_pack_level).
LdiPackInfo steep_pack_info(const LdiPackInfo& pack);
constexpr std::uint32_t steep_pack_level(std::uint32_t set) { return std::uint32_t(kSteepElevations.size()) - 1 - set; }
// One tile's steep sets (level steep_pack_level(k): set k), sampled with the light `shading` (the
// scene's [ldi] sky rays, before the sun is applied) as the tiles' pack was.
std::vector<LdiImage> build_scene_steep_ldis(const Scene& scene, const LdiPackInfo& pack,
                                             const ShadingSettings& shading, std::size_t tile);
// A scene folder's two packs into the folder `files` (atomically each): the tiles' (files.pack(),
// as build_scene_ldi_pack) and the steep sets' (files.steep_pack()) where they are at most twice
// the tiles' in pixels (not with kSteepLevels levels or fewer), with one progress over both. Both
// record the light they were shaded with.
void build_scene_ldi_packs(const Scene& scene, const FolderFiles& files, const LdiBuildOptions& options,
                           const LdiSceneObserver& observer = {});

// The LDI stage of a folder's build (folder/scene_folder.h): the two packs of `options`, the
// flowers' share of the sky the view shades them with (renders/trace/field_sky.h), estimated once
// here instead of on the view's first frame, and the ground light under the plants
// (bake_scene_ground_light at kGroundLightResolution), baked here instead of at every opening. The
// LDIs are sampled from the tile set, not from the placed field: a pass of their own, into the
// staging folder, so that they are published with the scene they were made from.
FolderStage ldi_folder_stage(const LdiBuildOptions& options, const LdiSceneObserver& observer = {});

}  // namespace wangscape
