// The LDI renderer's inner parts (renders/view/ldi_renderer.h), shared by its sources: the frame's
// steps (ldi_renderer.cpp), the terrain's rasterizer (ldi_renderer_terrain.cpp) and its rays, the
// near field and occlusion (ldi_renderer_rays.cpp). Not for use outside them.
#pragma once

#include "renders/view/ldi_renderer.h"

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <limits>

#include "core/vecmath.h"

#include "renders/trace/scene_tracer.h"
#include "renders/view/ldi_warp.h"
#include "renders/view/terrain_raster.h"
#include "renders/view/tile_plan.h"
#include "renders/view/view_projection.h"
#include "renders/view/view_samples.h"

namespace wangscape {

namespace ldi_renderer_detail {

using namespace view_detail;

// The terrain is drawn this much (relative) farther than it is, so that where the near field's
// rays met the same ground (shaded with the flowers' shadows and sky share) the rasterized ground
// does not win by rounding: without it, a speckle of the two over the near field's ground.
constexpr float kTerrainDepthBias = 1.0f / 4096;
constexpr float kSplatScale = 1.5f;  // splat side over the projected depth-pixel size (measured: no holes)
// A far step's samples are blocks kept with their cover's probability: a larger splat than the
// block would add its excess to the cover (1.5^2 = 2.25 times: a sparse field drawn dense).
constexpr float kFarSplatScale = 1.0f;
constexpr int kMaxSplat = 24;  // pixels
// ViewEngine::automatic samples the near field with a grid of this many rays across and down.
constexpr int kShareGridX = 32, kShareGridY = 18;
// The near field: how far a flower reaches from its stem (meters), and how much further out the
// flowers are kept as sun occluders (a low sun's shadows fall into the near field from there).
constexpr double kNearFlowerRadius = 0.5;
constexpr double kNearShadowMargin = 4.0;
constexpr int kOcclusionBlock = 8;            // pixels: the side of a block of the occlusion test
constexpr std::uint32_t kTerrainPiece = 512;  // triangles: the terrain's unit of parallel work
// Meters a terrain skirt reaches below the errors it bridges (float rounding at the terrain's heights).
constexpr float kSkirtMargin = 0.01f;

// Keeps the nearest entry (ties: the smaller color), so the result does not depend on the order.
inline void depth_write(std::uint64_t& slot, std::uint64_t value) {
  std::atomic_ref<std::uint64_t> a(slot);
  std::uint64_t current = a.load(std::memory_order_relaxed);
  while (value < current && !a.compare_exchange_weak(current, value, std::memory_order_relaxed)) {
  }
}

using V3 = Vector3d;

}  // namespace ldi_renderer_detail

struct LdiRenderer::Impl {
  // The inner names the members use here (the renderer's sources bring them all in themselves).
  using V3 = Vector3d;
  using ThreadDepths = view_detail::ThreadDepths;
  static constexpr int kOcclusionBlock = ldi_renderer_detail::kOcclusionBlock;
  static constexpr float kNear = view_detail::kNear;
  static constexpr std::uint64_t kEmpty = view_detail::kEmpty;

  int width = 0, height = 0;
  std::vector<std::uint64_t> zbuffer;
  // The frame's camera: eye, axes (ENU), pixels per unit of tan, screen centre.
  ViewProjection view;
  TilePlan plan;  // which LDIs draw each placed tile this frame (choose_tiles)
  // Terrain vertices in camera space and on screen; the chunks drawn, nearest first, their distances, their
  // levels of detail (0 for those not drawn) and those levels' vertical errors (meters).
  std::vector<RasterVertex> raster_vertices;
  std::vector<std::uint32_t> chunk_order;
  std::vector<std::array<std::uint32_t, 2>> terrain_pieces;  // (chunk, its level's first triangle)
  std::vector<float> chunk_distance;
  std::vector<std::uint8_t> chunk_level;
  std::atomic<std::uint64_t> depth_pixels{0};
  tbb::enumerable_thread_specific<ThreadDepths> thread_depths;  // per thread, kept across frames
  // The near field: the real flowers of the tiles around the eye, ray traced (made on the first
  // frame that needs it; its flowers placed again only when the eye's window of tiles changes).
  std::unique_ptr<SceneTracer> near_tracer;
  std::unique_ptr<SceneTracer> whole_tracer;  // ViewEngine::embree and automatic: the whole scene
  std::optional<Extent> near_window;
  std::atomic<std::uint64_t> near_rays{0};
  std::vector<float> accumulated;  // set_samples: the samples' sum, linear light
  std::vector<float> block_far;    // the occlusion test's blocks: the farthest depth in each

  std::array<float, 3> to_camera(double x, double y, double z) const { return view.to_camera(x, y, z); }
  // The unit direction (ENU) of the ray through the screen point (x, y) (pixel centres at +0.5).
  V3 ray_through(double x, double y) const { return view.ray_through(x, y); }
  std::array<float, 3> direction_to_camera(double x, double y, double z) const {
    const V3 d{x, y, z};
    return {float(dot(d, view.right)), float(dot(d, view.up)), float(dot(d, view.forward))};
  }
  // The farthest depth of each block of kOcclusionBlock x kOcclusionBlock pixels of block row
  // `by` (infinity where a pixel holds nothing yet) into block_far, sized by size_blocks().
  int blocks_wide() const { return (width + kOcclusionBlock - 1) / kOcclusionBlock; }
  void size_blocks() {
    block_far.assign(std::size_t(blocks_wide()) * std::size_t((height + kOcclusionBlock - 1) / kOcclusionBlock), 0.0f);
  }
  void measure_block_row(int by) {
    float* far = block_far.data() + std::size_t(by) * std::size_t(blocks_wide());
    std::fill(far, far + blocks_wide(), 0.0f);
    for (int y = by * kOcclusionBlock; y < std::min(height, (by + 1) * kOcclusionBlock); ++y) {
      const std::uint64_t* row = zbuffer.data() + std::size_t(y) * std::size_t(width);
      for (int x = 0; x < width; ++x) {
        const float depth = row[x] == kEmpty ? std::numeric_limits<float>::infinity()
                                             : std::bit_cast<float>(std::uint32_t(row[x] >> 32));
        far[x / kOcclusionBlock] = std::max(far[x / kOcclusionBlock], depth);
      }
    }
  }
  // True when every block the pixel box [x0, x1] x [y0, y1] meets (clamped to the screen; none
  // when it is off the screen) holds only depths nearer than `nearest`: whatever lies there at
  // `nearest` or beyond is hidden.
  bool screen_box_hidden(int x0, int y0, int x1, int y1, float nearest) const {
    const int bx0 = std::max(0, x0) / kOcclusionBlock, by0 = std::max(0, y0) / kOcclusionBlock;
    const int bx1 = std::min(width - 1, x1) / kOcclusionBlock, by1 = std::min(height - 1, y1) / kOcclusionBlock;
    for (int by = by0; by <= by1; ++by)
      for (int bx = bx0; bx <= bx1; ++bx)
        if (!(block_far[std::size_t(by) * std::size_t(blocks_wide()) + std::size_t(bx)] < nearest)) return false;
    return true;
  }
  // The same for a box in the world, its screen box widened by `margin` pixels (false when it
  // reaches behind the eye).
  bool box_hidden(const std::array<double, 3>& low, const std::array<double, 3>& high, int margin) const {
    float nearest = std::numeric_limits<float>::infinity();
    float x0 = std::numeric_limits<float>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
    for (int k = 0; k < 8; ++k) {
      const auto c = to_camera(k & 1 ? high[0] : low[0], k & 2 ? high[1] : low[1], k & 4 ? high[2] : low[2]);
      if (c[2] < kNear) return false;
      nearest = std::min(nearest, c[2]);
      const float px = view.cx + view.focal * c[0] / c[2], py = view.cy - view.focal * c[1] / c[2];
      x0 = std::min(x0, px);
      x1 = std::max(x1, px);
      y0 = std::min(y0, py);
      y1 = std::max(y1, py);
    }
    return screen_box_hidden(int(std::floor(x0)) - margin, int(std::floor(y0)) - margin, int(std::ceil(x1)) + margin,
                             int(std::ceil(y1)) + margin, nearest);
  }
  // True when all eight corners of the box lie outside one plane of the view frustum.
  bool box_outside_frustum(const std::array<double, 3>& low, const std::array<double, 3>& high) const {
    return view.box_outside_frustum(low, high, kNear);
  }
};

}  // namespace wangscape
