// The terrain's rasterizer, one row of a triangle at a time in vector lanes: which pixels of a
// span the triangle covers, their depth and their perspective-correct attributes (step 7 of
// docs/viewer.md). Internal to renders/view.
#pragma once

#include <array>
#include <cstdint>

namespace wangscape::view_detail {

// A screen triangle: its corners' pixel positions, the reciprocal of twice its signed area,
// their reciprocal camera depths and the attributes interpolated across it (world x, y relative
// to the eye; the light's red, green, blue).
struct ScreenTriangle {
  float ax = 0, ay = 0, bx = 0, by = 0, cx = 0, cy = 0, inv_area = 0, iza = 0, izb = 0, izc = 0;
  static constexpr int kAttributes = 5;
  std::array<float, kAttributes> a{}, b{}, c{};
};

// Up to kTerrainRowPixels pixels of one row: covered or not, and for those covered the depth
// (with the terrain's bias) and the attributes.
constexpr int kTerrainRowPixels = 128;
struct TerrainRow {
  alignas(64) std::int32_t covered[kTerrainRowPixels];
  alignas(64) float depth[kTerrainRowPixels];
  alignas(64) float attribute[ScreenTriangle::kAttributes][kTerrainRowPixels];
};

// Pixels x0 .. x0 + count - 1 (count <= kTerrainRowPixels) of row y: covered when their centre
// is inside the triangle or on an edge (barycentric weights >= 0, either winding); depth is the
// camera depth times depth_scale.
void rasterize_row(const ScreenTriangle& t, int y, int x0, int count, float depth_scale, TerrainRow& out);

}  // namespace wangscape::view_detail
