#include "generator/tiling.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdlib>
#include <map>
#include <numeric>
#include <set>
#include <string>
#include <tuple>

#include "core/hash.h"

namespace wangscape {

namespace {

constexpr std::array<const char*, kSlotCount> kSlotNames = {"N", "E", "S", "W", "NE", "SE", "SW", "NW"};

bool slot_present(const TileSet& set, int slot) { return slot < kNE ? set.has_edges : set.has_corners; }

// Number of colors a slot draws from (1 when the set does not color it).
std::uint32_t slot_radix(const TileSet& set, int slot) {
  if (!slot_present(set, slot)) return 1;
  if (slot == kN || slot == kS) return static_cast<std::uint32_t>(std::max(set.horizontal_colors, 1));
  if (slot == kE || slot == kW) return static_cast<std::uint32_t>(std::max(set.vertical_colors, 1));
  return static_cast<std::uint32_t>(std::max(set.corner_colors, 1));
}

std::uint32_t color_of(const Tile& tile, int slot) {
  const int c = tile.colors[static_cast<std::size_t>(slot)];
  return c < 0 ? 0u : static_cast<std::uint32_t>(c);
}

// "N=1, W=0" for the slots in `slots` (in slot order), values from `values`.
std::string describe_colors(const std::vector<int>& slots, const std::array<std::uint32_t, kSlotCount>& values) {
  std::string text;
  for (const int slot : slots) {
    if (!text.empty()) text += ", ";
    text += std::string(kSlotNames[static_cast<std::size_t>(slot)]) + "=" +
            std::to_string(values[static_cast<std::size_t>(slot)]);
  }
  return text;
}

// SplitMix64's generator: mix64 of the state, which then steps.
std::uint64_t splitmix64(std::uint64_t& state) {
  const std::uint64_t z = mix64(state);
  state += 0x9E3779B97F4A7C15ull;
  return z;
}

// lowbias32 (Chris Wellons): a cheap 32-bit bijection with good avalanche; vectorises.
inline std::uint32_t mix32(std::uint32_t x) {
  x ^= x >> 16;
  x *= 0x7FEB352Du;
  x ^= x >> 15;
  x *= 0x846CA68Bu;
  x ^= x >> 16;
  return x;
}

// A uniform integer in [0, count) from 32 random bits.
inline std::uint32_t scale(std::uint32_t bits, std::uint32_t count) {
  return static_cast<std::uint32_t>((static_cast<std::uint64_t>(bits) * count) >> 32);
}

// ---------------------------------------------------------------------------------------------
// Sequential (scanline, bottom-left) tiling.

// A neighbour already placed hands some of its colors to the new tile: target slot of the new
// tile <- source slot of the neighbour.
struct Link {
  int target;
  int source;
};

// Candidate tiles grouped by the colors of the constrained slots (a mixed-radix key).
class CandidateTable {
 public:
  CandidateTable(const TileSet& set, std::vector<int> constrained) : slots_(std::move(constrained)) {
    std::uint64_t key_count = 1;
    for (const int slot : slots_) {
      weight_[static_cast<std::size_t>(slot)] = static_cast<std::uint32_t>(key_count);
      key_count *= slot_radix(set, slot);
      if (key_count > (1u << 24))
        throw Error(set.describe() + ": too many color combinations to tile (more than 2^24)");
    }
    begin_.assign(key_count + 1, 0);
    std::vector<std::uint32_t> keys(set.size());
    for (std::size_t t = 0; t < set.size(); ++t) {
      keys[t] = key_of_tile(set.tiles[t]);
      ++begin_[keys[t] + 1];
    }
    std::partial_sum(begin_.begin(), begin_.end(), begin_.begin());
    tiles_.resize(set.size());
    std::vector<std::uint32_t> fill(begin_.begin(), begin_.end() - 1);
    for (std::size_t t = 0; t < set.size(); ++t) tiles_[fill[keys[t]]++] = static_cast<std::uint16_t>(t);
  }

  std::uint32_t key_of_tile(const Tile& tile) const {
    std::uint32_t key = 0;
    for (const int slot : slots_) key += weight_[static_cast<std::size_t>(slot)] * color_of(tile, slot);
    return key;
  }
  // The key a neighbour imposes through `links` (only the constrained targets count).
  std::uint32_t key_from(const Tile& neighbour, std::span<const Link> links) const {
    std::uint32_t key = 0;
    for (const Link& link : links)
      key += weight_[static_cast<std::size_t>(link.target)] * color_of(neighbour, link.source);
    return key;
  }
  std::span<const std::uint16_t> candidates(std::uint32_t key) const {
    return {tiles_.data() + begin_[key], tiles_.data() + begin_[key + 1]};
  }
  const std::vector<int>& slots() const { return slots_; }
  std::size_t key_count() const { return begin_.size() - 1; }
  // Colors per slot encoded in `key` (for messages).
  std::array<std::uint32_t, kSlotCount> decode(std::uint32_t key, const TileSet& set) const {
    std::array<std::uint32_t, kSlotCount> values{};
    for (const int slot : slots_)
      values[static_cast<std::size_t>(slot)] = (key / weight_[static_cast<std::size_t>(slot)]) % slot_radix(set, slot);
    return values;
  }

 private:
  std::vector<int> slots_;
  std::array<std::uint32_t, kSlotCount> weight_{};
  std::vector<std::uint32_t> begin_;
  std::vector<std::uint16_t> tiles_;
};

// The constraint geometry of a sweep: rows away from the previous row ("vertical" neighbour:
// north for scanline, south for bottom-left), each row west to east.
struct Sweep {
  std::vector<Link> vertical;   // from the previous-row neighbour
  std::vector<Link> west;       // from the western neighbour when there is a previous row
  std::vector<Link> west_only;  // from the western neighbour in the first row
  std::vector<Link> diagonal;   // from the diagonal tile (west of vertical) to the vertical one
};

Sweep make_sweep(TilingAlgorithm algorithm) {
  if (algorithm == TilingAlgorithm::scanline)
    return {{{kN, kS}, {kNW, kSW}, {kNE, kSE}}, {{kW, kE}, {kSW, kSE}}, {{kW, kE}, {kSW, kSE}, {kNW, kNE}}, {}};
  return {{{kS, kN}, {kSW, kNW}, {kSE, kNE}}, {{kW, kE}, {kNW, kNE}}, {{kW, kE}, {kNW, kNE}, {kSW, kSE}}, {}};
}

// Keeps the links whose slots the set colors.
std::vector<Link> present_links(const TileSet& set, const std::vector<Link>& links) {
  std::vector<Link> kept;
  for (const Link& link : links)
    if (slot_present(set, link.target)) kept.push_back(link);
  return kept;
}

std::vector<int> targets_of(const std::vector<Link>& a, const std::vector<Link>& b = {}) {
  std::vector<int> slots;
  for (const Link& link : a) slots.push_back(link.target);
  for (const Link& link : b) slots.push_back(link.target);
  std::sort(slots.begin(), slots.end());
  return slots;
}

// Classes of tiles that a row (rows true) or a column never leaves, as masks of tile indices (sets
// of at most 64 tiles): a tile's east side (E, NE, SE) is the west side (W, NW, SW) of the tile
// after it, so linking each tile's two sides joins the west sides a row can pass through; a
// tile's class is its west side's. Columns: south sides (S, SW, SE) through north sides (N, NW,
// NE). One class for most sets; cohen8-corners has two each way (W xor NW xor SW is the same on
// both sides of each of its tiles, and S xor SW xor SE).
std::vector<std::uint64_t> side_classes(const TileSet& set, bool rows) {
  const std::vector<Link> passes = present_links(set, rows ? std::vector<Link>{{kW, kE}, {kNW, kNE}, {kSW, kSE}}
                                                           : std::vector<Link>{{kS, kN}, {kSW, kNW}, {kSE, kNE}});
  // Keys of west (south) sides; a tile's east (north) side is the key it hands the next tile.
  const CandidateTable sides(set, targets_of(passes));
  std::vector<std::uint32_t> parent(sides.key_count());
  std::iota(parent.begin(), parent.end(), 0u);
  const auto root = [&](std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (const Tile& t : set.tiles) parent[root(sides.key_of_tile(t))] = root(sides.key_from(t, passes));
  std::map<std::uint32_t, std::size_t> class_of_root;
  std::vector<std::uint64_t> classes;
  for (std::size_t t = 0; t < set.size(); ++t) {
    const auto [it, added] = class_of_root.emplace(root(sides.key_of_tile(set.tiles[t])), classes.size());
    if (added) classes.push_back(0);
    classes[it->second] |= std::uint64_t{1} << t;
  }
  return classes;
}

class SweepTiler {
 public:
  SweepTiler(const TileSet& set, const TilingOptions& options)
      : set_(set),
        options_(options),
        vertical_(present_links(set, make_sweep(options.algorithm).vertical)),
        west_(present_links(set, make_sweep(options.algorithm).west)),
        west_only_(present_links(set, make_sweep(options.algorithm).west_only)),
        interior_(set, targets_of(vertical_, west_)),
        first_row_(set, targets_of(west_only_)),
        first_column_(set, targets_of(vertical_)) {
    if (set.size() > 65535) throw Error(set.describe() + ": more than 65535 tiles");
    const std::string algorithm(to_string(options.algorithm));
    vertical_key_.resize(set.size());
    west_key_.resize(set.size());
    for (std::size_t t = 0; t < set.size(); ++t) {
      vertical_key_[t] = interior_.key_from(set.tiles[t], vertical_);
      west_key_[t] = interior_.key_from(set.tiles[t], west_);
    }
    for (const Tile& tile : set.tiles) diagonals_.insert(diagonal_signature(tile));
    // Distinct (key, diagonal edge, shared corner) classes: what matters of a neighbour here.
    std::set<std::array<std::uint32_t, 3>> vertical_classes, west_classes;
    std::vector<std::size_t> vertical_examples, west_examples;
    for (std::size_t t = 0; t < set.size(); ++t) {
      const Tile& tile = set.tiles[t];
      if (vertical_classes
              .insert({vertical_key_[t], static_cast<std::uint32_t>(tile.w() + 1),
                       static_cast<std::uint32_t>((scanline_ ? tile.sw() : tile.nw()) + 1)})
              .second)
        vertical_examples.push_back(t);
      if (west_classes
              .insert({west_key_[t], static_cast<std::uint32_t>((scanline_ ? tile.n() : tile.s()) + 1),
                       static_cast<std::uint32_t>((scanline_ ? tile.ne() : tile.se()) + 1)})
              .second)
        west_examples.push_back(t);
    }
    for (const std::size_t v : vertical_examples)
      for (const std::size_t w : west_examples)
        if (can_meet(set.tiles[v], set.tiles[w])) require(interior_, vertical_key_[v] + west_key_[w], algorithm);
    // Every constraint a previously placed tile can impose must have a candidate.
    for (const Tile& tile : set.tiles) {
      require(first_row_, first_row_.key_from(tile, west_only_), algorithm);
      require(first_column_, first_column_.key_from(tile, vertical_), algorithm);
    }
    prepare_pairs();
    if (options.forbid_identical_neighbours) {
      if (set.size() <= kMaskTiles) {
        prepare_row_lookahead();
      } else {
        check_can_forbid_identical(algorithm);
      }
    }
  }

  // Fills `row` (width tiles) given the previous row (empty for the first row).
  void next_row(std::span<const std::uint16_t> previous, std::span<std::uint16_t> row) {
    const std::size_t width = row.size();
    ++rows_done_;
    if (!vertical_mask_.empty()) return next_row_with_lookahead(previous, row);
    if (previous.empty()) {
      row[0] = pick(set_.tiles.size());
      for (std::size_t i = 1; i < width; ++i)
        row[i] = choose(first_row_.candidates(first_row_.key_from(set_.tiles[row[i - 1]], west_only_)), row[i - 1],
                        row[i - 1]);
      return;
    }
    row[0] = choose(first_column_.candidates(first_column_.key_from(set_.tiles[previous[0]], vertical_)), previous[0],
                    previous[0]);
    if (options_.forbid_identical_neighbours) {
      for (std::size_t i = 1; i < width; ++i)
        row[i] =
            choose(interior_.candidates(vertical_key_[previous[i]] + west_key_[row[i - 1]]), previous[i], row[i - 1]);
      return;
    }
    if (!pairs_.empty()) {
      // The hot loop for two-choice sets (cohen*): one table load and one random bit per tile;
      // the entry carries each candidate's west key, so the loop never looks the tile up again.
      std::uint32_t west = west_key_[row[0]];
      for (std::size_t i = 1; i < width; ++i) {
        const std::uint64_t entry = pairs_[vertical_key_[previous[i]] + west];
        const auto half = static_cast<std::uint32_t>(entry >> (32 * next_bit()));
        row[i] = static_cast<std::uint16_t>(half);
        west = half >> 16;
      }
      return;
    }
    // The general hot loop: two table lookups and one random draw per tile.
    for (std::size_t i = 1; i < width; ++i) {
      const auto candidates = interior_.candidates(vertical_key_[previous[i]] + west_key_[row[i - 1]]);
      row[i] = candidates[scale(next_bits(), static_cast<std::uint32_t>(candidates.size()))];
    }
  }

 private:
  // When every interior constraint leaves at most two candidates and keys fit 16 bits, packs
  // each key's candidates as two (tile, west key) halves of a 64-bit entry.
  void prepare_pairs() {
    if (options_.forbid_identical_neighbours || interior_.key_count() > 65536) return;
    std::vector<std::uint64_t> pairs(interior_.key_count(), 0);
    for (std::size_t key = 0; key < pairs.size(); ++key) {
      const auto candidates = interior_.candidates(static_cast<std::uint32_t>(key));
      if (candidates.size() > 2) return;
      if (candidates.empty()) continue;  // never reached: require() checked every reachable key
      const auto half = [&](std::uint16_t t) { return std::uint64_t{t} | (std::uint64_t{west_key_[t]} << 16); };
      pairs[key] = half(candidates.front()) | (half(candidates.back()) << 32);
    }
    pairs_ = std::move(pairs);
  }

  // One random bit (0 or 1), 64 per generator draw.
  unsigned next_bit() {
    if (bits_left_ == 0) {
      bit_word_ = splitmix64(rng_);
      bits_left_ = 64;
    }
    --bits_left_;
    const auto bit = static_cast<unsigned>(bit_word_ & 1);
    bit_word_ >>= 1;
    return bit;
  }

  // Sets of at most 64 tiles forbid identical neighbours with a row lookahead: a backward pass
  // counts, per position and tile, the ways the rest of the row can be completed from it, and
  // each tile is drawn in proportion to them. So a pair of neighbours that leaves no other choice
  // (cohen12: north (1,2,1,0), west (1,0,0,0)) is never reached, and each row is uniform among
  // the rows that can follow the previous one. Drawing each tile uniformly among its viable
  // candidates instead favours the tiles a forbidden neighbour forces, which lays a lattice of
  // alike tiles (cohen8 at 128 x 128: periodicity 0.056 at offset (1, 1), against 0.035).
  static constexpr std::size_t kMaskTiles = 64;
  // The tilt of the row draw (next_row_with_lookahead), chosen over 10 seeds of cohen8 at 64 and
  // 128 (docs/tileset-format.md); cohen8 itself has since moved to kCohen8Tilt.
  static constexpr double kTiltTwoRowsBack = 0.85, kTiltTwoRowsBackBeside = 0.88, kTiltPreviousRowTwoAside = 0.85;
  using TileMask = std::uint64_t;
  static TileMask bit(std::size_t t) { return TileMask{1} << t; }

  // Some sets draw each row in proportion to the product, over its tiles, of exp(log weight) per
  // tile equal to the tile `columns` aside (either side) `rows_back` rows back, or `columns` back in
  // the row itself (rows_back 0): one log weight per offset of kTiltOffsets, from the set's table.
  // Rows uniform among those that may follow give cohen8 at 128 x 128 a mean autocorrelation of
  // +0.036 at (0, 2), +0.022 at (2, 1), +0.012 at (3, 0) (seeds 1000+, 20 tilings); the weights were
  // fitted so that it is about 0 at every one of these offsets (each round: 40 tilings of 128 x 128,
  // log weight -= 5 x mean autocorrelation; scanline and bottom-left agreed within 0.01 and are
  // averaged and mirrored). cohen8 over seeds 1-100: no offset within 6 of the origin but the
  // forbidden neighbours keeps more than 0.005 (the five-term tilt before it: +0.015 at (0, 2),
  // +0.011 at (3, 0)). docs/tileset-format.md gives the figures.
  struct TiltOffset {
    int columns, rows_back;
  };
  static constexpr std::array<TiltOffset, 12> kTiltOffsets = {
      {{1, 1}, {2, 1}, {3, 1}, {0, 2}, {1, 2}, {2, 2}, {0, 3}, {1, 3}, {2, 3}, {1, 4}, {2, 0}, {3, 0}}};
  using TiltTable = std::array<double, kTiltOffsets.size()>;
  // Edge sets of eight tiles with two colours each way (cohen8: two tiles per north and west).
  static constexpr TiltTable kCohen8Tilt = {-0.03, -0.16, -0.04, -0.31, -0.22,  -0.05,
                                            -0.05, -0.03, 0.02,  0.035, -0.045, -0.08};
  // The complete edge set with two colours each way (complete-edge-2) and the complete corner set
  // with two (corner-2), fitted likewise (30 rounds of 40 tilings): rows uniform among those that
  // may follow had +0.010 at (1, 1) and +0.009 at (1, 2).
  static constexpr TiltTable kCompleteEdge2Tilt = {-0.128, -0.022, 0.001, -0.013, 0.004, 0.009,
                                                   0.005,  -0.003, 0.002, 0.0,    0.005, -0.015};
  static constexpr TiltTable kCorner2Tilt = {-0.038, -0.068, 0.015, 0.211, -0.073, -0.02,
                                             -0.067, 0.026,  0.01,  0.007, 0.049,  -0.051};
  static constexpr std::size_t kEqualityTiltRows = 4, kTiltTiles = 16;
  // The most chain states a row may hold (1.6 x 10^7 doubles, 128 MB). A row that would hold more is
  // drawn untilted: for sets of 16 tiles the first row beyond 4096 tiles (every tile may stand
  // there), complete-edge-2's later rows beyond 32768; cohen8's first row beyond 32768.
  static constexpr std::size_t kMaxTiltStates = std::size_t{1} << 24;

  // The table for this set, or none.
  const TiltTable* tilt_table() const {
    if (row_classes_.size() != 1 || column_classes_.size() != 1) return nullptr;
    if (set_.size() == 8 && set_.has_edges && !set_.has_corners && tilt_) return &kCohen8Tilt;
    if (set_.size() == 16 && set_.has_edges && !set_.has_corners && tilt_) return &kCompleteEdge2Tilt;
    if (set_.size() == 16 && set_.has_corners && !set_.has_edges && set_.corner_colors == 2) return &kCorner2Tilt;
    return nullptr;
  }

  void prepare_row_lookahead() {
    row_classes_ = side_classes(set_, true);
    column_classes_ = side_classes(set_, false);
    if (const TiltTable* table = tilt_table()) {
      equality_tilt_ = true;
      for (std::size_t k = 0; k < table->size(); ++k) {
        tilt_factor_[k] = std::exp((*table)[k]);
        if (kTiltOffsets[k].rows_back == 0)
          tilt_in_row_[static_cast<std::size_t>(kTiltOffsets[k].columns)] = tilt_factor_[k];
      }
    }
    vertical_mask_.assign(set_.size(), 0);
    east_mask_.assign(set_.size(), 0);
    for (std::size_t t = 0; t < set_.size(); ++t) {
      for (const std::uint16_t c : first_column_.candidates(first_column_.key_from(set_.tiles[t], vertical_)))
        vertical_mask_[t] |= bit(c);
      for (const std::uint16_t c : first_row_.candidates(first_row_.key_from(set_.tiles[t], west_only_)))
        east_mask_[t] |= bit(c);
    }
  }

  // One of `classes` that meets `mask`, uniformly (the class a row or column keeps, side_classes).
  // Some class always does: the classes hold every tile and `mask` is never empty.
  TileMask draw_class(TileMask mask, const std::vector<TileMask>& classes) {
    std::vector<TileMask> open;
    for (const TileMask c : classes)
      if ((c & mask) != 0) open.push_back(c);
    return open[scale(next_bits(), static_cast<std::uint32_t>(open.size()))];
  }

  void next_row_with_lookahead(std::span<const std::uint16_t> previous, std::span<std::uint16_t> row) {
    if (equality_tilt_ && next_row_tilted(previous, row)) return;
    const std::size_t width = row.size(), tiles = set_.size();
    const TileMask all = tiles == 64 ? ~TileMask{0} : bit(tiles) - 1;
    // A set whose rows keep a class (side_classes; cohen8-corners): drawn uniformly, a row took the
    // class the previous one did not have (a row of the same class has far fewer ways to differ
    // from it), so no tile equalled any tile of the rows above and below (periodicity -0.016 at
    // (i, 1) and +0.014 at (i, 2) for every i; 0.0505 against 0.0237 at 128 x 128, the peaks at
    // offsets far along). So each row draws its class first, uniformly among those it can take, as
    // the tiling without the option does; the first row draws each column's class likewise (its
    // neighbours otherwise differ in class more often than not), unless that leaves no row.
    std::vector<TileMask> column_class;
    if (previous.empty() && column_classes_.size() > 1)
      for (std::size_t i = 0; i < width; ++i) column_class.push_back(draw_class(all, column_classes_));
    const auto allowed_at = [&](std::size_t i) {
      if (!previous.empty()) return vertical_mask_[previous[i]] & ~bit(previous[i]);
      return column_class.empty() ? all : column_class[i];
    };
    // A row drawn uniformly among those that may follow the previous one repeats the tiles two
    // rows back more often than chance (cohen8 at 128 x 128: periodicity 0.035 at offset (0, 2),
    // against 0.015 without the option); lowering those tiles' weight moved the peak to (1, 2),
    // then to (2, 1). Each tile's weight is therefore the product of kTiltTwoRowsBack if it equals
    // the tile two rows back, kTiltTwoRowsBackBeside per equal tile beside that one, and
    // kTiltPreviousRowTwoAside per equal tile two columns aside in the previous row; the row is
    // drawn in proportion to the product of its tiles' weights. Only for two colors on each
    // alphabet (cohen8-corners; cohen8 now draws with kCohen8Tilt): cohen12 and owen12 are below
    // the plain tiling untilted, and the tilt put cohen12 at 64 x 64 just above it (0.0441 against
    // 0.0438).
    const auto weight = [&](std::size_t i, std::size_t t) {
      if (!tilt_ || history_.size() < 2) return 1.0;
      const std::vector<std::uint16_t>& two_back = history_[1];
      double w = two_back[i] == t ? kTiltTwoRowsBack : 1.0;
      if (i > 0 && two_back[i - 1] == t) w *= kTiltTwoRowsBackBeside;
      if (i + 1 < width && two_back[i + 1] == t) w *= kTiltTwoRowsBackBeside;
      if (i >= 2 && previous[i - 2] == t) w *= kTiltPreviousRowTwoAside;
      if (i + 2 < width && previous[i + 2] == t) w *= kTiltPreviousRowTwoAside;
      return w;
    };
    // completions_[i * tiles + t]: the ways to complete the row from tile t at position i, scaled
    // per position (only ratios at one position matter), 0 where t cannot stand; possible[i]: the
    // tiles with some.
    std::vector<TileMask> possible(width);
    const auto count_completions = [&] {
      completions_.assign(width * tiles, 0.0);
      std::fill(possible.begin(), possible.end(), TileMask{0});
      possible[width - 1] = allowed_at(width - 1);
      for (TileMask rest = possible[width - 1]; rest != 0; rest &= rest - 1)
        completions_[(width - 1) * tiles + static_cast<std::size_t>(std::countr_zero(rest))] =
            weight(width - 1, static_cast<std::size_t>(std::countr_zero(rest)));
      for (std::size_t i = width - 1; i-- > 0;) {
        double largest = 0;
        for (TileMask rest = allowed_at(i); rest != 0; rest &= rest - 1) {
          const auto t = static_cast<std::size_t>(std::countr_zero(rest));
          double ways = 0;
          for (TileMask next = east_mask_[t] & possible[i + 1] & ~bit(t); next != 0; next &= next - 1)
            ways += completions_[(i + 1) * tiles + static_cast<std::size_t>(std::countr_zero(next))];
          if (ways == 0) continue;
          ways *= weight(i, t);
          completions_[i * tiles + t] = ways;
          possible[i] |= bit(t);
          largest = std::max(largest, ways);
        }
        for (std::size_t t = 0; t < tiles; ++t) completions_[i * tiles + t] /= std::max(largest, 1e-300);
      }
    };
    count_completions();
    if (possible[0] == 0 && !column_class.empty()) {
      column_class.clear();
      count_completions();
    }
    if (possible[0] == 0) throw no_row(width, previous.empty());
    for (std::size_t i = 0; i < width; ++i) {
      TileMask choices = possible[i];
      if (i > 0) choices &= east_mask_[row[i - 1]] & ~bit(row[i - 1]);
      if (i == 0 && row_classes_.size() > 1) choices &= draw_class(choices, row_classes_);
      row[i] = pick_weighted(choices, std::span(completions_).subspan(i * tiles, tiles));
    }
    remember_row(row);
  }

  Error no_row(std::size_t width, bool first) const {
    return Error(set_.describe() + ": " + std::string(to_string(options_.algorithm)) +
                 " tiling cannot forbid identical neighbours: no row of " + std::to_string(width) + " tiles " +
                 (first ? std::string("to start with") : "can follow sweep row " + std::to_string(rows_done_ - 1)));
  }

  // The row drawn in proportion to the product of the tilt's weights, among the rows that may
  // follow: a chain over (tile two back, tile one back, tile) carries the in-row terms too. Each
  // position's allowed tiles (at most kTiltTiles) are listed; positions -2 and -1 hold one stand-in
  // that every tile may follow. False, with nothing drawn, if the chain would exceed kMaxTiltStates.
  bool next_row_tilted(std::span<const std::uint16_t> previous, std::span<std::uint16_t> row) {
    constexpr std::size_t kTiles = kTiltTiles;
    constexpr std::uint16_t kNone = 0xFFFF;
    const std::size_t width = row.size(), positions = width + 2;  // position p is column p - 2
    tilt_count_.assign(positions, 1);
    tilt_tile_.assign(positions * kTiles, kNone);
    tilt_weight_.assign(positions * kTiles, 1.0);
    tilt_next_.assign(positions * kTiles, 0);
    // The weight of each tile at column i from the rows before: factors per equal tile there.
    std::array<double, kTiles> by_tile{};
    for (std::size_t i = 0; i < width; ++i) {
      by_tile.fill(1.0);
      for (std::size_t k = 0; k < kTiltOffsets.size(); ++k) {
        const auto [columns, rows_back] = kTiltOffsets[k];
        if (rows_back == 0 || rows_back > static_cast<int>(history_.size())) continue;
        const std::vector<std::uint16_t>& back = history_[static_cast<std::size_t>(rows_back - 1)];
        const auto aside = static_cast<std::size_t>(columns);
        if (i + aside < width) by_tile[back[i + aside]] *= tilt_factor_[k];
        if (aside > 0 && i >= aside) by_tile[back[i - aside]] *= tilt_factor_[k];
      }
      const TileMask allowed =
          previous.empty() ? bit(set_.size()) - 1 : vertical_mask_[previous[i]] & ~bit(previous[i]);
      std::size_t count = 0;
      for (TileMask rest = allowed; rest != 0; rest &= rest - 1, ++count) {
        const auto t = static_cast<std::uint16_t>(std::countr_zero(rest));
        tilt_tile_[(i + 2) * kTiles + count] = t;
        tilt_weight_[(i + 2) * kTiles + count] = by_tile[t];
      }
      tilt_count_[i + 2] = count;
    }
    // Where each position's chain states begin (a, b, c: list indices at p - 2, p - 1, p).
    tilt_offset_.assign(positions + 1, 0);
    for (std::size_t p = 2; p < positions; ++p)
      tilt_offset_[p + 1] = tilt_offset_[p] + tilt_count_[p - 2] * tilt_count_[p - 1] * tilt_count_[p];
    if (tilt_offset_[positions] > kMaxTiltStates) return false;
    // Which tiles of the next position may follow each tile (east edge, not identical).
    for (std::size_t p = 0; p + 1 < positions; ++p)
      for (std::size_t k = 0; k < tilt_count_[p]; ++k) {
        const std::uint16_t t = tilt_tile_[p * kTiles + k];
        std::uint16_t next = 0;
        for (std::size_t d = 0; d < tilt_count_[p + 1]; ++d) {
          const std::uint16_t u = tilt_tile_[(p + 1) * kTiles + d];
          if (t == kNone || ((east_mask_[t] & ~bit(t)) & bit(u)) != 0) next |= static_cast<std::uint16_t>(1u << d);
        }
        tilt_next_[p * kTiles + k] = next;
      }
    const auto tile = [&](std::size_t p, std::size_t k) { return tilt_tile_[p * kTiles + k]; };
    const auto state = [&](std::size_t p, std::size_t a, std::size_t b, std::size_t c) {
      return tilt_offset_[p] + (a * tilt_count_[p - 1] + b) * tilt_count_[p] + c;
    };
    const std::array<double, 4>& in_row = tilt_in_row_;
    // ways[state(p, a, b, c)]: the weighted completions of the positions after p; written for
    // every triple that may stand at p - 2, p - 1, p, which are the only ones read.
    tilt_ways_.resize(tilt_offset_[positions]);
    // Calls visit(a, b, c) for each of those triples.
    const auto for_each_state = [&](std::size_t p, const auto& visit) {
      for (std::size_t a = 0; a < tilt_count_[p - 2]; ++a)
        for (unsigned bs = tilt_next_[(p - 2) * kTiles + a]; bs != 0; bs &= bs - 1)
          for (unsigned cs = tilt_next_[(p - 1) * kTiles + static_cast<std::size_t>(std::countr_zero(bs))]; cs != 0;
               cs &= cs - 1)
            visit(a, static_cast<std::size_t>(std::countr_zero(bs)), static_cast<std::size_t>(std::countr_zero(cs)));
    };
    for (std::size_t p = positions; p-- > 2;) {
      double largest = 0;
      for_each_state(p, [&](std::size_t a, std::size_t b, std::size_t c) {
        double sum = p + 1 == positions ? 1.0 : 0.0;
        if (p + 1 < positions)
          for (unsigned ds = tilt_next_[p * kTiles + c]; ds != 0; ds &= ds - 1) {
            const auto d = static_cast<std::size_t>(std::countr_zero(ds));
            const std::uint16_t u = tile(p + 1, d);
            sum += tilt_weight_[(p + 1) * kTiles + d] * (tile(p - 1, b) == u ? in_row[2] : 1.0) *
                   (tile(p - 2, a) == u ? in_row[3] : 1.0) * tilt_ways_[state(p + 1, b, c, d)];
          }
        tilt_ways_[state(p, a, b, c)] = sum;
        largest = std::max(largest, sum);
      });
      if (largest == 0) throw no_row(width, previous.empty());
      // Only ratios within a position matter: keep the counts in range.
      for_each_state(p, [&](std::size_t a, std::size_t b, std::size_t c) { tilt_ways_[state(p, a, b, c)] /= largest; });
    }
    std::size_t a = 0, b = 0;        // list indices at p - 2 and p - 1
    std::uint16_t before_a = kNone;  // the tile at p - 3
    std::array<double, kTiles> weight{};
    for (std::size_t p = 2; p < positions; ++p) {
      TileMask drawable = 0;  // the list indices that may stand here with some completion
      for (unsigned cs = tilt_next_[(p - 1) * kTiles + b]; cs != 0; cs &= cs - 1) {
        const auto c = static_cast<std::size_t>(std::countr_zero(cs));
        const std::uint16_t t = tile(p, c);
        weight[c] = tilt_weight_[p * kTiles + c] * (tile(p - 2, a) == t ? in_row[2] : 1.0) *
                    (before_a == t ? in_row[3] : 1.0) * tilt_ways_[state(p, a, b, c)];
        if (weight[c] > 0) drawable |= bit(c);
      }
      const std::size_t chosen = pick_weighted(drawable, weight);
      row[p - 2] = tile(p, chosen);
      before_a = tile(p - 2, a);
      a = b;
      b = chosen;
    }
    remember_row(row);
    return true;
  }

  // Keeps the rows drawn last (the last first) for the tilts, which read up to kEqualityTiltRows back.
  void remember_row(std::span<const std::uint16_t> row) {
    if (history_.size() < kEqualityTiltRows) history_.emplace_back();
    std::rotate(history_.rbegin(), history_.rbegin() + 1, history_.rend());
    history_.front().assign(row.begin(), row.end());
  }

  // A member t of a non-empty mask, drawn in proportion to weight[t] (all positive there).
  std::uint16_t pick_weighted(TileMask mask, std::span<const double> weight) {
    double total = 0;
    for (TileMask rest = mask; rest != 0; rest &= rest - 1)
      total += weight[static_cast<std::size_t>(std::countr_zero(rest))];
    double target = total * (next_bits() / 4294967296.0);
    auto chosen = static_cast<std::size_t>(std::countr_zero(mask));
    for (TileMask rest = mask; rest != 0; rest &= rest - 1) {
      chosen = static_cast<std::size_t>(std::countr_zero(rest));
      target -= weight[chosen];
      if (target < 0) break;
    }
    return static_cast<std::uint16_t>(chosen);
  }

  std::uint32_t next_bits() {
    if (spare_bits_left_) {
      spare_bits_left_ = false;
      return spare_bits_;
    }
    const std::uint64_t bits = splitmix64(rng_);
    spare_bits_ = static_cast<std::uint32_t>(bits >> 32);
    spare_bits_left_ = true;
    return static_cast<std::uint32_t>(bits);
  }
  std::uint16_t pick(std::size_t count) {
    return static_cast<std::uint16_t>(scale(next_bits(), static_cast<std::uint32_t>(count)));
  }

  // A uniform choice among `candidates`, skipping the neighbours when identical ones are forbidden.
  std::uint16_t choose(std::span<const std::uint16_t> candidates, std::uint16_t neighbour_a,
                       std::uint16_t neighbour_b) {
    if (!options_.forbid_identical_neighbours)
      return candidates[scale(next_bits(), static_cast<std::uint32_t>(candidates.size()))];
    std::uint32_t allowed = 0;
    for (const std::uint16_t t : candidates) allowed += (t != neighbour_a && t != neighbour_b) ? 1 : 0;
    std::uint32_t index = scale(next_bits(), allowed);  // allowed > 0: checked in the constructor
    for (const std::uint16_t t : candidates)
      if (t != neighbour_a && t != neighbour_b && index-- == 0) return t;
    return candidates[0];
  }

  // What a tile offers as the diagonal neighbour (west of the vertical one): its colors facing
  // the vertical neighbour, the western one, and the shared corner.
  std::array<int, 3> diagonal_signature(const Tile& d) const {
    return scanline_ ? std::array<int, 3>{d.e(), d.s(), d.se()} : std::array<int, 3>{d.e(), d.n(), d.ne()};
  }
  // Whether `vertical` and `west` can both touch the next tile: they agree on the corner they
  // share (when coded) and some tile fits diagonally between them.
  bool can_meet(const Tile& vertical, const Tile& west) const {
    const int shared_v = scanline_ ? vertical.sw() : vertical.nw();
    const int shared_w = scanline_ ? west.ne() : west.se();
    if (shared_v != shared_w) return false;
    return diagonals_.count({vertical.w(), scanline_ ? west.n() : west.s(), shared_v}) > 0;
  }

  void require(const CandidateTable& table, std::uint32_t key, const std::string& algorithm) const {
    if (!table.candidates(key).empty()) return;
    throw Error(set_.describe() + ": " + algorithm + " tiling needs a tile with " +
                describe_colors(table.slots(), table.decode(key, set_)) + "; none found");
  }

  void check_can_forbid_identical(const std::string& algorithm) const {
    const auto fail = [&](const CandidateTable& table, std::uint32_t key, std::size_t a, std::size_t b) {
      throw Error(set_.describe() + ": " + algorithm + " tiling cannot forbid identical neighbours: every tile with " +
                  describe_colors(table.slots(), table.decode(key, set_)) + " equals a neighbour (tile " +
                  std::to_string(a) + (a == b ? "" : " or tile " + std::to_string(b)) + ")");
    };
    const auto has_other = [](std::span<const std::uint16_t> candidates, std::size_t a, std::size_t b) {
      return std::any_of(candidates.begin(), candidates.end(), [&](std::uint16_t t) { return t != a && t != b; });
    };
    for (std::size_t t = 0; t < set_.size(); ++t) {
      const std::uint32_t row_key = first_row_.key_from(set_.tiles[t], west_only_);
      if (!has_other(first_row_.candidates(row_key), t, t)) fail(first_row_, row_key, t, t);
      const std::uint32_t column_key = first_column_.key_from(set_.tiles[t], vertical_);
      if (!has_other(first_column_.candidates(column_key), t, t)) fail(first_column_, column_key, t, t);
    }
    for (std::size_t v = 0; v < set_.size(); ++v)
      for (std::size_t w = 0; w < set_.size(); ++w) {
        const std::uint32_t key = vertical_key_[v] + west_key_[w];
        const auto candidates = interior_.candidates(key);
        if (candidates.size() > 2 || has_other(candidates, v, w)) continue;
        if (can_meet(set_.tiles[v], set_.tiles[w])) fail(interior_, key, w, v);
      }
  }

  const TileSet& set_;
  TilingOptions options_;
  bool scanline_ = options_.algorithm == TilingAlgorithm::scanline;
  std::set<std::array<int, 3>> diagonals_;
  std::vector<Link> vertical_, west_, west_only_;
  CandidateTable interior_, first_row_, first_column_;
  std::vector<std::uint32_t> vertical_key_, west_key_;
  std::uint64_t rng_ = mix64(options_.seed ^ 0x5CA11E5EED5ull);
  std::uint32_t spare_bits_ = 0;
  std::uint64_t bit_word_ = 0;
  int bits_left_ = 0;
  std::vector<std::uint64_t> pairs_;                   // two-choice fast path (see prepare_pairs)
  std::vector<TileMask> vertical_mask_, east_mask_;    // row lookahead (forbid, <= 64 tiles)
  std::vector<double> completions_;                    // its counts, width x tiles
  std::vector<std::vector<std::uint16_t>> history_;    // the rows drawn last, the last first (remember_row)
  TiltTable tilt_factor_{};                            // exp(log weight) per kTiltOffsets entry
  std::array<double, 4> tilt_in_row_ = {1, 1, 1, 1};   // the in-row entries' factors, by columns back
  std::vector<std::size_t> tilt_count_, tilt_offset_;  // next_row_tilted's lists, kept for their storage
  std::vector<std::uint16_t> tilt_tile_;
  std::vector<double> tilt_weight_, tilt_ways_;
  std::vector<std::uint16_t> tilt_next_;
  std::vector<TileMask> row_classes_, column_classes_;  // side_classes (row lookahead)
  bool tilt_ = set_.horizontal_colors == 2 && set_.vertical_colors == 2;
  bool equality_tilt_ = false;  // the set has a tilt_table() (set when the row lookahead is prepared)
  int rows_done_ = 0;
  bool spare_bits_left_ = false;
};

// Whether `set` holds exactly Culik's 13 tiles, in any order.
bool is_culik13(const TileSet& set) {
  static const TileSet culik = builtin_tileset("culik13");
  return set.size() == culik.size() && set.has_edges && !set.has_corners &&
         std::is_permutation(set.tiles.begin(), set.tiles.end(), culik.tiles.begin());
}

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

// Rows of hashed tiles computed in parallel this many at a time when streaming.
constexpr int kHashRowBlock = 64;

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

// ---------------------------------------------------------------------------------------------
// Hashed tiling.

namespace {
int repair_margin(bool balances);  // (after the repair's constants, below)
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

// The hash of a point, given its row's key: also the inner loop of fill_row.
static inline std::uint32_t point_hash(std::uint32_t row_key, std::int64_t x) {
  const auto ux = static_cast<std::uint64_t>(x);
  return mix32(row_key ^ (static_cast<std::uint32_t>(ux) * 0x9E3779B9u) ^
               (static_cast<std::uint32_t>(ux >> 32) * 0x85EBCA6Bu));
}

static inline std::uint32_t hashed_color(std::uint32_t hash, std::uint32_t alphabet) {
  return ((hash >> 16) * alphabet) >> 16;
}

// A color other than `avoid`, uniform over the alphabet - 1 others.
static inline std::uint32_t color_other_than(std::uint32_t hash, std::uint32_t avoid, std::uint32_t alphabet) {
  return (avoid + 1 + hashed_color(hash, alphabet - 1)) % alphabet;
}

// Colors of the `count` points first_x, first_x + 2, ... of a line of the doubled grid (edges).
[[gnu::target_clones("avx2", "default")]] static void hash_colors(std::uint32_t row_key, std::int64_t first_x,
                                                                  std::size_t count, std::uint32_t alphabet,
                                                                  std::uint32_t* colors) {
  for (std::size_t k = 0; k < count; ++k)
    colors[k] = hashed_color(point_hash(row_key, first_x + 2 * static_cast<std::int64_t>(k)), alphabet);
}

// Colors of the `count` lattice vertices first_x, first_x + 1, ... of a row (corners).
[[gnu::target_clones("avx2", "default")]] static void hash_corners(std::uint32_t row_key, std::int64_t first_x,
                                                                   std::size_t count, std::uint32_t alphabet,
                                                                   std::uint32_t* colors) {
  for (std::size_t k = 0; k < count; ++k)
    colors[k] = hashed_color(point_hash(row_key, first_x + static_cast<std::int64_t>(k)), alphabet);
}

namespace {
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
  const auto alphabet = [&](const Element& e) {
    return e.kind == ColorPatch::kHorizontal ? radix[kN] : e.kind == ColorPatch::kVertical ? radix[kE] : radix[kNE];
  };
  const int count = static_cast<int>(free_elements.size());
  std::vector<std::uint32_t> start(free_elements.size()), tried(free_elements.size(), 0);
  for (int k = 0; k < count; ++k) {
    const Element& e = free_elements[static_cast<std::size_t>(k)];
    start[static_cast<std::size_t>(k)] = static_cast<std::uint32_t>(
        repair_hash(seed, kRepairRounds, e.kind, patch.global_x(e), patch.global_y(e)) % alphabet(e));
  }
  int depth = 0;
  for (std::uint64_t steps = 0; depth < count; ++steps) {
    if (depth < 0 || steps > (1u << 22))
      throw Error("hashed tiling: cannot forbid identical neighbours in the block at tile (" +
                  std::to_string(patch.i0 + bi) + ", " + std::to_string(patch.j0 + bj) + ")");
    const auto d = static_cast<std::size_t>(depth);
    const Element& e = free_elements[d];
    if (tried[d] == alphabet(e)) {  // every color failed: back up
      tried[d] = 0;
      --depth;
      continue;
    }
    patch.at(e) = static_cast<std::uint8_t>((start[d] + tried[d]++) % alphabet(e));
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

}  // namespace

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
  using Element = ColorPatch::Element;
  const auto alphabet = [&](const Element& e) {
    return e.kind == ColorPatch::kHorizontal ? radix_[kN] : e.kind == ColorPatch::kVertical ? radix_[kE] : radix_[kNE];
  };
  std::vector<std::uint64_t> keys(pw * ph);
  // Each round works on the tiles whose colors are still right: `skip` tiles in from every side.
  int skip = 0;
  const auto compute_keys = [&] {
    for (int j = skip; j < patch.height - skip; ++j)
      for (int i = skip; i < patch.width - skip; ++i)
        keys[static_cast<std::size_t>(j) * pw + static_cast<std::size_t>(i)] = patch.key(i, j);
  };
  const auto inside = [&](int i, int j) {
    return i >= skip && j >= skip && i < patch.width - skip && j < patch.height - skip;
  };
  const auto key = [&](int i, int j) { return keys[static_cast<std::size_t>(j) * pw + static_cast<std::size_t>(i)]; };
  const RepairTilt& tilt = has_edges_ ? kEdgeTilt : kCornerTilt;
  std::vector<Element> redraw;
  std::array<Element, 8> choices{};
  for (int round = 0; round < kRepairRounds; ++round) {
    compute_keys();
    redraw.clear();
    for (int j = skip; j < patch.height - skip; ++j)
      for (int i = skip; i < patch.width - skip; ++i) {
        const std::int64_t gi = patch.i0 + i, gj = patch.j0 + j;
        for (const bool east : {true, false}) {
          const int i2 = east ? i + 1 : i, j2 = east ? j : j + 1;
          if (!inside(i2, j2) || key(i, j) != key(i2, j2)) continue;
          const std::uint64_t h = repair_hash(seed_, round, east ? 1 : 2, gi, gj);
          const bool second = ((h >> 32) & 1) != 0;
          const int n = has_edges_ ? patch.edges_along(second ? i2 : i, second ? j2 : j, east, choices)
                                   : patch.corners_shared_with(i, j, east, choices);
          redraw.push_back(choices[h % static_cast<std::uint64_t>(n)]);
        }
        if (round >= kTiltRounds) continue;
        for (std::size_t o = 0; o < tilt.offsets.size(); ++o) {
          const int i2 = i + tilt.offsets[o].di, j2 = j + tilt.offsets[o].dj;
          if (!inside(i2, j2) || key(i, j) != key(i2, j2)) continue;
          const std::uint64_t h = repair_hash(seed_, round, 3 + static_cast<int>(o), gi, gj);
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
          static_cast<std::uint32_t>(repair_hash(seed_, round, 16 + e.kind, patch.global_x(e), patch.global_y(e))),
          color, alphabet(e)));
    }
    skip += round < kTiltRounds ? 3 : 1;
  }
  // What is left: exact repairs of the blocks (on a fixed lattice of kRepairBlock tiles) that hold a
  // tile of an identical pair. Blocks reaching into the margin's outer part are not needed.
  compute_keys();
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
  for (int j = skip; j < patch.height - skip; ++j)
    for (int i = skip; i < patch.width - skip; ++i) {
      if (inside(i + 1, j) && key(i, j) == key(i + 1, j)) {
        flag(i, j);
        flag(i + 1, j);
      }
      if (inside(i, j + 1) && key(i, j) == key(i, j + 1)) {
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
      if (!inside(bi - 1, bj - 1) || !inside(bi + kRepairBlock, bj + kRepairBlock)) continue;
      repair_block(patch, bi, bj, seed_, radix_);
    }
  if (balances_) balance_corner_frequencies(patch, kRepairMargin, seed_);
  for (int r = 0; r < height; ++r)
    for (int k = 0; k < width; ++k)
      out[static_cast<std::size_t>(r) * w + static_cast<std::size_t>(k)] = lookup_[code(patch.colors(k + m, r + m))];
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
}  // namespace

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

// ---------------------------------------------------------------------------------------------
// Aperiodic tiling of Culik's 13 tiles.

namespace {

using u128 = unsigned __int128;
using i128 = __int128;

// A real (or a column times a real) in fixed point: whole + fraction / 2^128. Reals of the orbit lie
// in [1/3, 2]; products k x of a column k (|k| < 2^61) keep their floor in `whole`.
struct Fixed {
  i128 whole = 0;
  u128 fraction = 0;

  void add(const Fixed& other) {
    fraction += other.fraction;
    whole += other.whole + (fraction < other.fraction ? 1 : 0);
  }
};

// k x, exactly.
Fixed times(std::int64_t k, const Fixed& x) {
  const u128 m = k < 0 ? u128(0) - u128(k) : u128(k);  // |k|, fits 64 bits
  const u128 low_part = m * static_cast<std::uint64_t>(x.fraction);
  const u128 high_part = m * static_cast<std::uint64_t>(x.fraction >> 64);
  Fixed product;
  product.fraction = low_part + (high_part << 64);
  product.whole =
      static_cast<i128>(m) * x.whole + static_cast<i128>(high_part >> 64) + (product.fraction < low_part ? 1 : 0);
  if (k >= 0) return product;
  // -(w + f) = -(w + 1) + (1 - f) when f > 0.
  if (product.fraction != 0) {
    product.fraction = u128(0) - product.fraction;
    product.whole = -product.whole - 1;
  } else {
    product.whole = -product.whole;
  }
  return product;
}

// Culik's rows: see culik_tile. Row r reads x_r on its S edges and writes x_{r+1} = f(x_r) on its N
// edges; x_0 is drawn from the seed in [1/3, 2) with 128 fraction bits. Tripling is exact; halving
// drops the last bit when it is set, rounding down or, when that would turn a tile of the row into
// none of the set, up. Either way the tiling stays valid: the rows an edge joins read the same real.
// Column k = origin_i + local i, so windows side by side with one seed continue one tiling.
class CulikTiler {
 public:
  CulikTiler(const TileSet& set, const TilingOptions& options, int width) : set_(set), first_column_(options.origin_i) {
    if (!is_culik13(set))
      throw Error(set.describe() +
                  ": the aperiodic algorithm tiles only Culik's 13-tile set (culik13); expected that set, or "
                  "the scanline, bottom-left or hash algorithm for this one");
    index_.fill(kMissing);
    for (std::size_t t = 0; t < set.size(); ++t) index_[code(set.tiles[t])] = static_cast<std::uint16_t>(t);
    if (options.forbid_identical_neighbours)
      throw Error(set.describe() +
                  ": the aperiodic algorithm cannot forbid identical neighbours (Culik's "
                  "construction fixes every tile)");
    std::uint64_t state = mix64(options.seed ^ 0xC011C13A9E810D1Cull);
    // Uniform in [0, 2), redrawn below 1/3 (floor(2^128 / 3) + 1 = 0x55..56).
    const u128 third = (u128(0x5555555555555555ull) << 64) | 0x5555555555555556ull;
    do {
      x_.whole = splitmix64(state) & 1;
      const std::uint64_t high = splitmix64(state);  // two statements: a fixed order of draws
      x_.fraction = (u128(high) << 64) | splitmix64(state);
    } while (x_.whole == 0 && x_.fraction < third);
    x_floors_ = floors(x_, width);
  }

  // Fills the next row north.
  void next_row(std::span<std::uint16_t> row) {
    const bool triples = triples_at(x_);
    std::array<Fixed, 2> candidates{};
    std::size_t count = 1;
    if (triples) {
      candidates[0] = tripled(x_);
    } else {
      candidates[0] = halved(x_);
      if ((x_.fraction & 1) != 0) {  // the dropped bit: down, else up
        candidates[1] = candidates[0];
        candidates[1].add(Fixed{0, 1});
        count = 2;
      }
    }
    for (std::size_t c = 0; c < count; ++c) {
      std::vector<std::int64_t> y_floors = floors(candidates[c], static_cast<int>(row.size()));
      if (!fill(row, triples, triples_at(candidates[c]), y_floors)) continue;
      x_ = candidates[c];
      x_floors_ = std::move(y_floors);
      ++rows_done_;
      return;
    }
    throw Error(set_.describe() + ": aperiodic row " + std::to_string(rows_done_) +
                " has no tiles at 128-bit precision for either rounding of its real; try another --seed");
  }

 private:
  static constexpr std::uint16_t kMissing = 0xFFFF;
  // Tiles indexed by their colors, N and S < 4, E and W < 5.
  static std::size_t code(const Tile& t) {
    return static_cast<std::size_t>(((t.n() * 5 + t.e()) * 4 + t.s()) * 5 + t.w());
  }

  // x <= 2/3: x has no whole part and 3 x.fraction <= 2^129, i.e. x.fraction <= floor(2^129 / 3) = 0xAA..AA.
  static bool triples_at(const Fixed& x) {
    const u128 two_thirds = (u128(0xAAAAAAAAAAAAAAAAull) << 64) | 0xAAAAAAAAAAAAAAAAull;
    return x.whole == 0 && x.fraction <= two_thirds;
  }
  static Fixed tripled(const Fixed& x) {
    Fixed y = x;
    y.add(x);
    y.add(x);
    return y;
  }
  // x / 2 rounded down.
  static Fixed halved(const Fixed& x) { return {x.whole >> 1, (x.fraction >> 1) | (u128(x.whole & 1) << 127)}; }

  // floor(k x) for the columns k = first .. first + width (each tile's west and east edge).
  std::vector<std::int64_t> floors(const Fixed& x, int width) const {
    std::vector<std::int64_t> out(static_cast<std::size_t>(width) + 1);
    Fixed product = times(first_column_, x);
    for (std::int64_t& f : out) {
      f = static_cast<std::int64_t>(product.whole);
      product.add(x);
    }
    return out;
  }

  // The row's tiles, false when one is not in the set.
  bool fill(std::span<std::uint16_t> row, bool triples, bool next_triples, const std::vector<std::int64_t>& y_floors) {
    for (std::size_t i = 0; i < row.size(); ++i) {
      const auto tile =
          culik_tile(triples, next_triples, {x_floors_[i], x_floors_[i + 1], y_floors[i], y_floors[i + 1]});
      if (!tile || index_[code(*tile)] == kMissing) return false;
      row[i] = index_[code(*tile)];
    }
    return true;
  }

  const TileSet& set_;
  std::int64_t first_column_ = 0;
  std::array<std::uint16_t, 4 * 5 * 4 * 5> index_{};
  Fixed x_;
  std::vector<std::int64_t> x_floors_;
  int rows_done_ = 0;
};

}  // namespace

// ---------------------------------------------------------------------------------------------

void stream_tiling(const TileSet& set, int width, int height, const TilingOptions& options, const TilingRowSink& row) {
  check_window(set, width, height, options);
  const auto w = static_cast<std::size_t>(width);
  if (options.algorithm == TilingAlgorithm::hash) {
    const HashedTiling hashed(set, options.seed, options.forbid_identical_neighbours);
    std::vector<std::uint16_t> block(w * kHashRowBlock);
    for (int first = 0; first < height; first += kHashRowBlock) {
      const int rows = std::min(kHashRowBlock, height - first);
      fill_hashed_rows(hashed, options.forbid_identical_neighbours, options.origin_i, options.origin_j + first, width,
                       rows, block);
      for (int r = 0; r < rows; ++r)
        row(first + r, std::span<const std::uint16_t>(block.data() + static_cast<std::size_t>(r) * w, w));
    }
    return;
  }
  if (options.algorithm == TilingAlgorithm::aperiodic) {
    CulikTiler tiler(set, options, width);
    std::vector<std::uint16_t> current(w);
    for (int r = 0; r < height; ++r) {
      tiler.next_row(current);
      row(r, current);
    }
    return;
  }
  SweepTiler tiler(set, options);
  std::vector<std::uint16_t> previous, current(w);
  const bool from_north = options.algorithm == TilingAlgorithm::scanline;
  for (int r = 0; r < height; ++r) {
    tiler.next_row(previous, current);
    row(from_north ? height - 1 - r : r, current);
    previous.swap(current);
    current.resize(w);
  }
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
    const HashedTiling hashed(set, options.seed, options.forbid_identical_neighbours);
    if (options.forbid_identical_neighbours) {
      for (int first = 0; first < height; first += kHashRowBlock)
        fill_hashed_rows(hashed, true, options.origin_i, options.origin_j + first, width,
                         std::min(kHashRowBlock, height - first),
                         std::span(tiling.tiles).subspan(static_cast<std::size_t>(first) * w));
      return tiling;
    }
    tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
      for (int r = rows.begin(); r < rows.end(); ++r)
        hashed.fill_row(options.origin_i, options.origin_j + r,
                        std::span(tiling.tiles.data() + static_cast<std::size_t>(r) * w, w));
    });
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
