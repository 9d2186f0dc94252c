// The terrain's rasterizer (the LDI renderer's step 7, renders/view/ldi_renderer_terrain.cpp), on
// its own so that it can be tested alone: triangles in camera space in, a packed depth and colour
// z-buffer out (renders/view/ldi_warp.h's entries). Perspective-correct attributes, pixel centres
// at +0.5; a pixel on an edge two triangles share is drawn by one of them, or by both where its
// centre lies exactly on the edge. Internal to renders/view.
#pragma once

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>

#include "renders/view/ldi_warp.h"
#include "renders/view/view_projection.h"

namespace wangscape {

// A vertex: camera space (right, up, forward; meters), then what is interpolated across the
// triangle: its ground position relative to the eye and its light; then, set by place_on_screen
// (once per vertex, not per triangle: a mesh's vertex is shared by about six), its screen
// position and inverse depth.
struct RasterVertex {
  float x, y, z, wx, wy, lr, lg, lb;
  float sx = 0, sy = 0, iz = 0;
};

// Sets v's screen position and inverse depth (v in front of the near plane).
inline void place_on_screen(const ViewProjection& view, RasterVertex& v) {
  v.sx = view.cx + view.focal * v.x / v.z;
  v.sy = view.cy - view.focal * v.y / v.z;
  v.iz = 1 / v.z;
}

// Where the rasterizer draws: the frame's projection and z-buffer (width x height packed entries).
struct RasterTarget {
  const ViewProjection* view = nullptr;
  int width = 0, height = 0;
  std::uint64_t* zbuffer = nullptr;
  float depth_bias = 0;     // drawn this much (relative) farther than it is
  int occlusion_block = 8;  // pixels: the rows of a large triangle are skipped by blocks `hidden` says are
};

// The sign of the screen area of a triangle wound counter-clockwise seen from above when its upper
// side faces the eye (the terrain is a height field and the eye above it, so where a ray meets
// an underside it has met the upper side first: only skirts are seen from either side).
inline constexpr float kUpperSide = -1;

// True when the screen point (fx, fy) lies in triangle abc (placed on screen, 1 / its signed
// area given), with the weights of a and b. Either winding. A point exactly on an edge two
// triangles share is in both (the z-buffer keeps one of their equal depths).
inline bool covers(const RasterVertex& a, const RasterVertex& b, const RasterVertex& c, float inv_area, float fx,
                   float fy, float& wa, float& wb) {
  wa = ((b.sx - fx) * (c.sy - fy) - (b.sy - fy) * (c.sx - fx)) * inv_area;
  wb = ((c.sx - fx) * (a.sy - fy) - (c.sy - fy) * (a.sx - fx)) * inv_area;
  // The third edge by its own function too (not 1 - wa - wb), so that two triangles meeting on an
  // edge agree exactly on which side of it a point lies: a silhouette's pixels then belong to its
  // upper side whenever to its underside, which may be skipped.
  return !(wa < 0 || wb < 0 || ((a.sx - fx) * (b.sy - fy) - (a.sy - fy) * (b.sx - fx)) * inv_area < 0);
}

// Rasterizes abc, all in front of the near plane and placed on screen: each pixel whose centre it
// covers, nearer than what the z-buffer holds there, goes to shade(px, py, depth, wx, wy, lr, lg,
// lb) (depth with the bias; the attributes perspective-correct), which writes it. With
// `one_sided`, a triangle seen from below is skipped. hidden(x0, y0, x1, y1, nearest) says a
// screen box holds only nearer depths (always false: no occlusion test). Counts the pixels it
// tests into `tests`.
template <class Shade, class Hidden>
void raster_triangle(const RasterTarget& target, const RasterVertex& a, const RasterVertex& b, const RasterVertex& c,
                     bool one_sided, const Shade& shade, const Hidden& hidden, std::uint64_t& tests) {
  const float ax = a.sx, ay = a.sy, bx = b.sx, by = b.sy, cx = c.sx, cy = c.sy;
  const float area = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
  if (!(std::abs(area) > 1e-12f) || (one_sided && area * kUpperSide < 0)) return;
  const int x0 = std::max(0, int(std::floor(std::min({ax, bx, cx})))),
            x1 = std::min(target.width - 1, int(std::ceil(std::max({ax, bx, cx}))));
  const int y0 = std::max(0, int(std::floor(std::min({ay, by, cy})))),
            y1 = std::min(target.height - 1, int(std::ceil(std::max({ay, by, cy}))));
  if (x0 > x1 || y0 > y1) return;
  // Ground wholly behind what the LDIs and the near field drew (most of it, inside the field).
  const float nearest = std::min({a.z, b.z, c.z}) * (1 + target.depth_bias);
  if (hidden(x0, y0, x1, y1, nearest)) return;
  const float inv_area = 1.0f / area;
  const float iza = a.iz, izb = b.iz, izc = c.iz;
  // Per row, the span where the three weights are >= 0 (each is linear in x), widened by a
  // margin: the exact test, covers(), decides; the span only skips what surely fails (thin far
  // triangles have bounding boxes many times their area, and most of the ground's far triangles
  // are a pixel or less). The span's and the test's rounding differ by far less than a
  // sixteenth of a pixel on screen, up to 1e5 pixels out (test
  // TerrainRaster.TheRowSpansHoldEveryPixelTheTestCovers); beyond, a whole pixel.
  const float slope_a = (by - cy) * inv_area, slope_b = (cy - ay) * inv_area, slope_c = -slope_a - slope_b;
  // Their inverses (0 for 0, the sign kept), divided once here, not per row: the span is widened
  // anyway.
  const auto inverse = [](float slope) { return slope != 0 ? 1 / slope : 0.0f; };
  const float reach = std::max({std::abs(ax), std::abs(ay), std::abs(bx), std::abs(by), std::abs(cx), std::abs(cy)});
  const float span_margin = reach < 1e5f ? 1.0f / 16 : 1.0f;
  const float inverse_a = inverse(slope_a), inverse_b = inverse(slope_b), inverse_c = inverse(slope_c);
  for (int py = y0; py <= y1; ++py) {
    // A large triangle: its rows a block row at a time, skipped where that row is hidden.
    if ((py == y0 || py % target.occlusion_block == 0) && y1 - y0 >= target.occlusion_block &&
        hidden(x0, py, x1, py, nearest)) {
      py = (py / target.occlusion_block + 1) * target.occlusion_block - 1;
      continue;
    }
    const float fy = float(py) + 0.5f;
    const float wa0 = (bx * (cy - fy) - (by - fy) * cx) * inv_area, wb0 = (cx * (ay - fy) - (cy - fy) * ax) * inv_area;
    float lo = float(x0) + 0.5f, hi = float(x1) + 0.5f;
    bool empty = false;
    for (const auto& [w0, inverse_slope] :
         {std::pair{wa0, inverse_a}, std::pair{wb0, inverse_b}, std::pair{1 - wa0 - wb0, inverse_c}}) {
      if (inverse_slope > 0)
        lo = std::max(lo, -w0 * inverse_slope);
      else if (inverse_slope < 0)
        hi = std::min(hi, -w0 * inverse_slope);
      else
        empty |= w0 < 0;
    }
    if (empty || !(lo <= hi + 2)) continue;
    const int span_x0 = std::max(x0, int(std::ceil(lo - 0.5f - span_margin))),
              span_x1 = std::min(x1, int(std::floor(hi - 0.5f + span_margin)));
    tests += std::uint64_t(std::max(0, span_x1 - span_x0 + 1));
    for (int px = span_x0; px <= span_x1; ++px) {
      float wa, wb;
      if (!covers(a, b, c, inv_area, float(px) + 0.5f, fy, wa, wb)) continue;
      float wc = 1 - wa - wb;
      const float iz = wa * iza + wb * izb + wc * izc;
      const float z = 1 / iz;
      const float drawn_depth = z * (1 + target.depth_bias);
      // Early depth test: most ground under the field is hidden by flowers drawn before it.
      const std::uint64_t drawn =
          std::atomic_ref<std::uint64_t>(target.zbuffer[std::size_t(py) * std::size_t(target.width) + std::size_t(px)])
              .load(std::memory_order_relaxed);
      if (view_detail::pack_entry(drawn_depth, 0, 0, 0) > drawn) continue;
      wa *= iza * z;
      wb *= izb * z;
      wc *= izc * z;
      shade(px, py, drawn_depth, wa * a.wx + wb * b.wx + wc * c.wx, wa * a.wy + wb * b.wy + wc * c.wy,
            wa * a.lr + wb * b.lr + wc * c.lr, wa * a.lg + wb * b.lg + wc * c.lg, wa * a.lb + wb * b.lb + wc * c.lb);
    }
  }
}

// Draws triangle v (camera space; the vertices in front of the near plane placed on screen): culled when wholly behind
// the near plane (view_detail::kNear) or beyond one side of the frustum, clipped at the near plane, then rasterized.
template <class Shade, class Hidden>
void draw_triangle(const RasterTarget& target, const RasterVertex (&v)[3], bool one_sided, const Shade& shade,
                   const Hidden& hidden, std::uint64_t& tests) {
  using view_detail::kNear;
  int behind = 0;
  for (const RasterVertex& q : v) behind += q.z < kNear;
  if (behind == 3) return;
  // A quick reject: all three beyond one side plane.
  auto out = [&](auto&& side) { return side(v[0]) && side(v[1]) && side(v[2]); };
  if (out([&](const RasterVertex& q) { return q.x > q.z * target.view->tan_x; }) ||
      out([&](const RasterVertex& q) { return q.x < -q.z * target.view->tan_x; }) ||
      out([&](const RasterVertex& q) { return q.y > q.z * target.view->tan_y; }) ||
      out([&](const RasterVertex& q) { return q.y < -q.z * target.view->tan_y; }))
    return;
  if (behind == 0) {
    raster_triangle(target, v[0], v[1], v[2], one_sided, shade, hidden, tests);
    return;
  }
  // Clip against the near plane (Sutherland-Hodgman): 3 or 4 vertices, drawn as a fan.
  RasterVertex poly[4];
  int n = 0;
  for (int k = 0; k < 3; ++k) {
    const RasterVertex& p = v[k];
    const RasterVertex& q = v[(k + 1) % 3];
    const bool pin = p.z >= kNear, qin = q.z >= kNear;
    if (pin) poly[n++] = p;
    if (pin != qin) {
      const float f = (kNear - p.z) / (q.z - p.z);
      auto lerp = [f](float a, float b) { return a + (b - a) * f; };
      poly[n] = {lerp(p.x, q.x),   lerp(p.y, q.y),   kNear,           lerp(p.wx, q.wx), lerp(p.wy, q.wy),
                 lerp(p.lr, q.lr), lerp(p.lg, q.lg), lerp(p.lb, q.lb)};
      place_on_screen(*target.view, poly[n++]);
    }
  }
  for (int k = 1; k + 1 < n; ++k)
    raster_triangle(target, poly[0], poly[k], poly[k + 1], one_sided, shade, hidden, tests);
}

}  // namespace wangscape
