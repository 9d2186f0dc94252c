#include "scene/wind.h"

#include <cmath>
#include <numbers>

namespace wangscape {

namespace {

constexpr double kRadiansPerDegree = std::numbers::pi / 180;

// The waves of the field, relative to the wind: the angle of a wave's travel from the wind's
// direction, its length as a share of gust_scale, its phase, and its amplitude along the wind
// and across it as shares of the strength. Lengths that are no simple ratio of each other, and
// angles spread to either side, so that the crests do not line up into stripes and plants a few
// gusts apart, along the wind or across it, sway apart (tests/scene/wind_test.cpp).
struct WaveShape {
  double degrees_from_wind, length_share, phase, along, across;
};
constexpr std::array<WaveShape, 4> kWaveShapes = {{
    {-20, 1.00, 0.0, 0.20, 0.00},
    {35, 0.71, 2.1, 0.14, 0.00},
    {-65, 0.47, 4.4, 0.11, 0.00},
    {20, 0.29, 1.0, 0.00, 0.15},  // a sideways flutter, shorter and weaker
}};
// The lean with every wave at zero, as a share of the strength: a plant in the wind always leans
// downwind, between 0.10 and 1.0 of the strength along the wind.
constexpr double kMeanLeanShare = 0.55;

// sin and cos of a direction, with the zeros of the compass's quarters exact (no 6e-17 terms in
// the POV-Ray functions).
std::array<double, 2> sin_cos(double radians) {
  const auto exact = [](double x) { return std::abs(x) < 1e-12 ? 0.0 : x; };
  return {exact(std::sin(radians)), exact(std::cos(radians))};
}

}  // namespace

WindLean WindField::lean(double east, double north, double seconds) const {
  WindLean out = base;
  for (const WindWave& w : waves) {
    const double s = std::sin(w.k_east * east + w.k_north * north + w.k_time * seconds + w.phase);
    out.east += w.amplitude_east * s;
    out.north += w.amplitude_north * s;
  }
  return out;
}

WindField wind_field(const WindConfig& config) {
  const double toward = config.direction * kRadiansPerDegree;
  const auto [wind_east, wind_north] = sin_cos(toward);              // the wind's unit vector
  const double across_east = wind_north, across_north = -wind_east;  // its right hand
  WindField field;
  field.base = {kMeanLeanShare * config.strength * wind_east, kMeanLeanShare * config.strength * wind_north};
  for (std::size_t i = 0; i < kWaveShapes.size(); ++i) {
    const WaveShape& shape = kWaveShapes[i];
    const double angle = toward + shape.degrees_from_wind * kRadiansPerDegree;
    const double k = 2 * std::numbers::pi / (shape.length_share * config.gust_scale);
    WindWave& w = field.waves[i];
    const auto [sin_angle, cos_angle] = sin_cos(angle);
    w.k_east = k * sin_angle;
    w.k_north = k * cos_angle;
    // The field travels with the wind: a crest at p at time 0 is at p + wind * speed * t.
    w.k_time = -(w.k_east * wind_east + w.k_north * wind_north) * config.speed;
    w.phase = shape.phase;
    w.amplitude_east = config.strength * (shape.along * wind_east + shape.across * across_east);
    w.amplitude_north = config.strength * (shape.along * wind_north + shape.across * across_north);
  }
  return field;
}

std::array<double, 9> lean_rotation(const WindLean& lean) {
  // R = Ry(east) * Rx(-north) over ENU (x east, y north, z up).
  const double a = -lean.north * kRadiansPerDegree, b = lean.east * kRadiansPerDegree;
  const double ca = std::cos(a), sa = std::sin(a), cb = std::cos(b), sb = std::sin(b);
  // Rx(a) = [1 0 0; 0 ca -sa; 0 sa ca], Ry(b) = [cb 0 sb; 0 1 0; -sb 0 cb].
  return {cb, sb * sa, sb * ca, 0, ca, -sa, -sb, cb * sa, cb * ca};
}

}  // namespace wangscape
