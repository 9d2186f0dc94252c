// The one shading model, traced: the LDI build pre-shades its samples with it and the Embree
// reference renderer shades its pixels with it, so both show the same light. Diffuse surfaces lit
// by the sun (with Embree shadow rays) and by the sky (ambient occlusion from N hemisphere rays);
// thin translucent parts (petals, leaves) also pass the sun that falls on their back. The light
// itself (settings, sun share, lit(), the sky) is scene/shading_light.h, which the far field uses too.
#pragma once

#include <array>
#include <cstdint>

#include "core/hash.h"
#include "scene/shading_light.h"
#include "templates/mesh.h"

// Embree's scene handle (embree3/rtcore_scene.h: typedef struct RTCSceneTy* RTCScene), declared
// here so that users of this header need not include Embree.
struct RTCSceneTy;

namespace wangscape {

// A point to shade, in the scene space of the Embree scene given to shade().
struct SurfaceSample {
  Vec3f position{};                    // meters
  Vec3f normal{0, 0, 1};               // unit, turned towards the viewer (surfaces are two-sided)
  Vec3f base_color{0.5f, 0.5f, 0.5f};  // linear RGB
  float translucency = 0;              // 0..1 of the sun on the back that comes through
  // The share of the open sky this point sees, used where no sky rays are cast (ao_rays = 0):
  // 1 under the open sky, or an estimate made beforehand (SceneTracer::bake_sky).
  float sky = 1;
};

// The normal of the triangle (a, b, c) by its winding, not made unit (its length: twice the area).
Vec3f face_normal(const std::array<float, 3>& a, const std::array<float, 3>& b, const std::array<float, 3>& c);

// The model's own normal at (u, v) of triangle `prim` (interpolated, or the face's), not unit.
Vec3f model_normal(const Mesh& mesh, unsigned prim, float u, float v);
// `r` made unit; up (0, 0, 1) when it has no length.
Vec3f unit_or_up(const Vec3f& r);

// The surface of triangle `prim` of a model hit at barycentric (u, v): the normal (smooth where
// the mesh has normals, else the triangle's), turned by the instance's yaw about +z and made unit
// (+z when degenerate), and the triangle's material (base color times its image's texel at the
// interpolated uv, translucency; left as they are when the triangle has none). A uniform scale does not change normals.
// Not yet turned towards the viewer.
void model_surface(const Mesh& mesh, unsigned prim, float u, float v, float cos_yaw, float sin_yaw, SurfaceSample& out);
// The material part of model_surface alone: base color (times its image's texel) and
// translucency, left as they are when the triangle has none.
void model_material(const Mesh& mesh, unsigned prim, float u, float v, SurfaceSample& out);

// Outgoing linear RGB at `sample`. Shadow and sky rays are rtcOccluded1 queries of `scene`
// (which must hold every occluder: in the LDI build, the 3 x 3 context); `random` seeds the sky
// directions, so the same inputs give the same bits. `rays_cast`, when given, is set to the number
// of Embree rays shade() traced. Thread-safe: reads the scene only.
Vec3f shade(RTCSceneTy* scene, const ShadingSettings& settings, const SurfaceSample& sample, std::uint64_t random,
            int* rays_cast = nullptr);

// The sun's share of light at `sample` (cos, or through a translucent part's back) where its
// shadow ray toward the sun meets nothing (with settings.shadows): what shade() lights it by.
// Adds the rays it cast to *rays_cast.
float shadowed_sun_share(RTCSceneTy* scene, const ShadingSettings& settings, const SurfaceSample& sample,
                         int* rays_cast);

// The share of the sky a point at `position` facing unit `normal` sees: settings.ao_rays
// cosine-weighted rays over the hemisphere of `normal`, each open unless something lies within
// settings.ao_distance (1 when ao_rays is 0); `random` seeds the directions.
float open_sky_share(RTCSceneTy* scene, const ShadingSettings& settings, const Vec3f& position, const Vec3f& normal,
                     std::uint64_t random);

// shade() of up to 16 samples with no sky rays (settings.ao_rays is not used: each sample's own
// `sky` share), their sun-shadow rays cast as one rtcOccluded16 packet: the same colors shade()
// gives each with ao_rays = 0. Samples whose `valid` entry is false are skipped. Returns the rays cast.
int shade_in_the_open16(RTCSceneTy* scene, const ShadingSettings& settings, const SurfaceSample* samples,
                        const bool* valid, Vec3f* out);

// Linear RGB (times exposure) to 8-bit sRGB, clamped.
std::array<std::uint8_t, 3> to_srgb8(const Vec3f& linear);

// (The samplers' deterministic random numbers: mix64 and unit_float of core/hash.h.)

}  // namespace wangscape
