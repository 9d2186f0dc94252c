// Statistics of a tiling: is it valid, how often each tile occurs, how often neighbours are
// identical, and how periodic it looks.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "generator/tiling.h"

namespace wangscape {

struct TilingStats {
  bool valid = false;
  std::string invalid_reason;              // check_tiling's message when !valid
  std::vector<std::uint64_t> frequencies;  // occurrences per tile index of the set
  double identical_neighbour_rate = 0.0;   // fraction of E-W and N-S neighbour pairs that are the same tile
  double periodicity = 0.0;                // see periodicity_score
  int period_di = 0, period_dj = 0;        // the offset (tiles) where that peak is
};

struct PeriodicityPeak {
  double score = 0.0;  // 1: the tiling repeats at this offset; near 0: no more alike than chance
  int di = 0, dj = 0;  // offset in tiles (di east, dj north)
};

// Largest off-origin peak of the autocorrelation of the tile-index field, normalised: for
// each offset d with |di|, |dj| <= max_offset (and within half the window), the probability
// that a tile equals the tile at +d, minus the chance level sum_k f_k^2, over 1 - sum_k f_k^2.
// A periodic tiling scores ~1 at its period; a stochastic one scores near 0. Evaluated on at
// most the central 256 x 256 tiles. A single-tile tiling scores 1.
PeriodicityPeak periodicity_score(const Tiling& tiling, int max_offset = 32);

// The normalised autocorrelation that periodicity_score maximises, at one offset (di east, dj
// north, either sign), over the whole tiling: 0 for tiles no more alike than chance, 1 where every
// tile equals the one at +d, 0 when no pair of tiles is that far apart.
double autocorrelation_at(const Tiling& tiling, int di, int dj);

TilingStats compute_tiling_stats(const TileSet& set, const Tiling& tiling);

}  // namespace wangscape
