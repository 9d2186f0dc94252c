#include "renders/trace/embree_reference.h"

#include <embree3/rtcore.h>
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <mutex>
#include <numbers>
#include <optional>
#include <string>

#include "core/error.h"
#include "core/vecmath.h"
#include "renders/trace/embree_device.h"
#include "renders/trace/ground_colors.h"
#include "renders/trace/scene_tracer.h"

namespace wangscape {

namespace {

using V3 = std::array<double, 3>;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

constexpr int kTile = 16;  // pixels: the unit of parallel work
void check_options(const Scene& scene, int width, int height, int spp) {
  const auto fail = [](const std::string& what) { throw Error("reference render: " + what); };
  if (width < 1 || height < 1 || width > kMaxReferenceSide || height > kMaxReferenceSide)
    fail("image " + std::to_string(width) + " x " + std::to_string(height) + " pixels; expected 1.." +
         std::to_string(kMaxReferenceSide) + " on each side");
  if (std::uint64_t(width) * std::uint64_t(height) > kMaxReferencePixels)
    fail("image " + std::to_string(width) + " x " + std::to_string(height) + " pixels; expected at most " +
         std::to_string(kMaxReferencePixels) + " pixels");
  if (spp < 1 || spp > kMaxReferenceSamples)
    fail(std::to_string(spp) + " samples per pixel; expected 1.." + std::to_string(kMaxReferenceSamples));
  for (const Mesh& m : scene.models)
    if (m.triangle_material.size() != m.triangles.size() ||
        (!m.normals.empty() && m.normals.size() != m.positions.size()))
      fail("model '" + m.name + "' has per-triangle materials or normals that do not match its triangles / vertices");
  if (!scene.terrain.normals.empty() && scene.terrain.normals.size() != scene.terrain.positions.size())
    fail("the terrain mesh has " + std::to_string(scene.terrain.normals.size()) + " normals for " +
         std::to_string(scene.terrain.positions.size()) + " vertices");
}

// What one tile of pixels needs.
struct Tracer {
  const SceneTracer& traced;
  const ShadingSettings& shading;
  const GroundColors& ground;
  CameraFrame frame;  // origin relative to traced.origin
  int width, height, spp, grid;
  std::uint64_t seed;

  struct Pixel {
    Vec3f color{};
    float coverage = 0, depth = std::numeric_limits<float>::infinity();
    std::uint64_t secondary = 0;
  };

  Pixel trace(int px, int py) const {
    Pixel out;
    const std::uint64_t pixel_key = mix64(seed ^ (std::uint64_t(std::uint32_t(py)) << 32 | std::uint32_t(px)));
    int hits = 0;
    for (int k = 0; k < spp; ++k) {
      const std::uint64_t h = mix64(pixel_key + std::uint64_t(k) * 0x9e3779b97f4a7c15ull);
      // Stratified: one jittered sample per cell of a grid x grid lattice over the pixel; a single
      // sample looks through the pixel's centre.
      float sx = 0.5f, sy = 0.5f;
      if (spp > 1) {
        sx = (float(k % grid) + unit_float(h)) / float(grid);
        sy = (float(k / grid) + unit_float(mix64(h))) / float(grid);
      }
      const double nx = 2.0 * (px + sx) / width - 1.0, ny = 1.0 - 2.0 * (py + sy) / height;
      V3 d{};
      for (std::size_t c = 0; c < 3; ++c) d[c] = frame.forward[c] + nx * frame.right[c] + ny * frame.up[c];
      d = normalized(d);
      Vec3f color{};
      if (const auto hit = traced.intersect(frame.origin, d)) {
        ++hits;
        out.depth = std::min(out.depth, hit->t);
        int rays = 0;
        color = shade(traced.scene(), shading, traced.surface(*hit, frame.origin, d, ground),
                      mix64(h ^ 0x5851f42d4c957f2dull), &rays);
        out.secondary += std::uint64_t(rays);
      } else {
        color = sky_radiance(shading, {float(d[0]), float(d[1]), float(d[2])});
      }
      for (std::size_t c = 0; c < 3; ++c) out.color[c] += color[c];
    }
    for (float& c : out.color) c /= float(spp);
    out.coverage = float(hits) / float(spp);
    return out;
  }
};

}  // namespace

CameraFrame reference_camera_frame(const Camera& camera, int width, int height) {
  const auto fail = [](const std::string& what) { throw Error("reference render: camera " + what); };
  check_field_of_view(camera.fov_degrees, "reference render: camera field of view");
  if (width < 1 || height < 1) fail("image must have at least one pixel");
  const auto basis = camera_basis(camera.position, camera.target);
  if (!basis) fail("looks straight up or down, or at its own position (no horizon to frame)");
  const V3 &p = camera.position, &f = basis->forward, &r = basis->right, &u = basis->up;
  const double half = std::tan(camera.fov_degrees * std::numbers::pi / 360.0);
  const double aspect = double(height) / double(width);
  CameraFrame frame;
  frame.origin = p;
  frame.forward = f;
  for (std::size_t c = 0; c < 3; ++c) {
    frame.right[c] = r[c] * half;
    frame.up[c] = u[c] * half * aspect;
  }
  return frame;
}

int reference_samples(const RenderSettings& render, int requested) {
  if (requested != 0) return requested;
  const int a = std::clamp(render.antialias_samples, 1, 32);
  return a * a;
}

namespace {

// A frame of `scene` (render_reference, ReferenceFrames::render): traced over `traced_already`,
// or over the scene built into Embree here about the frame's eye when that is null.
ReferenceImage trace_frame(const Scene& scene, const SceneTracer* traced_already, const ReferenceOptions& options) {
  const auto start = Clock::now();
  if (options.width < 0 || options.height < 0)
    throw Error("reference render: image " + std::to_string(options.width) + " x " + std::to_string(options.height) +
                " pixels; expected sizes >= 1 (or 0 for the scene's)");
  const int width = options.width > 0 ? options.width : scene.render.width;
  const int height = options.height > 0 ? options.height : scene.render.height;
  const int spp = reference_samples(scene.render, options.samples_per_pixel);
  check_options(scene, width, height, spp);
  const Camera camera = options.camera.value_or(scene.camera);
  CameraFrame frame = reference_camera_frame(camera, width, height);
  const int threads = options.threads.value_or(scene.render.threads);
  if (threads < 0) throw Error("reference render: " + std::to_string(threads) + " threads; expected >= 0 (0 = all)");
  std::unique_ptr<tbb::global_control> limit;
  if (threads > 0) limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, threads);

  ReferenceImage out;
  std::optional<SceneTracer> built;
  if (!traced_already) built.emplace(scene, frame.origin, SceneTracer::Layout::whole, options.wind_seconds);
  const SceneTracer& traced = traced_already ? *traced_already : *built;
  for (std::size_t c = 0; c < 3; ++c) frame.origin[c] -= traced.origin()[c];
  out.stats.build_seconds = seconds_since(start);
  out.stats.instances = traced.instances();
  out.stats.triangles = scene.terrain.triangles.size();
  for (const Mesh& m : scene.models) out.stats.triangles += m.triangles.size();

  const ShadingSettings shading = with_sun(options.shading, scene.sun);
  const GroundColors ground(scene.ground_texture.get(), shading.ground_color);
  const int grid = int(std::ceil(std::sqrt(double(spp))));
  const Tracer tracer{traced, shading, ground, frame, width, height, spp, grid, options.seed};

  out.image = ImageRgb8(width, height);
  const std::size_t pixels = std::size_t(width) * std::size_t(height);
  out.coverage.assign(pixels, 0.0f);
  out.depth.assign(pixels, std::numeric_limits<float>::infinity());
  const int tiles_x = (width + kTile - 1) / kTile, tiles_y = (height + kTile - 1) / kTile;
  std::atomic<std::uint64_t> secondary{0}, done{0};
  std::mutex progress_mutex;
  const auto render_start = Clock::now();
  tbb::parallel_for(tbb::blocked_range<int>(0, tiles_x * tiles_y), [&](const tbb::blocked_range<int>& range) {
    std::uint64_t rays = 0;
    for (int tile = range.begin(); tile != range.end(); ++tile) {
      const int x0 = (tile % tiles_x) * kTile, y0 = (tile / tiles_x) * kTile;
      const int x1 = std::min(width, x0 + kTile), y1 = std::min(height, y0 + kTile);
      for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x) {
          const Tracer::Pixel p = tracer.trace(x, y);
          const auto rgb = to_srgb8(p.color);
          out.image.set(x, y, {rgb[0], rgb[1], rgb[2]});
          const std::size_t i = std::size_t(y) * std::size_t(width) + std::size_t(x);
          out.coverage[i] = p.coverage;
          out.depth[i] = p.depth;
          rays += p.secondary;
        }
      const std::uint64_t d = done += std::uint64_t((x1 - x0) * (y1 - y0));
      if (options.progress) {
        std::lock_guard lock(progress_mutex);
        options.progress(d, pixels);
      }
    }
    secondary += rays;
  });

  traced.check("tracing");
  out.stats.render_seconds = seconds_since(render_start);
  out.stats.primary_rays = std::uint64_t(pixels) * std::uint64_t(spp);
  out.stats.secondary_rays = secondary.load();
  out.stats.samples_per_pixel = spp;
  out.stats.threads = int(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism));
  out.stats.seconds = seconds_since(start);
  return out;
}

}  // namespace

ReferenceImage render_reference(const Scene& scene, const ReferenceOptions& options) {
  return trace_frame(scene, nullptr, options);
}

struct ReferenceFrames::Impl {
  Impl(const Scene& scene, const std::array<double, 3>& origin) : traced(scene, origin) {}
  SceneTracer traced;
};

ReferenceFrames::ReferenceFrames(const Scene& scene, const std::array<double, 3>& origin)
    : scene_(scene), impl_(std::make_unique<Impl>(scene, origin)) {}

ReferenceFrames::~ReferenceFrames() = default;

ReferenceImage ReferenceFrames::render(const ReferenceOptions& options) const {
  impl_->traced.set_wind_time(options.wind_seconds);
  return trace_frame(scene_, &impl_->traced, options);
}

}  // namespace wangscape
