// The bridge between terrain/ and generator/: a DEM-backed Ground for placement, the tile
// and point filters of seed 003's masks, and the terrain options wangscape's subcommands
// share. Header-only parts are usable from bench/.
#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>

#include "generator/ground.h"
#include "generator/placement.h"
#include "terrain/mask.h"
#include "terrain/terrain.h"

namespace wangscape::cli {

// A Terrain seen as a generator Ground (ENU meters). Holds a pointer: the terrain must
// outlive it. Thread-safe like Terrain.
struct TerrainGround {
  const Terrain* terrain = nullptr;

  Extent extent() const {
    const Extent r = terrain->extent();
    return {r.min_x, r.min_y, r.max_x, r.max_y};
  }
  std::optional<double> height(double x, double y) const { return terrain->height(x, y); }
  std::optional<double> slope_degrees(double x, double y) const { return terrain->slope_degrees(x, y); }
};
static_assert(Ground<TerrainGround>);

// Seed 003's rule as placement filters. Without fair edges a tile is instantiated only if
// all of its ground passes (a staircase along the contour); with fair edges every tile
// that may pass is laid and each flower is kept only if its own ground passes, so the
// field's border follows the contour.
struct TerrainTileFilter {
  const TerrainFilter* filter = nullptr;
  bool fair_edges = false;
  bool operator()(const TileCell& cell) const {
    const Extent r{cell.bounds.min_x, cell.bounds.min_y, cell.bounds.max_x, cell.bounds.max_y};
    return fair_edges ? filter->tile_may_pass(r) : filter->tile_passes(r);
  }
};
struct TerrainPointFilter {
  const TerrainFilter* filter = nullptr;
  bool fair_edges = false;
  bool operator()(double x, double y, double z) const {
    if (fair_edges) return filter->point_passes(x, y, z);
    // The tile test already holds for all of the tile; the height test is a compare.
    const auto& max_height = filter->options().max_height_m;
    return !max_height || z <= *max_height;
  }
};

// "LAT,LON" in WGS 84 degrees (e.g. "46.2,-122.19"). Throws std::invalid_argument naming
// the text when it is not two numbers in range.
LatLon parse_lat_lon(const std::string& text);
// A CLI11 check for --origin (a usage error, exit 2, when the text is not LAT,LON).
CLI::Validator lat_lon_validator();

// `wangscape scatter` over a DEM: --dem FILE --max-height M --max-slope DEG --mask PNG
// --fair-edges --origin LAT,LON.
struct TerrainScatterOptions {
  std::string dem;
  double max_height_m = std::numeric_limits<double>::quiet_NaN();  // NaN: no limit
  double max_slope_deg = std::numeric_limits<double>::quiet_NaN();
  std::string mask;  // PNG stretched over the terrain, white = flowers
  bool fair_edges = false;
  std::string origin;  // LAT,LON; empty = the DEM's center
  bool active() const { return !dem.empty(); }
};
// Adds those options to a subcommand; the terrain ones need --dem. Returns the --dem option.
CLI::Option* add_terrain_scatter_options(CLI::App& sub, TerrainScatterOptions& options);

// A loaded DEM with its ground tests, ready to scatter over.
class TerrainScatter {
 public:
  // Loads the DEM and checks that the tile size fits the terrain and that some ground can
  // pass the tests. Throws Error or std::runtime_error with the file or value at fault.
  TerrainScatter(const TerrainScatterOptions& options, double tile_size);

  const Terrain& terrain() const { return *terrain_; }
  // The ENU area the scatter covers: the terrain's extent.
  Extent area() const { return TerrainGround{terrain_.get()}.extent(); }
  // place_instances over the terrain with the tile and point filters; z = ground height.
  PlacementStats place(const FilledTileSet& filled, const PlacementOptions& options,
                       const std::function<void(const InstanceBatch&)>& sink) const;
  // Why a scatter produced no instance, in one sentence (for an explained empty result).
  std::string explain_empty() const;

 private:
  std::unique_ptr<Terrain> terrain_;
  std::unique_ptr<TerrainFilter> filter_;
  bool fair_edges_ = false;
  double tile_size_ = 0;
};

}  // namespace wangscape::cli
