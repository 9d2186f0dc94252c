// The periodicity score (generator/tiling_stats.h) with and without forbid_identical_neighbours over
// many seeds, with the standard errors that say whether a difference is more than seed noise (one
// tiling's score is mostly noise; 200 seeds leave about +-1 % of the plain score at 64 and 128).
// The library directly, so no process per tiling (bench/no_identical_neighbours_bench.sh runs the CLI).
//   build/release/bench/no_identical_neighbours_seeds_bench corner-2 hash 128 200
// Prints the mean score without and with the option (+- standard error), their paired difference
// as a share of the plain score, and the tile frequencies with the option (chance level, extremes).
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bench/mean_and_error.h"
#include "core/error.h"
#include "generator/tiling.h"
#include "generator/tiling_stats.h"

int main(int argc, char** argv) {
  using namespace wangscape;
  using bench::MeanAndError;
  if (argc != 5) {
    std::fprintf(stderr, "usage: %s SET ALGORITHM SIZE SEEDS (e.g. corner-2 hash 128 200)\n", argv[0]);
    return 2;
  }
  try {
    const TileSet set = builtin_tileset(argv[1]);
    const TilingAlgorithm algorithm = parse_tiling_algorithm(argv[2]);
    const int size = std::atoi(argv[3]), seeds = std::atoi(argv[4]);
    if (size < 2 || seeds < 2)
      throw Error(std::string("no_identical_neighbours_seeds_bench: SIZE '") + argv[3] + "', SEEDS '" + argv[4] +
                  "': expected whole numbers of at least 2");
    MeanAndError plain, forbidden, difference;
    std::vector<double> frequency(set.size(), 0.0);
    for (int seed = 1; seed <= seeds; ++seed) {
      TilingOptions options;
      options.algorithm = algorithm;
      options.seed = static_cast<std::uint64_t>(seed);
      const double without = periodicity_score(make_tiling(set, size, size, options)).score;
      options.forbid_identical_neighbours = true;
      const TilingStats stats = compute_tiling_stats(set, make_tiling(set, size, size, options));
      if (!stats.valid) throw Error("no_identical_neighbours_seeds_bench: " + stats.invalid_reason);
      const double with = stats.periodicity;
      for (std::size_t t = 0; t < set.size(); ++t)
        frequency[t] += static_cast<double>(stats.frequencies[t]) / (static_cast<double>(size) * size * seeds);
      plain.add(without);
      forbidden.add(with);
      difference.add(with - without);
    }
    double chance = 0, lowest = 1, highest = 0;
    for (const double f : frequency) {
      chance += f * f;
      lowest = std::min(lowest, f);
      highest = std::max(highest, f);
    }
    std::printf(
        "%s %s %d x %d, seeds 1-%d: without %.5f +- %.5f, with %.5f +- %.5f, difference %+.5f +- %.5f (%+.1f %% "
        "+- %.1f %%); with the option: tile frequencies %.4f..%.4f (1/%zu = %.4f), chance level %.4f\n",
        argv[1], argv[2], size, size, seeds, plain.mean(), plain.error(), forbidden.mean(), forbidden.error(),
        difference.mean(), difference.error(), 100 * difference.mean() / plain.mean(),
        100 * difference.error() / plain.mean(), lowest, highest, set.size(), 1.0 / static_cast<double>(set.size()),
        chance);
  } catch (const Error& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
