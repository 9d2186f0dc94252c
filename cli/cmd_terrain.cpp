// wangscape terrain info FILE [--json] [--origin LAT,LON]: what a DEM holds and where the
// scene frame puts it.
// wangscape terrain height SOURCE E,N... [--latlon LAT,LON]... [--above M] [--json]: the ground
// height at points of the scene frame (the E,N of scene files, --camera and view paths), of a
// DEM, a scene file or a built scene folder.
#include <fmt/core.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <vector>

#include "cli/command.h"
#include "core/error.h"
#include "core/json_text.h"
#include "core/number_text.h"
#include "exporters/reports.h"
#include "folder/scene_folder.h"
#include "scene/scene_file.h"
#include "scene/scene_ground.h"
#include "terrain/terrain.h"

namespace wangscape::cli {

namespace {

struct TerrainInfoOptions {
  std::string file;
  std::string origin;  // "LAT,LON", empty = DEM center
  bool json = false;
};

struct TerrainHeightOptions {
  std::string source;               // a DEM, a scene file (.toml) or a scene folder
  std::vector<std::string> points;  // "E,N", ENU meters
  std::vector<std::string> latlon;  // "LAT,LON", WGS 84 degrees
  std::string origin;               // with a DEM: "LAT,LON", empty = DEM center
  double above = 0;                 // meters added to the ground height
  bool json = false;
};

// The ground of SOURCE as the scene sees it: a scene folder's or a scene file's [terrain]
// (origin and crop), or a DEM with its center (or --origin) as the origin.
SceneGround load_ground(const TerrainHeightOptions& options) {
  const std::filesystem::path source = options.source;
  const bool folder = std::filesystem::is_directory(source);
  if (folder || source.extension() == ".toml") {
    if (!options.origin.empty())
      throw Error("--origin: the scene's [terrain] sets the origin of '" + options.source + "'; give it there");
    const SceneConfig config =
        folder ? SceneFolder::open(source, SceneFolder::Parts::scene_file).config() : load_scene_config(source);
    return SceneGround::load(config.terrain);
  }
  TerrainConfig terrain;
  terrain.dem = source;
  if (!options.origin.empty()) {
    const auto origin = parse_lat_lon(options.origin);
    terrain.origin_latitude = origin[0];
    terrain.origin_longitude = origin[1];
  }
  return SceneGround::load(terrain);
}

void print_heights(const TerrainHeightOptions& options) {
  const SceneGround ground = load_ground(options);
  struct Point {
    double east, north, ground;
  };
  std::vector<Point> points;
  for (const auto& text : options.points) {
    const auto en = parse_number_list(text, ',', 2, 2);  // checked by the option's validator
    points.push_back({(*en)[0], (*en)[1], ground.height_or_error((*en)[0], (*en)[1])});
  }
  for (const auto& text : options.latlon) {
    const auto ll = parse_lat_lon(text);
    const auto en = ground.to_enu(ll[0], ll[1]);
    points.push_back({en[0], en[1], ground.height_or_error(en[0], en[1])});
  }
  if (options.json) {
    nlohmann::json out = nlohmann::json::array();
    for (const Point& p : points) {
      const auto ll = ground.terrain() ? ground.terrain()->frame().to_lat_lon(p.east, p.north)
                                       : LatLon{ground.origin()[0], ground.origin()[1]};
      out.push_back({{"east_m", p.east},
                     {"north_m", p.north},
                     {"ground_m", p.ground},
                     {"position_m", {p.east, p.north, p.ground + options.above}},
                     {"latitude_deg", ll.lat},
                     {"longitude_deg", ll.lon}});
    }
    fmt::print("{}\n", json_text(out, 2));
    return;
  }
  // E,N,H: the form of --camera and of a path keyframe's position.
  for (const Point& p : points)
    fmt::print("{},{},{}\n", fixed_text(p.east, 2), fixed_text(p.north, 2), fixed_text(p.ground + options.above, 2));
}

}  // namespace

void register_terrain_command(CLI::App& app, const GlobalOptions&) {
  auto* terrain_command =
      app.add_subcommand("terrain", "Inspect DEMs: what one holds, the ground height at a point of the scene");
  terrain_command->require_subcommand(1);
  auto options = std::make_shared<TerrainInfoOptions>();
  auto* info = terrain_command->add_subcommand("info", "Print a DEM's CRS, size, spacing, heights and georeference");
  info->add_option("file", options->file, "DEM file (USGS ASCII DEM, GeoTIFF, SRTM .hgt, ESRI .asc)")->required();
  info->add_flag("--json", options->json, "Print JSON instead of text");
  info->add_option("--origin", options->origin, "Scene origin LAT,LON in WGS 84 degrees (default: DEM center)")
      ->check(lat_lon_validator());
  set_help_footer(info, "nothing: the DEM's figures on stdout",
                  {"wangscape terrain info data/SainteHelens.dem",
                   "wangscape terrain info data/SainteHelens.dem --json --origin 46.2,-122.19"});
  info->callback([options] {
    TerrainOptions terrain_options;
    if (!options->origin.empty()) {
      const auto origin = parse_lat_lon(options->origin);
      terrain_options.origin = LatLon{origin[0], origin[1]};
    }
    const Terrain terrain = Terrain::load(options->file, terrain_options);
    if (options->json)
      fmt::print("{}\n", json_text(terrain_info_json(terrain), 2));
    else
      fmt::print("{}", terrain_info_text(terrain));
  });

  auto height_options = std::make_shared<TerrainHeightOptions>();
  auto* height = terrain_command->add_subcommand(
      "height",
      "Print the ground height at points of the scene frame (E,N as in scene files, --camera and view paths), one "
      "line E,N,H each (meters): the position of a camera or path keyframe standing there");
  height
      ->add_option("source", height_options->source,
                   "A DEM (origin: its center, or --origin), a scene file (.toml) or a built scene folder (their "
                   "[terrain]: origin and crop)")
      ->required();
  height->add_option("points", height_options->points, "Points E,N in meters (east, north of the scene's origin)")
      ->check(CLI::Validator(
          [](std::string& text) {
            return parse_number_list(text, ',', 2, 2) ? std::string()
                                                      : "'" + text + "' is not E,N in meters, e.g. 0,6590";
          },
          "E,N"));
  height->add_option("--latlon", height_options->latlon, "A point by WGS 84 LAT,LON in degrees (repeatable)")
      ->check(lat_lon_validator());
  height->add_option("--above", height_options->above, "Add M meters to H (e.g. 1.7 for an eye at head height)")
      ->check(finite_number());
  height
      ->add_option("--origin", height_options->origin,
                   "With a DEM: the scene origin LAT,LON in WGS 84 degrees (default: the DEM's center)")
      ->check(lat_lon_validator());
  height->add_flag("--json", height_options->json,
                   "Print JSON: east_m, north_m, ground_m, position_m (with --above), latitude_deg, longitude_deg");
  set_help_footer(height,
                  "nothing: a line E,N,H per point on stdout (--json: objects), for --camera and path keyframes",
                  {"wangscape terrain height data/SainteHelens.dem 0,6590",
                   "wangscape terrain height data/SainteHelens.dem 0,6590 -200,6000 --above 1.7",
                   "wangscape terrain height data/SainteHelens.dem --latlon 46.2466,-122.1886 --json"});
  set_help_footer(terrain_command, "nothing: figures on stdout",
                  {"wangscape terrain info data/SainteHelens.dem",
                   "wangscape terrain height data/SainteHelens.dem 0,6590 --above 1.7"});
  height->callback([height_options] {
    if (height_options->points.empty() && height_options->latlon.empty())
      throw CLI::ValidationError("points", "give at least one point E,N or --latlon LAT,LON");
    print_heights(*height_options);
  });
}

}  // namespace wangscape::cli
