// What a scene folder's readers need to open it without making the scene again, written by the
// build into the folder it stages (exporters/scene_folder.h) and checked on open:
//  - DIR/tiles.json, the filled tile set (docs/filled-tileset-format.md): the Poisson fill and
//    its relaxation, which can take a minute;
//  - DIR/scene.cache (docs/scene-folder.md): a versioned binary file with the fingerprint of
//    DIR/scene.toml, the tiles of the field that received a flower, and the baked ground.
// With them, `view`, `render --engine embree` and the LDI tools skip the fill, the ground's bake
// and a placement pass: only the DEM and the models are loaded again.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "generator/instances.h"
#include "scene/scene.h"
#include "scene/scene_file.h"

namespace wangscape {

// A built scene folder's files (docs/scene-folder.md): its scene file, named once here.
inline constexpr const char* kFolderSceneFile = "scene.toml";
inline constexpr const char* kFolderStateFile = "scene.cache";
inline constexpr const char* kFolderTilesFile = "tiles.json";
inline constexpr std::uint32_t kFolderStateVersion = 1;
// The most bytes read of each (docs/limits.md): a 16,384 x 16,384 ground bake and 50 million
// placed tiles fit in the first; the largest fill (kMaxPointsPerTile) in the second.
inline constexpr std::uintmax_t kMaxFolderStateBytes = std::uintmax_t(1) << 30;
inline constexpr std::uintmax_t kMaxFolderTilesBytes = std::uintmax_t(1) << 28;

// The field's tile grid over its area (generator/placement.h tile_range) and the cells of it that
// received at least one flower, rows south to north. Cell c is tile (i0 + c % width, j0 + c / width).
struct PlacedTiles {
  std::int64_t i0 = 0, j0 = 0;
  std::int32_t width = 0, height = 0;
  std::vector<std::uint32_t> cells;  // ascending
};

// Marks the cells of a field's grid its instances stand in, batch by batch (one stream run).
class PlacedTileCollector {
 public:
  explicit PlacedTileCollector(const SceneField& field);
  void add(const InstanceBatch& batch);
  PlacedTiles result() const;

 private:
  double tile_size_ = 1;
  PlacedTiles grid_;
  std::vector<std::uint8_t> kept_;
};

// The placed tiles of `field`, by running its placement once.
PlacedTiles place_tiles(const SceneField& field);

// What the build left for its readers.
struct FolderState {
  ScenePrebuilt prebuilt;
  PlacedTiles placed;
};

// Writes DIR/tiles.json and DIR/scene.cache for `scene` (made from `scene_text`) into `dir` (the
// staging folder), atomically each. A scene without a field writes neither.
void write_folder_state(const std::filesystem::path& dir, const std::string& scene_text, const Scene& scene,
                        const PlacedTiles& placed);

// Reads them back and checks them against the folder's scene file text. Throws Error naming the
// file: missing or from another version (a folder of an older build: build it again), made for
// another scene.toml (the file was edited after the build), truncated or corrupt.
// make_scene(config, stage, &state.prebuilt) then gives the folder's Scene as the build made it.
FolderState read_folder_state(const std::filesystem::path& dir, const std::string& scene_text);

// The folder's Scene as its build made it: make_scene of `config` (the folder's scene file,
// load_scene_folder_config) with the state its build kept; its placed tiles into `placed` when
// given. Throws Error as read_folder_state and make_scene do.
Scene make_folder_scene(const std::filesystem::path& dir, const SceneConfig& config, const StageObserver& stage = {},
                        PlacedTiles* placed = nullptr);

}  // namespace wangscape
