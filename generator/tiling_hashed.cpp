// The hashed tiling (generator/tiling.h, HashedTiling): each edge or corner color hashed from its
// place, so any tile is known in O(1); with forbid_identical_neighbours, the hashed colors are
// repaired where neighbours come out identical (rounds of redraws, an exact repair of what is
// left, then balance rounds for corner sets with two colors).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstdlib>
#include <string>
#include <tuple>
#include <vector>

#include "generator/tiling_algorithms.h"

namespace wangscape {

using tiling_detail::color_of;
using tiling_detail::kSlotNames;
using tiling_detail::slot_present;
using tiling_detail::slot_radix;

namespace {

// lowbias32 (Chris Wellons): a cheap 32-bit bijection with good avalanche; vectorises.
inline std::uint32_t mix32(std::uint32_t x) {
  x ^= x >> 16;
  x *= 0x7FEB352Du;
  x ^= x >> 15;
  x *= 0x846CA68Bu;
  x ^= x >> 16;
  return x;
}

// The hash of a point, given its row's key: also the inner loop of fill_row.
inline std::uint32_t point_hash(std::uint32_t row_key, std::int64_t x) {
  const auto ux = static_cast<std::uint64_t>(x);
  return mix32(row_key ^ (static_cast<std::uint32_t>(ux) * 0x9E3779B9u) ^
               (static_cast<std::uint32_t>(ux >> 32) * 0x85EBCA6Bu));
}

inline std::uint32_t hashed_color(std::uint32_t hash, std::uint32_t alphabet) {
  return ((hash >> 16) * alphabet) >> 16;
}

// A color other than `avoid`, uniform over the alphabet - 1 others.
inline std::uint32_t color_other_than(std::uint32_t hash, std::uint32_t avoid, std::uint32_t alphabet) {
  return (avoid + 1 + hashed_color(hash, alphabet - 1)) % alphabet;
}

// Colors of the `count` points first_x, first_x + 2, ... of a line of the doubled grid (edges).
[[gnu::target_clones("avx2", "default")]] void hash_colors(std::uint32_t row_key, std::int64_t first_x,
                                                           std::size_t count, std::uint32_t alphabet,
                                                           std::uint32_t* colors) {
  for (std::size_t k = 0; k < count; ++k)
    colors[k] = hashed_color(point_hash(row_key, first_x + 2 * static_cast<std::int64_t>(k)), alphabet);
}

// Colors of the `count` lattice vertices first_x, first_x + 1, ... of a row (corners).
[[gnu::target_clones("avx2", "default")]] void hash_corners(std::uint32_t row_key, std::int64_t first_x,
                                                            std::size_t count, std::uint32_t alphabet,
                                                            std::uint32_t* colors) {
  for (std::size_t k = 0; k < count; ++k)
    colors[k] = hashed_color(point_hash(row_key, first_x + static_cast<std::int64_t>(k)), alphabet);
}

constexpr std::uint64_t kEdgeSalt = 0x3C6EF372FE94F82Bull;
constexpr std::uint64_t kCornerSalt = 0xA54FF53A5F1D36F1ull;
constexpr std::uint64_t kRepairSalt = 0x6A09E667F3BCC909ull;

// forbid_identical_neighbours on hashed tilings (HashedTiling::fill_window): the plain hashed colors,
// repaired where neighbours come out identical. Rounds: every pair of identical neighbours redraws
// one color (a new color, hashed from seed, round and place), all pairs at once: with edge colors,
// an edge of one of the two along their direction (N or S for neighbours east and west, see
// ColorPatch::edges_along), otherwise a corner they share. The first rounds also redraw, with a
// chance, a color of tiles alike at a RepairTilt's offsets (a tile that differs from both its
// neighbours is more often alike to the tile two steps on: about +0.007 in the periodicity at
// (2, 0) and (0, 2) for complete-edge-2, +0.014 at (1, 1) for corner-2; the tilt cancels it). What
// the rounds leave (under 10^-4 of the pairs for complete-edge-2, fewer for corner-2) an exact
// repair of the 4 x 4 block around it clears. Corner sets with two colors then run balance rounds.
constexpr int kRepairRounds = 8;
constexpr int kTiltRounds = 2;
constexpr int kRepairBlock = 4;
// How far (tiles) a color's final value may depend on the plain colors: 3 per tilt round (a
// color of a tile alike to one two tiles on), 1 per other round (a color of a tile next to two
// identical ones, or of one of them), then the block its tile lies in, the pairs around that block
// and their colors.
constexpr int kRepairMargin = 3 * kTiltRounds + (kRepairRounds - kTiltRounds) + kRepairBlock + 2;

// Corner sets with two colors: the repair leaves uneven tile frequencies (corner-2 at 128 x 128,
// seeds 1-48: 0.018 for 0000 and 1111, 0.046 for the tiles with one mirror axis, 0.105 for the
// checkerboards 0101 and 1010, against 1/16). A tile that is its own mirror across an axis can
// equal its neighbour across it, and two such tiles side by side always do, so the tiles with a
// mirror lose most to the repair. Uneven frequencies raise the chance level (0.072 against 0.0625)
// and with it every offset's noise, so the periodicity score (tiles drawn independently with these
// frequencies score 7 % above uniform ones), which was 13 % above the plain tiling's (seeds 1-200,
// 64 and 128; now 7.5-8 %; no tiling without identical neighbours gets within about 2.6 %: the
// neighbours' joint distribution alone raises the noise that much, docs/tileset-format.md). Balance
// rounds follow the repair: Metropolis moves towards tilings without identical neighbours weighted
// by the product of their tiles' kBalanceWeights, which lift the tiles with a mirror. In each round
// a corner moves with chance kBalanceMoveChance if no corner its move reads (within two, see
// balance_corner_frequencies) also moves with a higher hashed priority, so the moves of a round
// never read each other and the round keeps the weighted distribution. Each round reads 2 tiles
// further than the last: a margin of 2 * kBalanceRounds more. Three colors leave the frequencies
// near uniform (chance level 0.0125 against 0.0123) and balance rounds did not lower their score.
constexpr int kBalanceRounds = 8;
constexpr std::uint32_t kBalanceMoveChance = 1288490189u;  // 0.3 of 2^32
struct BalanceWeights {
  std::uint64_t both_mirrors, one_mirror, checkerboard, other;
};
// 5, 2, 0.6 and 1 (chosen over seeds 1-24 at 64 and 128 among a handful, docs/tileset-format.md),
// times 5: whole numbers, so that the acceptance test is exact on every platform.
constexpr BalanceWeights kBalanceWeights{25, 10, 3, 5};
constexpr std::uint64_t kBalanceSalt = 0xBB67AE8584CAA73Bull;

// Tiles computed around a window: what the repair reads, and the balance rounds' reach.
int repair_margin(bool balances) { return kRepairMargin + (balances ? 2 * kBalanceRounds : 0); }

struct Offset {
  int di, dj;
};
// The tilt goes with the pair rule, which it was tuned with: sets with edges redraw an edge along
// the pair (ColorPatch::edges_along), and with that rule a chance of 0.3 overshot, (2, 0) and
// (0, 2) at -0.02, where 0.1 puts them at -0.002 (0 leaves +0.007); sets with corners only redraw
// a corner the pair shares, and tiles sharing one corner, (1, 1) apart, are alike too. Their
// chance was 0.3 before the balance rounds; with them 0.15 (corner-2, 200 seeds at 64 x 64: 5.6 %
// above the plain score against 8.3 %; 0 gave 6.0 %; corner-3 4.0 % and 3.4 %, within noise).
struct RepairTilt {
  std::span<const Offset> offsets;
  std::uint32_t chance;  // of 2^32
};
constexpr std::array<Offset, 2> kEdgeTiltOffsets{{{2, 0}, {0, 2}}};
constexpr std::array<Offset, 4> kCornerTiltOffsets{{{2, 0}, {0, 2}, {1, 1}, {-1, 1}}};
constexpr RepairTilt kEdgeTilt{kEdgeTiltOffsets, 429496730u};      // 0.1
constexpr RepairTilt kCornerTilt{kCornerTiltOffsets, 644245094u};  // 0.15

std::int64_t floor_div(std::int64_t a, std::int64_t b) { return a / b - ((a % b != 0 && (a < 0) != (b < 0)) ? 1 : 0); }

// A draw of the repair, keyed by seed, round, what is drawn and where.
std::uint64_t repair_hash(std::uint64_t seed, int round, int what, std::int64_t x, std::int64_t y) {
  const std::uint64_t key = mix64(seed ^ kRepairSalt ^ static_cast<std::uint64_t>(round * 64 + what));
  return mix64(mix64(key ^ static_cast<std::uint64_t>(x)) ^ static_cast<std::uint64_t>(y));
}

// The colors of a window of tiles being repaired: horizontal edges H(i, y) (tile (i, j) has S = H(i,
// j), N = H(i, j + 1)), vertical edges V(x, j) (W = V(i, j), E = V(i + 1, j)) and corners C(x, y)
// (SW = C(i, j)), in local coordinates; (0, 0) is tile (i0, j0).
struct ColorPatch {
  enum Kind : int { kHorizontal, kVertical, kCorner };
  struct Element {
    int kind, x, y;
  };

  std::int64_t i0 = 0, j0 = 0;
  int width = 0, height = 0;
  bool edges = false, corners = false;
  std::vector<std::uint8_t> horizontal, vertical, corner;

  std::uint8_t& at(const Element& e) {
    if (e.kind == kHorizontal) return horizontal[static_cast<std::size_t>(e.y) * width + e.x];
    if (e.kind == kVertical) return vertical[static_cast<std::size_t>(e.y) * (width + 1) + e.x];
    return corner[static_cast<std::size_t>(e.y) * (width + 1) + e.x];
  }
  std::array<std::uint32_t, kSlotCount> colors(int i, int j) const {
    std::array<std::uint32_t, kSlotCount> c{};
    const auto w = static_cast<std::size_t>(width);
    const auto ui = static_cast<std::size_t>(i), uj = static_cast<std::size_t>(j);
    if (edges) {
      c[kS] = horizontal[uj * w + ui];
      c[kN] = horizontal[(uj + 1) * w + ui];
      c[kW] = vertical[uj * (w + 1) + ui];
      c[kE] = vertical[uj * (w + 1) + ui + 1];
    }
    if (corners) {
      c[kSW] = corner[uj * (w + 1) + ui];
      c[kSE] = corner[uj * (w + 1) + ui + 1];
      c[kNW] = corner[(uj + 1) * (w + 1) + ui];
      c[kNE] = corner[(uj + 1) * (w + 1) + ui + 1];
    }
    return c;
  }
  // All colors of a tile in one word: equal words, identical tiles.
  std::uint64_t key(int i, int j) const {
    std::uint64_t k = 0;
    for (const std::uint32_t c : colors(i, j)) k = (k << 8) | c;
    return k;
  }
  // The tile's edges (S, N, W, E) and corners (SW, SE, NW, NE) the set colors.
  int elements_of(int i, int j, std::array<Element, 8>& out) const {
    int n = 0;
    if (edges)
      for (const Element e : {Element{kHorizontal, i, j}, Element{kHorizontal, i, j + 1}, Element{kVertical, i, j},
                              Element{kVertical, i + 1, j}})
        out[static_cast<std::size_t>(n++)] = e;
    if (corners)
      for (const Element e : {Element{kCorner, i, j}, Element{kCorner, i + 1, j}, Element{kCorner, i, j + 1},
                              Element{kCorner, i + 1, j + 1}})
        out[static_cast<std::size_t>(n++)] = e;
    return n;
  }
  // The edges of tile (i, j) along the direction to its eastern (east: S and N) or northern (W and
  // E) neighbour. Only a tile alike across that axis (E = W for east) can equal that neighbour;
  // redrawing the edge the two share (as corner sets must) makes both unlike across it, so such
  // tiles grew rare (complete-edge-2: 0.036 of the tiles with N = S and E = W, 0.105 with neither,
  // against 1/16 each without the option), which raised the chance level and the noise of every
  // offset's autocorrelation, and the periodicity score with them (0.0105 against 0.0094 at
  // 128 x 128). An edge along keeps both tiles as alike across the axis as they were (frequencies
  // 0.061-0.066).
  int edges_along(int i, int j, bool east, std::array<Element, 8>& out) const {
    out[0] = east ? Element{kHorizontal, i, j} : Element{kVertical, i, j};
    out[1] = east ? Element{kHorizontal, i, j + 1} : Element{kVertical, i + 1, j};
    return 2;
  }
  // The two corners tile (i, j) shares with its eastern (east) or northern neighbour.
  int corners_shared_with(int i, int j, bool east, std::array<Element, 8>& out) const {
    out[0] = Element{kCorner, i + 1, j + 1};
    out[1] = east ? Element{kCorner, i + 1, j} : Element{kCorner, i, j + 1};
    return 2;
  }
  std::int64_t global_x(const Element& e) const { return i0 + e.x; }
  std::int64_t global_y(const Element& e) const { return j0 + e.y; }
};

// The colors an edge or corner of a patch draws from (radix: HashedTiling's colors per slot).
std::uint32_t alphabet_of(const ColorPatch::Element& e, const std::array<std::uint32_t, kSlotCount>& radix) {
  return e.kind == ColorPatch::kHorizontal ? radix[kN] : e.kind == ColorPatch::kVertical ? radix[kE] : radix[kNE];
}

// Tile (i, j) equals its mirror across its vertical axis (W = E and the corners likewise): a tile
// that does not can equal neither neighbour east or west, whatever they are. across_vertical false:
// the same across the horizontal axis, for neighbours north and south.
bool is_mirror(const std::array<std::uint32_t, kSlotCount>& c, bool across_vertical) {
  if (across_vertical) return c[kW] == c[kE] && c[kNW] == c[kNE] && c[kSW] == c[kSE];
  return c[kN] == c[kS] && c[kNW] == c[kSW] && c[kNE] == c[kSE];
}

// Redraws the colors inside the block of tiles [bi, bi + B) x [bj, bj + B) (not those on its
// border, which neighbouring blocks share) so that no two neighbours in it are identical and no
// tile on its border is its own mirror towards the outside (so it equals no outside neighbour,
// whatever that one's colors). Backtracking in a fixed order, colors tried from a hashed start:
// deterministic. Always succeeds with two or more colors per slot (edges: W != E on the west and
// east columns, a middle edge breaking any three equal; corners: checked exhaustively for two
// colors by a scratch program, see docs/tileset-format.md); throws if it ever does not.
void repair_block(ColorPatch& patch, int bi, int bj, std::uint64_t seed,
                  const std::array<std::uint32_t, kSlotCount>& radix) {
  using Element = ColorPatch::Element;
  constexpr int B = kRepairBlock;
  std::vector<Element> free_elements;
  for (int a = 1; a < B; ++a)
    for (int b = 0; b < B; ++b) {
      if (patch.edges) {
        free_elements.push_back({ColorPatch::kVertical, bi + a, bj + b});
        free_elements.push_back({ColorPatch::kHorizontal, bi + b, bj + a});
      }
      if (patch.corners && b > 0) free_elements.push_back({ColorPatch::kCorner, bi + b, bj + a});
    }
  const auto index_of = [&](const Element& e) {
    for (std::size_t k = 0; k < free_elements.size(); ++k)
      if (free_elements[k].kind == e.kind && free_elements[k].x == e.x && free_elements[k].y == e.y)
        return static_cast<int>(k);
    return -1;
  };
  // Checks: a pair of tiles in the block (kind 0, with the one east or north), or a border tile
  // that must not be its own mirror (kind 1 across the vertical axis, 2 across the horizontal).
  struct Check {
    int kind, i, j, i2, j2, last;
  };
  std::vector<Check> checks;
  const auto last_free = [&](int i, int j) {
    std::array<Element, 8> own{};
    int last = -1;
    const int n = patch.elements_of(i, j, own);
    for (int k = 0; k < n; ++k) last = std::max(last, index_of(own[static_cast<std::size_t>(k)]));
    return last;
  };
  for (int j = bj; j < bj + B; ++j)
    for (int i = bi; i < bi + B; ++i) {
      if (i + 1 < bi + B) checks.push_back({0, i, j, i + 1, j, std::max(last_free(i, j), last_free(i + 1, j))});
      if (j + 1 < bj + B) checks.push_back({0, i, j, i, j + 1, std::max(last_free(i, j), last_free(i, j + 1))});
      if (i == bi || i == bi + B - 1) checks.push_back({1, i, j, i, j, last_free(i, j)});
      if (j == bj || j == bj + B - 1) checks.push_back({2, i, j, i, j, last_free(i, j)});
    }
  const auto passes = [&](int depth) {
    for (const Check& c : checks) {
      if (c.last != depth) continue;
      if (c.kind == 0 ? patch.key(c.i, c.j) == patch.key(c.i2, c.j2) : is_mirror(patch.colors(c.i, c.j), c.kind == 1))
        return false;
    }
    return true;
  };
  const int count = static_cast<int>(free_elements.size());
  std::vector<std::uint32_t> start(free_elements.size()), tried(free_elements.size(), 0);
  for (int k = 0; k < count; ++k) {
    const Element& e = free_elements[static_cast<std::size_t>(k)];
    start[static_cast<std::size_t>(k)] = static_cast<std::uint32_t>(
        repair_hash(seed, kRepairRounds, e.kind, patch.global_x(e), patch.global_y(e)) % alphabet_of(e, radix));
  }
  int depth = 0;
  for (std::uint64_t steps = 0; depth < count; ++steps) {
    if (depth < 0 || steps > (1u << 22))
      throw Error("hashed tiling: cannot forbid identical neighbours in the block at tile (" +
                  std::to_string(patch.i0 + bi) + ", " + std::to_string(patch.j0 + bj) + ")");
    const auto d = static_cast<std::size_t>(depth);
    const Element& e = free_elements[d];
    if (tried[d] == alphabet_of(e, radix)) {  // every color failed: back up
      tried[d] = 0;
      --depth;
      continue;
    }
    patch.at(e) = static_cast<std::uint8_t>((start[d] + tried[d]++) % alphabet_of(e, radix));
    if (passes(depth)) ++depth;
  }
}

// A tile's weight in the balance rounds (kBalanceWeights), from its corners.
std::uint64_t balance_weight(const ColorPatch& patch, int i, int j) {
  const std::array<std::uint32_t, kSlotCount> c = patch.colors(i, j);
  const bool across_vertical = is_mirror(c, true), across_horizontal = is_mirror(c, false);
  if (across_vertical && across_horizontal) return kBalanceWeights.both_mirrors;
  if (across_vertical || across_horizontal) return kBalanceWeights.one_mirror;
  return c[kNW] == c[kSE] && c[kNE] == c[kSW] ? kBalanceWeights.checkerboard : kBalanceWeights.other;
}

// Whether a tile equals one of its four neighbours.
bool has_identical_neighbour(const ColorPatch& patch, int i, int j) {
  const std::uint64_t key = patch.key(i, j);
  return patch.key(i + 1, j) == key || patch.key(i - 1, j) == key || patch.key(i, j + 1) == key ||
         patch.key(i, j - 1) == key;
}

// The balance rounds (see kBalanceRounds) on the corners of `patch`, whose colors are right from
// `right` corners in from every side; they are right from right + 2 * kBalanceRounds after. A move
// of corner (x, y) changes the four tiles around it and reads them and their neighbours: the corners
// within two of it, less the four at (+-2, +-2), the corners whose priority it must beat.
void balance_corner_frequencies(ColorPatch& patch, int right, std::uint64_t seed) {
  const auto stride = static_cast<std::size_t>(patch.width) + 1;
  std::vector<std::uint32_t> priority(stride * (static_cast<std::size_t>(patch.height) + 1), 0);
  const auto priority_at = [&](int x, int y) {
    return priority[static_cast<std::size_t>(y) * stride + static_cast<std::size_t>(x)];
  };
  const auto around = [&](int x, int y, const auto& per_tile) {
    std::uint64_t product = 1;
    for (int j = y - 1; j <= y; ++j)
      for (int i = x - 1; i <= x; ++i) product *= per_tile(i, j);
    return product;
  };
  for (int round = 0; round < kBalanceRounds; ++round, right += 2) {
    const int last_x = patch.width - right, last_y = patch.height - right;
    const std::uint64_t round_key = mix64(seed ^ kBalanceSalt ^ static_cast<std::uint64_t>(round));
    // Priorities of the corners the moves below read; 0: the corner does not move this round.
    for (int y = right; y <= last_y; ++y) {
      const auto row_key = static_cast<std::uint32_t>(
          mix64(round_key ^ static_cast<std::uint64_t>(patch.j0 + y) * 0xD6E8FEB86659FD93ull));
      for (int x = right; x <= last_x; ++x) {
        const std::uint32_t h = point_hash(row_key, patch.i0 + x);
        priority[static_cast<std::size_t>(y) * stride + static_cast<std::size_t>(x)] =
            h < kBalanceMoveChance ? h + 1 : 0;
      }
    }
    for (int y = right + 2; y <= last_y - 2; ++y)
      for (int x = right + 2; x <= last_x - 2; ++x) {
        const std::uint32_t own = priority_at(x, y);
        if (own == 0) continue;
        bool moves = true;
        for (int dy = -2; dy <= 2 && moves; ++dy)
          for (int dx = -2; dx <= 2 && moves; ++dx)
            if ((dx != 0 || dy != 0) && (std::abs(dx) < 2 || std::abs(dy) < 2) && priority_at(x + dx, y + dy) >= own)
              moves = false;
        if (!moves) continue;
        std::uint8_t& color = patch.corner[static_cast<std::size_t>(y) * stride + static_cast<std::size_t>(x)];
        const std::uint8_t old_color = color;
        const std::uint64_t h =
            repair_hash(seed, kRepairRounds + 1 + round, ColorPatch::kCorner, patch.i0 + x, patch.j0 + y);
        const std::uint64_t before = around(x, y, [&](int i, int j) { return balance_weight(patch, i, j); });
        color = old_color ^ 1u;  // (two colors: the other one)
        const std::uint64_t after = around(x, y, [&](int i, int j) { return balance_weight(patch, i, j); });
        // Metropolis: accepted with chance min(1, after / before); products below 25^4, exact. Then
        // only if none of the four tiles it changed equals a neighbour.
        bool accepted = (h >> 32) * before < (std::uint64_t{1} << 32) * after;
        for (int j = y - 1; j <= y && accepted; ++j)
          for (int i = x - 1; i <= x && accepted; ++i) accepted = !has_identical_neighbour(patch, i, j);
        if (!accepted) color = old_color;
      }
  }
}

// The keys (ColorPatch::key) of a patch's tiles whose colors are still right: `skip` tiles in from
// every side (each repair round reads one or three tiles further).
class PatchKeys {
 public:
  explicit PatchKeys(const ColorPatch& patch)
      : patch_(patch), keys_(static_cast<std::size_t>(patch.width) * static_cast<std::size_t>(patch.height)) {}

  void compute() {
    for (int j = skip; j < patch_.height - skip; ++j)
      for (int i = skip; i < patch_.width - skip; ++i) keys_[index(i, j)] = patch_.key(i, j);
  }
  bool inside(int i, int j) const {
    return i >= skip && j >= skip && i < patch_.width - skip && j < patch_.height - skip;
  }
  std::uint64_t key(int i, int j) const { return keys_[index(i, j)]; }

  int skip = 0;

 private:
  std::size_t index(int i, int j) const {
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(patch_.width) + static_cast<std::size_t>(i);
  }

  const ColorPatch& patch_;
  std::vector<std::uint64_t> keys_;
};

// The redraw rounds (see kRepairRounds), the first kTiltRounds with the tilt.
void redraw_identical_neighbours(ColorPatch& patch, PatchKeys& keys, std::uint64_t seed,
                                 const std::array<std::uint32_t, kSlotCount>& radix) {
  using Element = ColorPatch::Element;
  const RepairTilt& tilt = patch.edges ? kEdgeTilt : kCornerTilt;
  std::vector<Element> redraw;
  std::array<Element, 8> choices{};
  for (int round = 0; round < kRepairRounds; ++round) {
    keys.compute();
    redraw.clear();
    for (int j = keys.skip; j < patch.height - keys.skip; ++j)
      for (int i = keys.skip; i < patch.width - keys.skip; ++i) {
        const std::int64_t gi = patch.i0 + i, gj = patch.j0 + j;
        for (const bool east : {true, false}) {
          const int i2 = east ? i + 1 : i, j2 = east ? j : j + 1;
          if (!keys.inside(i2, j2) || keys.key(i, j) != keys.key(i2, j2)) continue;
          const std::uint64_t h = repair_hash(seed, round, east ? 1 : 2, gi, gj);
          const bool second = ((h >> 32) & 1) != 0;
          const int n = patch.edges ? patch.edges_along(second ? i2 : i, second ? j2 : j, east, choices)
                                    : patch.corners_shared_with(i, j, east, choices);
          redraw.push_back(choices[h % static_cast<std::uint64_t>(n)]);
        }
        if (round >= kTiltRounds) continue;
        for (std::size_t o = 0; o < tilt.offsets.size(); ++o) {
          const int i2 = i + tilt.offsets[o].di, j2 = j + tilt.offsets[o].dj;
          if (!keys.inside(i2, j2) || keys.key(i, j) != keys.key(i2, j2)) continue;
          const std::uint64_t h = repair_hash(seed, round, 3 + static_cast<int>(o), gi, gj);
          if (static_cast<std::uint32_t>(h) >= tilt.chance) continue;
          const bool second = ((h >> 32) & 1) != 0;
          const int n = patch.elements_of(second ? i2 : i, second ? j2 : j, choices);
          redraw.push_back(choices[(h >> 33) % static_cast<std::uint64_t>(n)]);
        }
      }
    // Each color drawn once per round, however many pairs chose it: sort out the repeats.
    std::sort(redraw.begin(), redraw.end(), [](const Element& a, const Element& b) {
      return std::tie(a.kind, a.y, a.x) < std::tie(b.kind, b.y, b.x);
    });
    for (std::size_t k = 0; k < redraw.size(); ++k) {
      const Element& e = redraw[k];
      if (k > 0 && e.kind == redraw[k - 1].kind && e.x == redraw[k - 1].x && e.y == redraw[k - 1].y) continue;
      std::uint8_t& color = patch.at(e);
      color = static_cast<std::uint8_t>(color_other_than(
          static_cast<std::uint32_t>(repair_hash(seed, round, 16 + e.kind, patch.global_x(e), patch.global_y(e))),
          color, alphabet_of(e, radix)));
    }
    keys.skip += round < kTiltRounds ? 3 : 1;
  }
}

// What the rounds left: exact repairs of the blocks (on a fixed lattice of kRepairBlock tiles) that
// hold a tile of an identical pair. Blocks reaching into the margin's outer part are not needed.
void repair_blocks_left(ColorPatch& patch, PatchKeys& keys, std::uint64_t seed,
                        const std::array<std::uint32_t, kSlotCount>& radix) {
  keys.compute();
  const std::int64_t first_block_i = floor_div(patch.i0, kRepairBlock),
                     first_block_j = floor_div(patch.j0, kRepairBlock);
  const auto block_i = [&](int i) { return static_cast<int>(floor_div(patch.i0 + i, kRepairBlock) - first_block_i); };
  const auto block_j = [&](int j) { return static_cast<int>(floor_div(patch.j0 + j, kRepairBlock) - first_block_j); };
  const int blocks_w = block_i(patch.width - 1) + 1, blocks_h = block_j(patch.height - 1) + 1;
  std::vector<std::uint8_t> flagged(static_cast<std::size_t>(blocks_w) * static_cast<std::size_t>(blocks_h), 0);
  const auto flag = [&](int i, int j) {
    flagged[static_cast<std::size_t>(block_j(j)) * static_cast<std::size_t>(blocks_w) +
            static_cast<std::size_t>(block_i(i))] = 1;
  };
  for (int j = keys.skip; j < patch.height - keys.skip; ++j)
    for (int i = keys.skip; i < patch.width - keys.skip; ++i) {
      if (keys.inside(i + 1, j) && keys.key(i, j) == keys.key(i + 1, j)) {
        flag(i, j);
        flag(i + 1, j);
      }
      if (keys.inside(i, j + 1) && keys.key(i, j) == keys.key(i, j + 1)) {
        flag(i, j);
        flag(i, j + 1);
      }
    }
  for (int by = 0; by < blocks_h; ++by)
    for (int bx = 0; bx < blocks_w; ++bx) {
      if (!flagged[static_cast<std::size_t>(by) * static_cast<std::size_t>(blocks_w) + static_cast<std::size_t>(bx)])
        continue;
      const auto bi = static_cast<int>((first_block_i + bx) * kRepairBlock - patch.i0);
      const auto bj = static_cast<int>((first_block_j + by) * kRepairBlock - patch.j0);
      if (!keys.inside(bi - 1, bj - 1) || !keys.inside(bi + kRepairBlock, bj + kRepairBlock)) continue;
      repair_block(patch, bi, bj, seed, radix);
    }
}

// No two neighbours of `patch` identical, but in the margin's outer part: the rounds, then the
// exact repair of what they left.
void repair_identical_neighbours(ColorPatch& patch, std::uint64_t seed,
                                 const std::array<std::uint32_t, kSlotCount>& radix) {
  PatchKeys keys(patch);
  redraw_identical_neighbours(patch, keys, seed, radix);
  repair_blocks_left(patch, keys, seed, radix);
}

}  // namespace

HashedTiling::HashedTiling(const TileSet& set, std::uint64_t seed, bool forbid_identical_neighbours)
    : seed_(seed), forbid_(forbid_identical_neighbours) {
  for (int slot = 0; slot < kSlotCount; ++slot) radix_[static_cast<std::size_t>(slot)] = slot_radix(set, slot);
  has_edges_ = set.has_edges;
  has_corners_ = set.has_corners;
  std::uint64_t combinations = 1;
  for (const std::uint32_t r : radix_) combinations *= r;
  if (combinations > 65535 || set.size() > 65535)
    throw Error(set.describe() + ": hash tiling needs a complete set of at most 65535 tiles; this one needs " +
                std::to_string(combinations));
  constexpr std::uint16_t kMissing = 0xFFFF;
  lookup_.assign(combinations, kMissing);
  for (std::size_t t = 0; t < set.size(); ++t) {
    std::array<std::uint32_t, kSlotCount> colors{};
    for (int slot = 0; slot < kSlotCount; ++slot) colors[static_cast<std::size_t>(slot)] = color_of(set.tiles[t], slot);
    lookup_[code(colors)] = static_cast<std::uint16_t>(t);
  }
  std::vector<int> slots;
  for (int slot = 0; slot < kSlotCount; ++slot)
    if (slot_present(set, slot)) slots.push_back(slot);
  for (std::size_t c = 0; c < lookup_.size(); ++c) {
    if (lookup_[c] != kMissing) continue;
    std::array<std::uint32_t, kSlotCount> colors{};
    std::uint64_t rest = c;
    for (int slot = kSlotCount - 1; slot >= 0; --slot) {
      colors[static_cast<std::size_t>(slot)] =
          static_cast<std::uint32_t>(rest % radix_[static_cast<std::size_t>(slot)]);
      rest /= radix_[static_cast<std::size_t>(slot)];
    }
    std::string names, values;
    for (const int slot : slots) {
      names += std::string(names.empty() ? "" : ",") + kSlotNames[static_cast<std::size_t>(slot)];
      values += std::string(values.empty() ? "" : ",") + std::to_string(colors[static_cast<std::size_t>(slot)]);
    }
    throw Error(set.describe() + ": hash tiling needs a complete set; missing (" + names + ")=(" + values + ")");
  }
  if (forbid_)
    for (const int slot : slots)
      if (radix_[static_cast<std::size_t>(slot)] < 2)
        throw Error(set.describe() + ": hash tiling cannot forbid identical neighbours with a single " +
                    kSlotNames[static_cast<std::size_t>(slot)] + " color");
  balances_ = forbid_ && has_corners_ && !has_edges_ && radix_[kNE] == 2;
  margin_ = repair_margin(balances_);
}

std::uint32_t HashedTiling::code(const std::array<std::uint32_t, kSlotCount>& colors) const {
  std::uint32_t c = 0;
  for (int slot = 0; slot < kSlotCount; ++slot)
    c = c * radix_[static_cast<std::size_t>(slot)] + colors[static_cast<std::size_t>(slot)];
  return c;
}

std::uint32_t HashedTiling::tile_with_colors(const std::array<std::uint32_t, kSlotCount>& colors) const {
  for (int slot = 0; slot < kSlotCount; ++slot)
    if (colors[static_cast<std::size_t>(slot)] >= radix_[static_cast<std::size_t>(slot)])
      throw Error(std::string("hashed tiling: ") + kSlotNames[static_cast<std::size_t>(slot)] + " color " +
                  std::to_string(colors[static_cast<std::size_t>(slot)]) + " is outside the set's " +
                  std::to_string(radix_[static_cast<std::size_t>(slot)]) + " colors");
  return lookup_[code(colors)];
}

std::uint32_t HashedTiling::row_key(std::int64_t y, std::uint64_t salt) const {
  return static_cast<std::uint32_t>(mix64(seed_ ^ salt ^ (static_cast<std::uint64_t>(y) * 0xD6E8FEB86659FD93ull)));
}

std::uint32_t HashedTiling::color_at(std::int64_t x, std::int64_t y, std::uint32_t alphabet) const {
  return hashed_color(point_hash(row_key(y, kEdgeSalt), x), alphabet);
}

std::uint32_t HashedTiling::corner_at(std::int64_t x, std::int64_t y, std::uint32_t alphabet) const {
  return hashed_color(point_hash(row_key(y, kCornerSalt), x), alphabet);
}

// Forbidding identical neighbours by a rule that treats every place alike and looks a bounded
// distance cannot work (the constant coloring has no image without identical neighbours), and
// the rule used until issue 23 (odd edges differ from the even one before them, corners along even
// rows and columns) laid a lattice of period 2 (complete-edge-2 at 128 x 128: periodicity 0.062
// against 0.009 without the option). The repair below changes only colors near identical
// neighbours, and the exact block repair, tied to a lattice of blocks, acts almost never.
void HashedTiling::fill_window(std::int64_t first_i, std::int64_t first_j, int width, int height,
                               std::span<std::uint16_t> out) const {
  const auto w = static_cast<std::size_t>(width);
  if (!forbid_) {
    for (int r = 0; r < height; ++r) fill_row(first_i, first_j + r, out.subspan(static_cast<std::size_t>(r) * w, w));
    return;
  }
  const int m = margin_;
  ColorPatch patch;
  patch.i0 = first_i - m;
  patch.j0 = first_j - m;
  patch.width = width + 2 * m;
  patch.height = height + 2 * m;
  patch.edges = has_edges_;
  patch.corners = has_corners_;
  const auto pw = static_cast<std::size_t>(patch.width), ph = static_cast<std::size_t>(patch.height);
  if (has_edges_) {
    patch.horizontal.resize((ph + 1) * pw);
    patch.vertical.resize(ph * (pw + 1));
    for (std::size_t y = 0; y <= ph; ++y) {
      const std::int64_t gy = patch.j0 + static_cast<std::int64_t>(y);
      for (std::size_t i = 0; i < pw; ++i)
        patch.horizontal[y * pw + i] =
            static_cast<std::uint8_t>(color_at(2 * (patch.i0 + static_cast<std::int64_t>(i)) + 1, 2 * gy, radix_[kN]));
      if (y == ph) break;
      for (std::size_t x = 0; x <= pw; ++x)
        patch.vertical[y * (pw + 1) + x] =
            static_cast<std::uint8_t>(color_at(2 * (patch.i0 + static_cast<std::int64_t>(x)), 2 * gy + 1, radix_[kE]));
    }
  }
  if (has_corners_) {
    patch.corner.resize((ph + 1) * (pw + 1));
    for (std::size_t y = 0; y <= ph; ++y)
      for (std::size_t x = 0; x <= pw; ++x)
        patch.corner[y * (pw + 1) + x] = static_cast<std::uint8_t>(
            corner_at(patch.i0 + static_cast<std::int64_t>(x), patch.j0 + static_cast<std::int64_t>(y), radix_[kNE]));
  }
  repair_identical_neighbours(patch, seed_, radix_);
  if (balances_) balance_corner_frequencies(patch, kRepairMargin, seed_);
  for (int r = 0; r < height; ++r)
    for (int k = 0; k < width; ++k)
      out[static_cast<std::size_t>(r) * w + static_cast<std::size_t>(k)] = lookup_[code(patch.colors(k + m, r + m))];
}

std::uint32_t HashedTiling::tile_at(std::int64_t i, std::int64_t j) const {
  if (forbid_) {
    std::array<std::uint16_t, 1> tile{};
    fill_window(i, j, 1, 1, tile);
    return tile[0];
  }
  std::array<std::uint32_t, kSlotCount> colors{};
  if (has_edges_) {
    colors[kN] = color_at(2 * i + 1, 2 * j + 2, radix_[kN]);
    colors[kS] = color_at(2 * i + 1, 2 * j, radix_[kS]);
    colors[kE] = color_at(2 * i + 2, 2 * j + 1, radix_[kE]);
    colors[kW] = color_at(2 * i, 2 * j + 1, radix_[kW]);
  }
  if (has_corners_) {
    colors[kSW] = corner_at(i, j, radix_[kSW]);
    colors[kSE] = corner_at(i + 1, j, radix_[kSE]);
    colors[kNE] = corner_at(i + 1, j + 1, radix_[kNE]);
    colors[kNW] = corner_at(i, j + 1, radix_[kNW]);
  }
  return lookup_[code(colors)];
}

void HashedTiling::fill_row(std::int64_t first_i, std::int64_t j, std::span<std::uint16_t> out) const {
  if (forbid_) {
    fill_window(first_i, j, static_cast<int>(out.size()), 1, out);
    return;
  }
  if (has_corners_ == has_edges_) {
    for (std::size_t k = 0; k < out.size(); ++k)
      out[k] = static_cast<std::uint16_t>(tile_at(first_i + static_cast<std::int64_t>(k), j));
    return;
  }
  // Fast paths: colors of each line of points hashed once into small buffers (neighbouring tiles
  // share their E/W edges and corners), then combined into tile indices.
  constexpr std::size_t kChunk = 512;
  std::array<std::uint32_t, kChunk + 1> line_a, line_b, line_c;
  const std::uint16_t* lookup = lookup_.data();
  for (std::size_t done = 0; done < out.size(); done += kChunk) {
    const std::size_t count = std::min(kChunk, out.size() - done);
    const std::int64_t i0 = first_i + static_cast<std::int64_t>(done);
    std::uint16_t* tiles = out.data() + done;
    if (has_edges_) {
      const std::uint32_t h = radix_[kN], v = radix_[kE];
      hash_colors(row_key(2 * j + 2, kEdgeSalt), 2 * i0 + 1, count, h, line_a.data());  // N
      hash_colors(row_key(2 * j, kEdgeSalt), 2 * i0 + 1, count, h, line_b.data());      // S
      hash_colors(row_key(2 * j + 1, kEdgeSalt), 2 * i0, count + 1, v, line_c.data());  // W, then E
      for (std::size_t k = 0; k < count; ++k)
        tiles[k] = lookup[((line_a[k] * v + line_c[k + 1]) * h + line_b[k]) * v + line_c[k]];  // code(): N, E, S, W
    } else {
      const std::uint32_t c = radix_[kNE];
      hash_corners(row_key(j + 1, kCornerSalt), i0, count + 1, c, line_a.data());  // NW, then NE
      hash_corners(row_key(j, kCornerSalt), i0, count + 1, c, line_b.data());      // SW, then SE
      for (std::size_t k = 0; k < count; ++k)
        tiles[k] = lookup[((line_a[k + 1] * c + line_b[k + 1]) * c + line_b[k]) * c + line_a[k]];  // NE, SE, SW, NW
    }
  }
}

namespace {
// Rows first_j .. first_j + rows - 1 of a hashed window `width` tiles wide from origin_i into out,
// in parallel: row by row, or, repaired (forbid), in pieces of kRepairPiece columns, each computed
// with its margin.
void fill_hashed_rows(const HashedTiling& hashed, bool forbid, std::int64_t origin_i, std::int64_t first_j, int width,
                      int rows, std::span<std::uint16_t> out) {
  const auto w = static_cast<std::size_t>(width);
  if (!forbid) {
    tbb::parallel_for(0, rows, [&](int r) {
      hashed.fill_row(origin_i, first_j + r, out.subspan(static_cast<std::size_t>(r) * w, w));
    });
    return;
  }
  constexpr int kRepairPiece = 128;
  tbb::parallel_for(0, (width + kRepairPiece - 1) / kRepairPiece, [&](int piece) {
    const int first = piece * kRepairPiece, count = std::min(kRepairPiece, width - first);
    std::vector<std::uint16_t> tiles(static_cast<std::size_t>(count) * static_cast<std::size_t>(rows));
    hashed.fill_window(origin_i + first, first_j, count, rows, tiles);
    for (int r = 0; r < rows; ++r)
      std::copy_n(tiles.begin() + static_cast<std::ptrdiff_t>(r) * count, count,
                  out.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(r) * w) + first);
  });
}
// Rows of hashed tiles computed in parallel this many at a time when streaming.
constexpr int kHashRowBlock = 64;

}  // namespace

namespace tiling_detail {

void stream_hashed_tiling(const TileSet& set, int width, int height, const TilingOptions& options,
                          const TilingRowSink& row) {
  const auto w = static_cast<std::size_t>(width);
  const HashedTiling hashed(set, options.seed, options.forbid_identical_neighbours);
  std::vector<std::uint16_t> block(w * kHashRowBlock);
  for (int first = 0; first < height; first += kHashRowBlock) {
    const int rows = std::min(kHashRowBlock, height - first);
    fill_hashed_rows(hashed, options.forbid_identical_neighbours, options.origin_i, options.origin_j + first, width,
                     rows, block);
    for (int r = 0; r < rows; ++r)
      row(first + r, std::span<const std::uint16_t>(block.data() + static_cast<std::size_t>(r) * w, w));
  }
}

void fill_hashed_tiling(const TileSet& set, int width, int height, const TilingOptions& options,
                        std::span<std::uint16_t> tiles) {
  const auto w = static_cast<std::size_t>(width);
  const HashedTiling hashed(set, options.seed, options.forbid_identical_neighbours);
  if (options.forbid_identical_neighbours) {
    for (int first = 0; first < height; first += kHashRowBlock)
      fill_hashed_rows(hashed, true, options.origin_i, options.origin_j + first, width,
                       std::min(kHashRowBlock, height - first), tiles.subspan(static_cast<std::size_t>(first) * w));
    return;
  }
  tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
    for (int r = rows.begin(); r < rows.end(); ++r)
      hashed.fill_row(options.origin_i, options.origin_j + r, tiles.subspan(static_cast<std::size_t>(r) * w, w));
  });
}

}  // namespace tiling_detail

}  // namespace wangscape
