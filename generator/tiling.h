// Wang tilings: windows of the plane covered with tiles of a TileSet so that every shared
// edge (and corner, for corner-coded sets) matches. Coordinates: tile (i, j), i grows east,
// j grows north. Four algorithms:
//  - scanline (Cohen 2003, steps 1-5): rows from north to south, each row west to east; every
//    tile is drawn at random among those matching its northern and western neighbours;
//  - bottom_left (Shade 2002): the same from the south-west corner, rows south to north, each
//    tile matching its southern and western neighbours;
//  - hash (Wang tiles blog): edge (or corner) colors are hashed from their position, so any tile
//    is known in O(1) without its neighbours; needs a complete set;
//  - aperiodic (Culik 1996): Culik's 13 tiles only, built row by row from the orbit of a real
//    number under his multiplier (see culik_tile); never periodic.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "generator/tileset.h"

namespace wangscape {

enum class TilingAlgorithm { scanline, bottom_left, hash, aperiodic };

inline constexpr std::array<TilingAlgorithm, 4> kTilingAlgorithms{
    TilingAlgorithm::scanline, TilingAlgorithm::bottom_left, TilingAlgorithm::hash, TilingAlgorithm::aperiodic};

// "scanline", "bottom-left", "hash", "aperiodic"; parse throws Error naming the value.
std::string_view to_string(TilingAlgorithm algorithm);
TilingAlgorithm parse_tiling_algorithm(std::string_view text);
// The algorithm `text` names, or nothing (for readers that word their own error, with a line).
std::optional<TilingAlgorithm> find_tiling_algorithm(std::string_view text);
// Every algorithm's name, in kTilingAlgorithms' order (for the command line's choices).
std::vector<std::string> tiling_algorithm_names();

struct TilingOptions {
  TilingAlgorithm algorithm = TilingAlgorithm::scanline;
  std::uint64_t seed = 1;
  // As in Owen: no tile equals its western or northern (southern for bottom_left) neighbour.
  // For hash tilings, no tile equals any of its four neighbours (re-hashing the colors).
  // Aperiodic tilings refuse it: the construction fixes every tile.
  bool forbid_identical_neighbours = false;
  // Tile coordinates of the window's south-west tile. Hash tilings depend on both; aperiodic ones
  // on origin_i (windows side by side with one seed continue each other); other algorithms just
  // label their window with it. |i|, |j| stay within kMaxTileCoordinate.
  std::int64_t origin_i = 0, origin_j = 0;
};

// The largest tile coordinate (either sign) of any tiling: hashed tilings address edges on a
// grid twice as dense, which must not overflow 64 bits. Windows reaching beyond are refused.
inline constexpr std::int64_t kMaxTileCoordinate = std::int64_t{1} << 60;

// A width x height window; tiles[(local_j) * width + local_i], local_j = 0 is the southern row
// (j = origin_j), i grows east, j grows north; values index TileSet::tiles.
struct Tiling {
  int width = 0, height = 0;
  std::int64_t origin_i = 0, origin_j = 0;
  std::vector<std::uint16_t> tiles;

  std::uint16_t at(int local_i, int local_j) const {
    return tiles[static_cast<std::size_t>(local_j) * static_cast<std::size_t>(width) +
                 static_cast<std::size_t>(local_i)];
  }
};

// Tiles a width x height window. Throws Error when the size is not positive, the set
// cannot be tiled by the algorithm (naming the missing constraint), or the set cannot satisfy
// forbid_identical_neighbours. Deterministic from options.seed on any thread count.
Tiling make_tiling(const TileSet& set, int width, int height, const TilingOptions& options);

// Row-streaming variant for windows too large to hold: calls `row(local_j, tiles)` once per row,
// in the algorithm's order (scanline: north to south; the others: south to north).
// Memory is O(width). Produces exactly the rows make_tiling would.
using TilingRowSink = std::function<void(int local_j, std::span<const std::uint16_t> tiles)>;
void stream_tiling(const TileSet& set, int width, int height, const TilingOptions& options, const TilingRowSink& row);

// make_tiling through stream_tiling (the same tiles), calling rows_done(n) after each of the n
// rows (for a progress bar). Throws Error, as make_tiling, and for windows of more than 2^30
// tiles (2 bytes each in memory).
Tiling make_tiling(const TileSet& set, int width, int height, const TilingOptions& options,
                   const std::function<void(int rows_done)>& rows_done);

// O(1) random access for complete edge sets (edge colors hashed on the doubled grid, Wang tiles blog:
// N of tile (i,j) at (2i+1, 2j+2), S at (2i+1, 2j), E at (2i+2, 2j+1), W at (2i, 2j+1)) and
// complete corner sets (corner colors hashed on lattice vertices). Deterministic from seed, any int64 i, j.
// A set is complete when it holds every combination of its alphabets (K^4 tiles, or
// H^2 V^2 for edge sets with separate horizontal/vertical alphabets), in any order.
class HashedTiling {
 public:
  // Throws Error "tile set '<name>': hash tiling needs a complete set; missing
  // (N,E,S,W)=(1,0,0,1)" (or (NE,SE,SW,NW)=...) when the set is not complete.
  // forbid_identical_neighbours: the hashed colors are repaired where neighbours come out
  // identical (rounds of redrawing a color of theirs, then an exact repair of the 4 x 4 block
  // around what is left; see fill_window; corner sets with two colors then move corners towards
  // even tile frequencies), so no two neighbouring tiles are identical. Still O(1) per tile and
  // deterministic, but each call computes a margin of tiles around its window (margin_: 18, 34 for
  // corner sets with two colors): ask for windows (fill_window, make_tiling), not single tiles. Needs at
  // least two colors per alphabet.
  HashedTiling(const TileSet& set, std::uint64_t seed, bool forbid_identical_neighbours = false);

  std::uint32_t tile_at(std::int64_t i, std::int64_t j) const;
  // The tile with these colors (slots N, E, S, W, NE, SE, SW, NW; 0 where the set has none), for
  // callers that choose some colors themselves (e.g. corner marks from the terrain). Throws Error
  // for a color outside the set's alphabet.
  std::uint32_t tile_with_colors(const std::array<std::uint32_t, kSlotCount>& colors) const;
  // Tiles (first_i + k, j) for k in [0, out.size()). Thread-safe (const).
  void fill_row(std::int64_t first_i, std::int64_t j, std::span<std::uint16_t> out) const;
  // Tiles (first_i + k, first_j + r) into out[r * width + k], r < height, k < width; the same tiles
  // as fill_row and tile_at. Thread-safe (const).
  void fill_window(std::int64_t first_i, std::int64_t first_j, int width, int height,
                   std::span<std::uint16_t> out) const;

  // Edge color at a doubled-grid point, corner color at a lattice vertex, drawn from
  // `alphabet` colors, before any repair for forbid_identical_neighbours; exposed for tests and
  // for callers that hash corner marks the same way.
  std::uint32_t color_at(std::int64_t x, std::int64_t y, std::uint32_t alphabet) const;
  std::uint32_t corner_at(std::int64_t x, std::int64_t y, std::uint32_t alphabet) const;

 private:
  std::uint32_t code(const std::array<std::uint32_t, kSlotCount>& colors) const;
  std::uint32_t row_key(std::int64_t y, std::uint64_t salt) const;

  std::uint64_t seed_ = 0;
  bool forbid_ = false;
  bool balances_ = false;  // balance rounds after the repair (corner sets with two colors)
  int margin_ = 0;         // tiles computed around a window when forbidding identical neighbours
  bool has_edges_ = true, has_corners_ = false;
  std::array<std::uint32_t, kSlotCount> radix_{};  // colors per slot, 1 where the set has none
  // Maps the mixed-radix color code (slots N, E, S, W, NE, SE, SW, NW) to the tile index.
  std::vector<std::uint16_t> lookup_;
};

// Throws Error naming the first mismatching edge/corner, e.g. "tiling with 'cohen8':
// tile (3, 5) has N=1 but tile (3, 6) has S=0", or an out-of-range tile index.
void check_tiling(const TileSet& set, const Tiling& tiling);

}  // namespace wangscape
