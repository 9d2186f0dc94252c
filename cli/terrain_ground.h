// The bridge between terrain/ and generator/: a DEM-backed Ground for placement, and the
// terrain options wangscape's subcommands share. Header-only parts are usable from bench/.
#pragma once

#include <optional>
#include <string>

#include "generator/ground.h"
#include "terrain/terrain.h"

namespace wangscape::cli {

// A Terrain seen as a generator Ground (ENU meters). Holds a pointer: the terrain must
// outlive it. Thread-safe like Terrain.
struct TerrainGround {
  const Terrain* terrain = nullptr;

  Extent extent() const {
    const EnuRect r = terrain->extent();
    return {r.min_x, r.min_y, r.max_x, r.max_y};
  }
  std::optional<double> height(double x, double y) const { return terrain->height(x, y); }
  std::optional<double> slope_degrees(double x, double y) const { return terrain->slope_degrees(x, y); }
};
static_assert(Ground<TerrainGround>);

// "LAT,LON" in WGS 84 degrees (e.g. "46.2,-122.19"). Throws std::invalid_argument naming
// the text when it is not two numbers in range.
LatLon parse_lat_lon(const std::string& text);

}  // namespace wangscape::cli
