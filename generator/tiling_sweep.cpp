// The sweeps (generator/tiling.h): scanline (Cohen 2003, rows north to south) and bottom-left
// (Shade 2002, rows south to north), each row west to east, every tile drawn among those that
// match the neighbours already placed; with forbid_identical_neighbours, small sets draw whole
// rows with a lookahead and, for a few sets, a fitted tilt against repeats.
#include <algorithm>
#include <bit>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <string>
#include <vector>

#include "generator/tiling_algorithms.h"

namespace wangscape::tiling_detail {

namespace {

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

// A uniform integer in [0, count) from 32 random bits.
inline std::uint32_t scale(std::uint32_t bits, std::uint32_t count) {
  return static_cast<std::uint32_t>((static_cast<std::uint64_t>(bits) * count) >> 32);
}

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

}  // namespace

void stream_sweep_tiling(const TileSet& set, int width, int height, const TilingOptions& options,
                         const TilingRowSink& row) {
  const auto w = static_cast<std::size_t>(width);
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

}  // namespace wangscape::tiling_detail
