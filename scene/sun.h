// The sun of a scene: where it stands (compass azimuth and elevation, given or computed from a
// date and time with NOAA's solar position algorithm) and how strong it is.
#pragma once

#include <array>
#include <cstdint>

namespace wangscape {

struct Sun {
  double azimuth_degrees = 135.0;   // clockwise from north (compass)
  double elevation_degrees = 35.0;  // above the horizon
  double strength = 1.0;            // relative intensity
  // Unit vector from the ground towards the sun, ENU.
  std::array<double, 3> direction() const;
};

// The sun's position seen from (latitude, longitude) at a moment (NOAA solar position
// algorithm after Meeus, about 0.01 degree for years 1901-2099; refraction included near the
// horizon). Degrees: latitude/longitude WGS 84, azimuth clockwise from north.
struct SolarPosition {
  double azimuth_degrees = 0;         // compass, clockwise from north
  double elevation_degrees = 0;       // above the horizon, refraction included
  double true_elevation_degrees = 0;  // the geometric elevation, without refraction
};
SolarPosition solar_position(double latitude_degrees, double longitude_degrees, std::int64_t unix_seconds);

}  // namespace wangscape
