// The LDI renderer's terrain: its chunks in the frustum rasterized into the z-buffer.
#include "renders/view/ldi_renderer_impl.h"

namespace wangscape {

// Step 7: the terrain's chunks in the frustum rasterized, nearest first. Longer than the other
// steps because it holds its three short stages as lambdas over the frame's camera and buffers:
// shade a pixel, rasterize a triangle, clip a triangle at the near plane and draw it.
void LdiRenderer::draw_terrain() {
  Impl& m = *impl_;
  const ViewWorld& world = *world_;
  const double s = world.tile_size();
  // ---- the terrain: chunks in the frustum, their vertices to camera space, their triangles
  // rasterized, in parallel ----
  const ViewWorld::Terrain& terrain = world.terrain();
  const Luts& lut = luts();
  const float ex = float(m.view.eye[0]), ey = float(m.view.eye[1]);
  const float inv_s = float(1 / s);
  // A vertex of a clipped triangle: camera space, world x, y relative to the eye, light.
  struct Vertex {
    float x, y, z, wx, wy, lr, lg, lb;
  };
  auto shade_pixel = [&](int px, int py, float depth, float wx, float wy, float lr, float lg, float lb) {
    const double gx = double(wx) + m.view.eye[0], gy = double(wy) + m.view.eye[1];
    const auto base = world.ground_color(gx, gy);
    float r = base[0] * lr, g = base[1] * lg, b = base[2] * lb;
    // Beyond the LDIs: the tile's directional average color over the ground, by its cover.
    const std::int64_t ci = std::int64_t(std::floor(gx * inv_s)) - world.grid_i0();
    const std::int64_t cj = std::int64_t(std::floor(gy * inv_s)) - world.grid_j0();
    if (ci >= 0 && cj >= 0 && ci < world.grid_width() && cj < world.grid_height()) {
      const std::int32_t t = world.grid()[std::size_t(cj * world.grid_width() + ci)];
      if (t >= 0 && threshold(px, py) >= m.plan.far_from[std::size_t(t)]) {
        const float k = m.plan.far_cover[std::size_t(t)];
        r += (m.plan.far_r[std::size_t(t)] - r) * k;
        g += (m.plan.far_g[std::size_t(t)] - g) * k;
        b += (m.plan.far_b[std::size_t(t)] - b) * k;
      }
    }
    depth_write(m.zbuffer[std::size_t(py) * std::size_t(m.width) + std::size_t(px)],
                pack_entry(depth, lut.encode(r), lut.encode(g), lut.encode(b)));
  };
  // Counts the pixels it tests into `tests`. With `one_sided`, a triangle seen from below is
  // skipped: the terrain is a height field and the eye above it, so where a ray meets the
  // underside it has met the upper side first (only the skirts are seen from either side).
  auto raster = [&](const Vertex& a, const Vertex& b, const Vertex& c, bool one_sided, std::uint64_t& tests) {
    const float ax = m.view.cx + m.view.focal * a.x / a.z, ay = m.view.cy - m.view.focal * a.y / a.z;
    const float bx = m.view.cx + m.view.focal * b.x / b.z, by = m.view.cy - m.view.focal * b.y / b.z;
    const float cx = m.view.cx + m.view.focal * c.x / c.z, cy = m.view.cy - m.view.focal * c.y / c.z;
    const float area = (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
    if (!(std::abs(area) > 1e-12f) || (one_sided && area * kUpperSide < 0)) return;
    const int x0 = std::max(0, int(std::floor(std::min({ax, bx, cx})))),
              x1 = std::min(m.width - 1, int(std::ceil(std::max({ax, bx, cx}))));
    const int y0 = std::max(0, int(std::floor(std::min({ay, by, cy})))),
              y1 = std::min(m.height - 1, int(std::ceil(std::max({ay, by, cy}))));
    if (x0 > x1 || y0 > y1) return;
    // Ground wholly behind what the LDIs and the near field drew (most of it, inside the field).
    const float nearest = std::min({a.z, b.z, c.z}) * (1 + kTerrainDepthBias);
    if (m.screen_box_hidden(x0, y0, x1, y1, nearest)) return;
    const float inv_area = 1.0f / area;
    const float iza = 1 / a.z, izb = 1 / b.z, izc = 1 / c.z;
    // Per row, the span where the three weights are >= 0 (each is linear in x), widened by a
    // pixel: the exact test below decides, the span only skips what surely fails (thin far
    // triangles have bounding boxes many times their area).
    const float slope_a = (by - cy) * inv_area, slope_b = (cy - ay) * inv_area, slope_c = -slope_a - slope_b;
    // Their inverses (0 for 0, the sign kept), divided once here, not per row: the span is widened
    // by a pixel anyway.
    const auto inverse = [](float slope) { return slope != 0 ? 1 / slope : 0.0f; };
    const float inverse_a = inverse(slope_a), inverse_b = inverse(slope_b), inverse_c = inverse(slope_c);
    for (int py = y0; py <= y1; ++py) {
      // A large triangle: its rows a block row at a time, skipped where that row is hidden.
      if ((py == y0 || py % kOcclusionBlock == 0) && y1 - y0 >= kOcclusionBlock &&
          m.screen_box_hidden(x0, py, x1, py, nearest)) {
        py = (py / kOcclusionBlock + 1) * kOcclusionBlock - 1;
        continue;
      }
      const float fy = float(py) + 0.5f;
      const float wa0 = (bx * (cy - fy) - (by - fy) * cx) * inv_area,
                  wb0 = (cx * (ay - fy) - (cy - fy) * ax) * inv_area;
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
      const int span_x0 = std::max(x0, int(std::ceil(lo - 0.5f)) - 1),
                span_x1 = std::min(x1, int(std::floor(hi - 0.5f)) + 1);
      tests += std::uint64_t(std::max(0, span_x1 - span_x0 + 1));
      for (int px = span_x0; px <= span_x1; ++px) {
        const float fx = float(px) + 0.5f;
        // Barycentric weights (either winding), a pixel on a shared edge goes to one side only.
        float wa = ((bx - fx) * (cy - fy) - (by - fy) * (cx - fx)) * inv_area;
        float wb = ((cx - fx) * (ay - fy) - (cy - fy) * (ax - fx)) * inv_area;
        // The third edge by its own function too (not 1 - wa - wb), so that two triangles meeting
        // on an edge agree exactly on which side of it a pixel lies: a silhouette's pixels then
        // belong to its upper side whenever to its underside, which may be skipped.
        if (wa < 0 || wb < 0 || ((ax - fx) * (by - fy) - (ay - fy) * (bx - fx)) * inv_area < 0) continue;
        float wc = 1 - wa - wb;
        const float iz = wa * iza + wb * izb + wc * izc;
        const float z = 1 / iz;
        const float drawn_depth = z * (1 + kTerrainDepthBias);
        // Early depth test: most ground under the field is hidden by flowers drawn before it.
        const std::uint64_t drawn =
            std::atomic_ref<std::uint64_t>(m.zbuffer[std::size_t(py) * std::size_t(m.width) + std::size_t(px)])
                .load(std::memory_order_relaxed);
        if (pack_entry(drawn_depth, 0, 0, 0) > drawn) continue;
        wa *= iza * z;
        wb *= izb * z;
        wc *= izc * z;
        shade_pixel(px, py, drawn_depth, wa * a.wx + wb * b.wx + wc * c.wx, wa * a.wy + wb * b.wy + wc * c.wy,
                    wa * a.lr + wb * b.lr + wc * c.lr, wa * a.lg + wb * b.lg + wc * c.lg,
                    wa * a.lb + wb * b.lb + wc * c.lb);
      }
    }
  };
  auto draw_triangle = [&](const std::array<std::uint32_t, 3>& ids, bool one_sided, std::uint64_t& tests) {
    Vertex v[3];
    int behind = 0;
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t i = ids[std::size_t(k)];
      v[k] = {m.vx[i],
              m.vy[i],
              m.vz[i],
              terrain.x[i] - ex,
              terrain.y[i] - ey,
              terrain.light_r[i],
              terrain.light_g[i],
              terrain.light_b[i]};
      behind += v[k].z < kNear;
    }
    if (behind == 3) return;
    // A quick reject: all three beyond one side plane.
    auto out = [&](auto&& side) { return side(v[0]) && side(v[1]) && side(v[2]); };
    if (out([&](const Vertex& q) { return q.x > q.z * m.view.tan_x; }) ||
        out([&](const Vertex& q) { return q.x < -q.z * m.view.tan_x; }) ||
        out([&](const Vertex& q) { return q.y > q.z * m.view.tan_y; }) ||
        out([&](const Vertex& q) { return q.y < -q.z * m.view.tan_y; }))
      return;
    if (behind == 0) {
      raster(v[0], v[1], v[2], one_sided, tests);
      return;
    }
    // Clip against the near plane (Sutherland-Hodgman): 3 or 4 vertices, drawn as a fan.
    Vertex poly[4];
    int n = 0;
    for (int k = 0; k < 3; ++k) {
      const Vertex& p = v[k];
      const Vertex& q = v[(k + 1) % 3];
      const bool pin = p.z >= kNear, qin = q.z >= kNear;
      if (pin) poly[n++] = p;
      if (pin != qin) {
        const float f = (kNear - p.z) / (q.z - p.z);
        auto lerp = [f](float a, float b) { return a + (b - a) * f; };
        poly[n++] = {lerp(p.x, q.x),   lerp(p.y, q.y),   kNear,           lerp(p.wx, q.wx), lerp(p.wy, q.wy),
                     lerp(p.lr, q.lr), lerp(p.lg, q.lg), lerp(p.lb, q.lb)};
      }
    }
    for (int k = 1; k + 1 < n; ++k) raster(poly[0], poly[k], poly[k + 1], one_sided, tests);
  };
  // The chunks in the frustum, nearest first: the early depth test then skips the shading of
  // ground that nearer ground hides. Each at the coarsest level whose error projects to at most
  // terrain_error_ pixels at its nearest point.
  m.chunk_order.clear();
  std::fill(m.chunk_level.begin(), m.chunk_level.end(), 0);
  for (std::uint32_t k = 0; k < terrain.chunks.size(); ++k) {
    const ViewWorld::Terrain::Chunk& chunk = terrain.chunks[k];
    const V3 low{chunk.low[0], chunk.low[1], chunk.low[2]}, high{chunk.high[0], chunk.high[1], chunk.high[2]};
    if (m.box_outside_frustum(low, high) || m.box_hidden(low, high, 0)) continue;
    double squared = 0;
    for (std::size_t c = 0; c < 3; ++c) {
      const double d = std::max({low[c] - m.view.eye[c], m.view.eye[c] - high[c], 0.0});
      squared += d * d;
    }
    m.chunk_distance[k] = float(squared);
    m.chunk_order.push_back(k);
    if (terrain_error_ <= 0) continue;
    const double allowed = terrain_error_ * std::sqrt(squared) / double(m.view.focal);  // meters at that distance
    for (std::uint32_t level = chunk.level_count; level-- > 1;)
      if (terrain.levels[chunk.first_level + level].error <= allowed) {
        m.chunk_level[k] = std::uint8_t(level);
        break;
      }
  }
  // The level chunk k is drawn at this frame (0, the fine mesh, where not drawn).
  const auto level_of = [&](std::size_t k) -> const ViewWorld::Terrain::Level& {
    return terrain.levels[terrain.chunks[k].first_level + m.chunk_level[k]];
  };
  std::sort(m.chunk_order.begin(), m.chunk_order.end(), [&](std::uint32_t p, std::uint32_t q) {
    return m.chunk_distance[p] != m.chunk_distance[q] ? m.chunk_distance[p] < m.chunk_distance[q] : p < q;
  });
  // The chunks' vertices to camera space, then their triangles in pieces of at most
  // kTerrainPiece, nearest chunk first: under the field the mesh is refined, so one chunk there
  // can hold many times the others' triangles, and drawn whole it kept one thread busy while the
  // other waited (from above, two threads drew the terrain only 1.27 times as fast as one).
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m.chunk_order.size(), 1), [&](const auto& r) {
    for (std::size_t o = r.begin(); o != r.end(); ++o) {
      const std::uint32_t k = m.chunk_order[o];
      const ViewWorld::Terrain::Chunk& chunk = terrain.chunks[k];
      const ViewWorld::Terrain::Level& level = level_of(k);
      // A skirt bridges this level's vertical error and its neighbours' (each within its error of
      // the fine surface, so their sides are at most the sum apart).
      float drop = level.height_error + kSkirtMargin;
      float neighbours_error = 0;
      for (const std::int32_t n : chunk.neighbours)  // level 0 (the fine mesh, or not drawn): 0
        if (n >= 0) neighbours_error = std::max(neighbours_error, level_of(std::size_t(n)).height_error);
      drop += neighbours_error;
      const std::uint32_t skirts = level.first_vertex + level.vertex_count - level.skirt_vertices;
      for (std::uint32_t v = level.first_vertex; v < level.first_vertex + level.vertex_count; ++v) {
        const auto c = m.to_camera(terrain.x[v], terrain.y[v], v < skirts ? terrain.z[v] : terrain.z[v] - drop);
        m.vx[v] = c[0];
        m.vy[v] = c[1];
        m.vz[v] = c[2];
      }
    }
  });
  m.terrain_pieces.clear();
  for (const std::uint32_t k : m.chunk_order) {
    const ViewWorld::Terrain::Level& level = level_of(k);
    for (std::uint32_t first = 0; first < level.triangle_count; first += kTerrainPiece)
      m.terrain_pieces.push_back({k, first});
  }
  std::atomic<std::uint64_t> triangles{0}, tests{0};
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m.terrain_pieces.size(), 1), [&](const auto& r) {
    std::uint64_t drawn = 0, tested = 0;
    for (std::size_t o = r.begin(); o != r.end(); ++o) {
      const auto [k, first] = m.terrain_pieces[o];
      const ViewWorld::Terrain::Chunk& chunk = terrain.chunks[k];
      const ViewWorld::Terrain::Level& level = level_of(k);
      const std::uint32_t skirts = level.first_triangle + level.triangle_count - level.skirt_triangles;
      const std::uint32_t begin = level.first_triangle + first;
      const std::uint32_t end = level.first_triangle + std::min(level.triangle_count, first + kTerrainPiece);
      for (std::uint32_t t = begin; t < end; ++t) draw_triangle(terrain.triangles[t], t < skirts, tested);
      drawn += end - begin;
      // The fine mesh's triangles that its coarser neighbours' grids leave out (with the chunk's
      // first piece).
      if (m.chunk_level[k] == 0 && first == 0)
        for (std::uint32_t b = chunk.first_borrowed; b < chunk.first_borrowed + chunk.borrowed_count; ++b)
          if (m.chunk_level[terrain.borrowed[b].owner] != 0) {
            draw_triangle(terrain.borrowed[b].ids, true, tested);
            ++drawn;
          }
    }
    triangles += drawn;
    tests += tested;
  });
  stats_.terrain_triangles = triangles;
  stats_.terrain_pixels = tests;
}

}  // namespace wangscape
