// The LDI build (Shade 2002, section 4; Cohen 2003, section 4.1): every tile of a filled tile set, with
// its models, sampled by Embree into multiresolution, view-dependent, pre-shaded Layered Depth
// Images. Per tile, level (1..L tiles from the viewer) and direction (8 compass azimuths), one
// orthographic LDI of the tile's prism, sampled in a 3 x 3 context of matching neighbours:
//  - rays are jittered inside their pixel (deterministic per pixel from the seed), clipped to the
//    centre prism and traced once with an intersection filter that records every hit and rejects
//    it (Embree's next_hit pattern), so every surface along the ray is kept;
//  - hits are de-duplicated by (instance, geometry, primitive), those outside the centre prism
//    dropped, and hits closer than a merge distance along the ray merged into the front one;
//  - each sample is shaded once (renders/trace/traced_shading.h) with shadow and sky rays in the context.
// Units: meters; tile-local coordinates (x east from the tile's west edge, y north from its south
// edge, z up from the ground plane at z = 0).
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <span>
#include <string_view>
#include <utility>
#include <vector>

#include "folder/ldi.h"
#include "folder/ldi_pack.h"
#include "generator/poisson_tiles.h"
#include "renders/trace/traced_shading.h"
#include "templates/mesh.h"

namespace wangscape {

// Where the viewer stands and what it sees: fixes each level's distance, elevation and resolution.
struct LdiViewSettings {
  int levels = 7;            // level k (1-based) = the tile whose near edge is k tiles from the viewer
  int directions = 8;        // azimuths 0, 360/D, ... (compass degrees the rays travel towards)
  double head_height = 1.7;  // meters: the viewer's eye above the ground
  // The view the resolutions are derived for (Shade 2002: "a splat of one pixel"). With 512 pixels
  // and 60 degrees, the default scene's set (4 m tiles, prism top 2.92 m) gets 427, 220, 148, 111,
  // 89, 74, 64 against Shade 2002's 468, 232, 151, 111, 88, 73, 62 (its view size is not given):
  // levels 3-7 within 3 %, level 1 9 % lower (Shade 2002's flowers and box height are not given;
  // here the box top is 1.2 m above the eye and the near edge 4 m away).
  int image_width = 512;    // pixels
  double fov_degrees = 60;  // horizontal
};

// What the ground under the flowers contributes to an LDI.
enum class LdiGround : std::uint8_t {
  none,     // not sampled
  visible,  // one sample where a ray reaches it without meeting a flower first (where it shows through)
  always,   // the last layer of every ray that reaches it
};
// The grounds by the names users write, for the command line's choices.
inline constexpr std::array<std::pair<LdiGround, std::string_view>, 3> kLdiGroundNames{
    {{LdiGround::none, "none"}, {LdiGround::visible, "visible"}, {LdiGround::always, "always"}}};

struct LdiBuildOptions {
  double tile_size = 4.0;  // meters
  LdiViewSettings view;
  ShadingSettings shading;
  LdiGround ground = LdiGround::visible;
  std::uint64_t seed = 1;     // ray jitter and sky directions
  double merge_pixels = 1.0;  // hits closer than this many pixel sizes along a ray merge into the front one
  int max_hits = 64;          // per ray, before de-duplication and merging; further hits are dropped (counted)
  // Which 3 x 3 context of matching neighbours each tile is sampled in: the k-th consistent one
  // in index order (modulo how many exist). Which samples exist, their depths and normals do not
  // depend on it (tested); their shading does where shadows and sky light come from flowers that
  // stand wholly inside a neighbour.
  int context_choice = 0;
  // 1: rtcIntersect1; 4, 8 or 16: rtcIntersectN over runs of a row (same LDIs; 16 measured
  // fastest, bench/ldi_bench BM_LdiSamplerRays).
  int packet_width = 16;
  // Each flower an instance of its model's scene (single-level instancing), or false: each
  // context flattened into one scene holding a transformed copy of every flower (about 20 % less
  // CPU for the whole build, bench/ldi_bench BM_LdiTileBreakdown; 3 x 3 x 20 x 5,000 triangles).
  bool instancing = false;
  // LDIs done / total and rays traced so far; called from worker threads, one call at a time.
  std::function<void(std::uint64_t done, std::uint64_t total, std::uint64_t rays)> progress;
};

// What the build did.
struct LdiBuildReport {
  std::uint64_t ldis = 0;
  std::uint64_t primary_rays = 0;    // one per pixel whose ray crosses the prism
  std::uint64_t secondary_rays = 0;  // shadow and sky rays
  std::uint64_t hits = 0;            // filter calls recorded (before de-duplication)
  std::uint64_t duplicate_hits = 0, outside_hits = 0, merged_hits = 0, dropped_hits = 0;
  std::uint64_t depth_pixels = 0;
  double seconds = 0;               // wall clock of the whole call
  double sampling_seconds = 0;      // of it, tracing and shading (no Embree scene builds, no writing)
  double sampling_cpu_seconds = 0;  // CPU time (all threads of the process) of the tracing and shading
};

// Per-level figures of a set: what the pack header records.
struct LdiLevels {
  double prism_top = 0;                    // meters: the tallest model instance, plus a margin
  std::vector<std::uint32_t> resolutions;  // pixels across a tile side, per level
  std::vector<double> distances;           // meters from the viewer to the tile's near edge
  std::vector<double> elevations;          // degrees below the horizon, per level
};
// Shade 2002's derivation: the tile's bounding box (side tile_size, height prism_top) is put with its
// near edge level x tile_size ahead of a viewer at head height, the camera turned to look at the
// centre of the box's top, and the box top projected; its larger screen dimension (pixels of a
// image_width-wide view with a fov_degrees horizontal field of view) is the resolution. The
// elevation is that of the ray from the eye to the tile's centre on the ground.
LdiLevels ldi_levels(const LdiViewSettings& view, double tile_size, double prism_top);

// The 3 x 3 contexts (tile indices by block (dy + 1) * 3 + (dx + 1), centre = tile) whose every
// shared edge matches, in index order, at most `limit` of them.
std::vector<std::array<std::uint16_t, 9>> consistent_contexts(const TileSet& set, std::size_t tile, std::size_t limit);

// The tallest instance of `filled` with `models` (meters, plus a 1 cm margin; at least 5 cm).
double ldi_prism_top(const FilledTileSet& filled, std::span<const Mesh> models);

// Builds the levels x directions LDIs of tile `tile` (frame.level is 0-based). `models` are indexed
// by the points' variant (any meshes: tests use quads and boxes). Deterministic from the inputs:
// the same bits on any thread count. Throws Error for bad inputs or an Embree error.
std::vector<LdiImage> build_tile_ldis(const FilledTileSet& filled, std::span<const Mesh> models,
                                      const LdiBuildOptions& options, std::size_t tile,
                                      LdiBuildReport* report = nullptr);

// The same at levels of the caller's (resolutions and elevations; e.g. the view's steep set,
// seen from above): options.view.levels is taken from `levels`, its other view settings ignored.
std::vector<LdiImage> build_tile_ldis(const FilledTileSet& filled, std::span<const Mesh> models,
                                      LdiBuildOptions options, std::size_t tile, const LdiLevels& levels);

// The pack header of a build with these inputs.
LdiPackInfo ldi_pack_info(const FilledTileSet& filled, std::span<const Mesh> models, const LdiBuildOptions& options);

// Builds every tile and writes the pack to `path` (atomically). Parallel with TBB; the bytes do
// not depend on the thread count.
LdiBuildReport build_ldi_pack(const FilledTileSet& filled, std::span<const Mesh> models, const LdiBuildOptions& options,
                              const std::filesystem::path& path);
// The same at levels of the caller's (the steep sets), the pack's header `info` describing them
// (one level per entry of `levels`, options' directions, the set's tiles); options.view.levels is
// taken from `levels`.
LdiBuildReport build_ldi_pack(const FilledTileSet& filled, std::span<const Mesh> models, LdiBuildOptions options,
                              const LdiLevels& levels, const LdiPackInfo& info, const std::filesystem::path& path);

}  // namespace wangscape
