#include "scene/shading_light.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/vecmath.h"
#include "scene/sun.h"

namespace wangscape {

Vec3f sun_direction_from_degrees(double azimuth_degrees, double elevation_degrees) {
  const double az = azimuth_degrees * std::numbers::pi / 180, el = elevation_degrees * std::numbers::pi / 180;
  return {static_cast<float>(std::sin(az) * std::cos(el)), static_cast<float>(std::cos(az) * std::cos(el)),
          static_cast<float>(std::sin(el))};
}

ShadingSettings with_sun(ShadingSettings base, const Sun& sun) {
  const auto d = sun.direction();
  base.sun_direction = {float(d[0]), float(d[1]), float(d[2])};
  for (float& c : base.sun_color) c *= float(sun.strength);
  return base;
}

SkyGradient sky_gradient(const ShadingSettings& s) {
  constexpr Vec3f kHaze{0.80f, 0.85f, 0.90f};
  const float strongest = std::max({s.sky_color[0], s.sky_color[1], s.sky_color[2], 1e-6f});
  SkyGradient g;
  for (int c = 0; c < 3; ++c) {
    g.horizon[c] = 0.4f * s.sky_color[c] + 0.6f * kHaze[c];
    // Overhead the weaker channels fall off faster: blue stays, grey turns to blue.
    g.zenith[c] = 0.9f * s.sky_color[c] * std::pow(s.sky_color[c] / strongest, 1.5f);
  }
  return g;
}

Vec3f sky_radiance(const ShadingSettings& s, const Vec3f& direction) {
  const float length = std::sqrt(dot(direction, direction));
  const float up = length > 0 ? std::clamp(direction[2] / length, 0.0f, 1.0f) : 0.0f;
  const SkyGradient g = sky_gradient(s);
  const float toward_zenith = std::sqrt(up);
  Vec3f out;
  for (int c = 0; c < 3; ++c) out[c] = (g.horizon[c] + (g.zenith[c] - g.horizon[c]) * toward_zenith) * s.exposure;
  return out;
}

}  // namespace wangscape
