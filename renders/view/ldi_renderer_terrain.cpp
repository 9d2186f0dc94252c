// The LDI renderer's terrain: its chunks in the frustum rasterized into the z-buffer.
#include "renders/view/ldi_renderer_impl.h"
#include "renders/view/terrain_raster.h"

namespace wangscape {

using namespace ldi_renderer_detail;  // the renderer's inner parts (ldi_renderer_impl.h)

// The terrain's chunks to draw and their levels (step 7's first part): into chunk_order and chunk_level.
void LdiRenderer::choose_chunks() {
  Impl& m = *impl_;
  const ViewWorld::Terrain& terrain = world_->terrain();
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
  std::sort(m.chunk_order.begin(), m.chunk_order.end(), [&](std::uint32_t p, std::uint32_t q) {
    return m.chunk_distance[p] != m.chunk_distance[q] ? m.chunk_distance[p] < m.chunk_distance[q] : p < q;
  });
}

namespace {
// The shade a placed tile's plants cast on the terrain (renders/ldi/ground_light.h). It fades out
// where the ground is seen low, by the sine of the pixel's ray below the horizon: none below kLow,
// all above kHigh (seen low, ground between the plants is where the LDIs left a gap the truth
// fills with leaves).
struct PlantShade {
  static constexpr double kLow = 0.26, kHigh = 0.64;  // 15 and 40 degrees
  PlantShade(const ViewWorld& world, const ViewProjection& camera)
      : light(world.ground_light()),
        tiles(world.tiles().tile),
        view(camera),
        // The open sky's part of the terrain's light (its vertices': the sun's where it reaches
        // them, and the open sky), and level-0 texels per meter of a pixel's footprint.
        open_sky(lit(world.sun_shading(), {1, 1, 1}, 0, 1)),
        texels_per_meter(float(light.resolution() / world.tile_size() / camera.focal)) {}
  // The terrain's light `l` at pixel (px, py), `depth` away, at (u, v) in placed tile t (or none,
  // -1), shaded by the plants.
  void apply(std::int32_t t, float u, float v, int px, int py, float depth, float (&l)[3]) const {
    if (t < 0 || light.empty()) return;
    const double sine = -view.ray_through(double(px) + 0.5, double(py) + 0.5)[2];
    const float seen = float(std::clamp((sine - kLow) / (kHigh - kLow), 0.0, 1.0));
    if (!(seen > 0)) return;
    auto [sun, sky] = light.shares(tiles[std::size_t(t)], u, v, depth * texels_per_meter);
    sun = 1 + (sun - 1) * seen;
    sky = 1 + (sky - 1) * seen;
    for (std::size_t c = 0; c < 3; ++c) l[c] = (l[c] - open_sky[c]) * sun + open_sky[c] * sky;
  }
  const TileGroundLight& light;
  const std::vector<std::uint32_t>& tiles;
  const ViewProjection& view;
  Vec3f open_sky;
  float texels_per_meter;
};
}  // namespace

// Step 7: the terrain's chunks in the frustum rasterized (renders/view/terrain_raster.h), nearest
// first, each pixel shaded with the ground's colour and light and, beyond the LDIs, the tile's
// far-field colour.
void LdiRenderer::draw_terrain() {
  Impl& m = *impl_;
  const ViewWorld& world = *world_;
  // ---- the terrain: chunks in the frustum, their vertices to camera space, their triangles
  // rasterized, in parallel ----
  const ViewWorld::Terrain& terrain = world.terrain();
  const Luts& lut = luts();
  const float ex = float(m.view.eye[0]), ey = float(m.view.eye[1]);
  const PlantShade plant_shade(world, m.view);
  auto shade_pixel = [&](int px, int py, float depth, float wx, float wy, float lr, float lg, float lb) {
    const double gx = double(wx) + m.view.eye[0], gy = double(wy) + m.view.eye[1];
    const auto base = world.ground_color(gx, gy);
    float u = 0, v = 0;
    const std::int32_t t = world.placed_tile_at(gx, gy, u, v);
    float light[3] = {lr, lg, lb};
    plant_shade.apply(t, u, v, px, py, depth, light);
    float r = base[0] * light[0], g = base[1] * light[1], b = base[2] * light[2];
    // Beyond the LDIs: the tile's directional average color over the ground, by its cover.
    if (t >= 0 && threshold(px, py) >= m.plan.far_from[std::size_t(t)]) {
      const float k = m.plan.far_cover[std::size_t(t)];
      r += (m.plan.far_r[std::size_t(t)] - r) * k;
      g += (m.plan.far_g[std::size_t(t)] - g) * k;
      b += (m.plan.far_b[std::size_t(t)] - b) * k;
    }
    depth_write(m.zbuffer[std::size_t(py) * std::size_t(m.width) + std::size_t(px)],
                pack_entry(depth, lut.encode(r), lut.encode(g), lut.encode(b)));
  };
  const RasterTarget target{&m.view, m.width, m.height, m.zbuffer.data(), kTerrainDepthBias, kOcclusionBlock};
  const auto hidden = [&](int x0, int y0, int x1, int y1, float nearest) {
    return m.screen_box_hidden(x0, y0, x1, y1, nearest);
  };
  auto draw_mesh_triangle = [&](const std::array<std::uint32_t, 3>& ids, bool one_sided, std::uint64_t& tests) {
    const RasterVertex v[3] = {m.raster_vertices[ids[0]], m.raster_vertices[ids[1]], m.raster_vertices[ids[2]]};
    draw_triangle(target, v, one_sided, shade_pixel, hidden, tests);
  };
  choose_chunks();
  // The level chunk k is drawn at this frame (0, the fine mesh, where not drawn).
  const auto level_of = [&](std::size_t k) -> const ViewWorld::Terrain::Level& {
    return terrain.levels[terrain.chunks[k].first_level + m.chunk_level[k]];
  };
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
        RasterVertex& q = m.raster_vertices[v];
        q = {c[0],
             c[1],
             c[2],
             terrain.x[v] - ex,
             terrain.y[v] - ey,
             terrain.light_r[v],
             terrain.light_g[v],
             terrain.light_b[v]};
        if (q.z >= view_detail::kNear) place_on_screen(m.view, q);
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
      for (std::uint32_t t = begin; t < end; ++t) draw_mesh_triangle(terrain.triangles[t], t < skirts, tested);
      drawn += end - begin;
      // The fine mesh's triangles that its coarser neighbours' grids leave out (with the chunk's
      // first piece).
      if (m.chunk_level[k] == 0 && first == 0)
        for (std::uint32_t b = chunk.first_borrowed; b < chunk.first_borrowed + chunk.borrowed_count; ++b)
          if (m.chunk_level[terrain.borrowed[b].owner] != 0) {
            draw_mesh_triangle(terrain.borrowed[b].ids, true, tested);
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
