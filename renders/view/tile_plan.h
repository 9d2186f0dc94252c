// Which LDIs draw each placed tile in a frame (steps 1-4 of docs/viewer-design.md), as a plan: per
// tile its distance, its level and the next one dithered in (with that one's share), its two
// nearest directions (with the second's share), the steep sets that stand in seen from above, its
// far-field colour, whether the frustum keeps it and whether the near field traces it instead;
// and the tiles to warp, back to front. A pure function of the world, the camera and the settings
// (LdiRenderer draws the plan; tests check it alone). Internal to renders/view.
#pragma once

#include <cstdint>
#include <vector>

#include "renders/view/view_projection.h"
#include "renders/view/view_world.h"

namespace wangscape {

struct TilePlanSettings {
  double detail = 1;                                // LdiRenderer::set_detail: the levels' distances divided by it
  double near_field = 0;                            // meters: tiles nearer are traced by the near field, not warped
  const std::vector<std::uint8_t>* mask = nullptr;  // LdiRenderer::set_tile_mask: 0 leaves a tile out
};

struct TilePlan {
  static constexpr std::uint8_t kInView = 1, kNear = 2;  // flags
  // Per placed tile (structure of arrays, the world's tile order).
  std::vector<float> distance;                 // meters from the eye to the tile's box at head height
  std::vector<std::uint8_t> level_a, level_b;  // the level drawn, and the next (dithered in by level_b_weight)
  std::vector<float> level_b_weight;
  std::vector<std::uint8_t> dir_a, dir_b;  // the two nearest directions (dir_b by dir_b_weight)
  std::vector<float> dir_b_weight;
  // Seen from above: 0 the pack, k the world's steep set k - 1; the tile's samples are drawn
  // from `steep` and, a share steep_low_weight of them, from the next lower one, steep_low.
  std::vector<std::uint8_t> steep, steep_low;
  std::vector<float> steep_low_weight;
  // The far field: the tile's colour over the ground by its cover, from the threshold far_from.
  std::vector<float> far_from, far_r, far_g, far_b, far_cover;
  std::vector<std::uint8_t> flags;                      // kInView, kNear
  std::vector<double> direction_east, direction_north;  // the pack's ray directions, horizontal unit
  // The tiles to warp, back to front (ties by index: the same order on any thread count).
  std::vector<std::uint32_t> order;
  // In the frustum: drawn, of them near, of them from the steep sets; drawn per level (the last:
  // beyond the last level, the far-field colour); outside it: culled.
  std::uint64_t drawn = 0, near = 0, steep_tiles = 0, culled = 0;
  std::vector<std::uint64_t> levels;
  bool any_steep = false;  // a tile to warp is drawn from the steep sets (ViewWorld::prepare_steep)
};

// Plans the frame of `view` into `plan` (its buffers reused: no allocation once sized). Thread-safe
// for different plans; parallel inside.
void plan_tiles(const ViewWorld& world, const ViewProjection& view, const TilePlanSettings& settings, TilePlan& plan);

}  // namespace wangscape
