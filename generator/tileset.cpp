#include "generator/tileset.h"

#include <algorithm>
#include <charconv>
#include <set>

namespace wangscape {

Tile Tile::edges(int n, int e, int s, int w) {
  Tile t;
  t.colors[kN] = static_cast<std::int8_t>(n);
  t.colors[kE] = static_cast<std::int8_t>(e);
  t.colors[kS] = static_cast<std::int8_t>(s);
  t.colors[kW] = static_cast<std::int8_t>(w);
  return t;
}

Tile Tile::corners(int ne, int se, int sw, int nw) {
  Tile t;
  t.colors[kNE] = static_cast<std::int8_t>(ne);
  t.colors[kSE] = static_cast<std::int8_t>(se);
  t.colors[kSW] = static_cast<std::int8_t>(sw);
  t.colors[kNW] = static_cast<std::int8_t>(nw);
  return t;
}

namespace {

constexpr int kMaxColors = 64;

std::string tile_label(std::size_t index) { return "tile " + std::to_string(index); }

// Parses the K of "prefix-K" (2..kMaxColors); returns 0 when `name` is not of that form.
int parse_suffix_count(std::string_view name, std::string_view prefix) {
  if (name.size() <= prefix.size() || name.substr(0, prefix.size()) != prefix) return 0;
  const std::string_view digits = name.substr(prefix.size());
  int k = 0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), k);
  if (ec != std::errc() || end != digits.data() + digits.size()) return 0;
  return k;
}

TileSet complete_edge_tileset(int k) {
  std::vector<Tile> tiles;
  for (int n = 0; n < k; ++n)
    for (int e = 0; e < k; ++e)
      for (int s = 0; s < k; ++s)
        for (int w = 0; w < k; ++w) tiles.push_back(Tile::edges(n, e, s, w));
  const std::string name = "complete-edge-" + std::to_string(k);
  return make_tileset(name, std::move(tiles), name);
}

TileSet complete_corner_tileset(int k) {
  std::vector<Tile> tiles;
  for (int ne = 0; ne < k; ++ne)
    for (int se = 0; se < k; ++se)
      for (int sw = 0; sw < k; ++sw)
        for (int nw = 0; nw < k; ++nw) tiles.push_back(Tile::corners(ne, se, sw, nw));
  const std::string name = "corner-" + std::to_string(k);
  return make_tileset(name, std::move(tiles), name);
}

// The 12-tile set of the Owen write-up, NESW digits exactly as printed there.
TileSet owen12_tileset() {
  constexpr std::array<const char*, 12> kTable = {"0312", "1302", "0203", "1013", "0310", "1200",
                                                  "0012", "0002", "1003", "0213", "1210", "1300"};
  std::vector<Tile> tiles;
  for (const char* nesw : kTable)
    tiles.push_back(Tile::edges(nesw[0] - '0', nesw[1] - '0', nesw[2] - '0', nesw[3] - '0'));
  return make_tileset("owen12", std::move(tiles), "owen12");
}

// Cohen 2003, section 3.4: the cohen8 edge tiles with their corners coded marked (1) or
// unmarked (0). The full set has all 16 codings per tile (128 tiles). Scanline tiling
// from the north-west constrains only NW, NE and SW, so the reduced set keeps, for each
// edge tile and each of the 8 (NE, SW, NW) codings, one SE mark; the two tiles sharing an
// (N, W) pair get opposite SE marks, so choosing between them still flips a coin for SE.
TileSet cohen8_corner_tileset(bool full) {
  const TileSet base = cohen_tileset("cohen8", 2, 2);
  std::vector<Tile> tiles;
  for (std::size_t t = 0; t < base.tiles.size(); ++t) {
    const Tile& edge_tile = base.tiles[t];
    const int pair_member = static_cast<int>(t % 2);  // cohen_tileset lists (N, W) pairs in twos
    for (int coding = 0; coding < 16; ++coding) {
      const int ne = (coding >> 3) & 1, sw = (coding >> 2) & 1, nw = (coding >> 1) & 1, se = coding & 1;
      if (!full && se != ((ne + sw + nw + pair_member) & 1)) continue;
      Tile tile = edge_tile;
      tile.colors[kNE] = static_cast<std::int8_t>(ne);
      tile.colors[kSE] = static_cast<std::int8_t>(se);
      tile.colors[kSW] = static_cast<std::int8_t>(sw);
      tile.colors[kNW] = static_cast<std::int8_t>(nw);
      tiles.push_back(tile);
    }
  }
  const std::string name = full ? "cohen8-corners-full" : "cohen8-corners";
  return make_tileset(name, std::move(tiles), name);
}

// Culik's 13 tiles, derived from the construction rather than typed in: every tile that some
// rational x = p/q in [1/3, 2] makes at some column k. A row of x = p/q repeats every 2q columns
// (k x and k f(x) both gain whole numbers), and denominators up to 24 already give all 13 (tests
// check the count, and that tilings use each one).
TileSet culik13_tileset() {
  std::set<std::array<std::int8_t, kSlotCount>> found;
  constexpr std::int64_t kLargestDenominator = 24;
  for (std::int64_t q = 1; q <= kLargestDenominator; ++q)
    for (std::int64_t p = (q + 2) / 3; p <= 2 * q; ++p) {  // p/q in [1/3, 2]
      const bool triples = 3 * p <= 2 * q;
      // y = f(x) = y_p / y_q
      const std::int64_t y_p = triples ? 3 * p : p, y_q = triples ? q : 2 * q;
      const bool next_triples = 3 * y_p <= 2 * y_q;
      for (std::int64_t k = 0; k < 2 * q; ++k)
        if (const auto tile =
                culik_tile(triples, next_triples, {k * p / q, (k + 1) * p / q, k * y_p / y_q, (k + 1) * y_p / y_q}))
          found.insert(tile->colors);
    }
  std::vector<Tile> tiles;
  for (const auto& colors : found) tiles.push_back(Tile{colors});
  return make_tileset("culik13", std::move(tiles), "culik13");
}

}  // namespace

std::optional<Tile> culik_tile(bool triples, bool next_triples, const std::array<std::int64_t, 4>& floors) {
  const auto [x0, x1, y0, y1] = floors;
  // Digits 0..2; a 0 that a halving row reads is color 3.
  const auto digit_color = [](std::int64_t digit, bool read_by_tripling) {
    return digit == 0 && !read_by_tripling ? std::int64_t{3} : digit;
  };
  // Tripling carries 3 floor(k x) - floor(k y) in {0, -1, -2} -> 0, 1, 2; halving carries
  // floor(k x) / 2 - floor(k y) in {0, 1/2} -> 3, 4.
  const auto carry_color = [&](std::int64_t x_floor, std::int64_t y_floor) {
    return triples ? y_floor - 3 * x_floor : 3 + x_floor - 2 * y_floor;
  };
  const std::int64_t n = digit_color(y1 - y0, next_triples), s = digit_color(x1 - x0, triples);
  const std::int64_t e = carry_color(x1, y1), w = carry_color(x0, y0);
  const auto within = [](std::int64_t c, std::int64_t lo, std::int64_t hi) { return c >= lo && c <= hi; };
  const bool carries_fit = triples ? within(e, 0, 2) && within(w, 0, 2) : within(e, 3, 4) && within(w, 3, 4);
  if (!carries_fit || !within(n, 0, 3) || !within(s, 0, 3)) return std::nullopt;
  return Tile::edges(static_cast<int>(n), static_cast<int>(e), static_cast<int>(s), static_cast<int>(w));
}

TileSet cohen_tileset(std::string name, int horizontal, int vertical) {
  // For each (N, W) pair and a coin b: E = (2N + W + b) mod vertical, S = (N + b) mod
  // horizontal. Every adjacent edge pair then appears exactly twice (checked in tests);
  // with 2 x 2 colors these are the eight even-parity tiles.
  std::vector<Tile> tiles;
  for (int n = 0; n < horizontal; ++n)
    for (int w = 0; w < vertical; ++w)
      for (int b = 0; b < 2; ++b) tiles.push_back(Tile::edges(n, (2 * n + w + b) % vertical, (n + b) % horizontal, w));
  const std::string source = name;
  return make_tileset(std::move(name), std::move(tiles), source);
}

TileSet make_tileset(std::string name, std::vector<Tile> tiles, std::string_view source) {
  const std::string where = "tile set '" + std::string(source) + "'";
  if (tiles.empty()) throw Error(where + ": no tiles");
  TileSet set;
  set.name = std::move(name);
  set.source = std::string(source);
  const Tile& first = tiles.front();
  set.has_edges = first.n() != kNoColor;
  set.has_corners = first.ne() != kNoColor;
  if (!set.has_edges && !set.has_corners)
    throw Error(where + ": " + tile_label(0) + " has neither edge nor corner colors");
  set.kind = set.has_edges ? TileKind::edge : TileKind::corner;

  std::set<std::array<std::int8_t, kSlotCount>> seen;
  for (std::size_t i = 0; i < tiles.size(); ++i) {
    const Tile& t = tiles[i];
    for (int slot = 0; slot < kSlotCount; ++slot) {
      const bool wanted = slot < kNE ? set.has_edges : set.has_corners;
      const int c = t.colors[static_cast<std::size_t>(slot)];
      if (wanted && (c < 0 || c >= kMaxColors))
        throw Error(where + ": " + tile_label(i) + " has color " + std::to_string(c) + " at " +
                    std::array{"n", "e", "s", "w", "ne", "se", "sw", "nw"}[static_cast<std::size_t>(slot)] +
                    "; expected 0.." + std::to_string(kMaxColors - 1));
      if (!wanted && c != kNoColor)
        throw Error(where + ": " + tile_label(i) + " colors " + (slot < kNE ? "edges" : "corners") +
                    " but the first tile does not; every tile must color the same parts");
    }
    if (!seen.insert(t.colors).second) throw Error(where + ": " + tile_label(i) + " repeats an earlier tile");
    if (set.has_edges) {
      set.horizontal_colors = std::max({set.horizontal_colors, t.n() + 1, t.s() + 1});
      set.vertical_colors = std::max({set.vertical_colors, t.e() + 1, t.w() + 1});
    }
    if (set.has_corners)
      set.corner_colors = std::max({set.corner_colors, t.ne() + 1, t.se() + 1, t.sw() + 1, t.nw() + 1});
  }
  set.tiles = std::move(tiles);
  return set;
}

bool is_builtin_tileset(std::string_view name) {
  static const std::set<std::string_view> kFixed = {
      "cohen8", "cohen12", "cohen18", "owen12", "cohen8-corners", "cohen8-corners-full", "culik13"};
  if (kFixed.count(name)) return true;
  const int edge_k = parse_suffix_count(name, "complete-edge-");
  const int corner_k = parse_suffix_count(name, "corner-");
  return (edge_k >= 2 && edge_k <= 8) || (corner_k >= 2 && corner_k <= 8);
}

TileSet builtin_tileset(std::string_view name) {
  if (name == "cohen8") return cohen_tileset("cohen8", 2, 2);
  if (name == "cohen12") return cohen_tileset("cohen12", 2, 3);
  if (name == "cohen18") return cohen_tileset("cohen18", 3, 3);
  if (name == "owen12") return owen12_tileset();
  if (name == "cohen8-corners") return cohen8_corner_tileset(false);
  if (name == "cohen8-corners-full") return cohen8_corner_tileset(true);
  if (name == "culik13") return culik13_tileset();
  // K up to 8: K^4 tiles (4096 at K = 8) is already far more than anyone fills with content.
  if (const int k = parse_suffix_count(name, "complete-edge-"); k >= 2 && k <= 8) return complete_edge_tileset(k);
  if (const int k = parse_suffix_count(name, "corner-"); k >= 2 && k <= 8) return complete_corner_tileset(k);
  throw Error("unknown tile set '" + std::string(name) +
              "'; expected a JSON file or one of cohen8, cohen12, cohen18, owen12, "
              "complete-edge-K, corner-K (K = 2..8), cohen8-corners, cohen8-corners-full, culik13");
}

std::string TileSet::describe() const { return "tile set '" + (source.empty() ? name : source) + "'"; }

std::vector<std::string> builtin_tileset_names() {
  return {"cohen8",          "cohen12",  "cohen18",  "owen12",         "complete-edge-2",
          "complete-edge-3", "corner-2", "corner-3", "cohen8-corners", "cohen8-corners-full",
          "culik13"};
}

}  // namespace wangscape
