#include "folder/ldi_info.h"

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "core/json_text.h"

namespace wangscape {

std::string ldi_info_text(const LdiPack& pack) {
  const LdiPackInfo& info = pack.info();
  const LdiPackStats stats = ldi_pack_stats(pack);
  std::string out;
  out += fmt::format("pack:         {}\n", pack.path().string());
  out +=
      fmt::format("tiles:        {}\nlevels:       {}\ndirections:   {}\n", info.tiles, info.levels, info.directions);
  out += fmt::format("tile size:    {:.3f} m, prism top {:.3f} m, head height {:.2f} m\n", info.tile_size,
                     info.prism_top, info.head_height);
  out += fmt::format("view:         {} pixels, {:.1f} degrees (what the resolutions are derived for)\n",
                     info.image_width, info.fov_degrees);
  out += "level  resolution  distance_m  elevation_deg  depth_pixels       bytes\n";
  for (std::uint32_t l = 0; l < info.levels; ++l)
    out += fmt::format("{:5}  {:10}  {:10.2f}  {:13.2f}  {:12}  {:10}\n", l + 1, info.resolutions[l],
                       info.level_distances[l], info.elevations[l], stats.depth_pixels_per_level[l],
                       stats.bytes_per_level[l]);
  out += "layers per pixel (pixels):";
  for (std::size_t k = 0; k < stats.layer_histogram.size(); ++k)
    out += fmt::format("{} {}:{}", k == 0 ? "" : ",", k, stats.layer_histogram[k]);
  out += "\n";
  out += fmt::format("pixels:       {}\ndepth pixels: {}\nbytes:        {} ({:.1f} MB)\n", stats.pixels,
                     stats.depth_pixels, pack.file_bytes(), double(pack.file_bytes()) / 1e6);
  return out;
}

std::string ldi_info_json(const LdiPack& pack) {
  const LdiPackInfo& info = pack.info();
  const LdiPackStats stats = ldi_pack_stats(pack);
  nlohmann::ordered_json j;
  j["tiles"] = info.tiles;
  j["levels"] = info.levels;
  j["directions"] = info.directions;
  j["resolutions"] = info.resolutions;
  j["depth_pixels"] = stats.depth_pixels;
  j["bytes"] = pack.file_bytes();
  j["file"] = pack.path().string();
  j["tile_size"] = info.tile_size;
  j["head_height"] = info.head_height;
  j["prism_top"] = info.prism_top;
  j["image_width"] = info.image_width;
  j["fov_degrees"] = info.fov_degrees;
  j["azimuths"] = info.azimuths;
  j["elevations"] = info.elevations;
  j["level_distances"] = info.level_distances;
  j["pixels"] = stats.pixels;
  j["depth_pixels_per_level"] = stats.depth_pixels_per_level;
  j["bytes_per_level"] = stats.bytes_per_level;
  j["layer_histogram"] = stats.layer_histogram;
  return json_text(j) + "\n";
}

}  // namespace wangscape
