// wangscape scatter --tileset tiles.json --plane 64x64 --tile-size 4 --out points.csv
// Lays a tiling of a filled tile set over a flat plane and writes every instance (CSV, or
// binary PLY for .ply); --metrics measures the quality figures of the result.
// With --dem FILE the ground is a DEM, the scene's one ground (scene/ground.h): z = ground
// height, tiles only where --max-height / --min-height / --max-slope / --mask allow (seed 003),
// --fair-edges for partial tiles.
#include <fmt/core.h>

#include <chrono>
#include <memory>
#include <optional>

#include "cli/command.h"
#include "cli/progress.h"
#include "core/memory_budget.h"
#include "exporters/image_io.h"
#include "exporters/point_writer.h"
#include "exporters/reports.h"
#include "generator/placement.h"
#include "generator/point_metrics.h"
#include "scene/filled_tileset_file.h"
#include "scene/scene.h"

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
};

// The scene's ground for --dem, with every mask the flags give.
SceneGround load_dem_ground(const ScatterOptions& options) {
  TerrainConfig terrain;
  terrain.dem = options.dem;
  if (!options.origin.empty()) {
    const auto origin = parse_lat_lon(options.origin);
    terrain.origin_latitude = origin[0];
    terrain.origin_longitude = origin[1];
  }
  MasksConfig masks;
  masks.max_height = options.max_height;
  masks.min_height = options.min_height;
  masks.max_slope = options.max_slope;
  masks.mask = options.mask;
  masks.fair_edges = options.fair_edges;
  return SceneGround::load(terrain, masks);
}

void run(const ScatterOptions& options, const GlobalOptions& global) {
  if (options.out.empty() && !options.metrics)
    throw std::runtime_error("scatter: nothing to do; give --out FILE and/or --metrics");
  if (!(options.tile_size > 0))
    throw std::runtime_error("--tile-size " + std::to_string(options.tile_size) + ": expected meters > 0");
  // Over a DEM: loaded and checked before any output is opened.
  std::optional<SceneGround> dem;
  if (!options.dem.empty()) {
    dem = load_dem_ground(options);
    dem->check_tile_size(options.tile_size, "--tile-size");
  }
  const Extent plane = dem ? dem->extent() : parse_plane(options.plane);
  const FilledTileSet filled = read_filled_tileset_json(options.tileset);

  PlacementOptions placement;
  placement.tile_size = options.tile_size;
  placement.seed = options.seed;
  placement.algorithm = parse_tiling_algorithm(options.algorithm);

  std::optional<PointWriter> writer;
  if (!options.out.empty()) writer.emplace(options.out);
  std::vector<float> xs, ys;
  const TileRange range = tile_range(plane, options.tile_size);
  const double tiles = static_cast<double>(range.width()) * range.height();
  std::size_t total_points = 0;
  for (const auto& t : filled.tiles) total_points += t.size();
  const double estimate =
      tiles * static_cast<double>(total_points) / double(std::max<std::size_t>(filled.tiles.size(), 1));
  if (estimate > kMaxFieldInstances)
    throw Error(
        fmt::format("scatter: {:.0f} x {:.0f} m in {:g} m tiles would place about {:.3g} instances; at most {:.0f} "
                    "million: a smaller --plane or a larger --tile-size",
                    plane.width(), plane.height(), options.tile_size, estimate, kMaxFieldInstances / 1e6));
  if (options.metrics) {
    check_memory_estimate(options.tileset, fmt::format("scatter --metrics over about {:.3g} instances", estimate),
                          kMetricsBytesPerPoint * estimate);
    xs.reserve(std::size_t(estimate * 1.05));  // no doubling past the estimate
    ys.reserve(std::size_t(estimate * 1.05));
  }
  Progress progress("scatter", static_cast<std::uint64_t>(estimate), global.quiet);
  const auto start = std::chrono::steady_clock::now();
  const auto sink = [&](const InstanceBatch& b) {
    if (writer) writer->write(b);
    if (options.metrics) {
      xs.insert(xs.end(), b.x.begin(), b.x.end());
      ys.insert(ys.end(), b.y.begin(), b.y.end());
    }
  };
  const PlacementStats stats =
      dem ? dem->place(filled, placement, sink) : place_instances(filled, FlatGround{plane, 0.0}, placement, sink);
  if (dem && stats.points == 0 && !global.quiet)
    fmt::print(stderr, "wangscape: empty result: {}\n", dem->explain_empty(options.tile_size));
  progress.finish();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (writer) writer->commit();

  if (options.metrics) {
    PointMetricsOptions metric_options;
    metric_options.area = plane;
    metric_options.tile_size = options.tile_size;
    metric_options.packing_diameter = 2.0 * filled.radius_packing * options.tile_size;
    const PointMetrics m = measure_points(xs, ys, metric_options);
    if (!options.spectrum_png.empty()) write_image(options.spectrum_png, draw_spectrum_plot(m.spectrum));
    if (options.json)
      fmt::print("{}\n", point_metrics_json(m, seconds).dump(2));
    else
      fmt::print("{}", point_metrics_text(m, metric_options.packing_diameter));
  } else if (!global.quiet) {
    fmt::print(stderr, "wangscape: {} instances from {} tiles -> {}\n", stats.points, stats.tiles, options.out);
  }
}

}  // namespace

void register_scatter_command(CLI::App& app, const GlobalOptions& global) {
  auto* sub = app.add_subcommand("scatter", "Lay a filled tile set over a flat plane and write every instance");
  auto options = std::make_shared<ScatterOptions>();
  sub->add_option("--tileset", options->tileset, "Filled tile set (wangscape tileset --per-tile N --out FILE)")
      ->required();
  auto* plane = sub->add_option("--plane", options->plane, "Plane size WIDTHxHEIGHT in meters (east x north)")
                    ->capture_default_str();
  sub->add_option("--tile-size", options->tile_size, "Tile side in meters")->capture_default_str();
  sub->add_option("--out", options->out, "Instances: CSV (x,y,z,variant,yaw,scale,tile), or binary PLY for .ply");
  sub->add_option("--seed", options->seed, "Tiling seed")->check(seed_number())->capture_default_str();
  sub->add_option("--algorithm", options->algorithm, "Tiling: scanline, bottom-left or hash (complete sets)")
      ->check(CLI::IsMember({"scanline", "bottom-left", "hash"}))
      ->capture_default_str();
  sub->add_flag("--metrics", options->metrics, "Print quality figures (rho, NN distances, densities, spectrum)");
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
  sub->callback([options, &global] { run(*options, global); });
}

}  // namespace wangscape::cli
