// What a scene folder's readers need to open it without making the scene again, written by the
// build into the folder it stages (folder/scene_folder.h, the kept state's stage) and checked on
// open (SceneFolder::open):
//  - DIR/tiles.json, the filled tile set (docs/filled-tileset-format.md): the Poisson fill and
//    its relaxation, which can take a minute;
//  - DIR/scene.cache (docs/scene-folder.md): a versioned binary file (core/binary_file.h) with
//    the fingerprint of DIR/scene.toml, the tiles of the field that received a flower with the
//    set's tile laid at each, the baked ground and the scene's models (their proxies too).
// With them, `view`, `render --engine embree` and the LDI tools skip the fill, the ground's bake,
// a placement pass, the tiling and the models' making: only the DEM is loaded again.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "folder/folder_files.h"
#include "generator/instances.h"
#include "scene/scene.h"
#include "scene/scene_file.h"

namespace wangscape {

// The most bytes of the tile set read (the largest fill, kMaxPointsPerTile, fits). scene.cache is
// read field by field, each count checked against the bytes left before anything is allocated.
inline constexpr std::uintmax_t kMaxFolderTilesBytes = std::uintmax_t(1) << 28;

// The field's tile grid over its area (generator/placement.h tile_range) and the cells of it that
// received at least one flower, rows south to north. Cell c is tile (i0 + c % width, j0 + c / width).
struct PlacedTiles {
  std::int64_t i0 = 0, j0 = 0;
  std::int32_t width = 0, height = 0;
  std::vector<std::uint32_t> cells;  // ascending
  // The set's tile laid at each of `cells` (placed_set_tiles), kept so that the view need not run
  // the tiling again; empty where not known (a version 1 folder, a placement pass's result).
  std::vector<std::uint16_t> set_tiles;
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

// The set's tile laid at each of placed.cells, in their order, by running the field's tiling over
// its grid (generator/placement.h RowTiles, as placement lays it).
std::vector<std::uint16_t> placed_set_tiles(const SceneField& field, const PlacedTiles& placed);

// What the build left for its readers.
struct FolderState {
  ScenePrebuilt prebuilt;
  PlacedTiles placed;
};

// Writes the tile set and the cache (files.tiles(), files.state()) for `scene` (made from
// `scene_text`) into the staging folder `files`, atomically each, with the set's tile at each
// placed cell (placed.set_tiles, or placed_set_tiles when empty) and the scene's models, every
// field of every mesh bit for bit. A scene without a field writes neither.
void write_folder_state(const FolderFiles& files, const std::string& scene_text, const Scene& scene,
                        const PlacedTiles& placed);

// Reads them back and checks them against the folder's scene file text. Throws Error naming the
// file: missing or from another version (a folder of an older build: build it again), made for
// another scene file (the file was edited after the build), truncated or corrupt (a set's tile
// the tile set does not hold among them, a model's vertex, material or image that is not there).
// A version 1 cache gives no placed.set_tiles; one of version 1 or 2 no prebuilt.models.
// make_scene(config, stage, &state.prebuilt) then gives the folder's Scene as the build made it.
FolderState read_folder_state(const FolderFiles& files, const std::string& scene_text);

}  // namespace wangscape
