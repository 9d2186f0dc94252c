// Height, normal and slope at ENU points: equal to the file's values at its samples,
// bilinear between them, no-data respected, consistent gradients, thread-safe.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <thread>

#include "terrain/terrain.h"
#include "terrain_test_support.h"

namespace wangscape {
namespace {

const Terrain& helens() {
  static const Terrain terrain = Terrain::load(test::saint_helens());
  return terrain;
}

// A random sample whose cell neighbourhood has data all around.
std::pair<int, int> interior_sample(const DemRaster& dem, std::mt19937& rng) {
  for (;;) {
    const int col = std::uniform_int_distribution<int>(1, dem.width - 2)(rng);
    const int row = std::uniform_int_distribution<int>(1, dem.height - 2)(rng);
    bool all = true;
    for (int dr = -1; dr <= 1; ++dr)
      for (int dc = -1; dc <= 1; ++dc) all = all && dem.at(col + dc, row + dr).has_value();
    if (all) return {col, row};
  }
}

void expect_heights_match_samples(const Terrain& terrain) {
  const DemRaster& dem = terrain.dem();
  std::mt19937 rng(11);
  for (int k = 0; k < 500; ++k) {
    const auto [col, row] = interior_sample(dem, rng);
    double x = col, y = row;
    terrain.samples_to_enu(std::span(&x, 1), std::span(&y, 1));
    const auto h = terrain.height(x, y);
    ASSERT_TRUE(h.has_value());
    // The lattice maps to the sample within ~1e-5 samples; times the steepest local
    // difference, that is well under a centimeter.
    EXPECT_NEAR(*h, *dem.at(col, row), 0.01) << col << ", " << row;
    // Half way to the east neighbour: the average (bilinear is linear along a row).
    double mx = col + 0.5, my = row;
    terrain.samples_to_enu(std::span(&mx, 1), std::span(&my, 1));
    EXPECT_NEAR(*terrain.height(mx, my), (*dem.at(col, row) + *dem.at(col + 1, row)) / 2, 0.01);
  }
}

TEST(Sampling, SainteHelensHeightsAreTheFileValuesAtSamples) { expect_heights_match_samples(helens()); }

TEST(Sampling, BoulderHeightsAreTheFileValuesAtSamples) {
  expect_heights_match_samples(Terrain::load(test::boulder()));
}

TEST(Sampling, NodataAndOutsideGiveNoHeight) {
  const Terrain& terrain = helens();
  const DemRaster& dem = terrain.dem();
  const Extent e = terrain.extent();
  EXPECT_FALSE(terrain.height(e.max_x + 1, 0).has_value());
  EXPECT_FALSE(terrain.height(0, e.min_y - 1).has_value());
  EXPECT_FALSE(terrain.height(std::nan(""), 0).has_value());
  EXPECT_FALSE(terrain.slope_degrees(e.max_x + 1, 0).has_value());
  // Every no-data sample has no ground at its position, and cells touching it neither.
  int checked = 0;
  for (int row = 0; row < dem.height; row += 3)
    for (int col = 0; col < dem.width; col += 3) {
      if (dem.at(col, row)) continue;
      double x = col, y = row;
      terrain.samples_to_enu(std::span(&x, 1), std::span(&y, 1));
      EXPECT_FALSE(terrain.height(x, y).has_value()) << col << ", " << row;
      ++checked;
    }
  EXPECT_GT(checked, 100);
  // Heights within the file's range everywhere they exist.
  std::mt19937 rng(5);
  for (int k = 0; k < 20000; ++k) {
    const double x = std::uniform_real_distribution<double>(e.min_x, e.max_x)(rng);
    const double y = std::uniform_real_distribution<double>(e.min_y, e.max_y)(rng);
    if (const auto h = terrain.height(x, y)) {
      ASSERT_GE(*h, dem.min_height);
      ASSERT_LE(*h, dem.max_height);
    }
  }
}

TEST(Sampling, GradientNormalAndSlopeAgreeWithFiniteDifferences) {
  const Terrain& terrain = helens();
  const Extent e = terrain.extent();
  std::mt19937 rng(3);
  int checked = 0;
  const double d = 1e-3;  // meters: a difference this small rarely straddles a cell edge
  for (int k = 0; k < 3000; ++k) {
    const double x = std::uniform_real_distribution<double>(e.min_x, e.max_x)(rng);
    const double y = std::uniform_real_distribution<double>(e.min_y, e.max_y)(rng);
    const auto s = terrain.sample(x, y);
    const auto hx0 = terrain.height(x - d, y), hx1 = terrain.height(x + d, y);
    const auto hy0 = terrain.height(x, y - d), hy1 = terrain.height(x, y + d);
    if (!s || !hx0 || !hx1 || !hy0 || !hy1) continue;
    ++checked;
    EXPECT_NEAR(s->height, *terrain.height(x, y), 1e-9);
    EXPECT_NEAR(s->dz_dx, (*hx1 - *hx0) / (2 * d), 0.02);
    EXPECT_NEAR(s->dz_dy, (*hy1 - *hy0) / (2 * d), 0.02);
    const auto n = *terrain.normal(x, y);
    EXPECT_NEAR(n[0] * n[0] + n[1] * n[1] + n[2] * n[2], 1.0, 1e-12);
    EXPECT_GT(n[2], 0.0);
    EXPECT_NEAR(*terrain.slope_degrees(x, y), std::acos(n[2]) * 180 / std::numbers::pi, 1e-9);
  }
  EXPECT_GT(checked, 2000);
}

TEST(Sampling, ThreadSafeAndDeterministic) {
  const Terrain& terrain = helens();
  const Extent e = terrain.extent();
  std::vector<double> xs(100000), ys(100000);
  std::mt19937 rng(9);
  for (std::size_t k = 0; k < xs.size(); ++k) {
    xs[k] = std::uniform_real_distribution<double>(e.min_x, e.max_x)(rng);
    ys[k] = std::uniform_real_distribution<double>(e.min_y, e.max_y)(rng);
  }
  auto heights = [&](std::size_t begin, std::size_t end, std::vector<double>& out) {
    for (std::size_t k = begin; k < end; ++k) out[k] = terrain.height(xs[k], ys[k]).value_or(-1);
  };
  std::vector<double> serial(xs.size()), parallel(xs.size());
  heights(0, xs.size(), serial);
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back(heights, xs.size() * t / 4, xs.size() * (t + 1) / 4, std::ref(parallel));
  for (auto& t : threads) t.join();
  EXPECT_EQ(serial, parallel);
}

}  // namespace
}  // namespace wangscape
