// The wind's field of leans (scene/wind.h), over many winds and places: it travels with the wind
// at its speed, a plant always leans downwind within the strength, neighbours lean together and
// far plants do not, and the rotation leans a plant's top the way the lean says. The [wind]
// section is read with its ranges.
#include "scene/wind.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "scene/scene_file.h"

namespace wangscape {
namespace {

constexpr double kRadiansPerDegree = std::numbers::pi / 180;

WindConfig random_wind(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> direction(0, 360), strength(1, 45), scale(2, 60), speed(0.5, 15);
  return {direction(rng), strength(rng), scale(rng), speed(rng)};
}

TEST(Wind, TheFieldTravelsWithTheWindAtItsSpeed) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> place(-5000, 5000), time(0, 100), step(0.01, 30);
  for (int trial = 0; trial < 400; ++trial) {
    const WindConfig config = random_wind(rng);
    const WindField field = wind_field(config);
    const double e = place(rng), n = place(rng), t = time(rng), dt = step(rng);
    const double toward = config.direction * kRadiansPerDegree;
    const double travel = config.speed * dt;
    const WindLean here = field.lean(e, n, t);
    const WindLean later = field.lean(e + travel * std::sin(toward), n + travel * std::cos(toward), t + dt);
    EXPECT_NEAR(here.east, later.east, 1e-6 * config.strength) << "trial " << trial;
    EXPECT_NEAR(here.north, later.north, 1e-6 * config.strength) << "trial " << trial;
    // And it does change where it does not travel along: the plant itself sways.
    if (trial % 4 == 0) {
      double change = 0;
      for (int k = 1; k <= 20; ++k) {
        const WindLean other = field.lean(e, n, t + k * 0.37 * config.gust_scale / config.speed);
        change = std::max(change, std::hypot(other.east - here.east, other.north - here.north));
      }
      EXPECT_GT(change, 0.1 * config.strength) << "trial " << trial;
    }
  }
}

TEST(Wind, APlantLeansDownwindWithinTheStrength) {
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> place(-3000, 3000), time(0, 600);
  for (int trial = 0; trial < 100; ++trial) {
    const WindConfig config = random_wind(rng);
    const WindField field = wind_field(config);
    const double toward = config.direction * kRadiansPerDegree;
    double least = 1e9, most = -1e9;
    for (int k = 0; k < 500; ++k) {
      const WindLean lean = field.lean(place(rng), place(rng), time(rng));
      const double along = lean.east * std::sin(toward) + lean.north * std::cos(toward);
      const double across = lean.east * std::cos(toward) - lean.north * std::sin(toward);
      least = std::min(least, along);
      most = std::max(most, along);
      ASSERT_LE(std::abs(across), 0.15 * config.strength + 1e-9);
    }
    EXPECT_GE(least, 0.10 * config.strength - 1e-9);
    EXPECT_LE(most, config.strength + 1e-9);
    // Gusts come and go: the lean spans much of its range.
    EXPECT_GT(most - least, 0.4 * config.strength) << "trial " << trial;
  }
}

// The correlation over time of the leans along the wind of two plants `apart` meters apart.
double lean_correlation(const WindField& field, const WindConfig& config, double apart, double across_angle) {
  const double angle = (config.direction + across_angle) * kRadiansPerDegree;
  std::vector<double> a, b;
  for (int k = 0; k < 4000; ++k) {
    const double t = k * 0.05;
    a.push_back(field.lean(100, 200, t).east);
    b.push_back(field.lean(100 + apart * std::sin(angle), 200 + apart * std::cos(angle), t).east);
  }
  const auto mean = [](const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x;
    return s / double(v.size());
  };
  const double ma = mean(a), mb = mean(b);
  double ab = 0, aa = 0, bb = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ab += (a[i] - ma) * (b[i] - mb);
    aa += (a[i] - ma) * (a[i] - ma);
    bb += (b[i] - mb) * (b[i] - mb);
  }
  return ab / std::sqrt(aa * bb);
}

TEST(Wind, NeighboursSwayTogetherAndFarPlantsDoNot) {
  const WindConfig config{90, 15, 20, 4};  // toward east: lean.east is the lean along the wind
  const WindField field = wind_field(config);
  for (const double across_angle : {0.0, 90.0}) {
    EXPECT_GT(lean_correlation(field, config, 0.3, across_angle), 0.95) << across_angle;
    // 2 to 6 gusts apart: a sum of a few waves never forgets wholly, but mostly.
    double far = 0;
    for (int k = 0; k <= 40; ++k) far += std::abs(lean_correlation(field, config, 40 + 2 * k, across_angle)) / 41;
    EXPECT_LT(far, 0.5) << across_angle;
  }
}

TEST(Wind, TheRotationLeansThePlantsTopAsTheLeanSays) {
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> degrees(-40, 40);
  for (int trial = 0; trial < 200; ++trial) {
    const WindLean lean{degrees(rng), degrees(rng)};
    const auto r = lean_rotation(lean);
    // Orthonormal, not a mirror.
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        double dot = 0;
        for (int k = 0; k < 3; ++k) dot += r[3 * k + i] * r[3 * k + j];
        EXPECT_NEAR(dot, i == j ? 1 : 0, 1e-12);
      }
    const double det =
        r[0] * (r[4] * r[8] - r[5] * r[7]) - r[1] * (r[3] * r[8] - r[5] * r[6]) + r[2] * (r[3] * r[7] - r[4] * r[6]);
    EXPECT_NEAR(det, 1, 1e-12);
    // The top (0, 0, 1) moves toward north by sin(north) first, then turns toward east by east.
    const double top[3] = {r[2], r[5], r[8]};
    EXPECT_NEAR(top[1], std::sin(lean.north * kRadiansPerDegree), 1e-12);
    EXPECT_NEAR(std::atan2(top[0], top[2]), lean.east * kRadiansPerDegree, 1e-12);
  }
  const auto calm = lean_rotation({});
  for (int k = 0; k < 9; ++k) EXPECT_EQ(calm[k], k % 4 == 0 ? 1.0 : 0.0);
}

TEST(Wind, TheSectionIsReadWithItsRanges) {
  const auto parse = [](const std::string& text) { return parse_scene_config(text, "wind.toml", "."); };
  EXPECT_FALSE(parse("name = \"calm\"\n").wind);
  const SceneConfig config = parse("[wind]\ndirection = 45\nstrength = 12.5\ngust_scale = 8\nspeed = 6\n");
  ASSERT_TRUE(config.wind);
  EXPECT_EQ(config.wind->direction, 45);
  EXPECT_EQ(config.wind->strength, 12.5);
  EXPECT_EQ(config.wind->gust_scale, 8);
  EXPECT_EQ(config.wind->speed, 6);
  const SceneConfig defaults = parse("[wind]\n");
  ASSERT_TRUE(defaults.wind);
  EXPECT_EQ(defaults.wind->strength, WindConfig{}.strength);
  const auto refused = [&](const std::string& text, const std::string& expected) {
    try {
      parse(text);
      ADD_FAILURE() << "accepted: " << text;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  };
  refused("[wind]\nstrength = 60\n", "wind.toml:2: 'wind.strength' must be between 0 and 45");
  refused("[wind]\n\ndirection = -10\n", "wind.toml:3: 'wind.direction' must be between 0 and 360");
  refused("[wind]\ngust_scale = 0\n", "'wind.gust_scale' must be between 0.5 and 100000");
  refused("[wind]\nspeed = nan\n", "'wind.speed' must be a finite number");
  refused("[wind]\nstrenght = 5\n", "strenght");
}

}  // namespace
}  // namespace wangscape
