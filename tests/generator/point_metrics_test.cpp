// Point metrics against sets whose figures are known: a hexagonal lattice, uniform random
// points, a hand-made set with close pairs.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "generator/point_metrics.h"
#include "generator/poisson_tiles.h"

namespace wangscape {
namespace {

TEST(PointMetrics, HexagonalLatticeHasRhoOneAndNoSpread) {
  std::vector<float> x, y;
  const double a = 0.5, h = a * std::sqrt(3.0) / 2;
  for (int row = 0; row < 80; ++row)
    for (int col = 0; col < 80; ++col) {
      x.push_back(static_cast<float>(col * a + (row % 2) * a / 2 + 0.1));
      y.push_back(static_cast<float>(row * h + 0.1));
    }
  PointMetricsOptions options;
  options.area = {0, 0, 80 * a, 80 * h};
  options.packing_diameter = a * 0.99;
  options.spectrum = false;
  const PointMetrics m = measure_points(x, y, options);
  EXPECT_NEAR(m.rho, 1.0, 0.01);
  EXPECT_NEAR(m.mean_nn, 1.0, 0.01);
  EXPECT_LT(m.nn_spread, 1e-3);
  EXPECT_EQ(m.close_pairs, 0u);
}

TEST(PointMetrics, UniformRandomPointsAreWhiteAndEvenlySpread) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 32.0f);
  std::vector<float> x(20000), y(20000);
  for (std::size_t k = 0; k < x.size(); ++k) x[k] = u(rng), y[k] = u(rng);
  PointMetricsOptions options;
  options.area = {0, 0, 32, 32};
  options.tile_size = 1;
  options.packing_diameter = 0.1;
  options.spectrum_window_tiles = 4;
  const PointMetrics m = measure_points(x, y, options);
  EXPECT_LT(m.rho, 0.05);
  // Poisson process: mean NN distance 1 / (2 sqrt(density)), over the hexagonal spacing.
  EXPECT_NEAR(m.mean_nn, 0.5 / std::sqrt(x.size() / 1024.0) / m.spacing, 0.02);
  EXPECT_NEAR(m.edge_density_ratio, 1.0, 0.05);
  EXPECT_NEAR(m.corner_density_ratio, 1.0, 0.1);
  ASSERT_FALSE(m.spectrum.power.empty());
  double mean_power = 0;
  for (double p : m.spectrum.power) mean_power += p / m.spectrum.power.size();
  EXPECT_NEAR(mean_power, 1.0, 0.1);
  EXPECT_NEAR(m.spectrum.mean_anisotropy_db, m.spectrum.noise_floor_db, 1.5);
}

TEST(PointMetrics, CountsExactlyThePairsCloserThanTheDiameter) {
  const std::vector<float> x = {1.0f, 1.05f, 3.0f, 3.0f, 5.0f, 5.3f};
  const std::vector<float> y = {1.0f, 1.0f, 3.0f, 3.09f, 5.0f, 5.0f};
  EXPECT_EQ(count_close_pairs(x, y, {0, 0, 8, 8}, 0.1), 2u);
  EXPECT_EQ(count_close_pairs(x, y, {0, 0, 8, 8}, 0.5), 3u);
  const NeighbourStats nn = nearest_neighbour_stats(x, y, {0, 0, 8, 8});
  EXPECT_NEAR(nn.min_distance, 0.05, 1e-6);
}

TEST(PointMetrics, HexagonalSpacing) { EXPECT_NEAR(hexagonal_spacing(1.0, 20.0), 0.24028, 1e-5); }

}  // namespace
}  // namespace wangscape
