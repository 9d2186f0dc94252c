// Structure against noise in sweep tilings without identical neighbours (issue 23 item 3). The
// periodicity score (generator/tiling_stats.h) is the peak of every offset's autocorrelation, so
// it rises either with structure (an offset alike more often than chance in every tiling) or with
// noise (each tiling's autocorrelation straying further from its mean). Over SEEDS tilings of
// SIZE x SIZE, without and with the option:
//   - the mean score (+- standard error) and the paired difference as a share of the plain score;
//   - structure: the largest mean autocorrelation, over the seeds, at an offset within 6 tiles
//     other than the origin and its four neighbours (which the option forbids);
//   - noise: 1 + sum over offsets r within 4 of (sum_kl P_kl(r)^2 - chance^2) / (chance - chance^2),
//     P_kl(r) the share of tiles k with an l at +r (pooled over the seeds). A far offset's
//     autocorrelation has about this times the variance of tiles drawn independently
//     (docs/tileset-format.md); each term is 0 where the tiles at r are independent, and with every
//     tile equally frequent above 0 otherwise.
//   build/release/bench/no_identical_neighbours_structure_bench cohen8 scanline 128 100
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bench/mean_and_error.h"
#include "core/error.h"
#include "generator/tiling.h"
#include "generator/tiling_stats.h"

namespace wangscape {
namespace {

using bench::MeanAndError;

constexpr int kStructureReach = 6, kNoiseReach = 4;

constexpr int kNoiseSide = 2 * kNoiseReach + 1;

// What one kind of tiling (without or with the option) gathers over the seeds.
struct Kind {
  explicit Kind(std::size_t tile_count)
      : mean_autocorrelation((kStructureReach + 1) * (2 * kStructureReach + 1), 0.0),
        joint(kNoiseSide * kNoiseSide * tile_count * tile_count, 0.0),
        frequency(tile_count, 0.0) {}
  MeanAndError score;
  std::vector<double> mean_autocorrelation;  // offsets (di, dj), |di| <= kStructureReach, 0 <= dj <= kStructureReach
  std::vector<double> joint;                 // pooled pair counts per noise offset and (k, l)
  std::vector<double> frequency;
  double tiles = 0;
};

std::size_t structure_index(int di, int dj) {
  return static_cast<std::size_t>(dj * (2 * kStructureReach + 1) + di + kStructureReach);
}

// Adds one tiling; returns its score.
double add(Kind& kind, const Tiling& tiling, std::size_t tile_count, int seeds) {
  const double score = periodicity_score(tiling).score;
  kind.score.add(score);
  for (int dj = 0; dj <= kStructureReach; ++dj)
    for (int di = -kStructureReach; di <= kStructureReach; ++di)
      kind.mean_autocorrelation[structure_index(di, dj)] += autocorrelation_at(tiling, di, dj) / seeds;
  // Tiles at least kNoiseReach from the border, so every offset sees the same tiles.
  for (int j = kNoiseReach; j < tiling.height - kNoiseReach; ++j)
    for (int i = kNoiseReach; i < tiling.width - kNoiseReach; ++i) {
      const std::size_t k = tiling.at(i, j);
      kind.frequency[k] += 1;
      kind.tiles += 1;
      for (int dj = -kNoiseReach; dj <= kNoiseReach; ++dj)
        for (int di = -kNoiseReach; di <= kNoiseReach; ++di) {
          const auto r = static_cast<std::size_t>((dj + kNoiseReach) * kNoiseSide + di + kNoiseReach);
          kind.joint[(r * tile_count + k) * tile_count + tiling.at(i + di, j + dj)] += 1;
        }
    }
  return score;
}

struct Summary {
  double highest = -1;
  int di = 0, dj = 0;
  double chance = 0, noise = 1;
};

Summary summarise(const Kind& kind, std::size_t tile_count) {
  Summary s;
  for (int dj = 0; dj <= kStructureReach; ++dj)
    for (int di = -kStructureReach; di <= kStructureReach; ++di)
      if (std::abs(di) + dj > 1 && kind.mean_autocorrelation[structure_index(di, dj)] > s.highest)
        s = {kind.mean_autocorrelation[structure_index(di, dj)], di, dj, 0, 1};
  for (const double f : kind.frequency) s.chance += (f / kind.tiles) * (f / kind.tiles);
  const std::size_t pairs = tile_count * tile_count;
  for (std::size_t r = 0; r * pairs < kind.joint.size(); ++r) {
    if (r == kind.joint.size() / pairs / 2) continue;  // the origin
    double sum = 0;
    for (std::size_t kl = 0; kl < pairs; ++kl)
      sum += (kind.joint[r * pairs + kl] / kind.tiles) * (kind.joint[r * pairs + kl] / kind.tiles);
    s.noise += (sum - s.chance * s.chance) / (s.chance - s.chance * s.chance);
  }
  return s;
}

}  // namespace
}  // namespace wangscape

int main(int argc, char** argv) {
  using namespace wangscape;
  if (argc != 5) {
    std::fprintf(stderr, "usage: %s SET ALGORITHM SIZE SEEDS (e.g. cohen8 scanline 128 100)\n", argv[0]);
    return 2;
  }
  try {
    const TileSet set = builtin_tileset(argv[1]);
    const TilingAlgorithm algorithm = parse_tiling_algorithm(argv[2]);
    const int size = std::atoi(argv[3]), seeds = std::atoi(argv[4]);
    if (size < 2 * kNoiseReach + 2 || seeds < 2)
      throw Error(std::string("no_identical_neighbours_structure_bench: SIZE '") + argv[3] + "', SEEDS '" + argv[4] +
                  "': expected whole numbers of at least 10 and 2");
    Kind plain(set.size()), forbidden(set.size());
    MeanAndError difference;
    for (int seed = 1; seed <= seeds; ++seed) {
      TilingOptions options;
      options.algorithm = algorithm;
      options.seed = static_cast<std::uint64_t>(seed);
      const double without = add(plain, make_tiling(set, size, size, options), set.size(), seeds);
      options.forbid_identical_neighbours = true;
      difference.add(add(forbidden, make_tiling(set, size, size, options), set.size(), seeds) - without);
    }
    std::printf("%s %s %d x %d, seeds 1-%d: score without %.5f +- %.5f, with %.5f +- %.5f (%+.1f %% +- %.1f %%)\n",
                argv[1], argv[2], size, size, seeds, plain.score.mean(), plain.score.error(), forbidden.score.mean(),
                forbidden.score.error(), 100 * difference.mean() / plain.score.mean(),
                100 * difference.error() / plain.score.mean());
    for (const auto& [name, kind] : {std::pair<const char*, const Kind*>{"without", &plain}, {"with", &forbidden}}) {
      const Summary s = summarise(*kind, set.size());
      std::printf("  %-7s: highest mean autocorrelation %+.4f at (%d, %d); chance level %.4f; noise %.3f\n", name,
                  s.highest, s.di, s.dj, s.chance, s.noise);
    }
  } catch (const Error& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
