#include "renders/view/tile_plan.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "renders/ldi/ldi_scene.h"
#include "renders/view/ldi_warp.h"

namespace wangscape {

namespace {

// Of the span between two steep sets' elevations, the lower part over which the lower set fades
// out (a dithered blend warps both sets' LDIs: in all the span it cost 58 -> 92 ms a frame from
// 25 m up at 1280 x 720).
constexpr double kSteepBlendBand = 0.25;
// A finer level is drawn from the steep sets too when seen this many times steeper than the pack
// sampled it, and its resolution is at most kSteepFinerResolution times the steep sets': its
// LDIs, sampled a few degrees below the horizon, show the sides of the plants, and from above
// their samples spread into sparse leaves over bare ground (straight down from 30 m: SSIM 0.27
// against the truth, 0.39 from the steep sets, where the exact image scores 0.81). The steep
// sets' coarser resolution costs less than the wrong angle there, but more than it 5 m up (the
// finest levels).
constexpr double kSteepFinerLevels = 2;
constexpr double kSteepFinerResolution = 2;
constexpr float kLevelBlendStart = 0.75f;  // of a level's range: where dithering into the next level starts
constexpr float kDirectionBand = 0.08f;    // of the angle between two directions: dithered either side of the bisector

// What every tile's choice shares in a frame.
struct PlanFrame {
  const ViewWorld& world;
  const ViewProjection& view;
  const TilePlanSettings& settings;
  const LdiPackInfo& info;
  const ViewWorld::Tiles& tiles;
  double s;
  std::uint32_t levels, directions, drawn_levels;
  double distance_scale, far_start, steep_far_start;
  float top;
  // The pack's levels, then the far steps: where (in the pack view's distances) level a starts.
  double level_start_from(std::uint32_t a, double far_begin) const {
    if (a == 0) return 0.0;
    if (a < levels) return double(info.level_distances[a]);
    return far_begin * double(1u << (a - levels));
  }
};

// Tile t's distance, level, steep sets, directions, far colour and flags into `plan`.
void choose_tile(const PlanFrame& f, std::size_t t, TilePlan& plan) {
  const double x0 = f.tiles.x0[t], y0 = f.tiles.y0[t];
  const double dx = std::max({x0 - f.view.eye[0], f.view.eye[0] - (x0 + f.s), 0.0});
  const double dy = std::max({y0 - f.view.eye[1], f.view.eye[1] - (y0 + f.s), 0.0});
  const double ground = 0.25 * (f.tiles.h[0][t] + f.tiles.h[1][t] + f.tiles.h[2][t] + f.tiles.h[3][t]);
  const double dz = std::max(0.0, f.view.eye[2] - ground - f.info.head_height);
  const double d = std::sqrt(dx * dx + dy * dy + dz * dz);
  plan.distance[t] = float(d);
  const double e =
      d * f.distance_scale / f.settings.detail;  // the distance at which the pack's view sees the tile this large

  // Level: the finest whose near distance the tile has passed; the last half of its range
  // dithers into the next (or into the far field after the last).
  const auto level_at = [&](double far_begin, float& wb) {
    std::uint32_t a = 0;
    while (a < f.drawn_levels && e >= f.level_start_from(a + 1, far_begin)) ++a;
    wb = 0;
    if (a < f.drawn_levels) {
      const double lo = f.level_start_from(a, far_begin), hi = f.level_start_from(a + 1, far_begin);
      const double into = (e - lo) / (hi - lo);
      wb = float(std::clamp((into - kLevelBlendStart) / (1 - kLevelBlendStart), 0.0, 1.0));
    }
    return a;
  };
  float wb = 0;
  std::uint32_t a = level_at(f.far_start, wb);
  // Seen from above, for the coarsest levels and the far steps: the LDIs (the pack's or a steep
  // set's) of the lowest elevation not below the view's to the tile, dithered with the next
  // lower steep set just above that set's elevation (a hard switch showed as a seam). Sampled from higher than the
  // eye, a one-layer LDI's samples cover the tile's top; from lower, they stand on its near side with a gap behind
  // (the streaks along the tile grid).
  const double rise = f.view.eye[2] - ground - 0.5 * f.top;
  const double hx = x0 + f.s / 2 - f.view.eye[0], hy = y0 + f.s / 2 - f.view.eye[1];
  const double horizontal = std::sqrt(hx * hx + hy * hy);
  const double view_elevation = std::atan2(rise, horizontal) * 180 / std::numbers::pi;
  plan.steep[t] = plan.steep_low[t] = 0;
  plan.steep_low_weight[t] = 0;
  // (The pack's own elevation for the level drawn: from head height, never steeper.)
  const double pack_elevation = double(f.info.elevations[std::min(a, f.levels - 1)]);
  const bool coarse = a + kSteepLevels >= f.levels;
  const bool finer_from_steep = a < f.levels && view_elevation > kSteepFinerLevels * pack_elevation &&
                                f.info.resolutions[a] <= kSteepFinerResolution * f.world.steep_resolution();
  if ((coarse || finer_from_steep) && view_elevation > pack_elevation) {
    const auto& sets = ViewWorld::steep_elevations();  // ascending
    if (coarse && view_elevation > double(sets[0])) a = level_at(f.steep_far_start, wb);
    std::size_t k = 0;
    while (k + 1 < sets.size() && view_elevation > double(sets[k])) ++k;
    plan.steep[t] = std::uint8_t(k + 1);
    plan.steep_low[t] = std::uint8_t(k);
    // (Not with the pack's: its far steps, sampled lower, would bring their rows back.)
    if (k > 0) {
      const double low = double(sets[k - 1]), high = double(sets[k]);
      const double into = (view_elevation - low) / (kSteepBlendBand * (high - low));
      plan.steep_low_weight[t] = float(std::clamp(1 - into, 0.0, 1.0));
    }
  }
  plan.level_a[t] = std::uint8_t(a);
  plan.level_b[t] = std::uint8_t(std::min(a + 1, f.drawn_levels));
  plan.level_b_weight[t] = wb;
  plan.far_from[t] = a >= f.drawn_levels ? 0.0f : (a + 1 == f.drawn_levels ? 1.0f - wb : 2.0f);

  // Direction: the two whose rays are closest to the view ray (largest dot products).
  const double vx = x0 + f.s / 2 - f.view.eye[0], vy = y0 + f.s / 2 - f.view.eye[1], vn = std::sqrt(vx * vx + vy * vy);
  const double ux = vn > 1e-9 ? vx / vn : f.view.forward[0], uy = vn > 1e-9 ? vy / vn : f.view.forward[1];
  std::uint32_t best = 0, second = 0;
  double best_dot = -2, second_dot = -2;
  for (std::uint32_t k = 0; k < f.directions; ++k) {
    const double c = plan.direction_east[k] * ux + plan.direction_north[k] * uy;
    if (c > best_dot) {
      second = best;
      second_dot = best_dot;
      best = k;
      best_dot = c;
    } else if (c > second_dot) {
      second = k;
      second_dot = c;
    }
  }
  float w2 = 0;
  if (f.directions > 1) {
    const double a1 = std::acos(std::clamp(best_dot, -1.0, 1.0)), a2 = std::acos(std::clamp(second_dot, -1.0, 1.0));
    const double share = a1 + a2 > 0 ? a1 / (a1 + a2) : 0;  // 0 on the best direction, 0.5 on the bisector
    w2 = float(0.5 * std::clamp((share - (0.5 - kDirectionBand)) / kDirectionBand, 0.0, 1.0));
  }
  plan.dir_a[t] = std::uint8_t(best);
  plan.dir_b[t] = std::uint8_t(second);
  plan.dir_b_weight[t] = w2;
  const auto& fa = f.world.far_colors()[std::size_t(f.tiles.tile[t]) * f.directions + best];
  const auto& fb = f.world.far_colors()[std::size_t(f.tiles.tile[t]) * f.directions + second];
  plan.far_r[t] = fa[0] * (1 - w2) + fb[0] * w2;
  plan.far_g[t] = fa[1] * (1 - w2) + fb[1] * w2;
  plan.far_b[t] = fa[2] * (1 - w2) + fb[2] * w2;
  plan.far_cover[t] = fa[3] * (1 - w2) + fb[3] * w2;

  // The frustum: culled when all eight corners of the tile's box are outside one plane.
  const bool in_view =
      !f.view.box_outside_frustum({x0, y0, double(f.tiles.z_min[t]) - 0.01},
                                  {x0 + f.s, y0 + f.s, double(f.tiles.z_max[t]) + f.top}, view_detail::kNear);
  // Near: ray traced from the real flowers instead (trace_near_field).
  plan.flags[t] = std::uint8_t((in_view ? TilePlan::kInView : 0) | (d < f.settings.near_field ? TilePlan::kNear : 0));
}

}  // namespace

void plan_tiles(const ViewWorld& world, const ViewProjection& view, const TilePlanSettings& settings, TilePlan& plan) {
  const std::size_t n = world.tiles().size();
  for (auto* v : {&plan.distance, &plan.far_from, &plan.far_r, &plan.far_g, &plan.far_b, &plan.far_cover,
                  &plan.level_b_weight, &plan.dir_b_weight, &plan.steep_low_weight})
    v->resize(n);
  for (auto* v : {&plan.level_a, &plan.level_b, &plan.dir_a, &plan.dir_b, &plan.steep, &plan.steep_low, &plan.flags})
    v->resize(n);
  plan.order.clear();
  plan.drawn = plan.near = plan.steep_tiles = plan.culled = 0;
  plan.levels.assign(std::size_t(world.pack().info().levels) + 1, 0);
  const LdiPackInfo& info = world.pack().info();
  const ViewWorld::Tiles& tiles = world.tiles();
  const double s = world.tile_size();
  // ---- tiles: distance, level, direction, frustum ----
  const std::uint32_t levels = info.levels, directions = info.directions;
  // The pack's levels were sized for its own view; this view's pixels per radian rescale the distances.
  const double pack_focal = double(info.image_width) / 2 / std::tan(double(info.fov_degrees) * std::numbers::pi / 360);
  const double distance_scale = pack_focal / double(view.focal);
  const double far_start = double(info.level_distances[levels - 1]) + s;
  const std::uint32_t drawn_levels = levels + world.far_steps();
  // Far step k averages blocks of 2^(k+1) of its LDI's depth pixels and starts at far_start 2^k,
  // where a block of the coarsest level's is about two pixels of the pack's view. Seen from above
  // the lowest steep set, where a block shows the tops of a few flowers, a far step starts no
  // sooner than where its block is one pixel: two pixels averaged a head into the leaves around
  // it (25 m up, 640 x 360, steep sets at the coarsest level's resolution: SSIM 0.418 against the
  // exact image's 0.454, 0.444 with this start). Seen lower, at grazing angles, the same start
  // gained nothing: the close-up 0.8765 either way at 28 % more depth pixels; from head height (the
  // scene's camera) 0.7735 -> 0.7732 at 37 % more.
  const double steep_far_start = std::max(far_start, pack_focal * s * 2 / double(world.steep_resolution()));
  const float top = info.prism_top;
  plan.direction_east.clear();
  plan.direction_north.clear();
  for (std::uint32_t k = 0; k < directions; ++k) {
    const double az = double(info.azimuths[k]) * std::numbers::pi / 180;
    plan.direction_east.push_back(std::sin(az));
    plan.direction_north.push_back(std::cos(az));
  }
  // Each tile's choice alone, in parallel (from above, 15,000 tiles took 1.8 ms on one thread);
  // then, in order, the counts and the tiles to draw.
  const PlanFrame frame{world,      view,         settings,       info,      tiles,           s,  levels,
                        directions, drawn_levels, distance_scale, far_start, steep_far_start, top};
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, tiles.size(), 512),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t t = r.begin(); t != r.end(); ++t) choose_tile(frame, t, plan);
                    });
  for (std::size_t t = 0; t < tiles.size(); ++t) {
    if (!(plan.flags[t] & TilePlan::kInView)) {
      ++plan.culled;
      continue;
    }
    const std::uint32_t a = plan.level_a[t];
    ++plan.drawn;
    ++plan.levels[std::min(a, levels)];
    const bool near = plan.flags[t] & TilePlan::kNear;
    plan.near += near;
    plan.steep_tiles += plan.steep[t] != 0;
    if (a < drawn_levels && !near &&
        (!settings.mask || settings.mask->empty() || (t < settings.mask->size() && (*settings.mask)[t])))
      plan.order.push_back(std::uint32_t(t));
  }
  plan.any_steep =
      std::any_of(plan.order.begin(), plan.order.end(), [&](std::uint32_t t) { return plan.steep[t] != 0; });
  // Back to front (the farthest first; ties by index: the same order on any thread count).
  tbb::parallel_sort(plan.order.begin(), plan.order.end(), [&](std::uint32_t p, std::uint32_t q) {
    return plan.distance[p] != plan.distance[q] ? plan.distance[p] > plan.distance[q] : p < q;
  });
}

}  // namespace wangscape
