// What `wangscape scatter` runs: a filled tile set laid over a flat plane or over a DEM (the
// scene's one ground, with every mask), every instance written (CSV, or binary PLY for .ply)
// and/or measured (generator/point_metrics). The work is estimated and refused above the field
// cap and, when measured, above the memory limit, before anything is placed or opened.
#pragma once

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include "generator/placement.h"
#include "generator/point_metrics.h"
#include "scene/scene_file.h"

namespace wangscape {

struct ScatterRequest {
  std::filesystem::path tileset;     // a filled tile set (wangscape tileset --per-tile N)
  Extent plane;                      // ENU meters, without a DEM
  std::optional<TerrainConfig> dem;  // over this DEM instead, with `masks`
  MasksConfig masks;
  PlacementOptions placement;                                                  // tile size, seed, algorithm
  std::filesystem::path out;                                                   // instances; empty: none written
  bool metrics = false;                                                        // measure the points
  std::function<void(std::uint64_t placed, std::uint64_t expected)> progress;  // from this thread
};

struct ScatterResult {
  PlacementStats stats;
  double seconds = 0;                   // of the placement (and writing)
  std::optional<PointMetrics> metrics;  // with request.metrics
  double packing_diameter = 0;          // meters: twice the set's packing radius, scaled
  std::string empty_reason;             // over a DEM with no instance: why (which mask)
};

// Throws Error for bad input (naming the file or value) and before any output for work beyond
// the caps; the output file is published whole or not at all.
ScatterResult run_scatter(const ScatterRequest& request);

}  // namespace wangscape
