#include "generator/tiling_stats.h"

#include <algorithm>
#include <optional>

namespace wangscape {

namespace {

// The tiles of a window of a tiling, with the chance that two of them are equal.
struct TileWindow {
  const Tiling& tiling;
  int i0, j0, width, height;
  double chance = 0.0;  // sum over tiles of their frequency squared

  TileWindow(const Tiling& t, int first_i, int first_j, int w, int h)
      : tiling(t), i0(first_i), j0(first_j), width(w), height(h) {
    std::vector<std::uint64_t> counts;
    for (int j = 0; j < height; ++j)
      for (int i = 0; i < width; ++i) {
        const std::uint16_t tile = at(i, j);
        if (tile >= counts.size()) counts.resize(tile + 1u, 0);
        ++counts[tile];
      }
    const double cells = static_cast<double>(width) * height;
    for (const std::uint64_t c : counts) chance += (c / cells) * (c / cells);
  }
  std::uint16_t at(int i, int j) const { return tiling.at(i0 + i, j0 + j); }

  // The normalised autocorrelation at (di, dj), or nothing when no pair is that far apart (or
  // every tile is the same).
  std::optional<double> autocorrelation(int di, int dj) const {
    std::uint64_t equal = 0, pairs = 0;
    for (int j = std::max(0, -dj); j < height && j + dj < height; ++j)
      for (int i = std::max(0, -di); i < width && i + di < width; ++i) {
        equal += at(i, j) == at(i + di, j + dj) ? 1 : 0;
        ++pairs;
      }
    if (pairs == 0 || chance >= 1.0 - 1e-12) return std::nullopt;
    return (static_cast<double>(equal) / static_cast<double>(pairs) - chance) / (1.0 - chance);
  }
};

}  // namespace

PeriodicityPeak periodicity_score(const Tiling& tiling, int max_offset) {
  // The central region the autocorrelation is measured on (bounded cost on huge tilings).
  constexpr int kRegion = 256;
  const int width = std::min(tiling.width, kRegion), height = std::min(tiling.height, kRegion);
  const TileWindow window(tiling, (tiling.width - width) / 2, (tiling.height - height) / 2, width, height);
  if (window.chance >= 1.0 - 1e-12) return {1.0, width > 1 ? 1 : 0, width > 1 ? 0 : 1};

  const int max_di = std::min(max_offset, width / 2), max_dj = std::min(max_offset, height / 2);
  PeriodicityPeak peak{-1.0, 0, 0};
  // Offsets in a half plane (d and -d give the same correlation).
  for (int dj = 0; dj <= max_dj; ++dj)
    for (int di = dj == 0 ? 1 : -max_di; di <= max_di; ++di)
      if (const auto score = window.autocorrelation(di, dj); score && *score > peak.score) peak = {*score, di, dj};
  if (peak.score < 0.0) peak = {0.0, 0, 0};  // windows too small to have any offset
  return peak;
}

double autocorrelation_at(const Tiling& tiling, int di, int dj) {
  return TileWindow(tiling, 0, 0, tiling.width, tiling.height).autocorrelation(di, dj).value_or(0.0);
}

TilingStats compute_tiling_stats(const TileSet& set, const Tiling& tiling) {
  TilingStats stats;
  try {
    check_tiling(set, tiling);
    stats.valid = true;
  } catch (const Error& e) {
    stats.invalid_reason = e.what();
  }
  stats.frequencies.assign(set.size(), 0);
  for (const std::uint16_t t : tiling.tiles)
    if (t < set.size()) ++stats.frequencies[t];
  std::uint64_t identical = 0, pairs = 0;
  for (int j = 0; j < tiling.height; ++j)
    for (int i = 0; i < tiling.width; ++i) {
      if (i + 1 < tiling.width) {
        identical += tiling.at(i, j) == tiling.at(i + 1, j) ? 1 : 0;
        ++pairs;
      }
      if (j + 1 < tiling.height) {
        identical += tiling.at(i, j) == tiling.at(i, j + 1) ? 1 : 0;
        ++pairs;
      }
    }
  stats.identical_neighbour_rate = pairs ? static_cast<double>(identical) / static_cast<double>(pairs) : 0.0;
  const PeriodicityPeak peak = periodicity_score(tiling);
  stats.periodicity = peak.score;
  stats.period_di = peak.di;
  stats.period_dj = peak.dj;
  return stats;
}

}  // namespace wangscape
