#include "renders/view/frame_cache.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>

#include "core/error.h"
#include "core/number_text.h"
#include "renders/trace/traced_shading.h"
#include "renders/view/frame_cache_impl.h"
#include "renders/view/ldi_renderer.h"
#include "renders/view/view_samples.h"

namespace wangscape {

using namespace frame_cache_detail;  // the cache's inner parts (frame_cache_impl.h)

using namespace view_detail;

namespace frame_cache_detail {

// Where objects kEnteringDepth away or farther may have come into view moving from `from` to `to`:
// at the edges the picture slides away from (a step right slides it left: the right edge), and at
// every edge stepping back; up to a quarter of the frame.
EnteringBand entering_band(const ViewProjection& from, const ViewProjection& to, int frame_width, int frame_height) {
  const Vector3d shift = from.eye - to.eye;  // in the new camera's axes below
  const double side = dot(to.right, shift), up = dot(to.up, shift), back = std::max(0.0, dot(to.forward, shift));
  const double reach = to.focal / kEnteringDepth;  // pixels a meter of shift moves such an object
  const auto width = [&](double pixels, int size) {
    return pixels > 0 ? std::min(size / 4, int(std::ceil(pixels)) + 1) : 0;
  };
  const double sideways_back = back / kEnteringDepth * to.cx, upward_back = back / kEnteringDepth * to.cy;
  return {width(side * reach + sideways_back, frame_width), width(-side * reach + sideways_back, frame_width),
          width(-up * reach + upward_back, frame_height), width(up * reach + upward_back, frame_height)};
}

}  // namespace frame_cache_detail

void FrameBudget::check() const {
  if (!(fps >= kMinViewFps && fps <= kMaxViewFps))
    throw Error("view: " + number_text(fps) + " frames/s; expected " + number_text(kMinViewFps) + " .. " +
                number_text(kMaxViewFps));
  if (!(pixel_ns > 0 && still_pixel_ns > 0 && sample_ns > 0 && still_sample_ns > 0))
    throw Error("view: a frame budget's costs must be positive");
}

// ---- the picture ----------------------------------------------------------------------------

namespace {

// A run of one row's pixels reconstructed at once (kReconstructionRadius): the samples of the
// three rows around it laid out a value to a lane, each row once for the three runs below, on and
// above it, so that each of the nine neighbours' weights is a few vector instructions over the
// run's pixels (with a Sample read and its weight worked out nine times a pixel, the walk's resolve
// took 8.7-9.6 ms a frame at 640 x 360 instead of 2.5).
constexpr int kRun = 128;
struct ReconstructionRows {
  // Per row slot and column of the run's kRun + 2: the sample's place in pixels from its pixel's
  // centre (0 for a still mean, which stands for its whole pixel), whether it is there, whether it
  // is the sky, its colour (the sky's own along its ray).
  alignas(64) float ox[3][kRun + 2], oy[3][kRun + 2], there[3][kRun + 2], sky[3][kRun + 2];
  alignas(64) float color[3][3][kRun + 2];

  // Row ny's samples of the run's columns into the slot ny falls in.
  void lay(const Sample* k, int width, int height, int ny, int x0, int n) {
    constexpr float inverse_sub = 1.0f / kSubScale;
    const int r = slot(ny);
    for (int c = 0; c < n + 2; ++c) {
      const int nx = x0 + c - 1;
      const bool inside = ny >= 0 && ny < height && nx >= 0 && nx < width;
      const Sample q = inside ? k[std::size_t(ny) * std::size_t(width) + std::size_t(nx)] : Sample{};
      const float centre = q.count >= 2 ? 0.0f : inverse_sub;
      ox[r][c] = float(q.sub_x) * centre;
      oy[r][c] = float(q.sub_y) * centre;
      there[r][c] = inside && !is_none(q.depth) ? 1.0f : 0.0f;
      sky[r][c] = q.source == SampleSource::sky ? 1.0f : 0.0f;
      for (int a = 0; a < 3; ++a) color[a][r][c] = q.color[std::size_t(a)];
    }
  }
  static int slot(int row) { return (row + 3) % 3; }  // rows from -1

  // The run's pixel i of row y: its tent-weighted sums, and the weight of the samples not sky.
  void weigh(int y, int n, float (*sum)[kRun], float* weights, float* ground) const {
    for (int i = 0; i < n; ++i) sum[0][i] = sum[1][i] = sum[2][i] = weights[i] = ground[i] = 0;
    for (int dy = -1; dy <= 1; ++dy) {
      const int r = slot(y + dy);
      for (int d = 0; d < 3; ++d)
        for (int i = 0; i < n; ++i) {
          const int c = i + d;
          const float weight = tent_weight(float(d - 1) + ox[r][c]) * tent_weight(float(dy) + oy[r][c]) * there[r][c];
          for (int a = 0; a < 3; ++a) sum[a][i] += weight * color[a][r][c];
          weights[i] += weight;
          ground[i] += weight * (1.0f - sky[r][c]);
        }
    }
  }
};

}  // namespace

void FrameCache::Impl::resolve(const ViewWorld& world, ImageRgb8& image) {
  const Sample* const k = kept[current].data();
  const Luts& lut = luts();
  const ViewProjection& view = projection;
  const int w = width, h = height;
  tbb::parallel_for(tbb::blocked_range<int>(0, height, 8), [&](const tbb::blocked_range<int>& r) {
    // Locals: the image's byte stores would otherwise reload them through memory at every pixel.
    const float cx = view.cx, cy = view.cy, focal = view.focal;
    Vec3f forward, right, up;
    for (std::size_t a = 0; a < 3; ++a) {
      forward[a] = float(view.forward[a]);
      right[a] = float(view.right[a]);
      up[a] = float(view.up[a]);
    }
    ReconstructionRows rows;
    alignas(64) float sum[3][kRun], weights[kRun], ground[kRun];
    for (int y = r.begin(); y != r.end(); ++y) row_has_holes[std::size_t(y)] = false;
    for (int x0 = 0; x0 < w; x0 += kRun) {
      const int n = std::min(kRun, w - x0);
      rows.lay(k, w, h, r.begin() - 1, x0, n);
      rows.lay(k, w, h, r.begin(), x0, n);
      for (int y = r.begin(); y != r.end(); ++y) {
        rows.lay(k, w, h, y + 1, x0, n);
        rows.weigh(y, n, sum, weights, ground);
        const float ray_up = -(float(y) + 0.5f - cy) / focal;
        const Sample* row = k + std::size_t(y) * std::size_t(w);
        std::uint8_t* out = image.pixels.data() + image.offset(x0, y);
        for (int i = 0; i < n; ++i, out += 3) {
          const Sample& s = row[x0 + i];
          if (is_none(s.depth)) {  // a hole: fill_holes
            row_has_holes[std::size_t(y)] = true;
            continue;
          }
          Vec3f c{s.color[0], s.color[1], s.color[2]};
          if (s.count < 2 && ground[i] > 0) {  // in motion, among samples of surfaces: reconstructed
            const float inverse = 1.0f / weights[i];
            c = {sum[0][i] * inverse, sum[1][i] * inverse, sum[2][i] * inverse};
          } else if (s.source == SampleSource::sky) {  // the sky along the pixel's own ray, as LdiRenderer draws it
            const float ray_right = (float(x0 + i) + 0.5f - cx) / focal;
            Vec3f d;
            for (std::size_t a = 0; a < 3; ++a) d[a] = forward[a] + ray_right * right[a] + ray_up * up[a];
            c = sky_radiance(world.shading(), d);
          }
          out[0] = lut.encode(c[0]);
          out[1] = lut.encode(c[1]);
          out[2] = lut.encode(c[2]);
        }
      }
    }
  });
}

// Holes the budget left are shown as the mean (linear) of the nearest ring of neighbours that
// have a sample, and stay holes: the next frame traces them first. (Kept as samples of their own,
// the farthest neighbour's, they spared later frames the holes but smeared near stems over the
// field: 4.7 dB below the exact image in the walk at 640 x 360, against 3.3 dB.) Returns how many.
std::uint64_t FrameCache::Impl::fill_holes(ImageRgb8& image) const {
  const Sample* const k = kept[current].data();
  const std::uint8_t* const rows_with_holes = row_has_holes.data();
  const Luts& lut = luts();
  const int w = width, h = height;
  std::atomic<std::uint64_t> filled{0};
  tbb::parallel_for(tbb::blocked_range<int>(0, h, 8), [&](const tbb::blocked_range<int>& r) {
    std::uint64_t holes = 0;
    for (int y = r.begin(); y != r.end(); ++y)
      for (int x = 0; rows_with_holes[y] && x < w; ++x) {
        if (!is_none(k[std::size_t(y) * std::size_t(w) + std::size_t(x)].depth)) continue;
        ++holes;
        std::uint8_t* out = image.pixels.data() + image.offset(x, y);
        for (int ring = 1; ring <= 4; ++ring) {
          float sum[3] = {0, 0, 0};
          int n = 0;
          for (int dy = -ring; dy <= ring; ++dy)
            for (int dx = -ring; dx <= ring; ++dx) {
              const int nx = x + dx, ny = y + dy;
              if ((std::abs(dx) != ring && std::abs(dy) != ring) || nx < 0 || ny < 0 || nx >= w || ny >= h ||
                  is_none(k[std::size_t(ny) * std::size_t(w) + std::size_t(nx)].depth))
                continue;
              const std::uint8_t* in = image.pixels.data() + image.offset(nx, ny);
              for (int c = 0; c < 3; ++c) sum[c] += lut.to_linear[in[c]];
              ++n;
            }
          if (n == 0) continue;
          for (int c = 0; c < 3; ++c) out[c] = lut.encode(sum[c] / float(n));
          break;
        }
      }
    filled += holes;
  });
  return filled.load();
}

// ---- the frame ------------------------------------------------------------------------------

FrameCache::FrameCache(LdiRenderer& renderer, const FrameBudget& budget)
    : renderer_(renderer), impl_(std::make_unique<Impl>()) {
  set_budget(budget);
}

FrameCache::~FrameCache() = default;

void FrameCache::set_budget(const FrameBudget& budget) {
  budget.check();
  budget_ = budget;
}

float FrameCache::depth_at(int x, int y) const {
  if (cold_samples_pending_) return renderer_.sky_at(x, y) ? kInf : renderer_.depth_at(x, y);
  return impl_->now()[std::size_t(y) * std::size_t(impl_->width) + std::size_t(x)].depth;
}

SampleSource FrameCache::source_at(int x, int y) const {
  if (cold_samples_pending_) return renderer_.sky_at(x, y) ? SampleSource::sky : cold_source_;
  return impl_->now()[std::size_t(y) * std::size_t(impl_->width) + std::size_t(x)].source;
}

double FrameCache::bytes_per_pixel() const {
  return impl_->pixels() ? double(impl_->bytes()) / double(impl_->pixels()) : 0;
}

std::uint64_t FrameCache::fresh_budget(bool still) const {
  const Impl& m = *impl_;
  double per_pixel = still ? budget_.still_pixel_ns : budget_.pixel_ns;
  double per_sample = still ? budget_.still_sample_ns : budget_.sample_ns;
  // Measured in motion; still, a pixel and a sample cost what the nominal costs say beside them.
  if (budget_.adaptive && m.measured_sample_ns > 0) {
    per_sample = m.measured_sample_ns * (still ? budget_.still_sample_ns / budget_.sample_ns : 1);
    per_pixel = m.measured_pixel_ns * (still ? budget_.still_pixel_ns / budget_.pixel_ns : 1);
  }
  const double frame_ns = 1e9 / budget_.fps - per_pixel * double(m.pixels());
  return std::uint64_t(std::clamp(frame_ns / per_sample, double(m.pixels()) / 256, double(m.pixels())));
}

void FrameCache::draw_cold(const Camera& camera) {
  Impl& m = *impl_;
  const ViewFrameStats& drawn = renderer_.render(camera);
  m.projection = ViewProjection::of(camera, m.width, m.height);
  cold_source_ = drawn.ray_cast ? SampleSource::ray : SampleSource::frame;
  cold_samples_pending_ = true;
  whole_is_cheaper_ = !drawn.ray_cast && drawn.near_tiles == 0;
  std::fill(m.need.begin(), m.need.end(), std::uint8_t(kKeep));
  image_.pixels = renderer_.image().pixels;
  stats_.cold = true;
  stats_.fresh = m.pixels();
  stats_.holes = stats_.filled = 0;
  stats_.budget = m.pixels();
  stats_.trace_ms = drawn.frame_ms;
}

void FrameCache::take_cold_samples() {
  Impl& m = *impl_;
  KeptSamples& k = m.now();
  const Luts& lut = luts();
  const ImageRgb8& frame = renderer_.image();
  const SampleSource source = cold_source_;
  tbb::parallel_for(tbb::blocked_range<int>(0, m.height, 8), [&](const tbb::blocked_range<int>& r) {
    for (int y = r.begin(); y != r.end(); ++y)
      for (int x = 0; x < m.width; ++x) {
        const std::size_t p = std::size_t(y) * std::size_t(m.width) + std::size_t(x);
        const std::uint8_t* rgb = frame.pixels.data() + frame.offset(x, y);
        const bool sky = renderer_.sky_at(x, y);
        k[p].depth = sky ? kInf : renderer_.depth_at(x, y);
        k[p].color = {lut.to_linear[rgb[0]], lut.to_linear[rgb[1]], lut.to_linear[rgb[2]]};
        k[p].sub_x = k[p].sub_y = 0;
        k[p].count = 0;
        k[p].age = 0;
        k[p].source = sky ? SampleSource::sky : source;
      }
  });
  cold_samples_pending_ = false;
}

const CachedFrameStats& FrameCache::render(const Camera& camera) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  Impl& m = *impl_;
  if (m.width != renderer_.width() || m.height != renderer_.height()) {
    m.resize(renderer_.width(), renderer_.height());
    image_ = ImageRgb8(m.width, m.height);
    warm_ = false;
  }
  const ViewProjection view = ViewProjection::of(camera, m.width, m.height);
  const bool still = warm_ && camera.position == previous_.position && camera.target == previous_.target &&
                     camera.fov_degrees == previous_.fov_degrees;
  // Where the whole frame is drawn by LDIs alone (no near field: from above, from afar), it is the
  // cheaper source and the closer to the truth (the flight at 640 x 360: 21.1 ms and 19.1 dB
  // drawn whole, 29.4 ms and 15.8 dB from the cache), so it is drawn whole unless still.
  const bool jump = !warm_ || camera.fov_degrees != previous_.fov_degrees || (!still && whole_is_cheaper_) ||
                    length(view.eye - m.projection.eye) > kJumpMeters ||
                    dot(view.forward, m.projection.forward) < kJumpCosine;
  stats_ = CachedFrameStats{};
  stats_.pixels = m.pixels();
  stats_.still = still;
  ++frame_index_;
  if (jump) {
    draw_cold(camera);
  } else {
    const auto ms_since = [](Clock::time_point from) {
      return std::chrono::duration<double, std::milli>(Clock::now() - from).count();
    };
    auto phase = Clock::now();
    if (cold_samples_pending_) take_cold_samples();
    const EnteringBand band = entering_band(m.projection, view, m.width, m.height);
    if (!still) m.reproject(view);
    stats_.phase_ms[0] = ms_since(phase);
    phase = Clock::now();
    m.projection = view;
    m.classify(frame_index_, still, band);
    const std::array<std::uint64_t, kNeeds> needs = m.count_needs();
    stats_.holes = needs[kHole];
    stats_.stretched = needs[kStretched];
    stats_.probes = needs[kProbe];
    stats_.refresh = needs[kStale] + needs[kRefresh];
    if (!still && double(needs[kHole]) > kColdHoleShare * double(m.pixels())) {
      draw_cold(camera);
    } else {
      const auto hole_cap = std::uint64_t(kMaxHoleShare * double(m.pixels()));
      stats_.budget = std::max(fresh_budget(still), needs[kHole] > hole_cap ? needs[kHole] - hole_cap : 0);
      const std::size_t n = still ? m.select_still(stats_.budget) : m.select(needs, stats_.budget, frame_index_);
      stats_.phase_ms[1] = ms_since(phase);
      phase = Clock::now();
      m.trace(renderer_, n, still);
      stats_.trace_ms = stats_.phase_ms[2] = ms_since(phase);
      phase = Clock::now();
      if (!still) m.drop_hidden(n);
      stats_.fresh = n;
      m.resolve(*renderer_.world(), image_);
      stats_.filled = m.fill_holes(image_);
      stats_.phase_ms[3] = ms_since(phase);
      if (n > 0 && !still) {
        const auto smoothed = [](double& mean, double ns) { mean = mean > 0 ? 0.8 * mean + 0.2 * ns : ns; };
        smoothed(m.measured_sample_ns, stats_.trace_ms * 1e6 / double(n));
        smoothed(m.measured_pixel_ns,
                 (stats_.phase_ms[0] + stats_.phase_ms[1] + stats_.phase_ms[3]) * 1e6 / double(m.pixels()));
      }
    }
  }
  still_frames_ = still ? still_frames_ + 1 : 0;
  stats_.still_frames = still_frames_;
  previous_ = camera;
  warm_ = true;
  stats_.frame_ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
  return stats_;
}

}  // namespace wangscape
