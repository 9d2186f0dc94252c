// The tilers behind generator/tiling.h, one file each: the sweeps (scanline and bottom-left,
// tiling_sweep.cpp), the hashed tiling (tiling_hashed.cpp) and Culik's aperiodic rows
// (tiling_culik.cpp); tiling.cpp checks a window and hands it to one of them. What they share:
// the color slots of a tile and the seed's generator. Internal to generator/.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <span>

#include "core/hash.h"
#include "generator/tiling.h"

namespace wangscape::tiling_detail {

inline constexpr std::array<const char*, kSlotCount> kSlotNames = {"N", "E", "S", "W", "NE", "SE", "SW", "NW"};

inline bool slot_present(const TileSet& set, int slot) { return slot < kNE ? set.has_edges : set.has_corners; }

// Number of colors a slot draws from (1 when the set does not color it).
inline std::uint32_t slot_radix(const TileSet& set, int slot) {
  if (!slot_present(set, slot)) return 1;
  if (slot == kN || slot == kS) return static_cast<std::uint32_t>(std::max(set.horizontal_colors, 1));
  if (slot == kE || slot == kW) return static_cast<std::uint32_t>(std::max(set.vertical_colors, 1));
  return static_cast<std::uint32_t>(std::max(set.corner_colors, 1));
}

inline std::uint32_t color_of(const Tile& tile, int slot) {
  const int c = tile.colors[static_cast<std::size_t>(slot)];
  return c < 0 ? 0u : static_cast<std::uint32_t>(c);
}

// SplitMix64's generator: mix64 of the state, which then steps.
inline std::uint64_t splitmix64(std::uint64_t& state) {
  const std::uint64_t z = mix64(state);
  state += 0x9E3779B97F4A7C15ull;
  return z;
}

// Each streams the rows of a window tiling.cpp has checked, as stream_tiling promises: in the
// algorithm's order, each row once.
void stream_sweep_tiling(const TileSet& set, int width, int height, const TilingOptions& options,
                         const TilingRowSink& row);
void stream_hashed_tiling(const TileSet& set, int width, int height, const TilingOptions& options,
                          const TilingRowSink& row);
void stream_culik_tiling(const TileSet& set, int width, int height, const TilingOptions& options,
                         const TilingRowSink& row);

// A checked window of hashed tiles into `tiles` (width x height, southern row first), its rows in
// parallel: make_tiling's path for hash tilings, which need no row order.
void fill_hashed_tiling(const TileSet& set, int width, int height, const TilingOptions& options,
                        std::span<std::uint16_t> tiles);

// Whether `set` holds exactly Culik's 13 tiles, in any order.
bool is_culik13(const TileSet& set);

}  // namespace wangscape::tiling_detail
