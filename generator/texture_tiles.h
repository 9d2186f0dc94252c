// Quilted texture Wang tiles (Cohen 2003, sections 3.2 and 3.5): every edge key owns one diamond
// sample of an exemplar image, and every tile is quilted from its four diamonds along its two
// diagonals with minimum-error boundary cuts (dynamic programming, as in image quilting).
//
// Geometry (pixels; tile pixel (x, y), y down, T = tile_size): the diamond of an edge is centred
// on the edge's midpoint and is read from a T x T window of an exemplar whose centre (a pixel
// corner) sits on that midpoint. The tile below an edge takes the diamond's lower half, the tile
// above its upper half, so the two rows (or columns) on either side of a shared edge are
// neighbouring rows of one exemplar window: no seam across tile edges, by construction. Inside a
// tile, quadrant NE is split between the N and E diamonds by a cut near the NE diagonal (and so
// on); cuts start at the tile centre and end at the tile corner, so every border pixel keeps its
// edge's diamond. The corner pixel of a tile lies on two edges; it takes the N or S diamond, so
// only the 2 x 2 pixels around a tiling vertex can differ across a vertical edge.
//
// Every diamond key (orientation, edge color and, in corner-colored sets, the corner marks at the
// edge's two ends) owns its own window, so no two keys show the same piece of the exemplar; the
// windows of one exemplar start half a tile apart (also at the offsets where diamonds meet) and
// come closer only when the exemplar has no room.
//
// Every tile also has an interior of its own (issue 23): a patch of the exemplar over all of the
// tile but its border row, inside a closed minimum-error cut that runs 1 to 1 + T/16 pixels in
// from the edges (the border row keeps its diamonds, so tiles stay seamless). With K colors per
// edge a neighbour shares each diamond with probability ~1/K; the interiors lower what repeats at
// one tile's shift (cohen8: 0.52 to 0.31 with a disc of radius 3/8 to 1/2 tile, 0.21 now;
// docs/texture-tiles.md).
//
// Two exemplars in a corner-colored set (cohen8-corners, corner-K; Cohen 2003, section 3.5):
// the tiles are quilted once from each exemplar, and each pixel shows the exemplar that the
// corner marks (mark m: exemplar m mod 2) interpolated across the tile, bent by seamless noise
// tiles of the same set, choose there. The boundary between the two exemplars is seamless and
// wanders away from the tile grid; pixels near a corner keep the corner's exemplar.
//
// Seam cost (the error reported): over all pairs of 4-neighbour pixels p, q of a tile whose
// sources differ, |A(p) - B(p)|^2 + |A(q) - B(q)|^2, where A, B are the two sources (exemplar
// colors through window and slot) and |.|^2 the squared RGB difference (0..3 * 255^2 per pixel).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "generator/image.h"
#include "generator/tileset.h"
#include "generator/tiling.h"

namespace wangscape {

struct TextureTileOptions {
  int tile_size = 128;  // pixels per tile side: even, >= 16, at most every exemplar's width and height
  int band = 0;         // cuts stay within this many pixels of the straight seam; 0 = tile_size / 16 (>= 2)
  // The sample search (Cohen 2003, section 3.2): `rounds` passes over all windows; each pass tries
  // `candidates` random positions per window and keeps the one that lowers the summed cut cost.
  int rounds = 3;
  int candidates = 24;
  // Windows of one exemplar stay at least this far apart (Chebyshev, pixels), also from the
  // offsets at which two diamonds meet in a tile, so no two diamonds are one contiguous piece of
  // the exemplar (which would make a near-periodic texture). They start half a tile apart and
  // come closer, halving, only while the exemplar has no room, down to this floor (0: down to 1 pixel; with
  // a floor, an exemplar without room for it is an error).
  int min_separation = 0;
  std::uint64_t seed = 1;
};

// A T x T window of exemplar `exemplar` covering [x - T/2, x + T/2) x [y - T/2, y + T/2).
struct TextureWindow {
  int exemplar = 0;
  int x = 0, y = 0;
  bool operator==(const TextureWindow&) const = default;
};

struct TextureTile {
  ImageRgb8 image;  // tile_size x tile_size, north at the top
  // Per pixel, row-major: window * 4 + slot (kN, kE, kS, kW) it was copied from (see texture_source_pixel).
  std::vector<std::uint16_t> source;
  std::uint64_t error = 0;  // the seam cost the cuts leave in this tile
};

struct TextureTileSet {
  TileSet set;
  int tile_size = 0;
  int marks = 1;  // corner marks (the set's corner colors, 1 when it has none)
  // Per exemplar quilted (one, or two for a corner-colored set with two exemplars), one window
  // per diamond key, in order of the key's first use in set.tiles.
  std::vector<TextureWindow> windows;
  std::vector<TextureTile> tiles;  // per tile of set.tiles

  std::uint64_t total_error() const;
};

// The sample search over the diamonds' windows; the tiles' interiors, chosen after it, are not in
// these costs.
struct TextureTileReport {
  std::uint64_t initial_cost = 0;  // the search objective (sum of the cuts' costs, all exemplars) before the search
  std::uint64_t final_cost = 0;    // ... and after it
  int candidates_tried = 0;
  int moves_accepted = 0;
};

// The exemplar pixel that tile pixel (x, y) shows when copied from `window` through `slot`
// (the edge whose diamond the window belongs to in that tile).
inline std::array<int, 2> texture_source_pixel(int tile_size, const TextureWindow& window, int slot, int x, int y) {
  const int half = tile_size / 2;
  switch (slot) {
    case kN:
      return {window.x + x - half, window.y + y};
    case kS:
      return {window.x + x - half, window.y + y - tile_size};
    case kE:
      return {window.x + x - tile_size, window.y + y - half};
    default:  // kW
      return {window.x + x, window.y + y - half};
  }
}

// Builds every tile of `set` (an edge set, a corner set, or an edge set with corner marks) from
// one or two exemplars. Deterministic from options.seed: the same bytes on any thread count.
// Throws Error naming the problem (exemplar smaller than a tile, no room for the
// windows at that separation, options out of range).
TextureTileSet make_texture_tiles(const TileSet& set, std::span<const ImageRgb8> exemplars,
                                  const TextureTileOptions& options, TextureTileReport* report = nullptr);

// The tiles laid by `tiling` (north at the top): width * T x height * T pixels. Throws
// Error when the image would exceed 2^28 pixels or a tile index is out of range.
ImageRgb8 draw_texture_tiling(const TextureTileSet& tiles, const Tiling& tiling);

// The figures of the `texture tiles --size 64 --preview 1024x512` picture (16 x 8 tiles of 64
// pixels over the set's default tiling) of `set` from `exemplars`, means over seeds 1..seeds:
// generator/image_spectrum.h's axis-to-diagonal energy ratio, repetition at one tile's shift and
// tile-period peak, of its luma. What the benchmark reports and the tests bound.
struct TexturePreviewFigures {
  double axis_ratio = 0, repetition = 0, peak = 0;
};
TexturePreviewFigures texture_preview_figures(const TileSet& set, std::span<const ImageRgb8> exemplars, int seeds);

}  // namespace wangscape
