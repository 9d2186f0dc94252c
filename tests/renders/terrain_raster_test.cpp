// The terrain's rasterizer alone (renders/view/terrain_raster.h, issue 36): triangles in camera
// space in, a z-buffer out, checked against the pinhole's own geometry.
#include "renders/view/terrain_raster.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <random>
#include <vector>

namespace wangscape {
namespace {

using view_detail::kEmpty;
using view_detail::pack_entry;

constexpr int kSize = 64;

// A 64 x 64 frame, 100 pixels per unit of tan, centred; its z-buffer and how often each pixel was shaded.
struct Frame {
  ViewProjection view;
  std::vector<std::uint64_t> zbuffer = std::vector<std::uint64_t>(kSize * kSize, kEmpty);
  std::vector<int> shaded = std::vector<int>(kSize * kSize, 0);
  std::vector<float> wx = std::vector<float>(kSize * kSize, 0);
  RasterTarget target;
  Frame() {
    view.focal = 100;
    view.cx = view.cy = kSize / 2.0f;
    view.tan_x = view.tan_y = (kSize / 2.0f) / view.focal;
    target = {&view, kSize, kSize, zbuffer.data(), 0, 8};
  }
  void draw(const RasterVertex& a, const RasterVertex& b, const RasterVertex& c, bool one_sided = false) {
    std::uint64_t tests = 0;
    RasterVertex v[3] = {a, b, c};
    for (RasterVertex& q : v)
      if (q.z >= view_detail::kNear) place_on_screen(view, q);
    draw_triangle(
        target, v, one_sided,
        [&](int px, int py, float depth, float x, float, float, float, float) {
          const std::size_t p = std::size_t(py) * kSize + std::size_t(px);
          zbuffer[p] = std::min(zbuffer[p], pack_entry(depth, 0, 0, 0));
          ++shaded[p];
          wx[p] = x;
        },
        [](int, int, int, int, float) { return false; }, tests);
  }
  float depth(int px, int py) const {
    return std::bit_cast<float>(std::uint32_t(zbuffer[std::size_t(py) * kSize + std::size_t(px)] >> 32));
  }
};

// Camera space (right, up, forward) with the ground position `wx` set to the point's x.
RasterVertex at(float x, float y, float z) { return {x, y, z, x, 0, 1, 1, 1}; }

// A quad as two triangles sharing a diagonal: every pixel whose centre it covers shaded once (twice
// only where the centre lies exactly on the diagonal), none left out, none outside, at the quad's
// depth.
TEST(TerrainRaster, TwoTrianglesSharingAnEdgeShadeEachPixelOnce) {
  Frame f;
  const float z = 5;  // x, y in [-1, 1] at 5 m: pixels 12 .. 52
  f.draw(at(-1, -1, z), at(1, -1, z), at(1, 1, z));
  f.draw(at(-1, -1, z), at(1, 1, z), at(-1, 1, z));
  for (int py = 0; py < kSize; ++py)
    for (int px = 0; px < kSize; ++px) {
      const float sx = (float(px) + 0.5f - f.view.cx) / f.view.focal * z;
      const float sy = -(float(py) + 0.5f - f.view.cy) / f.view.focal * z;
      const bool inside = std::abs(sx) < 1 && std::abs(sy) < 1, on_diagonal = sx == sy;
      const int shaded = f.shaded[std::size_t(py) * kSize + std::size_t(px)];
      EXPECT_TRUE(inside ? shaded == 1 || (on_diagonal && shaded == 2) : shaded == 0) << px << ", " << py;
      EXPECT_TRUE(!inside || std::abs(f.depth(px, py) - z) < 1e-4f) << px << ", " << py;
    }
}

// A plane tilted away: each pixel's depth is where its ray meets the plane, and the attribute is
// perspective-correct (the ray's x there).
TEST(TerrainRaster, ATiltedPlaneHasTheRaysDepthAndPerspectiveCorrectAttributes) {
  Frame f;
  // z = 4 + 3 (y + 1): from 4 m at the bottom edge to 10 m at the top.
  const auto plane = [](float x, float y) { return at(x, y, 4 + 3 * (y + 1)); };
  f.draw(plane(-2, -1), plane(2, -1), plane(2, 1));
  f.draw(plane(-2, -1), plane(2, 1), plane(-2, 1));
  int checked = 0;
  for (int py = 0; py < kSize; ++py)
    for (int px = 0; px < kSize; ++px) {
      if (!f.shaded[std::size_t(py) * kSize + std::size_t(px)]) continue;
      const float tx = (float(px) + 0.5f - f.view.cx) / f.view.focal,
                  ty = -(float(py) + 0.5f - f.view.cy) / f.view.focal;
      const float z = 7 / (1 - 3 * ty);  // z = 7 + 3 y with y = ty z
      EXPECT_NEAR(f.depth(px, py), z, 1e-3f * z);
      EXPECT_NEAR(f.wx[std::size_t(py) * kSize + std::size_t(px)], tx * z, 1e-3f * z);
      ++checked;
    }
  EXPECT_GT(checked, 500);
}

// Nearer ground wins whatever the order; a triangle seen from below is skipped one-sided; one
// across the near plane is clipped, never drawn nearer than it.
TEST(TerrainRaster, DepthTestUndersideAndNearPlane) {
  Frame f;
  f.draw(at(-1, -1, 3), at(1, -1, 3), at(0, 1, 3));
  f.draw(at(-1, -1, 6), at(1, -1, 6), at(0, 1, 6));
  EXPECT_NEAR(f.depth(kSize / 2, kSize / 2), 3, 1e-4f);
  Frame one_sided;
  one_sided.draw(at(-1, -1, 3), at(0, 1, 3), at(1, -1, 3), true);  // wound the other way
  one_sided.draw(at(-1, -1, 3), at(1, -1, 3), at(0, 1, 3), true);
  int drawn = 0;
  for (const int n : one_sided.shaded) drawn += n;
  Frame both;
  both.draw(at(-1, -1, 3), at(1, -1, 3), at(0, 1, 3));
  int expected = 0;
  for (const int n : both.shaded) expected += n;
  EXPECT_EQ(drawn, expected);  // only the upper side
  Frame clipped;
  clipped.draw(at(-1, -0.2f, -1), at(1, -0.2f, -1), at(0, -0.2f, 4));  // a floor from behind the eye
  int shaded = 0;
  for (int py = 0; py < kSize; ++py)
    for (int px = 0; px < kSize; ++px)
      if (clipped.shaded[std::size_t(py) * kSize + std::size_t(px)]) {
        EXPECT_GE(clipped.depth(px, py), view_detail::kNear * 0.999f);
        ++shaded;
      }
  EXPECT_GT(shaded, 50);
}

// The rows' spans only skip pixels: over thousands of random triangles (a pixel or less, slivers,
// and ones reaching far off the frame), the pixels drawn are exactly those whose centres covers()
// holds, found by testing every pixel of the frame.
TEST(TerrainRaster, TheRowSpansHoldEveryPixelTheTestCovers) {
  std::mt19937 random(17);
  std::uniform_real_distribution<float> unit(0, 1);
  int covered = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    // On screen: a centre in or near the frame, vertices a pixel, a frame or ~1e4 frames away.
    const float scale = std::array{1.5f, 40.0f, 6e5f}[std::size_t(trial % 3)];
    const float mx = unit(random) * kSize, my = unit(random) * kSize, z = 1 + 9 * unit(random);
    Frame f;
    RasterVertex v[3];
    for (RasterVertex& q : v) {
      const float sx = mx + (unit(random) - 0.5f) * scale, sy = my + (unit(random) - 0.5f) * (trial % 7 ? scale : 1);
      q = at((sx - f.view.cx) / f.view.focal * z, (f.view.cy - sy) / f.view.focal * z, z);
      place_on_screen(f.view, q);
    }
    std::uint64_t tests = 0;
    raster_triangle(
        f.target, v[0], v[1], v[2], false,
        [&](int px, int py, float, float, float, float, float, float) {
          ++f.shaded[std::size_t(py) * kSize + std::size_t(px)];
        },
        [](int, int, int, int, float) { return false; }, tests);
    const float area = (v[1].sx - v[0].sx) * (v[2].sy - v[0].sy) - (v[1].sy - v[0].sy) * (v[2].sx - v[0].sx);
    if (!(std::abs(area) > 1e-12f)) continue;
    for (int py = 0; py < kSize; ++py)
      for (int px = 0; px < kSize; ++px) {
        float wa, wb;
        const bool inside = covers(v[0], v[1], v[2], 1.0f / area, float(px) + 0.5f, float(py) + 0.5f, wa, wb);
        covered += inside;
        ASSERT_EQ(f.shaded[std::size_t(py) * kSize + std::size_t(px)], inside ? 1 : 0)
            << "trial " << trial << " pixel " << px << "," << py;
      }
  }
  EXPECT_GT(covered, 100000);  // the triangles did cover pixels
}

}  // namespace
}  // namespace wangscape
