// A small 8-bit RGB image: what previews are drawn into before exporters/ writes them.
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

}  // namespace wangscape
