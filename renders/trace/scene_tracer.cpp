#include "renders/trace/scene_tracer.h"

#include <embree3/rtcore.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <optional>
#include <vector>

#include "core/error.h"
#include "renders/trace/embree_device.h"
#include "scene/wind.h"

namespace wangscape {

namespace {

using V3 = std::array<double, 3>;
constexpr unsigned kTerrainId = 0;

}  // namespace

struct SceneTracer::Impl {
  mutable EmbreeDevice device;  // check() keeps its first error
  std::vector<EmbreeScene> models;
  std::unique_ptr<EmbreeScene> top;
  std::unique_ptr<EmbreeScene> terrain;  // Layout::part: instanced as geometry kTerrainId of top
  // The flowers as structure of arrays, indexed by Embree instance id - 1.
  std::vector<std::uint16_t> variant;
  std::vector<float> cos_yaw, sin_yaw, scale;
  std::vector<std::array<float, 3>> position;  // shifted frame
  // With the scene's wind and a time: each flower's lean at wind_seconds (scene/wind.h),
  // row-major 3 x 3, applied after its yaw and scale, about its base. Empty when standing still.
  std::vector<std::array<float, 9>> lean;
  std::optional<double> wind_seconds;
  // bake_sky: per model, per vertex, the sky share of the front (the triangles' winding) and the
  // back, interpolated across a triangle (per triangle, a leaf showed its facets).
  std::vector<std::vector<std::array<float, 2>>> model_sky;
  // bake_sky: per model, per triangle, its normal by winding (face_normal), which side a ray sees.
  std::vector<std::vector<Vec3f>> model_faces;
  V3 origin{};

  // Per model, per triangle, its normal by winding: which side of it a ray sees.
  void set_faces(const Scene& scene) {
    model_faces.assign(scene.models.size(), {});
    for (std::size_t v = 0; v < scene.models.size(); ++v) {
      const Mesh& mesh = scene.models[v];
      std::vector<Vec3f>& faces = model_faces[v];
      faces.resize(mesh.triangles.size());
      for (std::size_t p = 0; p < faces.size(); ++p) {
        const auto& tri = mesh.triangles[p];
        faces[p] = face_normal(mesh.positions[tri[0]], mesh.positions[tri[1]], mesh.positions[tri[2]]);
      }
    }
  }

  // Flower f's lean at wind_seconds, from its place as kept (so a frame's lean does not depend
  // on whether the flowers were added at its time or turned to it later).
  std::array<float, 9> lean_at(const WindField& wind, std::size_t f) const {
    const auto r =
        lean_rotation(wind.lean(double(position[f][0]) + origin[0], double(position[f][1]) + origin[1], *wind_seconds));
    std::array<float, 9> out;
    for (std::size_t c = 0; c < 9; ++c) out[c] = float(r[c]);
    return out;
  }

  // A direction of flower f's model turned as the flower stands: yaw, then its lean (no scale).
  Vec3f turn(std::size_t f, const Vec3f& d) const {
    const Vec3f yawed{cos_yaw[f] * d[0] - sin_yaw[f] * d[1], sin_yaw[f] * d[0] + cos_yaw[f] * d[1], d[2]};
    if (lean.empty()) return yawed;
    const auto& r = lean[f];
    return {r[0] * yawed[0] + r[1] * yawed[1] + r[2] * yawed[2], r[3] * yawed[0] + r[4] * yawed[1] + r[5] * yawed[2],
            r[6] * yawed[0] + r[7] * yawed[1] + r[8] * yawed[2]};
  }

  // Column-major 3 x 4: rotation about z by yaw, uniform scale, the lean, translation (as
  // POV-Ray's rotate, scale, rotate, translate of the same instance).
  std::array<float, 12> transform(std::size_t f) const {
    const float k = scale[f];
    const Vec3f x = turn(f, {k, 0, 0}), y = turn(f, {0, k, 0}), z = turn(f, {0, 0, k});
    return {x[0], x[1], x[2], y[0], y[1], y[2], z[0], z[1], z[2], position[f][0], position[f][1], position[f][2]};
  }

  void add_flowers(const Scene& scene, const InstanceBatch& batch) {
    for (std::size_t i = 0; i < batch.size(); ++i) {
      const std::uint16_t v = batch.variant[i];
      if (v >= scene.models.size())
        throw Error("reference render: an instance of variant " + std::to_string(v) + " but the scene has " +
                    std::to_string(scene.models.size()) + " models");
      const std::size_t f = variant.size();
      variant.push_back(v);
      cos_yaw.push_back(std::cos(batch.yaw[i]));
      sin_yaw.push_back(std::sin(batch.yaw[i]));
      scale.push_back(batch.scale[i]);
      position.push_back({float(batch.x[i] - origin[0]), float(batch.y[i] - origin[1]), float(batch.z[i] - origin[2])});
      if (scene.wind && wind_seconds) lean.push_back(lean_at(*scene.wind, f));
      const auto xfm = transform(f);
      RTCGeometry g = rtcNewGeometry(device.get(), RTC_GEOMETRY_TYPE_INSTANCE);
      rtcSetGeometryInstancedScene(g, models[v].get());
      rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xfm.data());
      rtcCommitGeometry(g);
      rtcAttachGeometryByID(top->get(), g, unsigned(f) + 1);
      rtcReleaseGeometry(g);
    }
  }
};

SceneTracer::SceneTracer(const Scene& scene, const std::array<double, 3>& origin, Layout layout,
                         std::optional<double> wind_seconds)
    : scene_(scene), impl_(std::make_unique<Impl>()) {
  Impl& t = *impl_;
  t.wind_seconds = wind_seconds;
  t.origin = {std::round(origin[0]), std::round(origin[1]), std::round(origin[2])};
  t.models = model_scenes(t.device, scene.models);
  t.top = std::make_unique<EmbreeScene>(t.device.get());
  if (!scene.terrain.triangles.empty()) {
    std::vector<std::array<float, 3>> shifted(scene.terrain.positions.size());
    for (std::size_t v = 0; v < shifted.size(); ++v)
      for (std::size_t c = 0; c < 3; ++c) shifted[v][c] = float(double(scene.terrain.positions[v][c]) - t.origin[c]);
    RTCGeometry g = triangle_geometry(t.device.get(), shifted, scene.terrain.triangles);
    if (layout == Layout::part) {
      t.terrain = std::make_unique<EmbreeScene>(t.device.get());
      rtcAttachGeometryByID(t.terrain->get(), g, 0);
      rtcCommitScene(t.terrain->get());
    } else {
      rtcAttachGeometryByID(t.top->get(), g, kTerrainId);
    }
    rtcReleaseGeometry(g);
  }
  if (layout == Layout::part) {
    set_flowers({});
    return;
  }
  if (scene.instances && !scene.models.empty())
    scene.instances([&](const InstanceBatch& batch) { t.add_flowers(scene, batch); });
  t.device.check("adding the terrain and the flowers");
  rtcCommitScene(t.top->get());
  t.device.check("building the scene");
}

void SceneTracer::set_flowers(const InstanceStream& flowers) {
  Impl& t = *impl_;
  t.top = std::make_unique<EmbreeScene>(t.device.get());
  t.variant.clear();
  t.cos_yaw.clear();
  t.sin_yaw.clear();
  t.scale.clear();
  t.position.clear();
  t.lean.clear();
  if (t.terrain) {
    RTCGeometry g = rtcNewGeometry(t.device.get(), RTC_GEOMETRY_TYPE_INSTANCE);
    rtcSetGeometryInstancedScene(g, t.terrain->get());
    const float identity[12] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
    rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, identity);
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(t.top->get(), g, kTerrainId);
    rtcReleaseGeometry(g);
  }
  if (flowers && !scene_.models.empty()) flowers([&](const InstanceBatch& batch) { t.add_flowers(scene_, batch); });
  t.device.check("adding the flowers");
  rtcCommitScene(t.top->get());
  t.device.check("building the scene");
}

void SceneTracer::set_wind_time(double seconds) {
  Impl& t = *impl_;
  if (!scene_.wind || seconds == t.wind_seconds) return;
  t.wind_seconds = seconds;
  t.lean.resize(t.variant.size());  // standing still until now: every flower leans from here on
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, t.lean.size()), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t f = r.begin(); f != r.end(); ++f) t.lean[f] = t.lean_at(*scene_.wind, f);
  });
  for (std::size_t f = 0; f < t.variant.size(); ++f) {
    RTCGeometry g = rtcGetGeometry(t.top->get(), unsigned(f) + 1);
    rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, t.transform(f).data());
    rtcCommitGeometry(g);
  }
  t.device.check("leaning the flowers in the wind");
  rtcCommitScene(t.top->get());
  t.device.check("building the scene");
}

void SceneTracer::bake_sky(const ShadingSettings& shading, int rays, int instances) {
  Impl& t = *impl_;
  if (shading.ao_rays <= 0) return;  // a scene lit without sky rays sees the open sky
  const std::size_t models = scene_.models.size();
  // Up to `instances` flowers of each model, spread over the order they were placed in.
  std::vector<std::vector<std::size_t>> all(models), chosen(models);
  for (std::size_t f = 0; f < t.variant.size(); ++f) all[t.variant[f]].push_back(f);
  for (std::size_t v = 0; v < models; ++v)
    for (int j = 0; j < instances && !all[v].empty(); ++j) {
      const std::size_t pick = all[v][all[v].size() * std::size_t(j) / std::size_t(instances)];
      if (chosen[v].empty() || chosen[v].back() != pick) chosen[v].push_back(pick);
    }
  t.model_sky.assign(models, {});
  t.set_faces(scene_);
  for (std::size_t v = 0; v < models; ++v) {
    const Mesh& mesh = scene_.models[v];
    const std::vector<Vec3f>& faces = t.model_faces[v];
    std::vector<std::array<float, 2>> sky(mesh.triangles.size(), {1.0f, 1.0f});  // per triangle
    t.model_sky[v].assign(mesh.positions.size(), {1.0f, 1.0f});
    if (chosen[v].empty()) continue;
    ShadingSettings per_flower = shading;
    per_flower.ao_rays = std::max(1, rays / int(chosen[v].size()));
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, mesh.triangles.size()), [&](const tbb::blocked_range<std::size_t>& r) {
          for (std::size_t p = r.begin(); p != r.end(); ++p) {
            const auto& tri = mesh.triangles[p];
            const auto &a = mesh.positions[tri[0]], &b = mesh.positions[tri[1]], &c = mesh.positions[tri[2]];
            Vec3f n = faces[p];
            const float length = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            if (!(length > 0)) continue;  // degenerate: the open sky
            for (float& x : n) x /= length;
            const float centre[3] = {(a[0] + b[0] + c[0]) / 3, (a[1] + b[1] + c[1]) / 3, (a[2] + b[2] + c[2]) / 3};
            for (int side = 0; side < 2; ++side) {
              float open = 0;
              for (const std::size_t f : chosen[v]) {
                const float k = t.scale[f];
                const Vec3f turned = t.turn(f, {centre[0], centre[1], centre[2]}), normal = t.turn(f, n);
                const Vec3f at{t.position[f][0] + k * turned[0], t.position[f][1] + k * turned[1],
                               t.position[f][2] + k * turned[2]};
                const float sign = side == 0 ? 1.0f : -1.0f;
                const Vec3f facing{sign * normal[0], sign * normal[1], sign * normal[2]};
                open += open_sky_share(
                    t.top->get(), per_flower, at, facing,
                    mix64((std::uint64_t(v) << 40) ^ (std::uint64_t(p) << 8) ^ std::uint64_t(side * 16) ^ f));
              }
              sky[p][std::size_t(side)] = open / float(chosen[v].size());
            }
          }
        });
    // To the vertices: the mean of the triangles around each, weighted by their areas.
    std::vector<std::array<double, 3>> sum(mesh.positions.size(), {0, 0, 0});  // front, back, weight
    for (std::size_t p = 0; p < mesh.triangles.size(); ++p) {
      const Vec3f& n = faces[p];
      const double area = std::sqrt(double(n[0]) * n[0] + double(n[1]) * n[1] + double(n[2]) * n[2]);
      for (const auto corner : mesh.triangles[p]) {
        sum[corner][0] += area * sky[p][0];
        sum[corner][1] += area * sky[p][1];
        sum[corner][2] += area;
      }
    }
    for (std::size_t i = 0; i < sum.size(); ++i)
      if (sum[i][2] > 0) t.model_sky[v][i] = {float(sum[i][0] / sum[i][2]), float(sum[i][1] / sum[i][2])};
  }
  t.device.check("estimating the flowers' share of the sky");
}

const SceneTracer::SkyShares& SceneTracer::sky_shares() const { return impl_->model_sky; }

void SceneTracer::set_sky_shares(SkyShares shares) {
  Impl& t = *impl_;
  if (!shares.empty()) {
    bool fits = shares.size() == scene_.models.size();
    for (std::size_t v = 0; fits && v < shares.size(); ++v)
      fits = shares[v].size() == scene_.models[v].positions.size();
    if (!fits)
      throw Error("the flowers' sky shares do not hold every vertex of the scene's " +
                  std::to_string(scene_.models.size()) + " models");
    t.set_faces(scene_);
  }
  t.model_sky = std::move(shares);
}

SceneTracer::~SceneTracer() = default;

const std::array<double, 3>& SceneTracer::origin() const { return impl_->origin; }
std::uint64_t SceneTracer::instances() const { return impl_->variant.size(); }
RTCSceneTy* SceneTracer::scene() const { return impl_->top->get(); }
void SceneTracer::check(std::string_view doing) const { impl_->device.check(doing); }

std::optional<SceneTracer::Hit> SceneTracer::intersect(const V3& from, const V3& d, float tfar) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  RTCRayHit rh{};
  rh.ray.org_x = float(from[0]);
  rh.ray.org_y = float(from[1]);
  rh.ray.org_z = float(from[2]);
  rh.ray.dir_x = float(d[0]);
  rh.ray.dir_y = float(d[1]);
  rh.ray.dir_z = float(d[2]);
  rh.ray.tnear = 0.0f;
  rh.ray.tfar = tfar;
  rh.ray.mask = 0xffffffffu;
  rh.hit.geomID = rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(impl_->top->get(), &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
  return Hit{rh.ray.tfar, rh.hit.u, rh.hit.v, rh.hit.geomID, rh.hit.instID[0], rh.hit.primID};
}

void SceneTracer::intersect16(const V3& from, const V3* d, const float* tfar, const bool* valid,
                              std::optional<Hit>* hit) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  alignas(64) RTCRayHit16 rh{};
  alignas(64) int active[16];
  for (int l = 0; l < 16; ++l) {
    active[l] = valid[l] ? -1 : 0;
    rh.ray.org_x[l] = float(from[0]);
    rh.ray.org_y[l] = float(from[1]);
    rh.ray.org_z[l] = float(from[2]);
    rh.ray.dir_x[l] = float(d[l][0]);
    rh.ray.dir_y[l] = float(d[l][1]);
    rh.ray.dir_z[l] = float(d[l][2]);
    rh.ray.tnear[l] = 0.0f;
    rh.ray.tfar[l] = valid[l] ? tfar[l] : 0.0f;
    rh.ray.mask[l] = 0xffffffffu;
    rh.hit.geomID[l] = rh.hit.instID[0][l] = RTC_INVALID_GEOMETRY_ID;
  }
  rtcIntersect16(active, impl_->top->get(), &context, &rh);
  for (int l = 0; l < 16; ++l) {
    hit[l].reset();
    if (valid[l] && rh.hit.geomID[l] != RTC_INVALID_GEOMETRY_ID)
      hit[l] = Hit{rh.ray.tfar[l], rh.hit.u[l], rh.hit.v[l], rh.hit.geomID[l], rh.hit.instID[0][l], rh.hit.primID[l]};
  }
}

SurfaceSample SceneTracer::surface(const Hit& h, const V3& from, const V3& d, const GroundColors& ground) const {
  const Impl& t = *impl_;
  SurfaceSample s;
  for (std::size_t c = 0; c < 3; ++c) s.position[c] = float(from[c] + h.t * d[c]);
  if (h.inst != RTC_INVALID_GEOMETRY_ID && h.inst != kTerrainId) {  // a flower (the terrain: an instance of its own)
    const unsigned f = h.inst - 1;
    const Mesh& mesh = scene_.models[t.variant[f]];
    // The normal turned as the flower stands (its yaw, and its lean in the wind), made unit.
    s.normal = unit_or_up(t.turn(f, model_normal(mesh, h.prim, h.u, h.v)));
    model_material(mesh, h.prim, h.u, h.v, s);
    if (!t.model_sky.empty()) {
      // The side the ray sees: the back where the triangle's winding faces away from the ray.
      const auto& tri = mesh.triangles[h.prim];
      const Vec3f turned = t.turn(f, t.model_faces[t.variant[f]][h.prim]);
      const bool back = double(turned[0]) * d[0] + double(turned[1]) * d[1] + double(turned[2]) * d[2] > 0;
      const auto& sky = t.model_sky[t.variant[f]];
      const std::size_t side = back ? 1 : 0;
      s.sky = (1 - h.u - h.v) * sky[tri[0]][side] + h.u * sky[tri[1]][side] + h.v * sky[tri[2]][side];
    }
  } else {
    model_surface(scene_.terrain, h.prim, h.u, h.v, 1.0f, 0.0f, s);
    s.base_color = ground.at(double(s.position[0]) + t.origin[0], double(s.position[1]) + t.origin[1]);
    s.translucency = 0;
  }
  // Two-sided: turn the normal towards the viewer.
  if (s.normal[0] * d[0] + s.normal[1] * d[1] + s.normal[2] * d[2] > 0)
    for (float& v : s.normal) v = -v;
  return s;
}

}  // namespace wangscape
