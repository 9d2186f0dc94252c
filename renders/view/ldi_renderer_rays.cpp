// The LDI renderer's rays: the tiles hidden behind the near field, the near field's rays, and
// the whole frame ray cast.
#include "renders/view/ldi_renderer_impl.h"

#include "renders/trace/traced_shading.h"

namespace wangscape {

using namespace ldi_renderer_detail;  // the renderer's inner parts (ldi_renderer_impl.h)

// ---- occlusion: the LDI tiles wholly behind the near field (every screen block their box
// covers holds a near surface nearer than the box's nearest point) are dropped from the order:
// their samples would all fail the depth test. Returns how many.
std::uint64_t LdiRenderer::cull_occluded_tiles() {
  Impl& m = *impl_;
  const ViewWorld& world = *world_;
  const ViewWorld::Tiles& tiles = world.tiles();
  const double s = world.tile_size();
  const float top = world.pack().info().prism_top;
  m.size_blocks();
  tbb::parallel_for(0, int(m.block_far.size()) / m.blocks_wide(), [&](int by) { m.measure_block_row(by); });
  const std::size_t before = order_.size();
  // Splats reach past the projected box by up to kMaxSplat pixels.
  std::erase_if(order_, [&](std::uint32_t t) {
    const std::array<double, 3> low{tiles.x0[t], tiles.y0[t], double(tiles.z_min[t]) - 0.01};
    const std::array<double, 3> high{tiles.x0[t] + s, tiles.y0[t] + s, double(tiles.z_max[t]) + top};
    return m.box_hidden(low, high, kMaxSplat);
  });
  return before - order_.size();
}

// How far along the unit ray `d` it is `reach` meters across the ground (a ray straight down
// meets the terrain first: unlimited).
static double reach_along(const V3& d, double reach) {
  if (std::isinf(reach)) return reach;
  const double across = std::sqrt(d[0] * d[0] + d[1] * d[1]);
  return across > 1e-9 ? reach / across : std::numeric_limits<double>::infinity();
}

// ---- the near field (the frame's first drawing): every pixel's ray, from the eye no further
// than the near tiles reach, traced against the real flowers of the tiles around the
// eye and the terrain; a hit is shaded by the one shading model (sun with its shadow ray, the open
// sky) and written into the z-buffer. Returns the rays cast (primary and shadow).
std::uint64_t LdiRenderer::trace_near_field() {
  const double reach = place_near_field();
  return cast_rays(*impl_->near_tracer, reach);
}

// ViewEngine::automatic: the share of a coarse grid of pixels (kShareGridX x kShareGridY) whose
// rays the near field's flowers and ground stop: where it is high the eye stands in the field.
double LdiRenderer::near_share() {
  Impl& m = *impl_;
  const double reach = place_near_field();
  const SceneTracer& tracer = *m.near_tracer;
  const V3 from{m.view.eye[0] - tracer.origin()[0], m.view.eye[1] - tracer.origin()[1],
                m.view.eye[2] - tracer.origin()[2]};
  int stopped = 0;
  for (int gy = 0; gy < kShareGridY; ++gy)
    for (int gx = 0; gx < kShareGridX; ++gx) {
      const V3 d = m.ray_through((gx + 0.5) * m.width / kShareGridX, (gy + 0.5) * m.height / kShareGridY);
      stopped += tracer.intersect(from, d, float(reach_along(d, reach))).has_value();
    }
  tracer.check("sampling the near field");
  return double(stopped) / (kShareGridX * kShareGridY);
}

// The near field's tracer holds the flowers of the tiles around the eye; returns how far (across
// the ground) its rays reach.
double LdiRenderer::place_near_field() {
  Impl& m = *impl_;
  const ViewWorld& world = *world_;
  const SceneField& field = *world.scene().field;
  const double s = world.tile_size();
  // The flowers of near tiles stand within this far of the eye, across the ground; the window
  // adds the shadows a sun low over the field casts into it from a little further out.
  const double reach = near_field_ + 1.5 * s + kNearFlowerRadius;
  const double margin = reach + kNearShadowMargin;
  const Extent window{std::floor((m.view.eye[0] - margin) / s) * s, std::floor((m.view.eye[1] - margin) / s) * s,
                      std::ceil((m.view.eye[0] + margin) / s) * s, std::ceil((m.view.eye[1] + margin) / s) * s};
  if (!m.near_tracer) {
    const Extent& area = world.scene().field_area;
    const double cx = (area.min_x + area.max_x) / 2, cy = (area.min_y + area.max_y) / 2;
    m.near_tracer = std::make_unique<SceneTracer>(world.scene(), std::array<double, 3>{cx, cy, m.view.eye[2]},
                                                  SceneTracer::Layout::part);
    // The models' sky share among the flowers of one fixed place, so that a frame does not depend
    // on where the view started: the world's (renders/trace/field_sky.h).
    m.near_tracer->set_sky_shares(world.sky_shares());
  }
  if (m.near_window != window) {
    m.near_tracer->set_flowers([&](const InstanceSink& sink) { field.place_in(window, sink); });
    m.near_window = window;
  }
  return reach;
}

// The whole frame ray cast (ViewEngine::embree, or automatic in the field): every flower of the
// scene and the terrain in one Embree scene, built on the first frame that needs it.
std::uint64_t LdiRenderer::ray_cast_frame() {
  return cast_rays(whole_scene(), std::numeric_limits<double>::infinity());
}

const SceneTracer& LdiRenderer::whole_scene() {
  Impl& m = *impl_;
  if (!m.whole_tracer) {
    const Extent& area = world_->scene().field_area;
    m.whole_tracer = std::make_unique<SceneTracer>(
        world_->scene(),
        std::array<double, 3>{(area.min_x + area.max_x) / 2, (area.min_y + area.max_y) / 2, m.view.eye[2]},
        SceneTracer::Layout::whole);
    m.whole_tracer->set_sky_shares(world_->sky_shares());  // the near field's: one look
  }
  return *m.whole_tracer;
}

// One ray through each pixel's centre, up to `reach` meters across the ground, shaded into the
// z-buffer: the near field's and the ray-cast frame's. Returns the rays cast.
std::uint64_t LdiRenderer::cast_rays(const SceneTracer& tracer, double reach) {
  Impl& m = *impl_;
  const ViewWorld& world = *world_;
  const V3 from{m.view.eye[0] - tracer.origin()[0], m.view.eye[1] - tracer.origin()[1],
                m.view.eye[2] - tracer.origin()[2]};
  // No sky rays: at one sample per pixel a few sky rays are noise that costs more than the
  // shading otherwise (measured on the close-up camera at 320 x 180 against the 16-sample truth:
  // 24.2 dB and SSIM 0.81 without, 20.5 dB and 0.56 with one ray, 24.1 dB and 0.73 with four at
  // 3.6 times the time). The flowers' sky share is the tracer's estimate (bake_sky) instead.
  ShadingSettings shading = world.sun_shading();
  shading.ao_rays = 0;
  const Luts& lut = luts();
  m.near_rays = 0;
  // 4 x 4 pixel blocks: one packet of 16 primary rays, then one of their sun-shadow rays.
  const int blocks_x = (m.width + 3) / 4, blocks_y = (m.height + 3) / 4;
  tbb::parallel_for(tbb::blocked_range<int>(0, blocks_y), [&](const tbb::blocked_range<int>& r) {
    std::uint64_t rays = 0;
    std::array<V3, 16> d;
    std::array<float, 16> tfar;
    std::array<double, 16> along;
    bool valid[16], hit_valid[16];
    std::optional<SceneTracer::Hit> hit[16];
    SurfaceSample surfaces[16];
    Vec3f colors[16];
    for (int by = r.begin(); by != r.end(); ++by)
      for (int bx = 0; bx < blocks_x; ++bx) {
        int lanes = 0;
        for (int l = 0; l < 16; ++l) {
          const int px = bx * 4 + (l & 3), py = by * 4 + (l >> 2);
          valid[l] = false;
          if (px >= m.width || py >= m.height) continue;
          d[l] = m.ray_through(double(px) + 0.5, double(py) + 0.5);
          along[l] = dot(d[l], m.view.forward);  // camera depth per meter of ray
          tfar[l] = float(reach_along(d[l], reach));
          valid[l] = true;
          ++lanes;
        }
        if (lanes == 0) continue;
        tracer.intersect16(from, d.data(), tfar.data(), valid, hit);
        rays += std::uint64_t(lanes);
        for (int l = 0; l < 16; ++l) {
          hit_valid[l] = valid[l] && hit[l].has_value();
          if (hit_valid[l]) surfaces[l] = tracer.surface(*hit[l], from, d[l], world.ground_colors());
        }
        rays += std::uint64_t(shade_in_the_open16(tracer.scene(), shading, surfaces, hit_valid, colors));
        for (int l = 0; l < 16; ++l) {
          if (!hit_valid[l]) continue;
          const int px = bx * 4 + (l & 3), py = by * 4 + (l >> 2);
          const float depth = float(double(hit[l]->t) * along[l]);
          std::uint64_t& slot = m.zbuffer[std::size_t(py) * std::size_t(m.width) + std::size_t(px)];
          slot = std::min(
              slot, pack_entry(depth, lut.encode(colors[l][0]), lut.encode(colors[l][1]), lut.encode(colors[l][2])));
        }
      }
    m.near_rays += rays;
  });
  tracer.check(std::isinf(reach) ? "ray casting the frame" : "tracing the near field");
  return m.near_rays.load();
}

}  // namespace wangscape
