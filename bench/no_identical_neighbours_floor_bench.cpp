// How low a corner tiling without identical neighbours can score (issue 23 item 3): the
// periodicity score (generator/tiling_stats.h) of tilings built by any means against the plain
// hashed tiling's, over many seeds.
//   build/release/bench/no_identical_neighbours_floor_bench corner-2 64 40 6     (97 s)
//   build/release/bench/no_identical_neighbours_floor_bench corner-2 128 16 6    (203 s)
// Per seed, four tilings of SIZE x SIZE: the hashed tiling without and with the option (the
// library), and each of them after a descent that lowers the score's own peaks directly:
// single corners recolored, kept when they lower the sum over the score's offsets of the
// autocorrelation to the fourth power (its peaks) and, for the one with the option, leave no
// identical neighbours; SWEEPS passes over every corner. No random access: every tile may depend
// on every other. Prints each kind's mean score (+- standard error) and its paired difference
// from the plain hashed tiling's as a share of it, the noise the score is the peak of
// (noise_terms) and, from SIZE 97, the peak at offsets the score (and the descent) leave out.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <string>
#include <vector>

#include "bench/mean_and_error.h"
#include "core/error.h"
#include "generator/tiling.h"
#include "generator/tiling_stats.h"

namespace wangscape {
namespace {

using bench::MeanAndError;

// The offsets periodicity_score maximises over (a half plane), with their pair counts.
struct Offset {
  int di, dj;
  double pairs;
};
std::vector<Offset> score_offsets(int size, int max_offset = 32) {
  const int reach = std::min(max_offset, size / 2);
  std::vector<Offset> offsets;
  for (int dj = 0; dj <= reach; ++dj)
    for (int di = dj == 0 ? 1 : -reach; di <= reach; ++di)
      offsets.push_back({di, dj, double(size - std::abs(di)) * double(size - dj)});
  return offsets;
}

// A corner tiling as its (size + 1)^2 corner colors; the tiles follow (corner sets only).
class CornerTiling {
 public:
  CornerTiling(const TileSet& set, const Tiling& start) : size_(start.width), colors_(set.corner_colors) {
    tile_of_.assign(std::size_t(colors_ * colors_ * colors_ * colors_), 0);
    for (std::size_t t = 0; t < set.size(); ++t) {
      const Tile& tile = set.tiles[t];
      tile_of_[key(tile.sw(), tile.se(), tile.nw(), tile.ne())] = std::uint16_t(t);
    }
    corner_.assign(std::size_t(size_ + 1) * std::size_t(size_ + 1), 0);
    for (int j = 0; j < size_; ++j)
      for (int i = 0; i < size_; ++i) {
        const Tile& tile = set.tiles[start.at(i, j)];
        corner(i, j) = tile.sw(), corner(i + 1, j) = tile.se(), corner(i, j + 1) = tile.nw(),
                  corner(i + 1, j + 1) = tile.ne();
      }
    tiles_.resize(std::size_t(size_) * std::size_t(size_));
    for (int j = 0; j < size_; ++j)
      for (int i = 0; i < size_; ++i) tiles_[index(i, j)] = tile_from_corners(i, j);
  }
  int size() const { return size_; }
  int colors() const { return colors_; }
  int& corner(int i, int j) { return corner_[std::size_t(j) * std::size_t(size_ + 1) + std::size_t(i)]; }
  std::uint16_t tile(int i, int j) const { return tiles_[index(i, j)]; }
  std::uint16_t tile_from_corners(int i, int j) {
    return tile_of_[key(corner(i, j), corner(i + 1, j), corner(i, j + 1), corner(i + 1, j + 1))];
  }
  void set_tile(int i, int j, std::uint16_t t) { tiles_[index(i, j)] = t; }
  Tiling tiling() const {
    Tiling t;
    t.width = t.height = size_;
    t.tiles = tiles_;
    return t;
  }

 private:
  std::size_t key(int sw, int se, int nw, int ne) const {
    return std::size_t(((ne * colors_ + nw) * colors_ + se) * colors_ + sw);
  }
  std::size_t index(int i, int j) const { return std::size_t(j) * std::size_t(size_) + std::size_t(i); }
  int size_, colors_;
  std::vector<std::uint16_t> tile_of_;
  std::vector<int> corner_;
  std::vector<std::uint16_t> tiles_;
};

// Lowers sum_d a(d)^4 over the score's offsets (a: the normalised autocorrelation) by recoloring
// single corners, `sweeps` passes in a random order; with `forbid`, no move lays identical
// neighbours. The counts of equal pairs per offset and of each tile are kept up to date.
void descend(CornerTiling& g, const std::vector<Offset>& offsets, bool forbid, int sweeps, std::uint64_t seed,
             std::size_t tile_count) {
  const int n = g.size();
  const double cells = double(n) * n;
  std::vector<double> equal(offsets.size(), 0.0), count(tile_count, 0.0);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) count[g.tile(i, j)] += 1;
  for (std::size_t k = 0; k < offsets.size(); ++k)
    for (int j = 0; j + offsets[k].dj < n; ++j)
      for (int i = std::max(0, -offsets[k].di); i < n && i + offsets[k].di < n; ++i)
        equal[k] += g.tile(i, j) == g.tile(i + offsets[k].di, j + offsets[k].dj) ? 1 : 0;
  double chance = 0;
  for (const double c : count) chance += (c / cells) * (c / cells);
  const auto energy = [&] {
    double e = 0;
    for (std::size_t k = 0; k < offsets.size(); ++k) {
      const double a = (equal[k] / offsets[k].pairs - chance) / (1 - chance);
      e += a * a * a * a;
    }
    return e;
  };
  // Changes tile (i, j) to t, keeping the counts.
  const auto change = [&](int i, int j, std::uint16_t t) {
    const std::uint16_t old = g.tile(i, j);
    if (old == t) return;
    for (std::size_t k = 0; k < offsets.size(); ++k) {
      const int di = offsets[k].di, dj = offsets[k].dj;
      if (i + di >= 0 && i + di < n && j + dj < n) {
        const std::uint16_t other = g.tile(i + di, j + dj);
        equal[k] += (other == t) - (other == old);
      }
      if (i - di >= 0 && i - di < n && j - dj >= 0) {
        const std::uint16_t other = g.tile(i - di, j - dj);
        equal[k] += (other == t) - (other == old);
      }
    }
    chance += ((count[t] + 1) * (count[t] + 1) - count[t] * count[t] + (count[old] - 1) * (count[old] - 1) -
               count[old] * count[old]) /
              (cells * cells);
    count[t] += 1, count[old] -= 1;
    g.set_tile(i, j, t);
  };
  const auto identical_beside = [&](int i, int j) {
    const std::uint16_t t = g.tile(i, j);
    return (i > 0 && g.tile(i - 1, j) == t) || (i + 1 < n && g.tile(i + 1, j) == t) ||
           (j > 0 && g.tile(i, j - 1) == t) || (j + 1 < n && g.tile(i, j + 1) == t);
  };
  std::uint64_t state = seed * 0x9E3779B97F4A7C15ULL + 1;
  const auto next = [&state] {
    state ^= state << 13, state ^= state >> 7, state ^= state << 17;
    return state;
  };
  double e = energy();
  std::vector<std::array<int, 2>> order;
  for (int cj = 0; cj <= n; ++cj)
    for (int ci = 0; ci <= n; ++ci) order.push_back({ci, cj});
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    for (std::size_t k = order.size(); k > 1; --k) std::swap(order[k - 1], order[next() % k]);
    for (const auto& [ci, cj] : order) {
      const int before = g.corner(ci, cj);
      const int after = (before + 1 + int(next() % std::uint64_t(g.colors() - 1))) % g.colors();
      g.corner(ci, cj) = after;
      std::vector<std::array<int, 3>> changed;  // i, j, old tile
      for (int j = cj - 1; j <= cj; ++j)
        for (int i = ci - 1; i <= ci; ++i)
          if (i >= 0 && j >= 0 && i < n && j < n) {
            changed.push_back({i, j, g.tile(i, j)});
            change(i, j, g.tile_from_corners(i, j));
          }
      bool keep = true;
      if (forbid)
        for (const auto& c : changed) keep = keep && !identical_beside(c[0], c[1]);
      const double e_after = keep ? energy() : e;
      if (keep && e_after < e) {
        e = e_after;
        continue;
      }
      g.corner(ci, cj) = before;
      for (auto c = changed.rbegin(); c != changed.rend(); ++c) change((*c)[0], (*c)[1], std::uint16_t((*c)[2]));
    }
  }
}

// The largest autocorrelation at offsets the score does not look at (and the descent does not
// lower): max(|di|, dj) from 33 to 48, where the window is at least 97 tiles wide; else nothing.
std::optional<double> held_out_peak(const Tiling& tiling) {
  constexpr int kFrom = 33, kTo = 48;
  if (tiling.width < 2 * kTo + 1) return std::nullopt;
  double peak = -1;
  for (int dj = 0; dj <= kTo; ++dj)
    for (int di = -kTo; di <= kTo; ++di)
      if (std::max(std::abs(di), dj) >= kFrom && (dj > 0 || di > 0))
        peak = std::max(peak, autocorrelation_at(tiling, di, dj));
  return peak;
}

// The noise of every far offset's autocorrelation (docs/tileset-format.md): for a tiling whose
// tiles are independent beyond some range, its variance is, up to the normalisation, chance -
// chance^2 plus the sum over offsets r != 0 of sum_kl P_kl(r)^2 - chance^2 (P_kl(r): the share of
// pairs at r that are k and l); here over |ri|, |rj| <= 3 (a half plane, doubled), with the
// neighbours' part (r = (1, 0) and (0, 1), doubled) on its own.
struct Noise {
  double total = 0, neighbours = 0;
};
Noise noise_terms(const Tiling& tiling, std::size_t tile_count) {
  const int n = tiling.width;
  std::vector<double> count(tile_count, 0.0);
  for (const std::uint16_t t : tiling.tiles) count[t] += 1;
  double chance = 0;
  for (const double c : count) chance += (c / (double(n) * n)) * (c / (double(n) * n));
  Noise noise;
  noise.total = chance - chance * chance;
  for (const Offset& r : score_offsets(n, 3)) {
    std::vector<double> joint(tile_count * tile_count, 0.0);
    const double pairs = r.pairs;
    for (int j = 0; j + r.dj < n; ++j)
      for (int i = std::max(0, -r.di); i < n && i + r.di < n; ++i)
        joint[tiling.at(i, j) * tile_count + tiling.at(i + r.di, j + r.dj)] += 1 / pairs;
    double term = -chance * chance;
    for (const double p : joint) term += p * p;
    noise.total += 2 * term;
    if (std::abs(r.di) + r.dj == 1) noise.neighbours += 2 * term;
  }
  return noise;
}

}  // namespace
}  // namespace wangscape

int main(int argc, char** argv) {
  using namespace wangscape;
  if (argc != 5) {
    std::fprintf(stderr, "usage: %s SET SIZE SEEDS SWEEPS (a corner set, e.g. corner-2 64 50 20)\n", argv[0]);
    return 2;
  }
  try {
    const TileSet set = builtin_tileset(argv[1]);
    const int size = std::atoi(argv[2]), seeds = std::atoi(argv[3]), sweeps = std::atoi(argv[4]);
    if (!set.has_corners || set.has_edges || size < 4 || seeds < 2 || sweeps < 0)
      throw Error(std::string("no_identical_neighbours_floor_bench: ") + argv[1] + " " + argv[2] + " " + argv[3] + " " +
                  argv[4] + ": expected a corner set, SIZE >= 4, SEEDS >= 2, SWEEPS >= 0");
    const std::vector<Offset> offsets = score_offsets(size);
    const char* names[] = {"hashed, plain", "hashed, option", "descended, plain", "descended, option"};
    MeanAndError score[4], difference[4], noise[4], neighbours[4], held_out[4];
    for (int seed = 1; seed <= seeds; ++seed) {
      double plain = 0;
      for (int kind = 0; kind < 4; ++kind) {
        TilingOptions options;
        options.algorithm = TilingAlgorithm::hash;
        options.seed = static_cast<std::uint64_t>(seed);
        options.forbid_identical_neighbours = kind % 2 == 1;
        Tiling tiling = make_tiling(set, size, size, options);
        if (kind >= 2) {
          CornerTiling g(set, tiling);
          descend(g, offsets, options.forbid_identical_neighbours, sweeps, options.seed, set.size());
          tiling = g.tiling();
        }
        const TilingStats stats = compute_tiling_stats(set, tiling);
        if (!stats.valid) throw Error("no_identical_neighbours_floor_bench: " + stats.invalid_reason);
        if (options.forbid_identical_neighbours && stats.identical_neighbour_rate > 0)
          throw Error("no_identical_neighbours_floor_bench: identical neighbours left");
        if (kind == 0) plain = stats.periodicity;
        score[kind].add(stats.periodicity);
        difference[kind].add(stats.periodicity - plain);
        const Noise terms = noise_terms(tiling, set.size());
        noise[kind].add(terms.total);
        if (const auto peak = held_out_peak(tiling)) held_out[kind].add(*peak);
        neighbours[kind].add(terms.neighbours);
      }
    }
    std::printf("%s %d x %d, seeds 1-%d, %d sweeps\n", argv[1], size, size, seeds, sweeps);
    for (int kind = 0; kind < 4; ++kind) {
      std::printf(
          "  %-18s score %.5f +- %.5f, against hashed plain %+.1f %% +- %.1f %%; noise %.4f, of it the neighbours' "
          "%.4f",
          names[kind], score[kind].mean(), score[kind].error(), 100 * difference[kind].mean() / score[0].mean(),
          100 * difference[kind].error() / score[0].mean(), noise[kind].mean(), neighbours[kind].mean());
      if (held_out[kind].count > 1)
        std::printf("; peak at offsets 33-48 %.5f +- %.5f", held_out[kind].mean(), held_out[kind].error());
      std::printf("\n");
    }
  } catch (const Error& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
