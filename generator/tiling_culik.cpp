// Culik's aperiodic tiling (generator/tiling.h, TilingAlgorithm::aperiodic): his 13 tiles laid
// row by row from the orbit of a real number under his multiplier, in 128-bit fixed point.
#include <algorithm>
#include <string>
#include <vector>

#include "generator/tiling_algorithms.h"

namespace wangscape::tiling_detail {

// Whether `set` holds exactly Culik's 13 tiles, in any order.
bool is_culik13(const TileSet& set) {
  static const TileSet culik = builtin_tileset("culik13");
  return set.size() == culik.size() && set.has_edges && !set.has_corners &&
         std::is_permutation(set.tiles.begin(), set.tiles.end(), culik.tiles.begin());
}

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

void stream_culik_tiling(const TileSet& set, int width, int height, const TilingOptions& options,
                         const TilingRowSink& row) {
  CulikTiler tiler(set, options, width);
  std::vector<std::uint16_t> current(static_cast<std::size_t>(width));
  for (int r = 0; r < height; ++r) {
    tiler.next_row(current);
    row(r, current);
  }
}

}  // namespace wangscape::tiling_detail
