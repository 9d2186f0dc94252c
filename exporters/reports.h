// What the inspection commands report, as JSON and as text for a terminal: a tiling's statistics
// (`wangscape tiling --stats`), a DEM (`terrain info`), the quality of scattered points
// (`scatter --metrics`), a tile set and its Poisson fill (`tileset`); and a tiling window as CSV. Numbers are
// locale-independent.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

#include "generator/point_metrics.h"
#include "generator/poisson_tiles.h"
#include "generator/tiling.h"
#include "generator/tiling_stats.h"
#include "scene/tileset_file.h"
#include "terrain/terrain.h"

namespace wangscape {

// How a tiling was made, for its report.
struct TilingRun {
  std::string algorithm;
  std::uint64_t seed = 0;
  bool no_identical_neighbours = false;
};
Json tiling_stats_json(const TileSet& set, const Tiling& tiling, const TilingRun& run, const TilingStats& stats);
std::string tiling_stats_text(const TileSet& set, const Tiling& tiling, const TilingRun& run, const TilingStats& stats);

// "i,j,tile" per tile, written atomically.
void write_tiling_csv(const std::filesystem::path& path, const Tiling& tiling);

// A DEM: CRS, size, spacing, heights, ENU extent and georeference.
Json terrain_info_json(const Terrain& terrain);
std::string terrain_info_text(const Terrain& terrain);

// Point metrics; `seconds` is the scatter's time, `packing_diameter` in meters.
Json point_metrics_json(const PointMetrics& metrics, double seconds);
std::string point_metrics_text(const PointMetrics& metrics, double packing_diameter);

// A tile set in a few lines (name, kind, tiles, colors).
std::string tileset_summary_text(const TileSet& set);
// One line on a Poisson fill: distinct points, rho after darts and after relaxation, radii.
std::string poisson_fill_text(const FilledTileSet& filled, const PoissonFillReport& report, int points_per_tile);

}  // namespace wangscape
