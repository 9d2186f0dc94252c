#include "scene/sun.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace wangscape {

std::array<double, 3> Sun::direction() const {
  const double az = azimuth_degrees * std::numbers::pi / 180.0;
  const double el = elevation_degrees * std::numbers::pi / 180.0;
  // Compass azimuth: 0 = north (+y), 90 = east (+x).
  return {std::sin(az) * std::cos(el), std::cos(az) * std::cos(el), std::sin(el)};
}

SolarPosition solar_position(double latitude, double longitude, std::int64_t unix_seconds) {
  // NOAA Global Monitoring Laboratory solar calculator (after Meeus, "Astronomical Algorithms").
  constexpr double kRad = std::numbers::pi / 180.0;
  const double julian_day = static_cast<double>(unix_seconds) / 86400.0 + 2440587.5;
  const double t = (julian_day - 2451545.0) / 36525.0;  // Julian centuries since J2000
  const double mean_longitude = std::fmod(280.46646 + t * (36000.76983 + t * 0.0003032), 360.0);
  const double mean_anomaly = 357.52911 + t * (35999.05029 - 0.0001537 * t);
  const double eccentricity = 0.016708634 - t * (0.000042037 + 0.0000001267 * t);
  const double m = mean_anomaly * kRad;
  const double center = std::sin(m) * (1.914602 - t * (0.004817 + 0.000014 * t)) +
                        std::sin(2 * m) * (0.019993 - 0.000101 * t) + std::sin(3 * m) * 0.000289;
  const double true_longitude = mean_longitude + center;
  const double omega = (125.04 - 1934.136 * t) * kRad;
  const double apparent_longitude = true_longitude - 0.00569 - 0.00478 * std::sin(omega);
  const double mean_obliquity = 23.0 + (26.0 + (21.448 - t * (46.815 + t * (0.00059 - t * 0.001813))) / 60.0) / 60.0;
  const double obliquity = (mean_obliquity + 0.00256 * std::cos(omega)) * kRad;
  const double declination = std::asin(std::sin(obliquity) * std::sin(apparent_longitude * kRad));
  const double y = std::pow(std::tan(obliquity / 2), 2);
  const double l0 = mean_longitude * kRad;
  const double equation_of_time_minutes =
      4.0 / kRad *
      (y * std::sin(2 * l0) - 2 * eccentricity * std::sin(m) + 4 * eccentricity * y * std::sin(m) * std::cos(2 * l0) -
       0.5 * y * y * std::sin(4 * l0) - 1.25 * eccentricity * eccentricity * std::sin(2 * m));
  std::int64_t seconds_of_day = unix_seconds % 86400;
  if (seconds_of_day < 0) seconds_of_day += 86400;
  double true_solar_minutes =
      std::fmod(static_cast<double>(seconds_of_day) / 60.0 + equation_of_time_minutes + 4.0 * longitude, 1440.0);
  if (true_solar_minutes < 0) true_solar_minutes += 1440.0;
  const double hour_angle =
      true_solar_minutes / 4.0 < 0 ? true_solar_minutes / 4.0 + 180.0 : true_solar_minutes / 4.0 - 180.0;
  const double lat = latitude * kRad;
  const double cos_zenith = std::clamp(
      std::sin(lat) * std::sin(declination) + std::cos(lat) * std::cos(declination) * std::cos(hour_angle * kRad), -1.0,
      1.0);
  const double zenith = std::acos(cos_zenith);
  const double elevation = 90.0 - zenith / kRad;

  double refraction_arcsec = 0;
  if (elevation <= 85.0) {
    const double te = std::tan(elevation * kRad);
    if (elevation > 5.0)
      refraction_arcsec = 58.1 / te - 0.07 / (te * te * te) + 0.000086 / std::pow(te, 5);
    else if (elevation > -0.575)
      refraction_arcsec =
          1735.0 + elevation * (-518.2 + elevation * (103.4 + elevation * (-12.79 + elevation * 0.711)));
    else
      refraction_arcsec = -20.772 / te;
  }

  double azimuth = 0;
  const double denominator = std::cos(lat) * std::sin(zenith);
  if (std::fabs(denominator) > 1e-12) {
    const double cos_azimuth =
        std::clamp((std::sin(lat) * std::cos(zenith) - std::sin(declination)) / denominator, -1.0, 1.0);
    const double a = std::acos(cos_azimuth) / kRad;
    azimuth = hour_angle > 0 ? std::fmod(a + 180.0, 360.0) : std::fmod(540.0 - a, 360.0);
  } else {
    azimuth = latitude > 0 ? 180.0 : 0.0;
  }
  return {azimuth, elevation + refraction_arcsec / 3600.0, elevation};
}

}  // namespace wangscape
