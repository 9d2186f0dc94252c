// wangscape terrain info FILE [--json] [--origin LAT,LON]: what a DEM holds and where the
// scene frame puts it.
#include <fmt/core.h>

#include <cmath>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/command.h"
#include "scene/ground.h"
#include "terrain/terrain.h"

namespace wangscape::cli {

namespace {

struct TerrainInfoOptions {
  std::string file;
  std::string origin;  // "LAT,LON", empty = DEM center
  bool json = false;
};

nlohmann::ordered_json to_json(const Terrain& terrain) {
  const DemRaster& dem = terrain.dem();
  const Extent extent = terrain.extent();
  nlohmann::ordered_json out;
  out["file"] = dem.path.string();
  out["driver"] = dem.driver;
  out["crs_name"] = dem.crs_name;
  out["geographic"] = dem.geographic;
  out["width"] = dem.width;
  out["height"] = dem.height;
  out["spacing_crs"] = {dem.spacing_x(), dem.spacing_y()};
  out["spacing_crs_units"] = dem.geographic ? "degree" : "metre";
  out["spacing_m"] = {terrain.spacing_m()[0], terrain.spacing_m()[1]};
  out["min_height_m"] = dem.min_height;
  out["max_height_m"] = dem.max_height;
  out["height_unit_in_file"] = dem.height_unit_in_file;
  out["nodata_count"] = dem.nodata_count;
  out["cell_count"] = dem.cell_count();
  out["extent_enu_m"] = {
      {"min_x", extent.min_x}, {"min_y", extent.min_y}, {"max_x", extent.max_x}, {"max_y", extent.max_y}};
  auto& georef = out["georeference"];
  for (const auto& field : georeference_fields(terrain.georeference()))
    std::visit([&](const auto& value) { georef[field.key] = value; }, field.value);
  return out;
}

void print_text(const Terrain& terrain) {
  const DemRaster& dem = terrain.dem();
  const TerrainGeoreference& g = terrain.georeference();
  const Extent e = terrain.extent();
  const char* unit = dem.geographic ? "deg" : "m";
  fmt::print("file:             {}\n", dem.path.string());
  fmt::print("driver:           {}\n", dem.driver);
  fmt::print("crs:              {} ({})\n", dem.crs_name, dem.geographic ? "geographic" : "projected");
  fmt::print("datum:            {}\n", g.horizontal_datum);
  fmt::print("size:             {} x {} samples\n", dem.width, dem.height);
  fmt::print("spacing:          {:.10g} x {:.10g} {} ({:.2f} x {:.2f} m)\n", dem.spacing_x(), dem.spacing_y(), unit,
             terrain.spacing_m()[0], terrain.spacing_m()[1]);
  fmt::print("heights:          {:.2f} .. {:.2f} m (file unit: {})\n", dem.min_height, dem.max_height,
             dem.height_unit_in_file);
  fmt::print("no-data cells:    {} of {}\n", dem.nodata_count, dem.cell_count());
  fmt::print("extent (ENU):     x {:.1f} .. {:.1f} m, y {:.1f} .. {:.1f} m ({:.1f} x {:.1f} m)\n", e.min_x, e.max_x,
             e.min_y, e.max_y, e.width(), e.height());
  fmt::print("origin:           lat {:.8f}, lon {:.8f} (WGS 84), z = 0 at orthometric height 0\n", g.origin_lat_deg,
             g.origin_lon_deg);
  fmt::print("utm zone:         {}{}\n", g.utm_zone, g.utm_north ? "N" : "S");
  fmt::print("convergence:      {:.6f} deg (UTM scale {:.8f})\n", g.convergence_deg, g.utm_scale);
  fmt::print("axes:             {}\n", g.axis_mapping);
  fmt::print("vertical datum:   {}\n", g.vertical_datum);
  fmt::print("datum note:       {}\n", g.datum_note);
}

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
      fmt::print("{}\n", to_json(terrain).dump(2));
    else
      print_text(terrain);
  });
}

}  // namespace wangscape::cli
