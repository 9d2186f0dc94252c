// The tiling interface (generator/tiling.h): algorithm names, the window's checks, streaming and
// whole windows handed to the tiler of each algorithm (tiling_algorithms.h), and the check of a
// finished tiling.
#include "generator/tiling.h"

#include <algorithm>
#include <string>
#include <vector>

#include "generator/tiling_algorithms.h"

namespace wangscape {

using tiling_detail::is_culik13;
using tiling_detail::kSlotNames;

namespace {

void check_size(const TileSet& set, int width, int height) {
  if (width <= 0 || height <= 0)
    throw Error(set.describe() + ": tiling size " + std::to_string(width) + "x" + std::to_string(height) +
                " is empty; expected at least 1x1");
}

// A window that is not empty and whose tile coordinates stay within +-kMaxTileCoordinate.
void check_window(const TileSet& set, int width, int height, const TilingOptions& options) {
  check_size(set, width, height);
  const auto within = [](std::int64_t origin, int size) {
    return origin >= -kMaxTileCoordinate && origin <= kMaxTileCoordinate - size;
  };
  if (!within(options.origin_i, width) || !within(options.origin_j, height))
    throw Error(set.describe() + ": a " + std::to_string(width) + "x" + std::to_string(height) + " window at origin " +
                std::to_string(options.origin_i) + "," + std::to_string(options.origin_j) +
                " reaches beyond tile coordinate +-2^60, the largest a tiling addresses");
  // The other algorithms would stop at the first pair of neighbours with no tile between them.
  if (options.algorithm != TilingAlgorithm::aperiodic && is_culik13(set))
    throw Error(set.describe() + ": Culik's aperiodic set cannot be laid by the " +
                std::string(to_string(options.algorithm)) +
                " algorithm (some neighbours have no tile between them); expected the aperiodic algorithm");
}

}  // namespace

std::string_view to_string(TilingAlgorithm algorithm) {
  switch (algorithm) {
    case TilingAlgorithm::scanline:
      return "scanline";
    case TilingAlgorithm::bottom_left:
      return "bottom-left";
    case TilingAlgorithm::hash:
      return "hash";
    case TilingAlgorithm::aperiodic:
      return "aperiodic";
  }
  return "?";
}

std::optional<TilingAlgorithm> find_tiling_algorithm(std::string_view text) {
  for (const TilingAlgorithm a : kTilingAlgorithms)
    if (text == to_string(a)) return a;
  return std::nullopt;
}

TilingAlgorithm parse_tiling_algorithm(std::string_view text) {
  if (const auto a = find_tiling_algorithm(text)) return *a;
  throw Error("unknown tiling algorithm '" + std::string(text) +
              "'; expected scanline, bottom-left, hash or aperiodic");
}

std::vector<std::string> tiling_algorithm_names() {
  std::vector<std::string> names;
  for (const TilingAlgorithm a : kTilingAlgorithms) names.emplace_back(to_string(a));
  return names;
}

void stream_tiling(const TileSet& set, int width, int height, const TilingOptions& options, const TilingRowSink& row) {
  check_window(set, width, height, options);
  if (options.algorithm == TilingAlgorithm::hash)
    return tiling_detail::stream_hashed_tiling(set, width, height, options, row);
  if (options.algorithm == TilingAlgorithm::aperiodic)
    return tiling_detail::stream_culik_tiling(set, width, height, options, row);
  tiling_detail::stream_sweep_tiling(set, width, height, options, row);
}

Tiling make_tiling(const TileSet& set, int width, int height, const TilingOptions& options,
                   const std::function<void(int rows_done)>& rows_done) {
  check_window(set, width, height, options);
  constexpr std::int64_t kMaxTiles = std::int64_t{1} << 30;
  if (std::int64_t{width} * height > kMaxTiles)
    throw Error("tiling: a window of " + std::to_string(width) + " x " + std::to_string(height) + " = " +
                std::to_string(std::int64_t{width} * height) + " tiles; at most 2^30 (" + std::to_string(kMaxTiles) +
                ") fit in memory");
  Tiling tiling;
  tiling.width = width;
  tiling.height = height;
  tiling.origin_i = options.origin_i;
  tiling.origin_j = options.origin_j;
  tiling.tiles.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height));
  int rows = 0;
  stream_tiling(set, width, height, options, [&](int local_j, std::span<const std::uint16_t> row) {
    std::copy(row.begin(), row.end(), tiling.tiles.begin() + static_cast<std::ptrdiff_t>(local_j) * width);
    if (rows_done) rows_done(++rows);
  });
  return tiling;
}

Tiling make_tiling(const TileSet& set, int width, int height, const TilingOptions& options) {
  check_window(set, width, height, options);
  Tiling tiling;
  tiling.width = width;
  tiling.height = height;
  tiling.origin_i = options.origin_i;
  tiling.origin_j = options.origin_j;
  const auto w = static_cast<std::size_t>(width);
  tiling.tiles.resize(w * static_cast<std::size_t>(height));
  if (options.algorithm == TilingAlgorithm::hash) {
    tiling_detail::fill_hashed_tiling(set, width, height, options, tiling.tiles);
    return tiling;
  }
  stream_tiling(set, width, height, options, [&](int local_j, std::span<const std::uint16_t> tiles) {
    std::copy(tiles.begin(), tiles.end(),
              tiling.tiles.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(local_j) * w));
  });
  return tiling;
}

void check_tiling(const TileSet& set, const Tiling& tiling) {
  const std::string where = "tiling with " + set.describe();
  if (tiling.width <= 0 || tiling.height <= 0 ||
      tiling.tiles.size() != static_cast<std::size_t>(tiling.width) * static_cast<std::size_t>(tiling.height))
    throw Error(where + ": " + std::to_string(tiling.tiles.size()) + " tiles do not fill a " +
                std::to_string(tiling.width) + "x" + std::to_string(tiling.height) + " window");
  const auto position = [&](int li, int lj) {
    return "tile (" + std::to_string(tiling.origin_i + li) + ", " + std::to_string(tiling.origin_j + lj) + ")";
  };
  for (int lj = 0; lj < tiling.height; ++lj)
    for (int li = 0; li < tiling.width; ++li)
      if (tiling.at(li, lj) >= set.size())
        throw Error(where + ": " + position(li, lj) + " is tile " + std::to_string(tiling.at(li, lj)) +
                    "; the set has " + std::to_string(set.size()) + " tiles");
  // Pairs of slots that must agree between a tile and its eastern / northern neighbour.
  struct Match {
    int own, other;
  };
  std::vector<Match> east, north;
  if (set.has_edges) {
    east.push_back({kE, kW});
    north.push_back({kN, kS});
  }
  if (set.has_corners) {
    east.insert(east.end(), {{kNE, kNW}, {kSE, kSW}});
    north.insert(north.end(), {{kNW, kSW}, {kNE, kSE}});
  }
  const auto compare = [&](int li, int lj, int oi, int oj, const std::vector<Match>& matches) {
    const Tile& a = set.tiles[tiling.at(li, lj)];
    const Tile& b = set.tiles[tiling.at(oi, oj)];
    for (const Match& m : matches)
      if (a.colors[static_cast<std::size_t>(m.own)] != b.colors[static_cast<std::size_t>(m.other)])
        throw Error(where + ": " + position(li, lj) + " has " + kSlotNames[static_cast<std::size_t>(m.own)] + "=" +
                    std::to_string(a.colors[static_cast<std::size_t>(m.own)]) + " but " + position(oi, oj) + " has " +
                    kSlotNames[static_cast<std::size_t>(m.other)] + "=" +
                    std::to_string(b.colors[static_cast<std::size_t>(m.other)]));
  };
  for (int lj = 0; lj < tiling.height; ++lj)
    for (int li = 0; li < tiling.width; ++li) {
      if (li + 1 < tiling.width) compare(li, lj, li + 1, lj, east);
      if (lj + 1 < tiling.height) compare(li, lj, li, lj + 1, north);
    }
}

}  // namespace wangscape
