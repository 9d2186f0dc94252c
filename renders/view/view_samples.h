// What the world and the renderer of the view both read from an LDI: the ordered dither, the
// sRGB lookups and the front samples of an LDI's pixels. Internal to renders/view.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include "core/color.h"
#include "folder/ldi_pack.h"
#include "renders/trace/traced_shading.h"

namespace wangscape::view_detail {

// LDI samples of the ground plane are drawn by the terrain instead: the last layer of a pixel
// this low (meters, plus 3/4 of a pixel: positions go through the pixel centre, rays did not).
constexpr float kGroundEpsilon = 0.002f;

// The ordered 4 x 4 (Bayer) dither: cell k of a pixel, its threshold (k + 0.5) / 16 in (0, 1),
// which decides which of two dithered LDIs owns the pixel.
constexpr std::uint8_t kBayerIndex[4][4] = {{0, 8, 2, 10}, {12, 4, 14, 6}, {3, 11, 1, 9}, {15, 7, 13, 5}};
inline int bayer_index(int x, int y) { return kBayerIndex[y & 3][x & 3]; }
inline float threshold(int x, int y) { return (float(bayer_index(x, y)) + 0.5f) / 16; }

struct Luts {
  std::array<float, 256> to_linear{};
  std::array<std::uint8_t, 4096> to_srgb{};
  Luts() {
    for (int i = 0; i < 256; ++i) to_linear[std::size_t(i)] = srgb_to_linear(float(i) / 255.0f);
    for (int i = 0; i < 4096; ++i) to_srgb[std::size_t(i)] = to_srgb8({float(i) / 4095.0f, 0, 0})[0];
  }
  std::uint8_t encode(float linear) const {
    return to_srgb[std::size_t(std::clamp(linear, 0.0f, 1.0f) * 4095.0f + 0.5f)];
  }
};
inline const Luts& luts() {
  static const Luts l;
  return l;
}

// The front sample of an LDI pixel of `count` layers lies on the ground plane (the terrain draws
// the ground; an LDI only adds what stands on it).
inline bool front_is_ground(const LdiView& v, int x, int y, std::uint8_t count, const DepthPixel& front) {
  return count == 1 && v.position(x, y, front)[2] < kGroundEpsilon + 0.75f * v.frame->pixel_size;
}

// Calls visit(x, y, front, is_ground) for the front sample of every pixel of `v` that has one.
template <class Visit>
void for_each_front_sample(const LdiView& v, Visit&& visit) {
  for (std::uint32_t y = 0; y < v.frame->height; ++y)
    for (std::uint32_t s = v.row_spans[y]; s < v.row_spans[y + 1]; ++s) {
      const LdiSpan& span = v.spans[s];
      std::uint32_t depth = span.first_depth;
      for (std::uint32_t k = 0; k < span.length; ++k) {
        const std::uint8_t count = v.counts[span.first_pixel + k];
        if (count == 0) continue;
        const DepthPixel& front = v.depth_pixels[depth];
        depth += count;
        const int x = int(span.x + k);
        visit(x, int(y), front, front_is_ground(v, x, int(y), count, front));
      }
    }
}

// A one-layer LDI of `v` at 1/factor of its resolution: per block of factor x factor pixels, the

}  // namespace wangscape::view_detail
