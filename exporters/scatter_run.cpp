#include "exporters/scatter_run.h"

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <cstdint>

#include "core/disk_space.h"
#include "core/error.h"
#include "core/memory_budget.h"
#include "core/number_text.h"
#include "exporters/gis_writer.h"
#include "exporters/point_writer.h"
#include "scene/filled_tileset_file.h"
#include "scene/scene.h"
#include "scene/scene_ground.h"

namespace wangscape {

double point_file_bytes_per_point(PointFileFormat format) {
  // PLY: float x, y, z, ushort variant, float yaw, scale, uint tile. CSV: the mean line of 7.9
  // million points over St. Helens (54.0 bytes: meters and radians with up to 9 digits, the tile).
  switch (format) {
    case PointFileFormat::ply:
      return 26.0;
    case PointFileFormat::csv:
      return 54.0;
    case PointFileFormat::geopackage:  // 800,288 plants over St. Helens: 106 MB with the spatial index
      return 133.0;
    case PointFileFormat::geojson:  // the same: 181 MB
      return 226.0;
  }
  return 226.0;
}

namespace {

// Refuses a scatter whose estimate passes --max-instances, the free disk, or (without --yes) the
// size a user should confirm, before anything is written.
void refuse_too_large(const ScatterRequest& request, const std::optional<PointFileFormat>& format, double estimate,
                      const std::string& about) {
  if (request.max_instances && estimate > double(*request.max_instances))
    throw Error(
        fmt::format("scatter: {} would place about {:.3g} instances; --max-instances is {}: a larger "
                    "--max-instances, a smaller area or a larger --tile-size",
                    about, estimate, *request.max_instances));
  if (!request.out.empty()) {
    const double bytes = estimate * point_file_bytes_per_point(*format);
    check_disk_estimate(
        request.out,
        fmt::format("scatter's points file '{}' (about {:.3g} instances: {})", request.out.string(), estimate, about),
        bytes,
        "free some space, write elsewhere (--out), or scatter less (a larger --tile-size, masks, "
        "--max-instances)");
    if (bytes > kLargeScatterFileBytes && !request.large_file_ok)
      throw Error(
          fmt::format("scatter's points file '{}' would hold about {:.3g} instances, about {} ({}); add "
                      "--yes to write it, or scatter less (a larger --tile-size, masks, a smaller area)",
                      request.out.string(), estimate, byte_text(bytes), about));
  }
}

// Each class of a multi-class set measured on its own: its points copied out of the union.
void measure_classes(const FilledTileSet& filled, double tile_size, const std::vector<float>& xs,
                     const std::vector<float>& ys, const std::vector<std::uint8_t>& point_class,
                     const std::vector<std::size_t>& class_sizes, const PointMetricsOptions& metric_options,
                     std::vector<ClassMetrics>& classes) {
  std::vector<float> class_xs, class_ys;
  for (std::size_t c = 0; c < class_sizes.size(); ++c) {
    class_xs.clear();
    class_ys.clear();
    class_xs.reserve(class_sizes[c]);
    class_ys.reserve(class_sizes[c]);
    for (std::size_t i = 0; i < point_class.size(); ++i)
      if (point_class[i] == c) {
        class_xs.push_back(xs[i]);
        class_ys.push_back(ys[i]);
      }
    ClassMetrics& m = classes.emplace_back();
    m.spacing = filled.classes[c].spacing * tile_size;
    m.edge_objects = filled.classes[c].edge_objects;
    PointMetricsOptions class_options = metric_options;
    class_options.packing_diameter = m.spacing;
    class_options.zone_width = std::min(filled.classes[c].spacing, 0.3) * tile_size;  // leaves an interior
    m.metrics = measure_points(class_xs, class_ys, class_options);
  }
}

}  // namespace

ScatterResult run_scatter(const ScatterRequest& request) {
  const double tile_size = request.placement.tile_size;
  if (!(tile_size > 0)) throw Error("--tile-size " + std::to_string(tile_size) + ": expected meters > 0");
  // The format by the name's extension, refused before anything is read or opened.
  std::optional<PointFileFormat> format;
  if (!request.out.empty()) format = point_file_format(request.out);
  const bool gis = format == PointFileFormat::geopackage || format == PointFileFormat::geojson;
  if (gis && !request.dem)
    throw Error(request.out, "",
                "a GIS layer needs --dem: its points stand in the DEM's coordinate reference system (or WGS 84), and "
                "a plane has neither; write .csv or .ply for a plane");
  if (!gis && request.gis_crs != GisCrsChoice::dem)
    throw Error(
        "--crs wgs84: only a GIS layer (--out FILE.gpkg or .geojson) has a CRS to choose; CSV and PLY points "
        "are in the scene's ENU meters");
  // Over a DEM: loaded and checked before any output is opened.
  std::optional<SceneGround> dem;
  if (request.dem) {
    dem = SceneGround::load(*request.dem, request.masks);
    dem->check_tile_size(tile_size, "--tile-size");
  }
  const Extent plane = dem ? dem->extent() : request.plane;
  const FilledTileSet filled = read_filled_tileset_json(request.tileset);

  // The tiles of the extent times the set's mean points per tile, times the share of the ground
  // the masks keep: the points are streamed, so this only sizes the file, the metrics' memory
  // and the progress bar.
  const TileRange range = tile_range(plane, tile_size);
  const double tiles = static_cast<double>(range.width()) * range.height();
  std::size_t total_points = 0;
  for (const auto& t : filled.tiles) total_points += t.size();
  const double estimate = tiles * static_cast<double>(total_points) /
                          double(std::max<std::size_t>(filled.tiles.size(), 1)) * (dem ? dem->growing_share() : 1.0);
  const std::string about = fmt::format("{:.0f} x {:.0f} m in {:g} m tiles{}", plane.width(), plane.height(), tile_size,
                                        dem ? " (after the masks)" : "");
  refuse_too_large(request, format, estimate, about);
  std::vector<float> xs, ys;
  // Several classes: each point's class beside its coordinates (its variant's class, looked up
  // once per variant), so that each class can be measured on its own after the union without a
  // second copy of every point held through the placement.
  const std::size_t class_count = request.metrics && filled.classes.size() > 1 ? filled.classes.size() : 0;
  constexpr std::uint8_t kNoClass = 0xff;  // the fill takes at most 255 classes
  std::vector<std::uint8_t> variant_class(class_count ? std::size_t(filled.variants) : 0);
  for (std::size_t v = 0; v < variant_class.size(); ++v)
    variant_class[v] = std::uint8_t(class_of_variant(filled, int(v)).value_or(kNoClass));
  std::vector<std::uint8_t> point_class;
  std::vector<std::size_t> class_sizes(class_count);  // counted as placed: sizes each class's copy
  if (request.metrics) {
    // The union's coordinates and classes stay while one class at a time is copied and measured.
    check_memory_estimate(request.tileset, fmt::format("scatter --metrics over about {:.3g} instances", estimate),
                          (kMetricsBytesPerPoint + (class_count ? 9.0 : 0.0)) * estimate);
    xs.reserve(std::size_t(estimate * 1.05));  // no doubling past the estimate
    ys.reserve(std::size_t(estimate * 1.05));
    if (class_count) point_class.reserve(std::size_t(estimate * 1.05));
  }

  std::optional<PointWriter> writer;
  std::optional<PlantPointWriter> gis_writer;
  if (gis)
    gis_writer.emplace(*dem->terrain(), request.out,
                       *format == PointFileFormat::geopackage ? GisVectorFormat::geopackage : GisVectorFormat::geojson,
                       request.gis_crs, plant_names(filled));
  else if (format)
    writer.emplace(request.out);
  const auto start = std::chrono::steady_clock::now();
  std::uint64_t placed = 0;
  const auto sink = [&](const InstanceBatch& b) {
    if (writer) writer->write(b);
    if (gis_writer) gis_writer->write(b);
    if (request.metrics) {
      xs.insert(xs.end(), b.x.begin(), b.x.end());
      ys.insert(ys.end(), b.y.begin(), b.y.end());
    }
    for (std::size_t i = 0; class_count && i < b.size(); ++i) {
      const std::uint8_t c = b.variant[i] < variant_class.size() ? variant_class[b.variant[i]] : kNoClass;
      point_class.push_back(c);
      if (c < class_count) ++class_sizes[c];
    }
    placed += b.size();
    if (request.max_instances && placed > *request.max_instances)
      throw Error(
          fmt::format("scatter: placed more than --max-instances {} instances (about {:.3g} were expected); "
                      "nothing was written",
                      *request.max_instances, estimate));
    if (request.progress) request.progress(placed, static_cast<std::uint64_t>(estimate));
  };
  ScatterResult result;
  result.estimate = estimate;
  result.stats = dem ? dem->place(filled, request.placement, sink)
                     : place_instances(filled, FlatGround{plane, 0.0}, request.placement, sink);
  if (dem && result.stats.points == 0) result.empty_reason = dem->explain_empty(tile_size);
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (writer) writer->commit();
  if (gis_writer) gis_writer->commit();
  result.packing_diameter = 2.0 * filled.radius_packing * tile_size;
  if (request.metrics) {
    PointMetricsOptions metric_options;
    metric_options.area = plane;
    metric_options.tile_size = tile_size;
    metric_options.packing_diameter = result.packing_diameter;
    result.metrics = measure_points(xs, ys, metric_options);
    measure_classes(filled, tile_size, xs, ys, point_class, class_sizes, metric_options, result.classes);
  }
  return result;
}

}  // namespace wangscape
