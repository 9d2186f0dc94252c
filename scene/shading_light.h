// The light of the one shading model: what a diffuse surface receives from the sun and from the
// open sky, and the sky seen along a ray. renders/trace/traced_shading.h traces its shadow and sky rays
// with Embree (the LDI build and the reference renderer); the far field (far_field.h) uses it
// with an open sky and no shadows. Pure functions: thread safe.
#pragma once

#include <array>

namespace wangscape {

struct Sun;

using Vec3f = std::array<float, 3>;

// Unit vector from the ground towards a sun at compass azimuth (degrees clockwise from north)
// and elevation (degrees above the horizon), ENU (x east, y north, z up).
Vec3f sun_direction_from_degrees(double azimuth_degrees, double elevation_degrees);

struct ShadingSettings {
  Vec3f sun_direction = sun_direction_from_degrees(135.0, 35.0);  // unit, towards the sun
  Vec3f sun_color{2.2f, 2.0f, 1.75f};                             // linear irradiance the sun brings
  Vec3f sky_color{0.38f, 0.45f, 0.60f};                           // linear, from an open hemisphere
  bool shadows = true;                                            // sun shadow rays (else every point is lit)
  int ao_rays = 8;                          // sky-light rays per sample; 0 = every point sees the open sky
  float ao_distance = 1.5f;                 // meters: occluders further than this do not darken the sky light
  float ray_offset = 1e-3f;                 // meters: shadow and sky rays start this far off the surface
  float exposure = 1.0f;                    // linear scale before the sRGB encoding
  Vec3f ground_color{0.30f, 0.24f, 0.15f};  // linear base color of the ground plane
};

// `base` lit by the scene's sun: its direction and its strength (a scale of sun_color). What
// the LDI build, the Embree reference and the far field all do, so they show the same light.
ShadingSettings with_sun(ShadingSettings base, const Sun& sun);

// The sun's share on a surface whose unit normal (turned towards the viewer) makes cosine
// `cos_sun` with the direction to the sun: cos_sun on the front; a translucent part (petals,
// leaves) passes `translucency` (0..1) of the sun on its back. Before shadows.
inline float sun_share(float cos_sun, float translucency) { return cos_sun > 0 ? cos_sun : -cos_sun * translucency; }

// Outgoing linear RGB (times exposure) of a diffuse surface of linear color `base` that gets
// `sun` of the sun (sun_share, 0 in shadow) and `sky` of the open sky (the unoccluded fraction).
inline Vec3f lit(const ShadingSettings& s, const Vec3f& base, float sun, float sky) {
  Vec3f out;
  for (int c = 0; c < 3; ++c) out[c] = base[c] * (s.sun_color[c] * sun + s.sky_color[c] * sky);
  for (float& c : out) c *= s.exposure;
  return out;
}

// The sky seen along a ray that meets nothing, linear RGB before exposure: `horizon` at and below
// the horizon, `zenith` straight up, mixed by the square root of the ray's up component. Both come
// from sky_color (the open sky's irradiance in lit()): a pale haze at the horizon, a deeper, bluer
// sky_color overhead. POV-Ray's sky_sphere and Blender's world draw this same gradient.
struct SkyGradient {
  Vec3f horizon{}, zenith{};
};
SkyGradient sky_gradient(const ShadingSettings& settings);

// Linear RGB (times exposure) of sky_gradient() seen along `direction` (need not be unit).
Vec3f sky_radiance(const ShadingSettings& settings, const Vec3f& direction);

}  // namespace wangscape
