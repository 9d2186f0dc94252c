// wangscape scatter --tileset tiles.json --plane 64x64 --tile-size 4 --out points.csv
// Lays a tiling of a filled tile set over a flat plane and writes every instance (CSV, binary
// PLY, or with --dem a GeoPackage or GeoJSON layer, by the extension); --metrics measures the
// quality figures of the result.
// With --dem FILE the ground is a DEM, the scene's one ground (scene/scene_ground.h): z = ground
// height, tiles only where --max-height / --min-height / --max-slope / --mask allow (Shade 2002),
// --fair-edges for partial tiles.
#include <fmt/core.h>

#include <array>
#include <memory>
#include <optional>
#include <string_view>
#include <utility>

#include "cli/command.h"
#include "cli/progress.h"
#include "core/number_text.h"
#include "exporters/image_io.h"
#include "exporters/point_writer.h"
#include "exporters/reports.h"
#include "exporters/scatter_run.h"
#include "generator/point_metrics.h"

namespace wangscape::cli {

namespace {

struct ScatterOptions {
  std::string tileset;
  std::string plane = "64x64";  // meters, east x north
  double tile_size = 4.0;       // meters
  std::string out;
  std::uint64_t seed = 1;
  std::string algorithm = "scanline";
  bool metrics = false;
  bool json = false;
  std::string spectrum_png;
  // --dem and its masks: the scene file's [terrain] and [masks] (no fair edges unless asked).
  std::string dem, origin, mask;
  std::optional<double> max_height, min_height, max_slope;
  bool fair_edges = false;
  std::optional<std::uint64_t> max_instances;
  bool yes = false;                      // --yes: a points file estimated above 1 GB is written
  GisCrsChoice crs = GisCrsChoice::dem;  // --crs: a GIS layer's coordinates
};

constexpr std::array<std::pair<GisCrsChoice, std::string_view>, 2> kGisCrsNames = {
    {{GisCrsChoice::dem, "dem"}, {GisCrsChoice::wgs84, "wgs84"}}};

// --metrics of a set of several classes: a row per class after the union's figures.
std::string class_metrics_text(const std::vector<ClassMetrics>& classes) {
  if (classes.empty()) return {};
  std::string text =
      "class  points    rho  meanNN  pairs < spacing (m)    edge  corner  anisotropy off the grid (dB)\n";
  for (std::size_t c = 0; c < classes.size(); ++c) {
    const PointMetrics& m = classes[c].metrics;
    const std::string zones = classes[c].edge_objects
                                  ? "    -       -"
                                  : fmt::format("{:.3f}   {:.3f}", m.edge_density_ratio, m.corner_density_ratio);
    text += fmt::format("{:5}  {:6}  {:.3f}   {:.3f}  {:6} < {:<10.4f} {}  {:6.2f}{}\n", c, m.count, m.rho, m.mean_nn,
                        m.close_pairs, classes[c].spacing, zones, m.spectrum.mean_anisotropy_off_grid_db,
                        classes[c].edge_objects ? "  (edge objects)" : "");
  }
  return text;
}

void run(const ScatterOptions& options, const GlobalOptions& global) {
  if (options.out.empty() && !options.metrics)
    throw std::runtime_error("scatter: nothing to do; give --out FILE and/or --metrics");
  ScatterRequest request;
  request.tileset = options.tileset;
  if (!options.dem.empty()) {
    TerrainConfig& terrain = request.dem.emplace();
    terrain.dem = options.dem;
    if (!options.origin.empty()) {
      const auto origin = parse_lat_lon(options.origin);
      terrain.origin_latitude = origin[0];
      terrain.origin_longitude = origin[1];
    }
    request.masks.max_height = options.max_height;
    request.masks.min_height = options.min_height;
    request.masks.max_slope = options.max_slope;
    request.masks.mask = options.mask;
    request.masks.fair_edges = options.fair_edges;
  } else {
    request.plane = parse_plane(options.plane);
  }
  request.placement.tile_size = options.tile_size;
  request.placement.seed = options.seed;
  request.placement.algorithm = parse_tiling_algorithm(options.algorithm);
  request.out = options.out;
  request.gis_crs = options.crs;
  request.metrics = options.metrics;
  request.max_instances = options.max_instances;
  request.large_file_ok = options.yes;
  const WriteReport report(global.quiet);
  std::optional<Progress> progress;
  // The bar says what the points file will hold, as estimated before its first byte (the file's
  // name was checked by then).
  std::string expected_file;
  request.progress = [&](std::uint64_t placed, std::uint64_t expected) {
    if (!progress) {
      progress.emplace("scatter", expected, global.quiet);
      if (!options.out.empty())
        expected_file =
            fmt::format("of about {}, {}",
                        expected >= 1000000 ? fmt::format("{:.3g} million instances", double(expected) / 1e6)
                                            : fmt::format("{} instances", expected),
                        byte_text(double(expected) * point_file_bytes_per_point(point_file_format(options.out))));
    }
    progress->update(placed, expected_file);
  };
  const ScatterResult result = run_scatter(request);
  if (progress) progress->finish();
  if (!result.empty_reason.empty() && !global.quiet)
    fmt::print(stderr, "wangscape: empty result: {}\n", result.empty_reason);
  if (result.metrics) {
    if (!options.spectrum_png.empty()) write_image(options.spectrum_png, draw_spectrum_plot(result.metrics->spectrum));
    if (options.json) {
      Json json = point_metrics_json(*result.metrics, result.seconds);
      if (!result.classes.empty()) {
        Json classes = Json::array();
        for (const ClassMetrics& c : result.classes) {
          Json one = point_metrics_json(c.metrics, result.seconds);
          one["class_spacing_m"] = c.spacing;
          one["edge_objects"] = c.edge_objects;
          classes.push_back(std::move(one));
        }
        json["classes"] = std::move(classes);
      }
      fmt::print("{}\n", json.dump(2));
    } else {
      fmt::print("{}{}", point_metrics_text(*result.metrics, result.packing_diameter),
                 class_metrics_text(result.classes));
    }
  }
  if (!options.out.empty())
    report.wrote(options.out, fmt::format("{} instances from {} tiles", result.stats.points, result.stats.tiles_kept));
}

}  // namespace

void register_scatter_command(CLI::App& app, const GlobalOptions& global) {
  auto* sub =
      app.add_subcommand("scatter", "Lay a filled tile set over a flat plane or a DEM and write every instance");
  auto options = std::make_shared<ScatterOptions>();
  sub->add_option("--tileset", options->tileset, "Filled tile set (wangscape tileset --per-tile N --out FILE)")
      ->required();
  auto* plane = sub->add_option("--plane", options->plane, "Plane size WIDTHxHEIGHT in meters (east x north)")
                    ->capture_default_str();
  sub->add_option("--tile-size", options->tile_size, "Tile side in meters")->capture_default_str();
  auto* out = sub->add_option("--out", options->out,
                              "Instances by the extension: .csv (x,y,z,variant,yaw,scale,tile), .ply (binary), or with "
                              "--dem .gpkg (GeoPackage) or .geojson: points with species, variant, scale, yaw, height, "
                              "rank")
                  ->check(output_file_path());
  sub->add_option("--max-instances", options->max_instances,
                  "Refuse to place more than N instances (default: no cap; the free disk space is checked)")
      ->check(CLI::Range(std::uint64_t{1}, std::uint64_t{1000000000000000}));  // 1e15: readable, not 309 digits
  sub->add_flag("--yes", options->yes, "Write a points file estimated above 1 GB (refused without it)");
  sub->add_option("--seed", options->seed, "Tiling seed")->check(seed_number())->capture_default_str();
  sub->add_option("--algorithm", options->algorithm,
                  "Tiling: scanline, bottom-left, hash (complete sets) or aperiodic (culik13)")
      ->check(CLI::IsMember(tiling_algorithm_names()))
      ->capture_default_str();
  sub->add_flag("--metrics", options->metrics,
                "Print quality figures (rho, NN distances, densities, spectrum); a set of several classes: also per "
                "class");
  sub->add_flag("--json", options->json, "With --metrics: print them as JSON");
  sub->add_option("--spectrum-png", options->spectrum_png, "With --metrics: plot the power spectrum into this PNG");
  auto* dem = sub->add_option("--dem", options->dem, "Scatter over this DEM (USGS DEM, GeoTIFF, SRTM .hgt, ESRI .asc)")
                  ->excludes(plane);
  sub->add_option("--max-height", options->max_height, "With --dem: flowers only where the ground is at most this (m)")
      ->check(finite_number())
      ->needs(dem);
  sub->add_option("--min-height", options->min_height, "With --dem: flowers only where the ground is at least this (m)")
      ->check(finite_number())
      ->needs(dem);
  sub->add_option("--max-slope", options->max_slope, "With --dem: flowers only where the slope is at most this (deg)")
      ->check(CLI::Range(0.0, 90.0))
      ->needs(dem);
  sub->add_option("--mask", options->mask, "With --dem: painted mask image over the DEM's extent, white = flowers")
      ->needs(dem);
  sub->add_flag("--fair-edges", options->fair_edges,
                "With --dem: keep partial tiles, drop only flowers whose own ground fails (border follows the contour)")
      ->needs(dem);
  sub->add_option("--origin", options->origin,
                  "With --dem: scene origin LAT,LON in WGS 84 degrees (default: DEM center)")
      ->check(lat_lon_validator())
      ->needs(dem);
  add_enum_option(sub, "--crs", options->crs, kGisCrsNames,
                  "With --out .gpkg or .geojson: the points in the DEM's CRS (dem) or in WGS 84 longitude, latitude")
      ->needs(out)
      ->needs(dem);
  set_help_footer(sub,
                  "--out FILE: every instance as CSV or binary PLY in the scene's ENU meters, or over a DEM as a "
                  "GeoPackage or GeoJSON point layer in the DEM's CRS (streamed: any count the disk holds); "
                  "--metrics: figures on stdout (--json), --spectrum-png a plot",
                  {"wangscape tileset --set cohen8 --per-tile 20 --out tiles.json",
                   "wangscape scatter --tileset tiles.json --plane 64x64 --tile-size 4 --out points.csv --metrics",
                   "wangscape scatter --tileset tiles.json --dem data/SainteHelens.dem --tile-size 8 --max-height 800 "
                   "--out points.gpkg"});
  sub->callback([options, &global] { run(*options, global); });
}

}  // namespace wangscape::cli
