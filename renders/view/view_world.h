// The scene folder as the real-time view reads it (renders/view/ldi_renderer.h draws it): the
// Scene, the mmap'ed LDI pack, the placed tiles with their terrain corners, the terrain mesh in
// chunks with its lighting, and the far field beyond the pack's levels.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "folder/folder_state.h"
#include "folder/ldi_pack.h"
#include "generator/image.h"
#include "renders/ldi/ground_light.h"
#include "renders/ldi/ldi_scene.h"
#include "renders/trace/ground_colors.h"
#include "renders/trace/scene_tracer.h"
#include "renders/trace/traced_shading.h"
#include "renders/view/stem_clearance.h"
#include "renders/view/terrain_chunks.h"
#include "scene/scene.h"

namespace wangscape {

// The scene folder as the view needs it: the Scene, the pack, the placed tiles with their
// terrain corners, the terrain mesh with its lighting and the far-field colors. Immutable.
class ViewWorld {
 public:
  // Opens the scene folder DIR with its pack (SceneFolder::open, Parts::pack): its Scene as the
  // build made it, the pack and the light it was shaded with, and what the folder holds beside
  // it. Throws Error naming the file at fault: each way a folder can be unusable
  // (folder/scene_folder.h), a pack of another tile set, a steep pack of another pack, damaged
  // sky shares or ground light, or one of another tile set.
  static std::shared_ptr<const ViewWorld> load(const std::filesystem::path& dir, const StageObserver& stage = {});
  // The packs, mapped, and what a folder holds beside them that the view would otherwise make:
  // the steep sets' pack and the flowers' sky shares (null, empty: made on first use), and the
  // ground light (empty: baked on opening).
  struct Packs {
    std::shared_ptr<const LdiPack> pack, steep_pack;
    std::filesystem::path sky_shares, ground_light;
  };
  // The same from a Scene already made and its packs shaded with the light `shading` (before
  // the sun), with the field's placed tiles as its folder keeps them (folder/folder_state.h) or,
  // without them, found by a placement pass. The scene's wind is left out (the view stands still).
  ViewWorld(Scene scene, Packs packs, const ShadingSettings& shading, const PlacedTiles* placed = nullptr);
  // What a test or a benchmark holds beside a pack file it built: a steep sets' pack file, the
  // sky shares' file and the ground light's (empty: made by the view).
  struct Prepared {
    std::filesystem::path steep_pack, sky_shares, ground_light;
  };
  // The same from a pack file.
  ViewWorld(Scene scene, const std::filesystem::path& pack_path, const ShadingSettings& shading = {},
            const PlacedTiles* placed = nullptr, const Prepared& prepared = {});

  struct Tiles {                          // structure of arrays, one entry per placed tile, rows south to north
    std::vector<double> x0, y0;           // the tile's south-west corner, meters
    std::vector<std::uint32_t> tile;      // index into the set (and the pack)
    std::vector<std::int32_t> cell;       // index into the tile grid
    std::array<std::vector<float>, 4> h;  // ground height at the corners: SW, SE, NW, NE
    std::vector<float> z_min, z_max;      // of the corners
    // [[species]]: per tile, per cell of a kPlantCells x kPlantCells grid over it (rows from the
    // south, cells from the west) and per species, how many of the kPlantRankSteps rank steps of
    // the species' plants grow there (its rules and density at the cell's centre); empty without.
    static constexpr int kPlantCells = 4;
    std::vector<std::array<std::uint8_t, kPlantCells * kPlantCells * kPlantSpecies>> plant_steps;
    std::size_t size() const { return tile.size(); }
  };
  // The terrain mesh in chunks with their levels of detail (renders/view/terrain_chunks.h).
  using Terrain = TerrainChunks;

  const Scene& scene() const { return scene_; }
  const LdiPack& pack() const { return *pack_; }
  const Tiles& tiles() const { return tiles_; }
  const Terrain& terrain() const { return terrain_; }
  double tile_size() const { return tile_size_; }
  // The grid of tile cells over the field's area (-1 where no tile was placed).
  std::int64_t grid_i0() const { return grid_i0_; }
  std::int64_t grid_j0() const { return grid_j0_; }
  int grid_width() const { return grid_width_; }
  int grid_height() const { return grid_height_; }
  const std::vector<std::int32_t>& grid() const { return grid_; }
  // Per (set tile, direction): the linear average color of the coarsest LDI's front flower
  // samples and the share of its front samples that are flowers (not ground).
  const std::vector<std::array<float, 4>>& far_colors() const { return far_; }
  // Beyond the pack's levels, the field goes on as one-layer LDIs (seed 003's future work), per
  // (set tile, direction) and step: step k has 1 / 2^(k+1) of the coarsest level's resolution
  // and is drawn over twice the distance of step k - 1; beyond the last step, the far colors.
  std::uint32_t far_steps() const { return far_steps_; }
  LdiView far_ldi(std::uint32_t tile, std::uint32_t direction, std::uint32_t step) const;
  // Seen from above: the steep sets (renders/ldi/ldi_scene.h, kSteepElevations), per set, (set
  // tile, direction), one LDI (step 0) and its one-layer far steps (step k + 1 as far step k). The
  // LDIs are the folder's steep pack where it has one, else sampled on first use (prepare_steep();
  // the default scene's first frame from above 6.4 s); the far steps are made on first use (0.19 s).
  // Then immutable; thread-safe.
  static constexpr std::array<float, 6> steep_elevations() { return kSteepElevations; }
  std::uint32_t steep_resolution() const { return wangscape::steep_resolution(pack_->info()); }
  void prepare_steep() const;
  LdiView steep_ldi(std::uint32_t set, std::uint32_t tile, std::uint32_t direction, std::uint32_t step) const;
  // Whether the steep sets come from a pack (the folder's), not sampled by the view.
  bool steep_from_pack() const { return steep_pack_ != nullptr; }
  // The flowers' share of the sky the view shades them with (renders/trace/field_sky.h): the
  // folder's, or estimated on first use (0.8 s for the default scene). Thread-safe.
  const SceneTracer::SkyShares& sky_shares() const;
  // Where an eye at `eye` stands kept out of the plants' stems (StemClearance): the walk's.
  Vector3d clear_of_stems(const Vector3d& eye) const { return stems_.keep_out(*scene_.field, eye); }
  // The ground's height (meters) at (x, y), or `fallback` off the ground.
  double ground_height(double x, double y, double fallback) const;
  // Linear base color of the ground at (x, y): the baked ground texture (bilinear), or the
  // shading model's ground color without [ground]; the Embree reference's (GroundColors).
  std::array<float, 3> ground_color(double x, double y) const { return ground_colors_.at(x, y); }
  const std::array<float, 3>& sun_direction() const { return sun_; }
  // The light the pack was shaded with (the scene's [ldi] sky rays; the Embree reference of
  // --compare uses it too).
  const ShadingSettings& shading() const { return shading_; }
  // That light with the scene's sun applied (with_sun): what shade() takes.
  const ShadingSettings& sun_shading() const { return sun_shading_; }
  // The ground's base colors (the bake, or the plain ground color), as the reference sees them.
  const GroundColors& ground_colors() const { return ground_colors_; }
  // The light each tile's plants leave on the ground under them (renders/ldi/ground_light.h):
  // the terrain's shade where a tile is placed. Texels of kGroundLightResolution across a tile:
  // the folder's, else baked on opening (0.17 s for the default scene).
  const TileGroundLight& ground_light() const { return ground_light_; }
  // The placed tile (an index of tiles()) whose square holds (x, y), and where in it (u, v: 0 .. 1
  // east and north); -1 where none is placed.
  std::int32_t placed_tile_at(double x, double y, float& u, float& v) const;

 private:
  Scene scene_;
  std::shared_ptr<const LdiPack> pack_;
  Tiles tiles_;
  Terrain terrain_;
  double tile_size_ = 4;
  std::int64_t grid_i0_ = 0, grid_j0_ = 0;
  int grid_width_ = 0, grid_height_ = 0;
  std::vector<std::int32_t> grid_;
  std::vector<std::array<float, 4>> far_;
  std::uint32_t far_steps_ = 0;
  std::vector<LdiImage> far_ldis_;  // (tile * directions + direction) * far_steps_ + step
  std::shared_ptr<const LdiPack> steep_pack_;
  mutable std::once_flag sky_once_;
  mutable SceneTracer::SkyShares sky_;
  mutable std::once_flag steep_once_;
  // Index (set * tiles + tile) * directions + direction: the sets' LDIs when sampled here (no
  // steep pack), and their far steps (far_steps_ each).
  mutable std::vector<LdiImage> steep_sampled_, steep_far_;
  std::array<float, 3> sun_{0, 0, 1};
  ShadingSettings shading_;
  ShadingSettings sun_shading_;
  GroundColors ground_colors_;  // of scene_'s bake, shading_'s plain ground
  TileGroundLight ground_light_;
  StemClearance stems_;  // of scene_'s models
};

}  // namespace wangscape
