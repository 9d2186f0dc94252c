// Previews drawn into an ImageRgb8: a tiling as one pseudo-colored block per tile (Cohen 2003,
// Fig. 2), and a tile set as a sheet showing each tile's edge and corner colors.
#pragma once

#include "generator/image.h"
#include "generator/tiling.h"

namespace wangscape {

// A distinct, stable color per tile index (golden-ratio hues, varied lightness).
Rgb8 tile_pseudo_color(std::size_t tile);

// One pixels_per_tile x pixels_per_tile block per tile, north at the top. Throws Error
// when pixels_per_tile < 1 or the image would exceed 2^28 pixels.
ImageRgb8 draw_tile_map(const Tiling& tiling, int pixels_per_tile = 4);

// Each tile drawn tile_pixels wide in a grid (columns ~ sqrt(n)): edge colors as the four
// triangles meeting at the center (N on top), corner colors as quadrants (corner sets) or as
// small squares in the corners (corner-coded edge sets); tiles in set order, row-major.
ImageRgb8 draw_tileset_sheet(const TileSet& set, int tile_pixels = 48);

}  // namespace wangscape
