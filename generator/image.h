// Small 8-bit RGB and 16-bit grey images: what previews and tiles are drawn into before
// exporters/ writes them.
#pragma once

#include <cstdint>
#include <vector>

namespace wangscape {

struct Rgb8 {
  std::uint8_t r = 0, g = 0, b = 0;
  bool operator==(const Rgb8&) const = default;
};

// Row-major, top row first, 3 bytes per pixel (R, G, B).
struct ImageRgb8 {
  int width = 0, height = 0;
  std::vector<std::uint8_t> pixels;

  ImageRgb8() = default;
  ImageRgb8(int w, int h, Rgb8 fill = {})
      : width(w), height(h), pixels(static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 3) {
    for (std::size_t p = 0; p < pixels.size(); p += 3) {
      pixels[p] = fill.r;
      pixels[p + 1] = fill.g;
      pixels[p + 2] = fill.b;
    }
  }

  std::size_t offset(int x, int y) const {
    return (static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x)) * 3;
  }
  Rgb8 at(int x, int y) const {
    const std::size_t o = offset(x, y);
    return {pixels[o], pixels[o + 1], pixels[o + 2]};
  }
  void set(int x, int y, Rgb8 c) {
    const std::size_t o = offset(x, y);
    pixels[o] = c.r;
    pixels[o + 1] = c.g;
    pixels[o + 2] = c.b;
  }
  // Fills the rectangle [x0, x0 + w) x [y0, y0 + h), clipped to the image.
  void fill_rect(int x0, int y0, int w, int h, Rgb8 c);
};

// Row-major, top row first, one 16-bit value per pixel (noise tiles: 0 = -1, 65535 = +1).
struct ImageGray16 {
  int width = 0, height = 0;
  std::vector<std::uint16_t> pixels;

  ImageGray16() = default;
  ImageGray16(int w, int h) : width(w), height(h), pixels(static_cast<std::size_t>(w) * static_cast<std::size_t>(h)) {}

  std::size_t offset(int x, int y) const {
    return static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + static_cast<std::size_t>(x);
  }
  std::uint16_t at(int x, int y) const { return pixels[offset(x, y)]; }
  void set(int x, int y, std::uint16_t v) { pixels[offset(x, y)] = v; }
};

}  // namespace wangscape
