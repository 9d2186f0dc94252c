#include "renders/view/terrain_row.h"

#include "renders/view/vector_clones.h"

namespace wangscape::view_detail {

// Branch-free over the pixels, so the compiler runs it in vector lanes (16 pixels at a time with
// AVX-512); the triangle is copied to locals so that no store into the row can alias it.
WANGSCAPE_VECTOR_CLONES void rasterize_row(const ScreenTriangle& t, int y, int x0, int count, float depth_scale,
                                           TerrainRow& out) {
  const float ax = t.ax, ay = t.ay, bx = t.bx, by = t.by, cx = t.cx, cy = t.cy, inv_area = t.inv_area;
  const float iza = t.iza, izb = t.izb, izc = t.izc;
  constexpr int kA = ScreenTriangle::kAttributes;
  float va[kA], vb[kA], vc[kA];
  for (int k = 0; k < kA; ++k) va[k] = t.a[std::size_t(k)], vb[k] = t.b[std::size_t(k)], vc[k] = t.c[std::size_t(k)];
  const float fy = float(y) + 0.5f;
  for (int i = 0; i < count; ++i) {
    const float fx = float(x0 + i) + 0.5f;
    // Barycentric weights (either winding); a pixel on a shared edge goes to one side only.
    const float wa = ((bx - fx) * (cy - fy) - (by - fy) * (cx - fx)) * inv_area;
    const float wb = ((cx - fx) * (ay - fy) - (cy - fy) * (ax - fx)) * inv_area;
    const float wc = 1 - wa - wb;
    out.covered[i] = std::int32_t(wa >= 0) & std::int32_t(wb >= 0) & std::int32_t(wc >= 0);
    const float iz = wa * iza + wb * izb + wc * izc;
    const float z = 1 / iz;
    out.depth[i] = z * depth_scale;
    const float pa = wa * (iza * z), pb = wb * (izb * z), pc = wc * (izc * z);
    for (int k = 0; k < kA; ++k) out.attribute[k][i] = pa * va[k] + pb * vb[k] + pc * vc[k];
  }
}

}  // namespace wangscape::view_detail
