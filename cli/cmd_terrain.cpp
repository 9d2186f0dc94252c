// wangscape terrain info FILE [--json] [--origin LAT,LON]: what a DEM holds and where the
// scene frame puts it.
#include <fmt/core.h>

#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/command.h"
#include "exporters/reports.h"
#include "scene/ground.h"
#include "terrain/terrain.h"

namespace wangscape::cli {

namespace {

struct TerrainInfoOptions {
  std::string file;
  std::string origin;  // "LAT,LON", empty = DEM center
  bool json = false;
};

}  // namespace

void register_terrain_command(CLI::App& app, const GlobalOptions&) {
  auto* terrain_command = app.add_subcommand("terrain", "Inspect digital elevation models");
  terrain_command->require_subcommand(1);
  auto options = std::make_shared<TerrainInfoOptions>();
  auto* info = terrain_command->add_subcommand("info", "Print a DEM's CRS, size, spacing, heights and georeference");
  info->add_option("file", options->file, "DEM file (USGS ASCII DEM, GeoTIFF, SRTM .hgt, ESRI .asc)")->required();
  info->add_flag("--json", options->json, "Print JSON instead of text");
  info->add_option("--origin", options->origin, "Scene origin LAT,LON in WGS 84 degrees (default: DEM center)")
      ->check(lat_lon_validator());
  info->callback([options] {
    TerrainOptions terrain_options;
    if (!options->origin.empty()) {
      const auto origin = parse_lat_lon(options->origin);
      terrain_options.origin = LatLon{origin[0], origin[1]};
    }
    const Terrain terrain = Terrain::load(options->file, terrain_options);
    if (options->json)
      fmt::print("{}\n", terrain_info_json(terrain).dump(2));
    else
      fmt::print("{}", terrain_info_text(terrain));
  });
}

}  // namespace wangscape::cli
