// The sun from a date and time, against published solar positions (within 0.1 degree), and the
// direction vector of a compass azimuth and elevation.
#include "scene/sun.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>

namespace wangscape {
namespace {

std::int64_t unix_time(int y, unsigned mo, unsigned d, int h, int mi, int s, int utc_offset_minutes = 0) {
  using namespace std::chrono;
  const sys_days day = year_month_day{year{y}, month{mo}, std::chrono::day{d}};
  return (day.time_since_epoch() + hours{h} + minutes{mi} + seconds{s} - minutes{utc_offset_minutes}).count();
}

struct Published {
  const char* where;
  double latitude, longitude;
  std::int64_t time;
  double azimuth, elevation;  // degrees; elevation with refraction, as NOAA's calculator gives it
};

// Sources: (1) NOAA's solar calculator (gml.noaa.gov/grad/solcalc) for the default scene's
// evening; (2) the worked example of NREL's Solar Position Algorithm (Reda & Andreas 2004,
// topocentric zenith 50.11162 deg, azimuth 194.34024 deg); (3) the reference table of the
// Toit solar-position package's tests (its source is not stated; its elevations include
// refraction, as NOAA's do).
const Published kPublished[] = {
    {"Mount St. Helens, July evening", 46.1914, -122.1956, unix_time(2024, 7, 20, 18, 30, 0, -7 * 60), 276.8, 22.3},
    {"Golden, Colorado (NREL SPA example)", 39.742476, -105.1786, unix_time(2003, 10, 17, 12, 30, 30, -7 * 60),
     194.34024, 90 - 50.11162},
    {"Tranbjerg, Denmark, October morning", 56.09, 10.1337, unix_time(2021, 10, 11, 8, 0, 0), 131.43, 16.17},
    {"Tranbjerg, Denmark, new year 2000", 56.09, 10.1337, unix_time(2000, 1, 1, 12, 0, 0), 188.71, 10.57},
    {"Troll station, Antarctica", -72.011667, 2.53472, unix_time(2000, 1, 1, 12, 0, 0), 357.92, 41.03},
    {"Rapa Nui, June evening", -27.11667, -109.36667, unix_time(2024, 6, 1, 0, 5, 0), 297.63, 4.63},
    {"Saint Martin, June dawn", 18.176191456792704, -63.11793075444335, unix_time(2024, 6, 1, 9, 0, 0), 63.23, -8.5},
};

TEST(Sun, AgreesWithPublishedPositionsWithinATenthOfADegree) {
  for (const auto& p : kPublished) {
    const SolarPosition s = solar_position(p.latitude, p.longitude, p.time);
    EXPECT_NEAR(s.azimuth_degrees, p.azimuth, 0.1) << p.where;
    EXPECT_NEAR(s.elevation_degrees, p.elevation, 0.1) << p.where;
  }
}

TEST(Sun, RefractionLiftsTheSunNearTheHorizonOnly) {
  const auto low = solar_position(-27.11667, -109.36667, unix_time(2024, 6, 1, 0, 5, 0));
  EXPECT_GT(low.elevation_degrees - low.true_elevation_degrees, 0.1);  // about 0.17 deg at 4.6 deg
  const auto high = solar_position(-72.011667, 2.53472, unix_time(2000, 1, 1, 12, 0, 0));
  EXPECT_LT(high.elevation_degrees - high.true_elevation_degrees, 0.03);
}

TEST(Sun, DirectionFollowsTheCompass) {
  const auto north = Sun{0, 0, 1}.direction();
  EXPECT_NEAR(north[1], 1, 1e-12);
  const auto east = Sun{90, 0, 1}.direction();
  EXPECT_NEAR(east[0], 1, 1e-12);
  const auto up = Sun{123, 90, 1}.direction();
  EXPECT_NEAR(up[2], 1, 1e-12);
  const auto d = Sun{225, 30, 1}.direction();
  EXPECT_NEAR(std::hypot(d[0], d[1], d[2]), 1, 1e-12);
  EXPECT_LT(d[0], 0);
  EXPECT_LT(d[1], 0);
  EXPECT_NEAR(d[2], 0.5, 1e-12);
}

}  // namespace
}  // namespace wangscape
