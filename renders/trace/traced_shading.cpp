#include "renders/trace/traced_shading.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/color.h"
#include "core/vecmath.h"
#include "scene/sun.h"

namespace wangscape {

namespace {

// Whether the segment from p along unit d up to `far` meters hits anything.
bool occluded(RTCScene scene, const Vec3f& p, const Vec3f& d, float far) {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray{};
  ray.org_x = p[0];
  ray.org_y = p[1];
  ray.org_z = p[2];
  ray.dir_x = d[0];
  ray.dir_y = d[1];
  ray.dir_z = d[2];
  ray.tnear = 0.0f;
  ray.tfar = far;
  ray.mask = 0xffffffffu;
  rtcOccluded1(scene, &context, &ray);
  return ray.tfar < 0.0f;  // Embree sets tfar to -inf on a hit
}

Vec3f offset_along(const Vec3f& p, const Vec3f& n, float distance) {
  return {p[0] + n[0] * distance, p[1] + n[1] * distance, p[2] + n[2] * distance};
}

}  // namespace

Vec3f face_normal(const std::array<float, 3>& p0, const std::array<float, 3>& p1, const std::array<float, 3>& p2) {
  const double e1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]};
  const double e2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
  return {float(e1[1] * e2[2] - e1[2] * e2[1]), float(e1[2] * e2[0] - e1[0] * e2[2]),
          float(e1[0] * e2[1] - e1[1] * e2[0])};
}

Vec3f model_normal(const Mesh& mesh, unsigned prim, float u, float v) {
  const auto& tri = mesh.triangles[prim];
  if (mesh.normals.empty()) return face_normal(mesh.positions[tri[0]], mesh.positions[tri[1]], mesh.positions[tri[2]]);
  Vec3f n{};
  const float w0 = 1 - u - v;
  for (std::size_t c = 0; c < 3; ++c)
    n[c] = w0 * mesh.normals[tri[0]][c] + u * mesh.normals[tri[1]][c] + v * mesh.normals[tri[2]][c];
  return n;
}

Vec3f unit_or_up(const Vec3f& r) {
  const float len = std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
  return len > 0 ? Vec3f{r[0] / len, r[1] / len, r[2] / len} : Vec3f{0, 0, 1};
}

void model_surface(const Mesh& mesh, unsigned prim, float u, float v, float cos_yaw, float sin_yaw,
                   SurfaceSample& out) {
  const Vec3f n = model_normal(mesh, prim, u, v);
  const Vec3f r{cos_yaw * n[0] - sin_yaw * n[1], sin_yaw * n[0] + cos_yaw * n[1], n[2]};
  out.normal = unit_or_up(r);
  model_material(mesh, prim, u, v, out);
}

void model_material(const Mesh& mesh, unsigned prim, float u, float v, SurfaceSample& out) {
  const auto& tri = mesh.triangles[prim];
  if (prim < mesh.triangle_material.size()) {
    const std::uint16_t slot = mesh.triangle_material[prim];
    if (slot < mesh.materials.size()) {
      const Material& material = mesh.materials[slot];
      out.base_color = material.base_color;
      out.translucency = material.translucency;
      // The image's texel at the interpolated uv multiplies the base colour (glTF's rule).
      if (material.base_color_map && mesh.uvs.size() == mesh.positions.size()) {
        const float w0 = 1 - u - v;
        const float s = w0 * mesh.uvs[tri[0]][0] + u * mesh.uvs[tri[1]][0] + v * mesh.uvs[tri[2]][0];
        const float t = w0 * mesh.uvs[tri[0]][1] + u * mesh.uvs[tri[1]][1] + v * mesh.uvs[tri[2]][1];
        const auto texel = material.base_color_map->at(s, t);
        for (std::size_t c = 0; c < 3; ++c) out.base_color[c] *= texel[c];
      }
    }
  }
}

float open_sky_share(RTCSceneTy* scene, const ShadingSettings& s, const Vec3f& p, const Vec3f& n,
                     std::uint64_t random) {
  if (s.ao_rays <= 0) return 1.0f;
  // Cosine-weighted directions over the hemisphere of n, so the unoccluded fraction is the
  // irradiance share of a uniform sky. Frame from Duff et al. 2017 (no branch on n's axis).
  const float sign = std::copysign(1.0f, n[2]);
  const float a = -1.0f / (sign + n[2]), b = n[0] * n[1] * a;
  const Vec3f t{1.0f + sign * n[0] * n[0] * a, sign * b, -sign * n[0]};
  const Vec3f bt{b, sign + n[1] * n[1] * a, -n[1]};
  const Vec3f from = offset_along(p, n, s.ray_offset);
  // Eight rays from one point at a time: one rtcOccluded8 packet (measured faster than singles).
  int open = 0;
  for (int k0 = 0; k0 < s.ao_rays; k0 += 8) {
    alignas(32) RTCRay8 packet{};
    alignas(32) int valid[8];
    for (int l = 0; l < 8; ++l) {
      const int k = k0 + l;
      valid[l] = k < s.ao_rays ? -1 : 0;
      if (k >= s.ao_rays) continue;
      const std::uint64_t h = mix64(random + static_cast<std::uint64_t>(k) * 0x632be59bd9b4e019ull);
      // Stratified in the first coordinate so few rays still cover the hemisphere.
      const float u1 = (static_cast<float>(k) + unit_float(h)) / static_cast<float>(s.ao_rays);
      const float u2 = unit_float(mix64(h));
      const float r = std::sqrt(u1), phi = 2.0f * std::numbers::pi_v<float> * u2;
      const float x = r * std::cos(phi), y = r * std::sin(phi), z = std::sqrt(std::max(0.0f, 1.0f - u1));
      packet.org_x[l] = from[0];
      packet.org_y[l] = from[1];
      packet.org_z[l] = from[2];
      packet.dir_x[l] = x * t[0] + y * bt[0] + z * n[0];
      packet.dir_y[l] = x * t[1] + y * bt[1] + z * n[1];
      packet.dir_z[l] = x * t[2] + y * bt[2] + z * n[2];
      packet.tnear[l] = 0.0f;
      packet.tfar[l] = s.ao_distance;
      packet.mask[l] = 0xffffffffu;
    }
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    rtcOccluded8(valid, scene, &context, &packet);
    for (int l = 0; l < 8; ++l)
      if (valid[l] != 0 && packet.tfar[l] >= 0.0f) ++open;  // tfar becomes -inf on a hit
  }
  return static_cast<float>(open) / static_cast<float>(s.ao_rays);
}

int shade_in_the_open16(RTCSceneTy* scene, const ShadingSettings& s, const SurfaceSample* samples, const bool* valid,
                        Vec3f* out) {
  alignas(64) RTCRay16 packet{};
  alignas(64) int active[16];
  float sun[16];
  int rays = 0;
  for (int l = 0; l < 16; ++l) {
    active[l] = 0;
    if (!valid[l]) continue;
    const SurfaceSample& sample = samples[l];
    const float cos_sun = dot(sample.normal, s.sun_direction);
    sun[l] = sun_share(cos_sun, sample.translucency);
    if (!(sun[l] > 0 && s.shadows)) continue;
    const Vec3f from = offset_along(sample.position, sample.normal, cos_sun > 0 ? s.ray_offset : -s.ray_offset);
    active[l] = -1;
    packet.org_x[l] = from[0];
    packet.org_y[l] = from[1];
    packet.org_z[l] = from[2];
    packet.dir_x[l] = s.sun_direction[0];
    packet.dir_y[l] = s.sun_direction[1];
    packet.dir_z[l] = s.sun_direction[2];
    packet.tnear[l] = 0.0f;
    packet.tfar[l] = std::numeric_limits<float>::infinity();
    packet.mask[l] = 0xffffffffu;
    ++rays;
  }
  if (rays > 0) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    rtcOccluded16(active, scene, &context, &packet);
  }
  for (int l = 0; l < 16; ++l) {
    if (!valid[l]) continue;
    if (active[l] != 0 && packet.tfar[l] < 0.0f) sun[l] = 0;  // tfar becomes -inf on a hit
    out[l] = lit(s, samples[l].base_color, sun[l], samples[l].sky);
  }
  return rays;
}

float shadowed_sun_share(RTCSceneTy* scene, const ShadingSettings& s, const SurfaceSample& sample, int* rays_cast) {
  // The front is lit by cos; a translucent part passes that share of the light on its back.
  const Vec3f& n = sample.normal;
  const float cos_sun = dot(n, s.sun_direction);
  float sun = sun_share(cos_sun, sample.translucency);
  if (sun > 0 && s.shadows) {
    const Vec3f from = offset_along(sample.position, n, cos_sun > 0 ? s.ray_offset : -s.ray_offset);
    ++*rays_cast;
    if (occluded(scene, from, s.sun_direction, std::numeric_limits<float>::infinity())) sun = 0;
  }
  return sun;
}

Vec3f shade(RTCSceneTy* scene, const ShadingSettings& s, const SurfaceSample& sample, std::uint64_t random,
            int* rays_cast) {
  int rays = 0;
  const float sun = shadowed_sun_share(scene, s, sample, &rays);
  const float sky = s.ao_rays > 0 ? open_sky_share(scene, s, sample.position, sample.normal, random) : sample.sky;
  rays += std::max(s.ao_rays, 0);

  if (rays_cast) *rays_cast = rays;
  return lit(s, sample.base_color, sun, sky);
}

std::array<std::uint8_t, 3> to_srgb8(const Vec3f& linear) {
  std::array<std::uint8_t, 3> out{};
  for (int c = 0; c < 3; ++c) out[c] = linear_to_srgb8(linear[c]);
  return out;
}

}  // namespace wangscape
