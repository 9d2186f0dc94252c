// The LDI pack: every LDI of a tile set (tiles x levels x directions) in one versioned binary
// file the real-time view memory-maps (docs/ldi-pack-format.md). Written through a temporary
// file and a rename; opened by mmap with every offset and count checked against the file size
// first, so a truncated or corrupt pack is refused with an Error naming the file, the LDI at
// fault and what is wrong.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/error.h"
#include "folder/ldi.h"

namespace wangscape {

class AtomicFile;

inline constexpr char kLdiPackMagic[8] = {'W', 'S', 'C', 'L', 'D', 'I', '\r', '\n'};
// 2: depth pixels carry the plant byte; 3: the light the pack was shaded with (LdiPackLight). A
// pack is written as version 3 when it records its light, else as version 2; both are read.
inline constexpr std::uint32_t kLdiPackVersion = 3, kLdiPackOldestVersion = 2;

// The light the pack's samples were shaded with (scene/shading_light.h ShadingSettings, recorded
// by folder/pack_light.h): the light before the sun (the sun's colour at strength 1), and the sun
// that lit it, its direction and strength. So a reader shades what it draws beside the pack (the
// terrain, the near field, the reference) as the pack was, without deriving it again.
struct LdiPackLight {
  std::array<float, 3> sun_direction{}, sun_color{}, sky_color{}, ground_color{};
  float sun_strength = 1, exposure = 1;
  std::uint32_t shadows = 1, sky_rays = 0;  // shadows: 1 with sun shadow rays, 0 without
  float sky_reach = 0, ray_offset = 0;      // meters
  bool operator==(const LdiPackLight&) const = default;
};

// What the pack says about its set (the header and the per-level / per-direction arrays).
struct LdiPackInfo {
  std::uint32_t tiles = 0, levels = 0, directions = 0;
  float tile_size = 0;                     // meters
  float head_height = 0;                   // meters, the viewer's eye above the ground
  float prism_top = 0;                     // meters, the top of every tile's prism (the bottom is the ground)
  std::uint32_t image_width = 0;           // pixels, of the view the resolutions were derived for
  float fov_degrees = 0;                   // horizontal, of that view
  std::vector<std::uint32_t> resolutions;  // per level: pixels across a tile side (Shade 2002's figure)
  std::vector<float> level_distances;      // per level: meters from the viewer to the tile's near edge
  std::vector<float> elevations;           // per level: degrees below the horizon the rays point
  std::vector<float> azimuths;             // per direction: compass degrees the rays travel towards
  std::optional<LdiPackLight> light;       // version 3 on
  bool operator==(const LdiPackInfo&) const = default;
};

// Streams LDIs into a pack: add() each (tile, level, direction) exactly once, in any order, then
// commit(). Nothing appears at `path` unless commit() succeeds.
class LdiPackWriter {
 public:
  LdiPackWriter(std::filesystem::path path, LdiPackInfo info);
  ~LdiPackWriter();
  LdiPackWriter(const LdiPackWriter&) = delete;
  LdiPackWriter& operator=(const LdiPackWriter&) = delete;

  void add(const LdiImage& ldi);  // where it goes: ldi.frame.tile / level / direction
  // Writes the index and the header, renames into place. Throws Error when an LDI is
  // missing or a write failed.
  void commit();

 private:
  std::filesystem::path path_;
  LdiPackInfo info_;
  std::unique_ptr<AtomicFile> file_;
  std::vector<std::uint64_t> offsets_, sizes_;
  std::uint64_t end_ = 0;
};

// A memory-mapped pack. Opening validates the whole structure (header, index, every LDI's spans,
// counts and depth-pixel ranges) before anything is handed out. Thread-safe after construction.
class LdiPack {
 public:
  explicit LdiPack(const std::filesystem::path& path);  // throws Error
  ~LdiPack();
  LdiPack(const LdiPack&) = delete;
  LdiPack& operator=(const LdiPack&) = delete;

  const LdiPackInfo& info() const { return info_; }
  const std::filesystem::path& path() const { return path_; }
  std::uint64_t file_bytes() const { return size_; }
  LdiView ldi(std::uint32_t tile, std::uint32_t level, std::uint32_t direction) const;
  // Bytes the LDI's block takes in the file.
  std::uint64_t ldi_bytes(std::uint32_t tile, std::uint32_t level, std::uint32_t direction) const;

 private:
  std::filesystem::path path_;
  const std::uint8_t* data_ = nullptr;
  std::uint64_t size_ = 0;
  LdiPackInfo info_;
  std::vector<LdiView> views_;
  std::vector<std::uint64_t> block_bytes_;
};

// Writes a whole pack from LDIs held in memory (tests, small sets).
void write_ldi_pack(const std::filesystem::path& path, const LdiPackInfo& info, std::span<const LdiImage> ldis);

// Totals for `wangscape ldi info` and the benchmarks.
struct LdiPackStats {
  std::uint64_t pixels = 0;        // all pixels of all LDIs (empty ones too)
  std::uint64_t depth_pixels = 0;  // all layers
  std::vector<std::uint64_t> depth_pixels_per_level, bytes_per_level;
  std::vector<std::uint64_t> layer_histogram;  // [k]: pixels with k layers (0: empty)
};
LdiPackStats ldi_pack_stats(const LdiPack& pack);

}  // namespace wangscape
