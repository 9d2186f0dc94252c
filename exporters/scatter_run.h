// What `wangscape scatter` runs: a filled tile set laid over a flat plane or over a DEM (the
// scene's one ground, with every mask), every instance written (CSV, binary PLY, or over a DEM a
// GeoPackage or GeoJSON layer: exporters/gis_writer.h) and/or measured (generator/point_metrics). The points are
// streamed, never held, so no count caps them: the work is estimated after the masks and refused, before anything is
// placed or opened, only where it would not fit: the file against the free disk space, the measured points against the
// memory limit, and the count against --max-instances when one is given.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "exporters/point_writer.h"
#include "generator/placement.h"
#include "generator/point_metrics.h"
#include "scene/scene_file.h"

namespace wangscape {

// A points file estimated above this is written only when asked for (--yes): a user who meant a
// small field should not find gigabytes streaming onto the disk.
inline constexpr double kLargeScatterFileBytes = 1e9;

struct ScatterRequest {
  std::filesystem::path tileset;     // a filled tile set (wangscape tileset --per-tile N)
  Extent plane;                      // ENU meters, without a DEM
  std::optional<TerrainConfig> dem;  // over this DEM instead, with `masks`
  MasksConfig masks;
  PlacementOptions placement;                  // tile size, seed, algorithm
  std::filesystem::path out;                   // instances (.csv, .ply, .gpkg, .geojson); empty: none written
  GisCrsChoice gis_crs = GisCrsChoice::dem;    // .gpkg and .geojson: the DEM's CRS or WGS 84
  bool metrics = false;                        // measure the points
  std::optional<std::uint64_t> max_instances;  // refuse more than this
  bool large_file_ok = false;                  // write a points file estimated above kLargeScatterFileBytes (--yes)
  std::function<void(std::uint64_t placed, std::uint64_t expected)> progress;  // from this thread
};

// With request.metrics and a set of several classes (species): one class's points on their own.
struct ClassMetrics {
  PointMetrics metrics;       // its pairs counted against the class's own spacing; its own spectrum
  double spacing = 0;         // meters: the least distance the fill keeps between two of its points
  bool edge_objects = false;  // all at the tile edges: no interior to compare their density with
};

struct ScatterResult {
  PlacementStats stats;
  double seconds = 0;                   // of the placement (and writing)
  std::optional<PointMetrics> metrics;  // with request.metrics: every point (the union of the classes)
  std::vector<ClassMetrics> classes;    // with request.metrics and several classes: per class
  double packing_diameter = 0;          // meters: twice the set's packing radius, scaled
  std::string empty_reason;             // over a DEM with no instance: why (which mask)
  double estimate = 0;                  // instances expected before placing (after the masks)
};

// Throws Error for bad input (naming the file or value), before any output for work beyond the
// limits above, and during the placement once more than max_instances are placed; the output
// file is published whole or not at all.
ScatterResult run_scatter(const ScatterRequest& request);

// About how many bytes a point takes in a file of `format`: 26 in PLY, 54 in CSV (a mean line),
// and in the GIS layers as measured over St. Helens (docs/limits.md).
double point_file_bytes_per_point(PointFileFormat format);

}  // namespace wangscape
