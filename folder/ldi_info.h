// What `wangscape ldi info` prints about a pack: tiles, levels, directions, the resolution of
// each level, depth pixels and bytes per level, the layer-count histogram and the totals; as text
// for people or as one JSON object for scripts.
#pragma once

#include <string>

#include "folder/ldi_pack.h"

namespace wangscape {

// Lines of "key: value" text, one level per line in a small table.
std::string ldi_info_text(const LdiPack& pack);

// {"tiles": T, "levels": L, "directions": D, "resolutions": [...], "depth_pixels": N, "bytes": B,
//  then "file", "tile_size", "head_height", "prism_top", "image_width", "fov_degrees",
//  "azimuths", "elevations", "level_distances", "pixels", "depth_pixels_per_level",
//  "bytes_per_level", "layer_histogram" ([k] = pixels with k layers)}, keys in this order, one line.
std::string ldi_info_json(const LdiPack& pack);

}  // namespace wangscape
