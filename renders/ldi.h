// One orthographic Layered Depth Image of a tile (seed 003 section 4): a grid of pixels, each with
// the pre-shaded depth pixels its ray met inside the tile's prism, front to back. Stored in
// compressed-row form: per row, spans of non-empty pixels; per pixel of a span its layer count;
// the depth pixels of a pixel contiguous. These structs are also the pack's on-disk records
// (little endian, docs/ldi-pack-format.md), so their sizes are fixed.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace wangscape {

// A depth pixel: 8 bytes. depth is 16-bit fixed point over the LDI's depth range; normal is
// octahedral (8 + 8 bits), unit, turned towards the viewer.
struct DepthPixel {
  std::uint8_t r = 0, g = 0, b = 0;  // sRGB, pre-shaded
  std::uint8_t material = 0;         // the model's material slot, kGroundMaterial for the ground
  std::uint16_t depth = 0;           // distance along the ray from the image plane: depth / 65535 * depth_range
  std::uint16_t normal = 0;          // octahedral: low byte u, high byte v
  bool operator==(const DepthPixel&) const = default;
};
static_assert(sizeof(DepthPixel) == 8);

inline constexpr std::uint8_t kGroundMaterial = 255;

// A run of non-empty pixels [x, x + length) of one row.
struct LdiSpan {
  std::uint16_t x = 0, length = 0;
  std::uint32_t first_pixel = 0;  // index of its first pixel in the LDI's counts
  std::uint32_t first_depth = 0;  // index of its first depth pixel
  bool operator==(const LdiSpan&) const = default;
};
static_assert(sizeof(LdiSpan) == 12);

// Where an LDI sits and how to decode it (96 bytes). Positions are tile-local meters (x east from
// the tile's west edge, y north from its south edge, z up from the ground). Pixel (x, y), row 0
// at the top, depth d meters: origin + (x + 0.5) p right - (y + 0.5) p up + d forward.
struct LdiFrame {
  std::uint32_t width = 0, height = 0;  // pixels
  std::uint32_t span_count = 0, pixel_count = 0, depth_pixel_count = 0;
  std::uint32_t tile = 0, level = 0, direction = 0;
  std::array<float, 3> origin{};   // meters: the top-left corner of the image at depth 0
  std::array<float, 3> right{};    // unit
  std::array<float, 3> up{};       // unit
  std::array<float, 3> forward{};  // unit: the direction the rays travel
  float pixel_size = 0;            // meters
  float depth_range = 0;           // meters: depth 65535 means this far from the image plane
  float azimuth_degrees = 0;       // compass direction the rays travel towards
  float elevation_degrees = 0;     // how far below the horizon they point
};
static_assert(sizeof(LdiFrame) == 96);

// Read-only view of an LDI (in memory or in a mapped pack).
struct LdiView {
  const LdiFrame* frame = nullptr;
  std::span<const std::uint32_t> row_spans;  // height + 1: spans of row y are [row_spans[y], row_spans[y + 1])
  std::span<const LdiSpan> spans;
  std::span<const std::uint8_t> counts;  // layers of each non-empty pixel, >= 1
  std::span<const DepthPixel> depth_pixels;

  // The depth pixels of pixel (x, y), front to back; empty when the ray met nothing.
  std::span<const DepthPixel> pixel(int x, int y) const;
  // Decoded depth in meters and the tile-local position of a depth pixel of pixel (x, y).
  float depth_meters(const DepthPixel& p) const { return float(p.depth) / 65535.0f * frame->depth_range; }
  std::array<float, 3> position(int x, int y, const DepthPixel& p) const;
};

// An LDI that owns its arrays (what the builder makes, what the pack writer takes).
struct LdiImage {
  LdiFrame frame;
  std::vector<std::uint32_t> row_spans;
  std::vector<LdiSpan> spans;
  std::vector<std::uint8_t> counts;
  std::vector<DepthPixel> depth_pixels;
  LdiView view() const { return {&frame, row_spans, spans, counts, depth_pixels}; }
};

// Octahedral encoding of a unit vector in 16 bits (8 per axis) and back.
std::uint16_t encode_octahedral(const std::array<float, 3>& n);
std::array<float, 3> decode_octahedral(std::uint16_t code);

}  // namespace wangscape
