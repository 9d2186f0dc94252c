// Wang tile sets: squares with colored edges (N, E, S, W) or colored corners
// (NE, SE, SW, NW), never rotated. Tiling coordinates: i grows east, j grows north.
#pragma once

#include "core/error.h"

#include <array>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace wangscape {

inline constexpr int kNoColor = -1;

// Slots of a tile's colors, usable as indices into Tile::colors.
enum Slot : int { kN = 0, kE, kS, kW, kNE, kSE, kSW, kNW, kSlotCount };

struct Tile {
  // N, E, S, W edge colors then NE, SE, SW, NW corner colors; kNoColor where the set does
  // not color that part (corner sets have no edge colors; most edge sets no corner colors).
  std::array<std::int8_t, kSlotCount> colors{kNoColor, kNoColor, kNoColor, kNoColor,
                                             kNoColor, kNoColor, kNoColor, kNoColor};

  int n() const { return colors[kN]; }
  int e() const { return colors[kE]; }
  int s() const { return colors[kS]; }
  int w() const { return colors[kW]; }
  int ne() const { return colors[kNE]; }
  int se() const { return colors[kSE]; }
  int sw() const { return colors[kSW]; }
  int nw() const { return colors[kNW]; }
  bool operator==(const Tile&) const = default;

  static Tile edges(int n, int e, int s, int w);
  static Tile corners(int ne, int se, int sw, int nw);
};

enum class TileKind : std::uint8_t { edge, corner };

struct TileSet {
  std::string name;
  std::string source;  // where the set came from (file path, or the built-in name), for messages
  TileKind kind = TileKind::edge;
  bool has_edges = true;     // edge colors present (edge sets)
  bool has_corners = false;  // corner colors present (corner sets, corner-coded edge sets)
  // Alphabet sizes: N/S edges use horizontal_colors, E/W edges vertical_colors; corners
  // use corner_colors. Zero where the set has no such colors.
  int horizontal_colors = 0;
  int vertical_colors = 0;
  int corner_colors = 0;
  std::vector<Tile> tiles;

  std::size_t size() const { return tiles.size(); }
  // "tile set '<source>'": how error messages name the set.
  std::string describe() const;
};

// Builds a tile set from explicit tiles: derives the alphabets, checks colors are in
// range and that no tile is listed twice. `source` names the input in error messages
// (a file name or a built-in name).
TileSet make_tileset(std::string name, std::vector<Tile> tiles, std::string_view source);

// The built-in sets by name: cohen8, cohen12, cohen18, owen12, complete-edge-K,
// corner-K, cohen8-corners (64 tiles), cohen8-corners-full (128 tiles), culik13 (aperiodic).
// Throws Error naming the unknown set.
TileSet builtin_tileset(std::string_view name);
bool is_builtin_tileset(std::string_view name);
std::vector<std::string> builtin_tileset_names();

// Cohen-style stochastic edge sets with `horizontal` N/S colors and `vertical` E/W colors:
// two tiles for every (N, W) pair, and every pair of adjacent edges (NW, NE, SW, SE)
// appears on exactly two tiles, so scanline tiling works from any corner.
TileSet cohen_tileset(std::string name, int horizontal, int vertical);

// Culik's strictly aperiodic set of 13 tiles (Culik 1996, after Kari 1996). A row of tiles
// multiplies a real x by 3 (x in [1/3, 2/3]) or by 1/2 (x in (2/3, 2]): its S edges read x's
// balanced representation B_k(x) = floor((k + 1) x) - floor(k x) (k the column), its N edges write
// that of y = f(x), and each W/E edge carries q floor(k x) - floor(k y) (q the multiplier), so every
// tile has q S + W = N + E. Colors: N/S 0, 1, 2 are digits, 3 is a digit 0 that a halving row reads
// (without it the halving tile 0/0 with equal carries would tile the plane alone); W/E 0, 1, 2 are
// the tripling carries 0, -1, -2 and 3, 4 the halving carries 0, 1/2.
inline constexpr int kCulikTiles = 13;

// The tile at column k of a row whose multiplier is 3 (`triples`) or 1/2, under a row that
// `next_triples`, from floor(k x), floor((k + 1) x), floor(k y), floor((k + 1) y) (y = f(x)).
// Nothing when the floors give a carry outside the set's (y not exactly f(x)).
std::optional<Tile> culik_tile(bool triples, bool next_triples, const std::array<std::int64_t, 4>& floors);

}  // namespace wangscape
