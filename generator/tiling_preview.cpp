#include "generator/tiling_preview.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace wangscape {

void ImageRgb8::fill_rect(int x0, int y0, int w, int h, Rgb8 c) {
  for (int y = std::max(0, y0); y < std::min(height, y0 + h); ++y)
    for (int x = std::max(0, x0); x < std::min(width, x0 + w); ++x) set(x, y, c);
}

namespace {

Rgb8 from_hsv(double hue, double saturation, double value) {
  const double h = (hue - std::floor(hue)) * 6.0;
  const int sector = static_cast<int>(h) % 6;
  const double f = h - std::floor(h);
  const double p = value * (1 - saturation), q = value * (1 - saturation * f), t = value * (1 - saturation * (1 - f));
  double r = value, g = t, b = p;
  switch (sector) {
    case 1:
      r = q, g = value, b = p;
      break;
    case 2:
      r = p, g = value, b = t;
      break;
    case 3:
      r = p, g = q, b = value;
      break;
    case 4:
      r = t, g = p, b = value;
      break;
    case 5:
      r = value, g = p, b = q;
      break;
    default:
      break;
  }
  const auto byte = [](double v) { return static_cast<std::uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0)); };
  return {byte(r), byte(g), byte(b)};
}

// Edge and corner colors in the spirit of Cohen 2003, Fig. 1: N/S edges red/green, E/W edges
// blue/yellow, corners white (unmarked) / black (marked); further colors from a hue wheel.
Rgb8 horizontal_edge_color(int c) {
  static constexpr Rgb8 kFirst[] = {{220, 50, 47}, {80, 175, 60}, {240, 140, 30}};
  return c < 3 ? kFirst[c] : from_hsv(0.05 + 0.618 * c, 0.7, 0.85);
}
Rgb8 vertical_edge_color(int c) {
  static constexpr Rgb8 kFirst[] = {{40, 90, 210}, {240, 210, 40}, {150, 60, 190}};
  return c < 3 ? kFirst[c] : from_hsv(0.55 + 0.618 * c, 0.6, 0.9);
}
Rgb8 corner_color(int c) {
  static constexpr Rgb8 kFirst[] = {{245, 245, 245}, {25, 25, 25}, {140, 140, 140}};
  return c < 3 ? kFirst[c] : from_hsv(0.3 + 0.618 * c, 0.5, 0.6);
}

void check_pixels(std::int64_t width, std::int64_t height, const std::string& what) {
  if (width < 1 || height < 1 || width * height > (std::int64_t{1} << 28))
    throw Error(what + ": image of " + std::to_string(width) + "x" + std::to_string(height) +
                " pixels; expected 1 to 2^28 pixels");
}

}  // namespace

Rgb8 tile_pseudo_color(std::size_t tile) {
  const double golden = 0.6180339887498949;
  const double lightness[] = {0.95, 0.75, 0.55};
  return from_hsv(0.12 + golden * static_cast<double>(tile), tile % 2 ? 0.55 : 0.8, lightness[(tile / 2) % 3]);
}

ImageRgb8 draw_tile_map(const Tiling& tiling, int pixels_per_tile) {
  if (pixels_per_tile < 1)
    throw Error("tile map: " + std::to_string(pixels_per_tile) + " pixels per tile; expected at least 1");
  check_pixels(std::int64_t{tiling.width} * pixels_per_tile, std::int64_t{tiling.height} * pixels_per_tile, "tile map");
  ImageRgb8 image(tiling.width * pixels_per_tile, tiling.height * pixels_per_tile);
  for (int lj = 0; lj < tiling.height; ++lj)
    for (int li = 0; li < tiling.width; ++li)
      image.fill_rect(li * pixels_per_tile, (tiling.height - 1 - lj) * pixels_per_tile, pixels_per_tile,
                      pixels_per_tile, tile_pseudo_color(tiling.at(li, lj)));
  return image;
}

ImageRgb8 draw_tileset_sheet(const TileSet& set, int tile_pixels) {
  if (tile_pixels < 8)
    throw Error("tile set sheet: " + std::to_string(tile_pixels) + " pixels per tile; expected at least 8");
  const int count = static_cast<int>(set.size());
  const int columns = std::clamp(static_cast<int>(std::ceil(std::sqrt(static_cast<double>(count)))), 1, 16);
  const int rows = (count + columns - 1) / columns;
  const int gap = std::max(2, tile_pixels / 8);
  const int pitch = tile_pixels + gap;
  check_pixels(std::int64_t{columns} * pitch + gap, std::int64_t{rows} * pitch + gap, set.describe() + " sheet");
  ImageRgb8 image(columns * pitch + gap, rows * pitch + gap, {60, 60, 60});
  const int marker = std::max(2, tile_pixels / 5);
  for (int t = 0; t < count; ++t) {
    const Tile& tile = set.tiles[static_cast<std::size_t>(t)];
    const int x0 = gap + (t % columns) * pitch, y0 = gap + (t / columns) * pitch;
    for (int y = 0; y < tile_pixels; ++y)
      for (int x = 0; x < tile_pixels; ++x) {
        // Pixel center relative to the tile center, y up; |u| vs |v| picks the triangle.
        const double u = (x + 0.5) / tile_pixels - 0.5, v = 0.5 - (y + 0.5) / tile_pixels;
        Rgb8 c;
        if (set.has_edges) {
          if (std::abs(v) >= std::abs(u))
            c = horizontal_edge_color(v > 0 ? tile.n() : tile.s());
          else
            c = vertical_edge_color(u > 0 ? tile.e() : tile.w());
        } else {
          c = corner_color(v > 0 ? (u > 0 ? tile.ne() : tile.nw()) : (u > 0 ? tile.se() : tile.sw()));
        }
        image.set(x0 + x, y0 + y, c);
      }
    if (set.has_edges && set.has_corners) {
      const int far = tile_pixels - marker;
      image.fill_rect(x0 + far, y0, marker, marker, corner_color(tile.ne()));
      image.fill_rect(x0 + far, y0 + far, marker, marker, corner_color(tile.se()));
      image.fill_rect(x0, y0 + far, marker, marker, corner_color(tile.sw()));
      image.fill_rect(x0, y0, marker, marker, corner_color(tile.nw()));
    }
  }
  return image;
}

}  // namespace wangscape
