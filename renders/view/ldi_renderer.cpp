#include "renders/view/ldi_renderer.h"

#include <tbb/parallel_sort.h>

#include <chrono>

#include "core/color.h"
#include "core/error.h"
#include "renders/view/ldi_renderer_impl.h"

namespace wangscape {

using namespace ldi_renderer_detail;  // the renderer's inner parts (ldi_renderer_impl.h)

LdiRenderer::LdiRenderer(std::shared_ptr<const ViewWorld> world, int width, int height)
    : world_(std::move(world)), impl_(std::make_unique<Impl>()) {
  resize(width, height);
  Impl& m = *impl_;
  const std::size_t n = world_->tiles().size();
  for (auto* v : {&m.plan.distance, &m.plan.far_from, &m.plan.far_r, &m.plan.far_g, &m.plan.far_b, &m.plan.far_cover,
                  &m.plan.level_b_weight, &m.plan.dir_b_weight, &m.plan.steep_low_weight})
    v->assign(n, 0);
  for (auto* v : {&m.plan.level_a, &m.plan.level_b, &m.plan.dir_a, &m.plan.dir_b, &m.plan.steep, &m.plan.steep_low,
                  &m.plan.flags})
    v->assign(n, 0);
  order_.reserve(n);
  const std::size_t vertices = world_->terrain().x.size();
  m.raster_vertices.assign(vertices, RasterVertex{});
  m.chunk_order.reserve(world_->terrain().chunks.size());
  m.chunk_distance.assign(world_->terrain().chunks.size(), 0);
  m.chunk_level.assign(world_->terrain().chunks.size(), 0);
  stats_.levels.assign(world_->pack().info().levels + 1, 0);
}

LdiRenderer::~LdiRenderer() = default;

bool LdiRenderer::sky_at(int x, int y) const {
  return impl_->zbuffer[std::size_t(y) * std::size_t(impl_->width) + std::size_t(x)] == kEmpty;
}

float LdiRenderer::depth_at(int x, int y) const {
  const std::uint64_t e = impl_->zbuffer[std::size_t(y) * std::size_t(impl_->width) + std::size_t(x)];
  return e == kEmpty ? std::numeric_limits<float>::infinity() : std::bit_cast<float>(std::uint32_t(e >> 32));
}

double LdiRenderer::tile_distance(std::uint32_t t) const { return impl_->plan.distance[t]; }

LdiRenderer::TileChoice LdiRenderer::tile_choice(std::uint32_t t) const {
  return {impl_->plan.level_a[t], impl_->plan.steep[t]};
}

void LdiRenderer::set_detail(double detail) {
  if (!(detail >= kMinViewDetail && detail <= kMaxViewDetail))
    throw Error("view: detail " + std::to_string(detail) + "; expected " + std::to_string(kMinViewDetail) + " .. " +
                std::to_string(kMaxViewDetail) + " (1: the pack's levels at their own distances)");
  detail_ = detail;
}

void LdiRenderer::set_terrain_error(double pixels) {
  if (!(pixels >= 0 && pixels <= 64))
    throw Error("view: terrain error " + std::to_string(pixels) + " pixels; expected 0 .. 64 (0: the fine mesh)");
  terrain_error_ = pixels;
}

void LdiRenderer::set_near_field(double meters) {
  if (!(meters >= 0 && meters <= kMaxNearField))
    throw Error("view: near field " + std::to_string(meters) + " m; expected 0 .. " +
                std::to_string(int(kMaxNearField)) + " m (0: LDIs only)");
  near_field_ = meters;
}

// The frame's camera (its basis, focal length, centre) and empty buffers and counters.
void LdiRenderer::begin_frame(const Camera& camera) {
  Impl& m = *impl_;
  m.view = ViewProjection::of(camera, m.width, m.height, subpixel_);

  std::fill(m.zbuffer.begin(), m.zbuffer.end(), kEmpty);
  m.depth_pixels = 0;
  stats_.depth_pixels = 0;
  stats_.tiles_drawn = stats_.tiles_culled = stats_.steep_tiles = stats_.near_tiles = stats_.tiles_occluded = 0;
  stats_.terrain_triangles = stats_.terrain_pixels = 0;
  std::fill(stats_.levels.begin(), stats_.levels.end(), 0);
  order_.clear();
}

// Steps 1-4 of docs/viewer-design.md: the tiles' plan (renders/view/tile_plan.h), its counts, and
// the tiles to warp, back to front, into order_.
void LdiRenderer::choose_tiles() {
  Impl& m = *impl_;
  plan_tiles(*world_, m.view, {detail_, near_field_, &mask_}, m.plan);
  if (m.plan.any_steep) world_->prepare_steep();
  stats_.tiles_drawn = m.plan.drawn;
  stats_.tiles_culled = m.plan.culled;
  stats_.near_tiles = m.plan.near;
  stats_.steep_tiles = m.plan.steep_tiles;
  stats_.levels = m.plan.levels;
  order_.swap(m.plan.order);
}

// Steps 5, 6 and 8: the chosen LDIs warped in parallel, each thread into a z-buffer of its
// own, merged into the frame's.
void LdiRenderer::warp_tiles() {
  Impl& m = *impl_;
  const ViewWorld& world = *world_;
  const LdiPack& pack = world.pack();
  const ViewWorld::Tiles& tiles = world.tiles();
  const double s = world.tile_size();
  const LdiPackInfo& info = world.pack().info();
  const std::uint32_t levels = info.levels, drawn_levels = levels + world.far_steps();
  const WarpScreen screen{m.view.focal, m.view.cx, m.view.cy, m.width, m.height, kMaxSplat};
  // ---- the LDIs: tiles in parallel into the one z-buffer ----
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, order_.size(), 1), [&](const tbb::blocked_range<std::size_t>& r) {
        std::uint64_t counted = 0;
        ThreadDepths& depths = m.thread_depths.local();
        if (depths.entries.size() != m.zbuffer.size()) depths.reset(m.width, m.height);
        depths.written = true;
        for (std::size_t o = r.begin(); o != r.end(); ++o) {
          const std::uint32_t t = order_[o];
          // Up to two levels x two directions, each owning a slice of the dither thresholds.
          const float wl = m.plan.level_b_weight[t], wd = m.plan.dir_b_weight[t];
          struct Part {
            std::uint32_t level, direction;
            float from, to;
          };
          const std::uint32_t la = m.plan.level_a[t], lb = m.plan.level_b[t];
          const float split = 1 - wl;
          const Part parts[4] = {{la, m.plan.dir_a[t], 0, split * (1 - wd)},
                                 {la, m.plan.dir_b[t], split * (1 - wd), split},
                                 {lb, m.plan.dir_a[t], split, split + wl * (1 - wd)},
                                 {lb, m.plan.dir_b[t], split + wl * (1 - wd), 1}};
          // Each part's slice split again between the tile's two elevation sets.
          const float low_share = m.plan.steep_low_weight[t];
          for (int slice = 0; slice < 8; ++slice) {
            const Part& whole = parts[slice / 2];
            const float cut = whole.from + (whole.to - whole.from) * (1 - low_share);
            const bool lower = slice % 2 == 1;
            const Part part{whole.level, whole.direction, lower ? cut : whole.from, lower ? whole.to : cut};
            if (!(part.to > part.from) || part.level >= drawn_levels) continue;
            const bool far = part.level >= levels;
            const std::uint8_t set = lower ? m.plan.steep_low[t] : m.plan.steep[t];
            const LdiView v =
                set   ? world.steep_ldi(set - 1u, tiles.tile[t], part.direction, far ? part.level - levels + 1 : 0)
                : far ? world.far_ldi(tiles.tile[t], part.direction, part.level - levels)
                      : pack.ldi(tiles.tile[t], part.level, part.direction);
            const LdiFrame& f = *v.frame;
            Warp w;
            const double p = f.pixel_size;
            // Tile-local position of pixel (x, y) at depth d: origin + (x + .5) p right - (y + .5) p up + d forward.
            for (std::size_t k = 0; k < 3; ++k) {
              w.local_base[k] = float(f.origin[k] + 0.5 * p * f.right[k] - 0.5 * p * f.up[k]);
              w.local_x[k] = float(p * f.right[k]);
              w.local_y[k] = float(-p * f.up[k]);
              w.local_d[k] = f.forward[k];
            }
            w.base = m.to_camera(tiles.x0[t] + w.local_base[0], tiles.y0[t] + w.local_base[1], w.local_base[2]);
            w.step_x = m.direction_to_camera(w.local_x[0], w.local_x[1], w.local_x[2]);
            w.step_y = m.direction_to_camera(w.local_y[0], w.local_y[1], w.local_y[2]);
            w.step_d = m.direction_to_camera(w.local_d[0], w.local_d[1], w.local_d[2]);
            w.lift = m.direction_to_camera(0, 0, 1);
            w.h00 = tiles.h[0][t];
            w.h10 = tiles.h[1][t];
            w.h01 = tiles.h[2][t];
            w.h11 = tiles.h[3][t];
            w.inverse_tile = float(1 / s);
            w.depth_scale = f.depth_range / 65535.0f;
            // (A far LDI holds no ground samples: its low samples are flowers.)
            w.ground_below = far ? -std::numeric_limits<float>::infinity() : kGroundEpsilon + 0.75f * f.pixel_size;
            w.splat = float(p) * m.view.focal * (far ? kFarSplatScale : kSplatScale);
            w.owned = owned_thresholds(part.from, part.to);
            if (!tiles.plant_steps.empty()) w.plant_steps = tiles.plant_steps[t].data();
            w.screen = screen;
            counted += warp_ldi(v, w, depths);
          }
        }
        m.depth_pixels += counted;
      });
  // The threads' buffers merged into the frame's, a block row at a time, and emptied for the next
  // frame; the block row's farthest depths measured while it is in cache (the terrain's
  // occlusion test).
  m.size_blocks();
  tbb::parallel_for(0, int(m.block_far.size()) / m.blocks_wide(), [&](int by) {
    const std::size_t begin = std::size_t(by) * kOcclusionBlock * std::size_t(m.width);
    const std::size_t end = std::size_t(std::min(m.height, (by + 1) * kOcclusionBlock)) * std::size_t(m.width);
    for (ThreadDepths& depths : m.thread_depths) {
      if (!depths.written) continue;
      std::uint64_t* own = depths.entries.data();
      for (std::size_t i = begin; i < end; ++i) {
        m.zbuffer[i] = std::min(m.zbuffer[i], own[i]);
        own[i] = kEmpty;
      }
    }
    m.measure_block_row(by);
  });
  for (ThreadDepths& depths : m.thread_depths) depths.written = false;
}

// Step 9: the z-buffer's colors into the image, the sky where nothing was drawn.
void LdiRenderer::resolve() {
  Impl& m = *impl_;
  const ViewWorld& world = *world_;
  const Luts& lut = luts();
  // ---- resolve: the z-buffer's colors, the sky where nothing was drawn ----
  tbb::parallel_for(tbb::blocked_range<int>(0, m.height, 8), [&](const tbb::blocked_range<int>& r) {
    for (int py = r.begin(); py != r.end(); ++py) {
      const float ray_up = -(float(py) + 0.5f - m.view.cy) / m.view.focal;
      std::uint8_t* out = image_.pixels.data() + image_.offset(0, py);
      const std::uint64_t* row = m.zbuffer.data() + std::size_t(py) * std::size_t(m.width);
      for (int px = 0; px < m.width; ++px, out += 3) {
        const std::uint64_t e = row[px];
        if (e == kEmpty) {  // the sky of the shading model (as the Embree reference draws it)
          const float ray_right = (float(px) + 0.5f - m.view.cx) / m.view.focal;
          Vec3f d;
          for (std::size_t c = 0; c < 3; ++c)
            d[c] = float(m.view.forward[c]) + ray_right * float(m.view.right[c]) + ray_up * float(m.view.up[c]);
          const Vec3f sky = sky_radiance(world.shading(), d);
          out[0] = lut.encode(sky[0]);
          out[1] = lut.encode(sky[1]);
          out[2] = lut.encode(sky[2]);
        } else {
          out[0] = std::uint8_t(e >> 16);
          out[1] = std::uint8_t(e >> 8);
          out[2] = std::uint8_t(e);
        }
      }
    }
  });
}

void LdiRenderer::resize(int width, int height) {
  if (width < 1 || height < 1 || width > 16384 || height > 16384)
    throw Error("view: size " + std::to_string(width) + "x" + std::to_string(height) +
                " pixels; expected 1 .. 16384 per side");
  Impl& m = *impl_;
  m.width = width;
  m.height = height;
  m.zbuffer.assign(std::size_t(width) * std::size_t(height), kEmpty);  // (the threads' buffers follow it)
  image_ = ImageRgb8(width, height);
}

void LdiRenderer::apply(const ViewSettings& settings) {
  set_detail(settings.detail);
  set_near_field(settings.near_field);
  set_engine(settings.engine);
  set_samples(settings.samples);
}

void LdiRenderer::set_samples(int samples) {
  if (samples < 1 || samples > kMaxViewSamples)
    throw Error("view: " + std::to_string(samples) + " samples per pixel; expected 1 .. " +
                std::to_string(kMaxViewSamples));
  samples_ = samples;
}

void ViewFrameStats::add_work(const ViewFrameStats& sample) {
  frame_ms += sample.frame_ms;
  for (std::size_t p = 0; p < phase_ms.size(); ++p) phase_ms[p] += sample.phase_ms[p];
  depth_pixels += sample.depth_pixels;
  near_rays += sample.near_rays;
  terrain_triangles += sample.terrain_triangles;
  terrain_pixels += sample.terrain_pixels;
}

const ViewFrameStats& LdiRenderer::render(const Camera& camera) {
  if (samples_ <= 1) return render_sample(camera);
  // Jittered samples (the R2 sequence: the first at the pixel centres), averaged in linear light.
  std::vector<float>& sum = impl_->accumulated;
  sum.assign(image_.pixels.size(), 0.0f);
  std::array<float, 256> linear{};
  for (std::size_t v = 0; v < 256; ++v) linear[v] = srgb8_to_linear(std::uint8_t(v));
  ViewFrameStats total;  // the first sample's, with every sample's time and work
  for (int k = 0; k < samples_; ++k) {
    subpixel_ = r2_offset(k);
    const ViewFrameStats& one = render_sample(camera);
    for (std::size_t i = 0; i < sum.size(); ++i) sum[i] += linear[image_.pixels[i]];
    if (k == 0)
      total = one;
    else
      total.add_work(one);
  }
  subpixel_ = {0, 0};
  for (std::size_t i = 0; i < sum.size(); ++i) image_.pixels[i] = linear_to_srgb8(sum[i] / float(samples_));
  stats_ = std::move(total);
  return stats_;
}

const ViewFrameStats& LdiRenderer::render_sample(const Camera& camera) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  begin_frame(camera);
  const auto ms = [](auto from, auto to) { return std::chrono::duration<double, std::milli>(to - from).count(); };
  // The whole frame by rays (ViewEngine::embree, or automatic in the field).
  const auto ray_cast = [&](Clock::time_point traced_from) {
    stats_.near_rays = ray_cast_frame();
    stats_.ray_cast = true;
    stats_.depth_pixels = 0;
    const auto traced = Clock::now();
    resolve();
    const auto end = Clock::now();
    stats_.phase_ms = {ms(start, traced_from), 0, 0, ms(traced_from, traced), ms(traced, end)};
    stats_.frame_ms = ms(start, end);
  };
  if (engine_ == ViewEngine::embree) {
    ray_cast(start);
    return stats_;
  }
  choose_tiles();
  const auto tiles_done = Clock::now();
  // The near field first: what it hides is neither warped nor shaded after it.
  stats_.ray_cast = false;
  if (engine_ == ViewEngine::automatic && stats_.near_tiles && near_share() >= kRayCastShare) {
    ray_cast(tiles_done);
    return stats_;
  }
  stats_.near_rays = stats_.near_tiles ? trace_near_field() : 0;
  stats_.tiles_occluded = stats_.near_tiles ? cull_occluded_tiles() : 0;
  const auto near_done = Clock::now();
  warp_tiles();
  const auto ldis_done = Clock::now();
  draw_terrain();
  const auto terrain_done = Clock::now();
  resolve();
  const auto end = Clock::now();
  stats_.phase_ms = {ms(start, tiles_done), ms(near_done, ldis_done), ms(ldis_done, terrain_done),
                     ms(tiles_done, near_done), ms(terrain_done, end)};
  stats_.depth_pixels = impl_->depth_pixels;
  stats_.frame_ms = ms(start, end);
  return stats_;
}

}  // namespace wangscape
