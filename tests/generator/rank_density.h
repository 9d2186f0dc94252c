// Where a fill's points of low progressive rank fall across one tile: the rank test's profile
// (tests/generator/poisson_rank_test.cpp) and bench/poisson_bench.cpp's table and picture
// (docs/images/rank-density-across-tile.png) count them the same way.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "generator/poisson_tiles.h"

namespace wangscape::testing {

// Per d of `densities`, how many points of rank < d fall in each of bins x bins squares of a
// tile, [row * bins + column] (row 0 at y = 0, column 0 at x = 0): every tile of `set` counted
// once (a point counts in each tile that holds it), summed over the fills of seeds 1..fills
// (options.seed is replaced).
inline std::vector<std::vector<double>> rank_counts_across_tile(const TileSet& set, PoissonFillOptions options,
                                                                std::span<const double> densities, int fills,
                                                                int bins) {
  std::vector<std::vector<double>> count(densities.size(), std::vector<double>(std::size_t(bins) * bins, 0.0));
  const auto bin = [bins](float v) { return static_cast<std::size_t>(std::min(bins - 1, static_cast<int>(v * bins))); };
  for (int seed = 1; seed <= fills; ++seed) {
    options.seed = static_cast<std::uint64_t>(seed);
    for (const auto& tile : fill_poisson_tiles(set, options).tiles)
      for (const TilePoint& p : tile)
        for (std::size_t k = 0; k < densities.size(); ++k)
          if (p.rank < densities[k]) count[k][bin(p.y) * std::size_t(bins) + bin(p.x)] += 1;
  }
  return count;
}

// The progressive rank's evenness: per d of `densities`, the density of the points of rank < d
// across a tile in `bands` bands of 1 / bands tile sides (x and y pooled), over the mean band,
// counted as rank_counts_across_tile does. 1 everywhere: no tile grid shows.
inline std::vector<std::vector<double>> rank_density_across_tile(const TileSet& set, PoissonFillOptions options,
                                                                 std::span<const double> densities, int fills,
                                                                 int bands = 20) {
  std::vector<std::vector<double>> profiles;
  for (const std::vector<double>& count : rank_counts_across_tile(set, options, densities, fills, bands)) {
    std::vector<double>& profile = profiles.emplace_back(std::size_t(bands), 0.0);
    for (std::size_t row = 0; row < std::size_t(bands); ++row)
      for (std::size_t column = 0; column < std::size_t(bands); ++column) {
        profile[row] += count[row * std::size_t(bands) + column];
        profile[column] += count[row * std::size_t(bands) + column];
      }
    double mean = 0;
    for (const double c : profile) mean += c / bands;
    for (double& c : profile) c /= mean;
  }
  return profiles;
}

}  // namespace wangscape::testing
