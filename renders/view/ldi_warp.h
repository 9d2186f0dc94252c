// One LDI warped into a thread's z-buffer (step 6 of docs/viewer-design.md): each depth pixel moved to
// its place on the tile's two terrain triangles, projected and splatted. Internal to renders/view.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <vector>

#include "folder/ldi.h"
#include "renders/view/view_samples.h"

namespace wangscape::view_detail {

constexpr float kNear = 0.05f;  // meters: the near plane
constexpr std::uint64_t kEmpty = ~std::uint64_t{0};

// A z-buffer entry: depth in the high word, so the smaller entry is the nearer (ties: the
// smaller color), whatever order the entries come in.
inline std::uint64_t pack_entry(float depth, std::uint8_t r, std::uint8_t g, std::uint8_t b) {
  return std::uint64_t(std::bit_cast<std::uint32_t>(depth)) << 32 | std::uint64_t(r) << 16 | std::uint64_t(g) << 8 | b;
}

// Bit k set: the thresholds (k + 0.5) / 16 in [from, to), the Bayer cells a dithered LDI owns.
std::uint16_t owned_thresholds(float from, float to);
// Whether a dithered LDI owning the Bayer cells `owned` (owned_thresholds) draws pixel (x, y).
inline bool owns(std::uint16_t owned, int x, int y) { return owned == 0xffff || (owned >> bayer_index(x, y) & 1); }

// Splats are written straight into a z-buffer of the warping thread's own (no atomic write, no
// cache line shared between cores); the frame's z-buffer is then the per-pixel smallest entry
// of the threads' buffers, which is what any order of writes into one buffer leaves.
struct ThreadDepths {
  int width = 0;
  bool written = false;                // this frame: merged (and reset) only then
  std::vector<std::uint64_t> entries;  // kEmpty where nothing was written (the merge resets them)
  void reset(int frame_width, int frame_height) {
    width = frame_width;
    entries.assign(std::size_t(frame_width) * std::size_t(frame_height), kEmpty);
  }
  // One pixel (most splats), inside the frame.
  void write_pixel(int x, int y, std::uint64_t entry) {
    std::uint64_t& slot = entries[std::size_t(y) * std::size_t(width) + std::size_t(x)];
    slot = std::min(slot, entry);  // (no branch: which entry wins is a coin toss in a dense field)
  }
  // The pixels [xa, xb) x [ya, yb) that `owned` holds, not empty and inside the frame.
  void write(int xa, int xb, int ya, int yb, std::uint64_t entry, std::uint16_t owned) {
    for (int y = ya; y < yb; ++y) {
      std::uint64_t* row = entries.data() + std::size_t(y) * std::size_t(width);
      if (owned == 0xffff)
        for (int x = xa; x < xb; ++x) row[x] = std::min(row[x], entry);
      else
        for (int x = xa; x < xb; ++x)
          if (owns(owned, x, y)) row[x] = std::min(row[x], entry);
    }
  }
};

// The frame the LDIs are warped into: pixels per unit of tan, centre, size; the largest splat
// side (pixels).
struct WarpScreen {
  float focal = 1, cx = 0, cy = 0;
  int width = 0, height = 0, max_splat = 1;
};

// One LDI of one tile warped into the z-buffer: what stays fixed over its depth pixels.
struct Warp {
  std::array<float, 3> base{}, step_x{}, step_y{}, step_d{},
      lift{};  // camera space: pixel (0, 0), per x, per y, per meter of depth, per meter of shear
  std::array<float, 3> local_base{}, local_x{}, local_y{}, local_d{};  // tile-local position, likewise
  float h00 = 0, h10 = 0, h01 = 0, h11 = 0, inverse_tile = 1;
  float depth_scale = 0, splat = 0;  // meters per depth step; splat side times depth (pixels x meters)
  std::uint16_t owned = 0xffff;      // the dither thresholds this LDI owns (owned_thresholds)
  // [[species]]: the tile's ViewWorld::Tiles::plant_steps, the rank steps of each species that grow
  // in each cell of the tile (null: all).
  const std::uint8_t* plant_steps = nullptr;
  float ground_below = 0;  // meters: a last layer lower than this is the ground plane
  WarpScreen screen;
};

// Every depth pixel of `v` splatted into `out`; returns how many depth pixels were visited.
std::uint64_t warp_ldi(const LdiView& v, const Warp& w, ThreadDepths& out);

}  // namespace wangscape::view_detail
