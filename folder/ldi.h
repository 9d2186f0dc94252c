// One orthographic Layered Depth Image of a tile (Shade 2002, section 4): a grid of pixels, each with
// the pre-shaded depth pixels its ray met inside the tile's prism, front to back. Stored in
// compressed-row form: per row, spans of pixels (runs of non-empty pixels, short empty gaps
// included); per pixel of a span its layer count; the depth pixels of a pixel contiguous. These structs are also the
// pack's on-disk records (little endian, docs/ldi-pack-format.md), so their sizes are fixed.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace wangscape {

// A depth pixel: 8 bytes, byte-aligned (no padding, read in place from a mapped pack). depth is
// 16-bit fixed point over the LDI's depth range; normal is octahedral (8 + 8 bits), unit, turned
// towards the viewer. Both are stored little endian. plant says which plant the sample shows, so a
// view can thin the LDI as the scene's species rules and density thin the field (issue 26):
// species (0..6) in the top 3 bits, the plant's progressive rank in 32 steps below; kAnyPlant for
// the ground, a species beyond the seventh and anything else no rule removes.
inline constexpr std::uint8_t kAnyPlant = 0xff;
inline constexpr int kPlantRankSteps = 32;
inline constexpr int kPlantSpecies = 7;  // species that fit the byte beside kAnyPlant

struct DepthPixel {
  std::uint8_t r = 0, g = 0, b = 0;  // sRGB, pre-shaded
  std::uint8_t depth_bytes[2] = {0, 0};
  std::uint8_t normal_bytes[2] = {0, 0};
  std::uint8_t plant = kAnyPlant;

  // Distance along the ray from the image plane: depth() / 65535 * depth_range meters.
  std::uint16_t depth() const { return std::uint16_t(depth_bytes[0] | depth_bytes[1] << 8); }
  std::uint16_t normal() const { return std::uint16_t(normal_bytes[0] | normal_bytes[1] << 8); }
  static DepthPixel make(std::uint8_t r, std::uint8_t g, std::uint8_t b, std::uint16_t depth, std::uint16_t normal,
                         std::uint8_t plant = kAnyPlant) {
    return {
        r,    g, b, {std::uint8_t(depth), std::uint8_t(depth >> 8)}, {std::uint8_t(normal), std::uint8_t(normal >> 8)},
        plant};
  }
  bool operator==(const DepthPixel&) const = default;
};
static_assert(sizeof(DepthPixel) == 8 && alignof(DepthPixel) == 1);

// The plant byte of a plant of `species` with progressive rank `rank` in [0, 1).
inline std::uint8_t plant_byte(int species, float rank) {
  if (species < 0 || species >= kPlantSpecies) return kAnyPlant;
  const int step = rank >= 0 ? int(rank * float(kPlantRankSteps)) : 0;
  return std::uint8_t(species << 5 | (step < kPlantRankSteps ? step : kPlantRankSteps - 1));
}

// A run of pixels [x, x + length) of one row; it starts and ends with a non-empty pixel, and may
// hold short runs of empty ones (count 0) where that is smaller than starting a new span.
struct LdiSpan {
  std::uint16_t x = 0, length = 0;
  std::uint32_t first_pixel = 0;  // index of its first pixel in the LDI's counts
  std::uint32_t first_depth = 0;  // index of its first depth pixel
  bool operator==(const LdiSpan&) const = default;
};
static_assert(sizeof(LdiSpan) == 12);

// Every tile's prism: [0, tile size] x [0, tile size] x [kLdiPrismBottom, the pack's prism top],
// tile-local meters; its bottom just below the ground plane, so the ground is inside.
inline constexpr float kLdiPrismBottom = -1e-3f;

// Where an LDI sits and how to decode it (96 bytes). Positions are tile-local meters (x east from
// the tile's west edge, y north from its south edge, z up from the ground). Pixel (x, y), row 0
// at the top, depth d meters: origin + (x + 0.5) p right - (y + 0.5) p up + d forward.
struct LdiFrame {
  std::uint32_t width = 0, height = 0;                                   // pixels
  std::uint32_t span_count = 0, pixel_count = 0, depth_pixel_count = 0;  // pixel_count: pixels in spans
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
  std::span<const std::uint8_t> counts;  // layers of each pixel of the spans (0 in a gap)
  std::span<const DepthPixel> depth_pixels;

  // The depth pixels of pixel (x, y), front to back; empty when the ray met nothing.
  std::span<const DepthPixel> pixel(int x, int y) const;
  // Decoded depth in meters and the tile-local position of a depth pixel of pixel (x, y).
  float depth_meters(const DepthPixel& p) const { return float(p.depth()) / 65535.0f * frame->depth_range; }
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
