#include "renders/ldi/ldi_build.h"

#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <time.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <mutex>
#include <numbers>
#include <string>
#include <utility>

#include "core/error.h"
#include "core/vecmath.h"
#include "renders/ldi/tile_context.h"
#include "renders/trace/embree_device.h"

namespace wangscape {

namespace {

using V3 = Vector3d;
std::array<float, 3> to_float(const V3& a) { return {float(a[0]), float(a[1]), float(a[2])}; }

constexpr double kPi = std::numbers::pi;

// ---- Embree: the device, one prototype scene per model, one context scene per tile ----------

using Device = EmbreeDevice;

// One recorded hit along a ray.
struct Hit {
  float t, u, v;
  unsigned inst, geom, prim;
};

// The hits of one ray (one lane of a packet). Storage comes from the thread's scratch.
struct HitBuffer {
  Hit* hits = nullptr;
  int count = 0, capacity = 0;
  std::uint64_t recorded = 0, dropped = 0;
};

// Embree passes &base to the filter; the lanes follow it.
struct CollectContext {
  RTCIntersectContext base;
  HitBuffer* lanes;
};

// The multi-hit filter (Embree's next_hit pattern): record the hit, then reject it so that the
// traversal goes on and reports the next one. The ray's id names its lane, which stays right when
// Embree splits a packet into single rays.
void collect_hits(const RTCFilterFunctionNArguments* args) {
  auto* context = reinterpret_cast<const CollectContext*>(args->context);
  const unsigned n = args->N;
  for (unsigned i = 0; i < n; ++i) {
    if (args->valid[i] == 0) continue;
    // A hole of a leaf card's cutout is no hit (the geometry's user pointer: a model with cutouts).
    if (args->geometryUserPtr != nullptr &&
        in_cutout(*static_cast<const Mesh*>(args->geometryUserPtr), RTCHitN_primID(args->hit, n, i),
                  RTCHitN_u(args->hit, n, i), RTCHitN_v(args->hit, n, i))) {
      args->valid[i] = 0;
      continue;
    }
    HitBuffer& b = context->lanes[RTCRayN_id(args->ray, n, i)];
    ++b.recorded;
    if (b.count < b.capacity) {
      // The flower: the instance id, or without instancing the geometry id (one per flower).
      const unsigned geom = RTCHitN_geomID(args->hit, n, i), inst = RTCHitN_instID(args->hit, n, i, 0);
      b.hits[b.count++] = {RTCRayN_tfar(args->ray, n, i),
                           RTCHitN_u(args->hit, n, i),
                           RTCHitN_v(args->hit, n, i),
                           inst == RTC_INVALID_GEOMETRY_ID ? geom : inst,
                           geom,
                           RTCHitN_primID(args->hit, n, i)};
    } else {
      ++b.dropped;
    }
    args->valid[i] = 0;
  }
}

RTCGeometry triangle_geometry(RTCDevice device, std::span<const std::array<float, 3>> positions,
                              std::span<const std::array<std::uint32_t, 3>> triangles) {
  return wangscape::triangle_geometry(device, positions, triangles, &collect_hits);
}

// The flowers of one 3 x 3 context, as structure of arrays indexed by Hit::inst (the Embree
// instance id, or the geometry id when the context is flattened).
struct Instances {
  std::vector<std::uint16_t> variant;
  std::vector<std::uint8_t> plant;  // the depth pixels' plant byte (species and rank; the ground's last)
  std::vector<float> cos_yaw, sin_yaw, scale, x, y;
  unsigned ground_id = 0;  // Hit::inst of the ground quad
};

// ---- the tile set: model extents, contexts --------------------------------------------------

bool fits_east(const Tile& a, const Tile& b) {  // b east of a
  return a.e() == b.w() && a.ne() == b.nw() && a.se() == b.sw();
}
bool fits_north(const Tile& a, const Tile& b) {  // b north of a
  return a.n() == b.s() && a.nw() == b.sw() && a.ne() == b.se();
}

void check_inputs(const FilledTileSet& filled, std::span<const Mesh> models, const LdiBuildOptions& o) {
  auto fail = [](const std::string& what) { throw Error("LDI build: " + what); };
  if (!(o.tile_size > 0)) fail("tile size " + std::to_string(o.tile_size) + " m; expected > 0");
  if (o.view.levels < 1 || o.view.levels > 64) fail("levels " + std::to_string(o.view.levels) + "; expected 1..64");
  if (o.view.directions < 1 || o.view.directions > 64)
    fail("directions " + std::to_string(o.view.directions) + "; expected 1..64");
  if (!(o.view.head_height > 0)) fail("head height " + std::to_string(o.view.head_height) + " m; expected > 0");
  if (o.view.image_width < 16 || !(o.view.fov_degrees > 1 && o.view.fov_degrees < 170))
    fail("view of " + std::to_string(o.view.image_width) + " pixels, " + std::to_string(o.view.fov_degrees) +
         " degrees; expected >= 16 pixels and 1..170 degrees");
  if (o.packet_width != 1 && o.packet_width != 4 && o.packet_width != 8 && o.packet_width != 16)
    fail("packet width " + std::to_string(o.packet_width) + "; expected 1, 4, 8 or 16");
  if (o.max_hits < 1 || o.max_hits > 4096) fail("max hits " + std::to_string(o.max_hits) + "; expected 1..4096");
  if (!(o.merge_pixels >= 0)) fail("merge distance must be >= 0 pixels");
  if (o.shading.ao_rays < 0) fail("sky rays must be >= 0");
  if (filled.tiles.size() != filled.set.tiles.size() || filled.tiles.empty())
    fail("the filled set has " + std::to_string(filled.tiles.size()) + " point lists for " +
         std::to_string(filled.set.tiles.size()) + " tiles");
  for (std::size_t t = 0; t < filled.tiles.size(); ++t)
    for (const TilePoint& p : filled.tiles[t])
      if (p.variant >= models.size())
        fail("tile " + std::to_string(t) + " has a point of variant " + std::to_string(p.variant) + " but only " +
             std::to_string(models.size()) + " models were given");
  for (const Mesh& m : models)
    if (m.triangle_material.size() != m.triangles.size() ||
        (!m.normals.empty() && m.normals.size() != m.positions.size()))
      fail("model '" + m.name + "' has per-triangle materials or normals that do not match its triangles / vertices");
}

// CPU time of the whole process (every thread): what the build costs whatever else runs.
double process_cpu_seconds() {
  timespec t{};
  ::clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

// ---- one LDI's frame --------------------------------------------------------------------------

struct Frame {
  LdiFrame out;
  V3 origin, right, up, forward;
  double pixel = 0;
};

Frame make_frame(const LdiLevels& levels, double tile_size, int level, int direction, int directions) {
  const double az = 360.0 * direction / directions, el = levels.elevations[std::size_t(level)];
  const double a = az * kPi / 180, e = el * kPi / 180;
  Frame f;
  f.forward = {std::sin(a) * std::cos(e), std::cos(a) * std::cos(e), -std::sin(e)};
  f.right = {std::cos(a), -std::sin(a), 0.0};
  f.up = cross(f.right, f.forward);
  f.pixel = tile_size / levels.resolutions[std::size_t(level)];
  // The prism's extent on the image axes and along the rays.
  double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
  for (int c = 0; c < 8; ++c) {
    const V3 p{(c & 1) ? tile_size : 0.0, (c & 2) ? tile_size : 0.0, (c & 4) ? levels.prism_top : kLdiPrismBottom};
    const double q[3] = {dot(p, f.right), dot(p, f.up), dot(p, f.forward)};
    for (int k = 0; k < 3; ++k) lo[k] = std::min(lo[k], q[k]), hi[k] = std::max(hi[k], q[k]);
  }
  // ceil, but forgiving the rounding of an extent that is a whole number of pixels.
  const auto pixels = [&](double extent) { return std::max(1, int(std::ceil(extent / f.pixel - 1e-6))); };
  const int w = pixels(hi[0] - lo[0]), h = pixels(hi[1] - lo[1]);
  const double left = (lo[0] + hi[0]) / 2 - w * f.pixel / 2, top = (lo[1] + hi[1]) / 2 + h * f.pixel / 2;
  f.origin = left * f.right + top * f.up + lo[2] * f.forward;
  f.out.width = std::uint32_t(w);
  f.out.height = std::uint32_t(h);
  f.out.level = std::uint32_t(level);
  f.out.direction = std::uint32_t(direction);
  f.out.origin = to_float(f.origin);
  f.out.right = to_float(f.right);
  f.out.up = to_float(f.up);
  f.out.forward = to_float(f.forward);
  f.out.pixel_size = float(f.pixel);
  f.out.depth_range = float(hi[2] - lo[2]);
  f.out.azimuth_degrees = float(az);
  f.out.elevation_degrees = float(el);
  return f;
}

// ---- sampling ---------------------------------------------------------------------------------

// Everything a tile's LDIs share: the context scene and what shading needs to read back.
struct TileContext {
  const FilledTileSet& filled;
  std::span<const Mesh> models;
  const LdiBuildOptions& options;
  const LdiLevels& levels;
  std::size_t tile;
  RTCScene scene;
  const Instances& instances;
};

struct Counters {
  std::uint64_t primary = 0, secondary = 0, hits = 0, duplicate = 0, outside = 0, merged = 0, dropped = 0,
                depth_pixels = 0;
  double sampling_seconds = 0;      // wall clock inside the LDIs' parallel loops (no scene builds)
  double sampling_cpu_seconds = 0;  // CPU time of this process (all threads) in those loops
  void add(const Counters& o) {
    primary += o.primary, secondary += o.secondary, hits += o.hits, duplicate += o.duplicate;
    outside += o.outside, merged += o.merged, dropped += o.dropped, depth_pixels += o.depth_pixels;
  }
};

// A row's output before the rows are joined (spans' first_pixel / first_depth are row-relative).
struct RowOut {
  std::vector<LdiSpan> spans;
  std::vector<std::uint8_t> counts;
  std::vector<DepthPixel> depth_pixels;
};

constexpr int kMaxLanes = 16;
// Empty runs up to this long stay inside a span as zero counts (1 byte each, a span is 12).
constexpr int kMaxSpanGap = int(sizeof(LdiSpan)) - 1;

// Per-thread scratch, allocated once per thread and reused by every ray it traces.
struct Scratch {
  std::vector<Hit> storage;
  std::array<HitBuffer, kMaxLanes> lanes;
  std::vector<int> kept;
  explicit Scratch(int max_hits) : storage(std::size_t(max_hits) * kMaxLanes), kept(std::size_t(max_hits)) {
    for (int l = 0; l < kMaxLanes; ++l) {
      lanes[std::size_t(l)].hits = storage.data() + std::size_t(l) * std::size_t(max_hits);
      lanes[std::size_t(l)].capacity = max_hits;
    }
  }
};

// A ray of the LDI and its interval inside the prism.
struct PixelRay {
  std::array<float, 3> org;
  float t0 = 0, t1 = -1;  // empty when t1 < t0
  std::uint64_t random = 0;
};

class LdiSampler {
 public:
  LdiSampler(const TileContext& c, const Frame& f, std::uint64_t ldi_key)
      : c_(c),
        f_(f),
        key_(ldi_key),
        merge_(float(c.options.merge_pixels * f.pixel)),
        s_(float(c.options.tile_size)),
        top_(float(c.levels.prism_top)),
        dedupe_(std::max(1e-5f * s_, merge_)) {
    forward_ = to_float(f.forward);
  }

  PixelRay ray(int x, int y) const {
    PixelRay r;
    r.random = mix64(key_ ^ (std::uint64_t(std::uint32_t(y)) << 32 | std::uint32_t(x)));
    const double jx = unit_float(r.random), jy = unit_float(mix64(r.random));
    const V3 o = f_.origin + ((x + jx) * f_.pixel) * f_.right - ((y + jy) * f_.pixel) * f_.up;
    r.org = to_float(o);
    // Slab clip against the prism [0, s] x [0, s] x [bottom, top].
    double t0 = 0, t1 = 1e30;
    const double lo[3] = {0, 0, kLdiPrismBottom}, hi[3] = {double(s_), double(s_), double(top_)};
    for (int k = 0; k < 3; ++k) {
      const double d = f_.forward[std::size_t(k)];
      if (std::abs(d) < 1e-12) {
        if (o[std::size_t(k)] < lo[k] || o[std::size_t(k)] > hi[k]) return r;
        continue;
      }
      double a = (lo[k] - o[std::size_t(k)]) / d, b = (hi[k] - o[std::size_t(k)]) / d;
      if (a > b) std::swap(a, b);
      t0 = std::max(t0, a);
      t1 = std::min(t1, b);
    }
    if (t1 < t0) return r;
    // A little slack so that surfaces on the prism's faces are met; the inside test decides.
    const double slack = 1e-4 * s_;
    r.t0 = float(std::max(0.0, t0 - slack));
    r.t1 = float(t1 + slack);
    return r;
  }

  static void fill_embree_ray(RTCRay& ray, const PixelRay& p, const std::array<float, 3>& dir, unsigned id) {
    ray.org_x = p.org[0], ray.org_y = p.org[1], ray.org_z = p.org[2];
    ray.dir_x = dir[0], ray.dir_y = dir[1], ray.dir_z = dir[2];
    ray.tnear = p.t0, ray.tfar = p.t1;
    ray.time = 0, ray.mask = 0xffffffffu, ray.id = id, ray.flags = 0;
  }

  // Traces the row's rays, `width` at a time, and appends the pixels to `out`.
  template <int N>
  void trace_row(int y, Scratch& scratch, RowOut& out, Counters& counters) const {
    const int w = int(f_.out.width);
    CollectContext context;
    rtcInitIntersectContext(&context.base);
    context.base.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    context.lanes = scratch.lanes.data();
    std::array<PixelRay, N> rays;
    for (int x0 = 0; x0 < w; x0 += N) {
      const int lanes = std::min(N, w - x0);
      int live = 0;
      for (int l = 0; l < lanes; ++l) {
        rays[std::size_t(l)] = ray(x0 + l, y);
        scratch.lanes[std::size_t(l)].count = 0;
        if (rays[std::size_t(l)].t1 >= rays[std::size_t(l)].t0) ++live;
      }
      if (live > 0) {
        if constexpr (N == 1) {
          RTCRayHit rh{};
          fill_embree_ray(rh.ray, rays[0], forward_, 0);
          rh.hit.geomID = rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
          rtcIntersect1(c_.scene, &context.base, &rh);
        } else {
          trace_packet<N>(rays, lanes, context);
        }
      }
      for (int l = 0; l < lanes; ++l) {
        if (rays[std::size_t(l)].t1 < rays[std::size_t(l)].t0) continue;
        ++counters.primary;
        finish_pixel(x0 + l, rays[std::size_t(l)], scratch.lanes[std::size_t(l)], scratch, out, counters);
      }
    }
  }

 private:
  template <int N>
  void trace_packet(const std::array<PixelRay, N>& rays, int lanes, CollectContext& context) const {
    using RayHitN = std::conditional_t<N == 4, RTCRayHit4, std::conditional_t<N == 8, RTCRayHit8, RTCRayHit16>>;
    alignas(64) RayHitN rh{};
    alignas(64) int valid[N];
    for (int l = 0; l < N; ++l) {
      const bool ok = l < lanes && rays[std::size_t(l)].t1 >= rays[std::size_t(l)].t0;
      valid[l] = ok ? -1 : 0;
      if (!ok) continue;
      const PixelRay& p = rays[std::size_t(l)];
      rh.ray.org_x[l] = p.org[0], rh.ray.org_y[l] = p.org[1], rh.ray.org_z[l] = p.org[2];
      rh.ray.dir_x[l] = forward_[0], rh.ray.dir_y[l] = forward_[1], rh.ray.dir_z[l] = forward_[2];
      rh.ray.tnear[l] = p.t0, rh.ray.tfar[l] = p.t1;
      rh.ray.mask[l] = 0xffffffffu, rh.ray.id[l] = unsigned(l);
      rh.hit.geomID[l] = RTC_INVALID_GEOMETRY_ID;
    }
    if constexpr (N == 4) rtcIntersect4(valid, c_.scene, &context.base, &rh);
    if constexpr (N == 8) rtcIntersect8(valid, c_.scene, &context.base, &rh);
    if constexpr (N == 16) rtcIntersect16(valid, c_.scene, &context.base, &rh);
  }

  bool inside(const std::array<float, 3>& p) const {
    const float e = 1e-4f * s_;
    return p[0] >= -e && p[0] <= s_ + e && p[1] >= -e && p[1] <= s_ + e && p[2] >= kLdiPrismBottom - e &&
           p[2] <= top_ + e;
  }

  // De-duplicates, drops hits outside the prism, merges close ones, shades the rest.
  void finish_pixel(int x, const PixelRay& ray, HitBuffer& b, Scratch& scratch, RowOut& out, Counters& k) const {
    k.hits += b.recorded;
    k.dropped += b.dropped;
    b.recorded = b.dropped = 0;
    Hit* hits = b.hits;
    const int n = b.count;
    // Insertion sort by t: a handful of hits per ray.
    for (int i = 1; i < n; ++i) {
      const Hit h = hits[i];
      int j = i - 1;
      while (j >= 0 && hits[j].t > h.t) hits[j + 1] = hits[j], --j;
      hits[j + 1] = h;
    }
    const unsigned ground = c_.instances.ground_id;
    int kept = 0;
    bool flower_before = false;
    float last_t = -std::numeric_limits<float>::infinity();
    for (int i = 0; i < n; ++i) {
      const Hit& h = hits[i];
      // Embree may report a triangle twice (spatial splits): same ids at the same distance.
      bool duplicate = false;
      for (int j = i - 1; j >= 0 && !duplicate && hits[j].t >= h.t - dedupe_; --j)
        duplicate = hits[j].inst == h.inst && hits[j].geom == h.geom && hits[j].prim == h.prim;
      if (duplicate) {
        ++k.duplicate;
        continue;
      }
      const std::array<float, 3> p{ray.org[0] + h.t * forward_[0], ray.org[1] + h.t * forward_[1],
                                   ray.org[2] + h.t * forward_[2]};
      if (!inside(p)) {
        ++k.outside;
        continue;
      }
      const bool is_ground = h.inst == ground;
      if (is_ground &&
          (c_.options.ground == LdiGround::none || (c_.options.ground == LdiGround::visible && flower_before)))
        continue;
      if (h.t - last_t < merge_) {
        ++k.merged;
        continue;
      }
      if (kept == 255) break;  // a pixel's layer count is one byte
      scratch.kept[std::size_t(kept++)] = i;
      last_t = h.t;
      flower_before = flower_before || !is_ground;
    }
    if (kept == 0) return;

    // A gap shorter than a span record is cheaper stored as empty pixels inside the span.
    const int gap = out.spans.empty() ? kMaxSpanGap + 1 : x - int(out.spans.back().x) - int(out.spans.back().length);
    if (gap > kMaxSpanGap) {
      out.spans.push_back(
          {std::uint16_t(x), 0, std::uint32_t(out.counts.size()), std::uint32_t(out.depth_pixels.size())});
    } else {
      out.counts.insert(out.counts.end(), std::size_t(gap), std::uint8_t{0});
      out.spans.back().length = std::uint16_t(out.spans.back().length + gap);
    }
    ++out.spans.back().length;
    out.counts.push_back(std::uint8_t(kept));
    const float depth_scale = 65535.0f / f_.out.depth_range;
    for (int j = 0; j < kept; ++j) {
      const Hit& h = hits[scratch.kept[std::size_t(j)]];
      SurfaceSample s;
      s.position = {ray.org[0] + h.t * forward_[0], ray.org[1] + h.t * forward_[1], ray.org[2] + h.t * forward_[2]};
      if (h.inst == c_.instances.ground_id) {
        s.normal = {0, 0, 1};
        s.base_color = c_.options.shading.ground_color;
      } else {
        surface(h, s);
      }
      // Two-sided: turn the normal towards the viewer.
      if (s.normal[0] * forward_[0] + s.normal[1] * forward_[1] + s.normal[2] * forward_[2] > 0)
        for (float& v : s.normal) v = -v;
      int rays = 0;
      const Vec3f color = shade(c_.scene, c_.options.shading, s, mix64(ray.random + std::uint64_t(j) + 1), &rays);
      k.secondary += std::uint64_t(rays);
      const auto rgb = to_srgb8(color);
      const float d = std::clamp(h.t * depth_scale, 0.0f, 65535.0f);
      out.depth_pixels.push_back(DepthPixel::make(rgb[0], rgb[1], rgb[2], std::uint16_t(std::lround(d)),
                                                  encode_octahedral(s.normal), c_.instances.plant[h.inst]));
    }
    k.depth_pixels += std::uint64_t(kept);
  }

  // Normal (smooth where the model has normals) and material of a model hit.
  void surface(const Hit& h, SurfaceSample& s) const {
    const Instances& in = c_.instances;
    model_surface(c_.models[in.variant[h.inst]], h.prim, h.u, h.v, in.cos_yaw[h.inst], in.sin_yaw[h.inst], s);
  }

  const TileContext& c_;
  const Frame& f_;
  std::uint64_t key_;
  float merge_, s_, top_, dedupe_;
  std::array<float, 3> forward_{};
};

LdiImage sample_ldi(const TileContext& c, int level, int direction, tbb::enumerable_thread_specific<Scratch>& scratch,
                    Counters& total, std::mutex& total_mutex) {
  const Frame f = make_frame(c.levels, c.options.tile_size, level, direction, c.options.view.directions);
  const std::uint64_t key = mix64(mix64(mix64(c.options.seed) ^ std::uint64_t(c.tile)) ^
                                  (std::uint64_t(level) << 16 | std::uint64_t(direction)));
  const LdiSampler sampler(c, f, key);
  const int h = int(f.out.height);
  std::vector<RowOut> rows(static_cast<std::size_t>(h));
  tbb::parallel_for(tbb::blocked_range<int>(0, h), [&](const tbb::blocked_range<int>& range) {
    Scratch& s = scratch.local();
    Counters counters;
    for (int y = range.begin(); y != range.end(); ++y) {
      RowOut& row = rows[std::size_t(y)];
      // Room for a typical row up front (measured: under 1.4 layers per pixel), so that the
      // per-ray loop seldom grows a vector.
      const auto w = std::size_t(f.out.width);
      row.spans.reserve(w / 8 + 1);
      row.counts.reserve(w);
      row.depth_pixels.reserve(2 * w);
      switch (c.options.packet_width) {
        case 4:
          sampler.trace_row<4>(y, s, row, counters);
          break;
        case 8:
          sampler.trace_row<8>(y, s, row, counters);
          break;
        case 16:
          sampler.trace_row<16>(y, s, row, counters);
          break;
        default:
          sampler.trace_row<1>(y, s, row, counters);
          break;
      }
    }
    std::lock_guard lock(total_mutex);
    total.add(counters);
  });
  // Join the rows in order: the same bytes whatever thread did which row.
  LdiImage ldi;
  ldi.frame = f.out;
  ldi.frame.tile = std::uint32_t(c.tile);
  ldi.row_spans.reserve(std::size_t(h) + 1);
  ldi.row_spans.push_back(0);
  for (RowOut& row : rows) {
    const auto pixel0 = std::uint32_t(ldi.counts.size()), depth0 = std::uint32_t(ldi.depth_pixels.size());
    for (LdiSpan s : row.spans) {
      s.first_pixel += pixel0;
      s.first_depth += depth0;
      ldi.spans.push_back(s);
    }
    ldi.counts.insert(ldi.counts.end(), row.counts.begin(), row.counts.end());
    ldi.depth_pixels.insert(ldi.depth_pixels.end(), row.depth_pixels.begin(), row.depth_pixels.end());
    ldi.row_spans.push_back(std::uint32_t(ldi.spans.size()));
    row = RowOut{};
  }
  ldi.frame.span_count = std::uint32_t(ldi.spans.size());
  ldi.frame.pixel_count = std::uint32_t(ldi.counts.size());
  ldi.frame.depth_pixel_count = std::uint32_t(ldi.depth_pixels.size());
  return ldi;
}

// The models as Embree prototype scenes (built once, instanced by every context).
std::vector<EmbreeScene> prototype_scenes(Device& device, std::span<const Mesh> models) {
  return model_scenes(device, models, &collect_hits);
}

// The 3 x 3 context of `tile` as one Embree scene: per point an instance of its model's scene, or
// (flattened) its own copy of the model's triangles; the ground quad last.
EmbreeScene context_scene(Device& device, const FilledTileSet& filled, std::span<const Mesh> models,
                          std::span<const EmbreeScene> prototypes, const std::array<std::uint16_t, 9>& context,
                          const LdiBuildOptions& options, Instances& out) {
  const double tile_size = options.tile_size;
  EmbreeScene scene(device.get());
  std::vector<std::array<float, 3>> moved;
  out = Instances{};
  unsigned id = 0;
  for (int block = 0; block < 9; ++block) {
    const double ox = (block % 3 - 1) * tile_size, oy = (block / 3 - 1) * tile_size;
    for (const TilePoint& p : filled.tiles[context[std::size_t(block)]]) {
      const float c = std::cos(p.yaw), s = std::sin(p.yaw);
      const float x = float(ox + p.x * tile_size), y = float(oy + p.y * tile_size);
      // Column-major 3 x 4: rotation about z by yaw, uniform scale, translation.
      const float xfm[12] = {c * p.scale, s * p.scale, 0, -s * p.scale, c * p.scale, 0, 0, 0, p.scale, x, y, 0};
      const Mesh& mesh = models[p.variant];
      RTCGeometry g = nullptr;
      if (options.instancing) {
        g = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_INSTANCE);
        rtcSetGeometryInstancedScene(g, prototypes[p.variant].get());
        rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xfm);
        rtcCommitGeometry(g);
      } else if (!mesh.triangles.empty()) {
        moved.resize(mesh.positions.size());
        for (std::size_t v = 0; v < moved.size(); ++v) {
          const auto& q = mesh.positions[v];
          moved[v] = {xfm[0] * q[0] + xfm[3] * q[1] + xfm[9], xfm[1] * q[0] + xfm[4] * q[1] + xfm[10], xfm[8] * q[2]};
        }
        g = triangle_geometry(device.get(), moved, mesh.triangles);
        add_cutouts(g, mesh, false);  // collect_hits skips the holes itself
      }
      if (g) {
        rtcAttachGeometryByID(scene.get(), g, id);
        rtcReleaseGeometry(g);
      }
      ++id;
      out.variant.push_back(p.variant);
      out.plant.push_back(plant_byte(p.species, p.rank));
      out.cos_yaw.push_back(c);
      out.sin_yaw.push_back(s);
      out.scale.push_back(p.scale);
      out.x.push_back(x);
      out.y.push_back(y);
    }
  }
  // The ground under the whole context (z = 0).
  const float lo = float(-tile_size), hi = float(2 * tile_size);
  const std::array<std::array<float, 3>, 4> corners{{{lo, lo, 0}, {hi, lo, 0}, {hi, hi, 0}, {lo, hi, 0}}};
  const std::array<std::array<std::uint32_t, 3>, 2> triangles{{{0, 1, 2}, {0, 2, 3}}};
  RTCGeometry g = triangle_geometry(device.get(), corners, triangles);
  out.ground_id = id;
  out.plant.push_back(kAnyPlant);  // (indexed by Hit::inst like the flowers')
  rtcAttachGeometryByID(scene.get(), g, id);
  rtcReleaseGeometry(g);
  rtcCommitScene(scene.get());
  device.check("building a tile's context scene");
  return scene;
}

// The 3 x 3 context tile `tile` is sampled in (options.context_choice).
std::array<std::uint16_t, 9> chosen_context(const FilledTileSet& filled, const LdiBuildOptions& options,
                                            std::size_t tile) {
  const auto contexts = consistent_contexts(filled.set, tile, std::size_t(std::max(0, options.context_choice)) + 1);
  if (contexts.empty())
    throw Error("LDI build: tile " + std::to_string(tile) + " of " + filled.set.describe() +
                " has no 3 x 3 neighbourhood whose edges all match");
  return contexts[std::size_t(std::max(0, options.context_choice)) % contexts.size()];
}

// Builds every LDI of `tile` into `out` (levels x directions, level-major).
void build_tile(Device& device, std::span<const EmbreeScene> prototypes, const FilledTileSet& filled,
                std::span<const Mesh> models, const LdiBuildOptions& options, const LdiLevels& levels, std::size_t tile,
                std::vector<LdiImage>& out, Counters& counters, std::mutex& counters_mutex,
                const std::function<void()>& ldi_done) {
  Instances instances;
  const EmbreeScene scene =
      context_scene(device, filled, models, prototypes, chosen_context(filled, options, tile), options, instances);
  const TileContext c{filled, models, options, levels, tile, scene.get(), instances};
  tbb::enumerable_thread_specific<Scratch> scratch([&] { return Scratch(options.max_hits); });
  const int L = options.view.levels, D = options.view.directions;
  out.assign(std::size_t(L * D), LdiImage{});
  const auto start = std::chrono::steady_clock::now();
  const double cpu_start = process_cpu_seconds();
  tbb::parallel_for(0, L * D, [&](int i) {
    out[std::size_t(i)] = sample_ldi(c, i / D, i % D, scratch, counters, counters_mutex);
    if (ldi_done) ldi_done();
  });
  device.check("sampling tile " + std::to_string(tile));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const double cpu = process_cpu_seconds() - cpu_start;
  std::lock_guard lock(counters_mutex);
  counters.sampling_seconds += seconds;
  counters.sampling_cpu_seconds += cpu;
}

void fill_report(LdiBuildReport* report, const Counters& k, std::uint64_t ldis,
                 std::chrono::steady_clock::time_point start) {
  if (!report) return;
  report->ldis = ldis;
  report->primary_rays = k.primary;
  report->secondary_rays = k.secondary;
  report->hits = k.hits;
  report->duplicate_hits = k.duplicate;
  report->outside_hits = k.outside;
  report->merged_hits = k.merged;
  report->dropped_hits = k.dropped;
  report->depth_pixels = k.depth_pixels;
  report->sampling_seconds = k.sampling_seconds;
  report->sampling_cpu_seconds = k.sampling_cpu_seconds;
  report->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

// ---- public ---------------------------------------------------------------------------------

LdiLevels ldi_levels(const LdiViewSettings& view, double tile_size, double prism_top) {
  LdiLevels out;
  out.prism_top = prism_top;
  const V3 eye{0, 0, view.head_height};
  const double focal = view.image_width / 2.0 / std::tan(view.fov_degrees * kPi / 360);
  for (int k = 1; k <= view.levels; ++k) {
    const double near = k * tile_size;
    const V3 target{0, near + tile_size / 2, prism_top};
    const CameraBasis basis = *camera_basis(eye, target);  // the target is ahead, never straight down
    const V3 &f = basis.forward, &r = basis.right, &u = basis.up;
    double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
    for (int c = 0; c < 4; ++c) {
      const V3 q = V3{(c & 1) ? tile_size / 2 : -tile_size / 2, (c & 2) ? near + tile_size : near, prism_top} - eye;
      const double z = dot(q, f);
      if (!(z > 1e-9)) throw Error("LDI build: a tile corner is behind the viewer at level " + std::to_string(k));
      const double x = focal * dot(q, r) / z, y = focal * dot(q, u) / z;
      x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    }
    out.resolutions.push_back(std::uint32_t(std::max(1.0, std::ceil(std::max(x1 - x0, y1 - y0) - 1e-9))));
    out.distances.push_back(near);
    out.elevations.push_back(std::atan2(view.head_height, near + tile_size / 2) * 180 / kPi);
  }
  return out;
}

std::vector<std::array<std::uint16_t, 9>> consistent_contexts(const TileSet& set, std::size_t tile, std::size_t limit) {
  std::vector<std::array<std::uint16_t, 9>> found;
  if (tile >= set.tiles.size() || limit == 0) return found;
  const TileAdjacency adjacency(set);
  // Cells in the order they are chosen (edge neighbours first, from TileAdjacency's lists); each is
  // checked against the chosen cells beside it (block = (dy + 1) * 3 + (dx + 1): west = block - 1,
  // south = block - 3).
  constexpr int order[8] = {1, 3, 5, 7, 0, 2, 6, 8};
  std::array<std::uint16_t, 9> cells{};
  std::array<bool, 9> chosen{};
  cells[4] = std::uint16_t(tile);
  chosen[4] = true;
  const auto at = [&](int block) -> const Tile& { return set.tiles[cells[std::size_t(block)]]; };
  const auto fits = [&](int block) {
    const int bx = block % 3, by = block / 3;
    const Tile& t = at(block);
    if (bx > 0 && chosen[std::size_t(block - 1)] && !fits_east(at(block - 1), t)) return false;
    if (bx < 2 && chosen[std::size_t(block + 1)] && !fits_east(t, at(block + 1))) return false;
    if (by > 0 && chosen[std::size_t(block - 3)] && !fits_north(at(block - 3), t)) return false;
    if (by < 2 && chosen[std::size_t(block + 3)] && !fits_north(t, at(block + 3))) return false;
    return true;
  };
  const std::function<void(int)> choose = [&](int step) {
    if (found.size() >= limit) return;
    if (step == 8) {
      found.push_back(cells);
      return;
    }
    const int block = order[step];
    for (std::uint16_t candidate : adjacency.neighbours(tile, block % 3 - 1, block / 3 - 1)) {
      cells[std::size_t(block)] = candidate;
      chosen[std::size_t(block)] = true;
      if (fits(block)) choose(step + 1);
      chosen[std::size_t(block)] = false;
      if (found.size() >= limit) return;
    }
  };
  choose(0);
  return found;
}

double ldi_prism_top(const FilledTileSet& filled, std::span<const Mesh> models) {
  std::vector<float> heights;
  for (const Mesh& m : models) heights.push_back(measure_extent(m).max[2]);
  double top = 0;
  for (const auto& points : filled.tiles)
    for (const TilePoint& p : points)
      if (p.variant < heights.size()) top = std::max(top, double(heights[p.variant]) * p.scale);
  return std::max(top + 0.01, 0.05);
}

LdiPackInfo ldi_pack_info(const FilledTileSet& filled, std::span<const Mesh> models, const LdiBuildOptions& options) {
  check_inputs(filled, models, options);
  const LdiLevels levels = ldi_levels(options.view, options.tile_size, ldi_prism_top(filled, models));
  LdiPackInfo info;
  info.tiles = std::uint32_t(filled.tiles.size());
  info.levels = std::uint32_t(options.view.levels);
  info.directions = std::uint32_t(options.view.directions);
  info.tile_size = float(options.tile_size);
  info.head_height = float(options.view.head_height);
  info.prism_top = float(levels.prism_top);
  info.image_width = std::uint32_t(options.view.image_width);
  info.fov_degrees = float(options.view.fov_degrees);
  info.resolutions = levels.resolutions;
  for (double d : levels.distances) info.level_distances.push_back(float(d));
  for (double e : levels.elevations) info.elevations.push_back(float(e));
  for (int d = 0; d < options.view.directions; ++d) info.azimuths.push_back(float(360.0 * d / options.view.directions));
  return info;
}

namespace {
// One tile's LDIs at `levels` (null: the view's own), with its own Embree device.
std::vector<LdiImage> build_one_tile(const FilledTileSet& filled, std::span<const Mesh> models,
                                     const LdiBuildOptions& options, std::size_t tile, const LdiLevels* levels,
                                     LdiBuildReport* report) {
  const auto start = std::chrono::steady_clock::now();
  check_inputs(filled, models, options);
  if (tile >= filled.tiles.size())
    throw Error("LDI build: no tile " + std::to_string(tile) + " in " + filled.set.describe());
  const LdiLevels own =
      levels ? LdiLevels{} : ldi_levels(options.view, options.tile_size, ldi_prism_top(filled, models));
  Device device;
  const std::vector<EmbreeScene> prototypes = prototype_scenes(device, models);
  std::vector<LdiImage> out;
  Counters counters;
  std::mutex mutex;
  build_tile(device, prototypes, filled, models, options, levels ? *levels : own, tile, out, counters, mutex, {});
  fill_report(report, counters, out.size(), start);
  return out;
}
}  // namespace

EmbreeScene tile_context_scene(EmbreeDevice& device, std::span<const EmbreeScene> occluders,
                               const FilledTileSet& filled, std::span<const Mesh> models,
                               const LdiBuildOptions& options, std::size_t tile) {
  check_inputs(filled, models, options);
  if (tile >= filled.tiles.size())
    throw Error("LDI build: no tile " + std::to_string(tile) + " in " + filled.set.describe());
  if (occluders.size() != models.size()) throw Error("LDI build: one occluder scene per model expected");
  LdiBuildOptions instanced = options;
  instanced.instancing = true;
  Instances instances;
  return context_scene(device, filled, models, occluders, chosen_context(filled, options, tile), instanced, instances);
}

std::vector<LdiImage> build_tile_ldis(const FilledTileSet& filled, std::span<const Mesh> models,
                                      const LdiBuildOptions& options, std::size_t tile, LdiBuildReport* report) {
  return build_one_tile(filled, models, options, tile, nullptr, report);
}

std::vector<LdiImage> build_tile_ldis(const FilledTileSet& filled, std::span<const Mesh> models,
                                      LdiBuildOptions options, std::size_t tile, const LdiLevels& levels) {
  if (levels.elevations.size() != levels.resolutions.size() || levels.distances.size() != levels.resolutions.size())
    throw Error("LDI build: the levels' resolutions, distances and elevations differ in number");
  options.view.levels = int(levels.resolutions.size());
  return build_one_tile(filled, models, options, tile, &levels, nullptr);
}

LdiBuildReport build_ldi_pack(const FilledTileSet& filled, std::span<const Mesh> models, const LdiBuildOptions& options,
                              const std::filesystem::path& path) {
  return build_ldi_pack(filled, models, options,
                        ldi_levels(options.view, options.tile_size, ldi_prism_top(filled, models)),
                        ldi_pack_info(filled, models, options), path);
}

LdiBuildReport build_ldi_pack(const FilledTileSet& filled, std::span<const Mesh> models, LdiBuildOptions options,
                              const LdiLevels& levels, const LdiPackInfo& info, const std::filesystem::path& path) {
  const auto start = std::chrono::steady_clock::now();
  if (levels.resolutions.size() != info.levels || levels.elevations.size() != info.levels ||
      levels.distances.size() != info.levels || int(info.directions) != options.view.directions ||
      info.tiles != filled.tiles.size())
    throw Error(path, "", "LDI build: the pack's header does not describe the levels, directions and tiles built");
  options.view.levels = int(levels.resolutions.size());
  check_inputs(filled, models, options);
  Device device;
  const std::vector<EmbreeScene> prototypes = prototype_scenes(device, models);
  LdiPackWriter writer(path, info);
  Counters counters;
  std::mutex mutex;
  const std::uint64_t total = std::uint64_t(info.tiles) * info.levels * info.directions;
  std::atomic<std::uint64_t> done{0};
  std::mutex progress_mutex;
  const std::function<void()> ldi_done = [&] {
    const std::uint64_t d = ++done;
    if (!options.progress) return;
    std::uint64_t rays = 0;
    {
      std::lock_guard lock(mutex);
      rays = counters.primary + counters.secondary;
    }
    std::lock_guard lock(progress_mutex);
    options.progress(d, total, rays);
  };
  // Tile by tile (each tile's LDIs in parallel), written in index order: the bytes do not depend
  // on the thread count, and only one tile's LDIs are held at a time.
  std::vector<LdiImage> ldis;
  for (std::size_t t = 0; t < filled.tiles.size(); ++t) {
    build_tile(device, prototypes, filled, models, options, levels, t, ldis, counters, mutex, ldi_done);
    for (const LdiImage& ldi : ldis) writer.add(ldi);
  }
  writer.commit();
  LdiBuildReport report;
  fill_report(&report, counters, total, start);
  return report;
}

}  // namespace wangscape
