#include "exporters/reports.h"

#include <fmt/core.h>

#include <charconv>
#include <variant>

#include "core/atomic_file.h"
#include "core/printable.h"

namespace wangscape {

Json tiling_stats_json(const TileSet& set, const Tiling& tiling, const TilingRun& run, const TilingStats& stats) {
  Json out;
  out["set"] = set.name;
  out["tiles_in_set"] = set.size();
  out["width"] = tiling.width;
  out["height"] = tiling.height;
  out["origin"] = {tiling.origin_i, tiling.origin_j};
  out["algorithm"] = run.algorithm;
  out["seed"] = run.seed;
  out["no_identical_neighbours"] = run.no_identical_neighbours;
  out["valid"] = stats.valid;
  if (!stats.valid) out["invalid_reason"] = stats.invalid_reason;
  out["frequencies"] = stats.frequencies;
  out["identical_neighbour_rate"] = stats.identical_neighbour_rate;
  out["periodicity"] = stats.periodicity;
  out["periodicity_offset"] = {stats.period_di, stats.period_dj};
  return out;
}

std::string tiling_stats_text(const TileSet& set, const Tiling& tiling, const TilingRun& run,
                              const TilingStats& stats) {
  std::string out;
  out += fmt::format("set:                  {} ({} tiles)\n", printable(set.name), set.size());
  out += fmt::format("window:               {} x {} tiles from ({}, {})\n", tiling.width, tiling.height,
                     tiling.origin_i, tiling.origin_j);
  out += fmt::format("algorithm:            {}, seed {}{}\n", run.algorithm, run.seed,
                     run.no_identical_neighbours ? ", no identical neighbours" : "");
  out += fmt::format("valid:                {}\n", stats.valid ? "yes" : "no: " + stats.invalid_reason);
  out += fmt::format("identical neighbours: {:.4f}\n", stats.identical_neighbour_rate);
  out += fmt::format("periodicity:          {:.4f} (at offset {}, {}; ~1 periodic, ~0 stochastic)\n", stats.periodicity,
                     stats.period_di, stats.period_dj);
  out += fmt::format("frequencies:         ");
  for (std::size_t t = 0; t < stats.frequencies.size(); ++t) out += fmt::format(" {}:{}", t, stats.frequencies[t]);
  out += fmt::format("\n");
  return out;
}

void write_tiling_csv(const std::filesystem::path& path, const Tiling& tiling) {
  AtomicFile file(path);
  file.stream() << "i,j,tile\n";
  std::string line;
  const auto append = [&line](std::int64_t value, char end) {
    char digits[24];  // any 64-bit integer
    line.append(digits, std::to_chars(digits, digits + sizeof digits, value).ptr);
    line.push_back(end);
  };
  for (int lj = 0; lj < tiling.height; ++lj)
    for (int li = 0; li < tiling.width; ++li) {
      line.clear();
      append(tiling.origin_i + li, ',');
      append(tiling.origin_j + lj, ',');
      append(tiling.at(li, lj), '\n');
      file.stream() << line;
    }
  file.commit();
}

Json terrain_info_json(const Terrain& terrain) {
  const DemRaster& dem = terrain.dem();
  const Extent extent = terrain.extent();
  Json out;
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

std::string terrain_info_text(const Terrain& terrain) {
  std::string out;
  const DemRaster& dem = terrain.dem();
  const TerrainGeoreference& g = terrain.georeference();
  const Extent e = terrain.extent();
  const char* unit = dem.geographic ? "deg" : "m";
  out += fmt::format("file:             {}\n", dem.path.string());
  out += fmt::format("driver:           {}\n", dem.driver);
  out += fmt::format("crs:              {} ({})\n", dem.crs_name, dem.geographic ? "geographic" : "projected");
  out += fmt::format("datum:            {}\n", g.horizontal_datum);
  out += fmt::format("size:             {} x {} samples\n", dem.width, dem.height);
  out += fmt::format("spacing:          {:.10g} x {:.10g} {} ({:.2f} x {:.2f} m)\n", dem.spacing_x(), dem.spacing_y(),
                     unit, terrain.spacing_m()[0], terrain.spacing_m()[1]);
  out += fmt::format("heights:          {:.2f} .. {:.2f} m (file unit: {})\n", dem.min_height, dem.max_height,
                     dem.height_unit_in_file);
  out += fmt::format("no-data cells:    {} of {}\n", dem.nodata_count, dem.cell_count());
  out += fmt::format("extent (ENU):     x {:.1f} .. {:.1f} m, y {:.1f} .. {:.1f} m ({:.1f} x {:.1f} m)\n", e.min_x,
                     e.max_x, e.min_y, e.max_y, e.width(), e.height());
  out += fmt::format("origin:           lat {:.8f}, lon {:.8f} (WGS 84), z = 0 at orthometric height 0\n",
                     g.origin_lat_deg, g.origin_lon_deg);
  out += fmt::format("utm zone:         {}{}\n", g.utm_zone, g.utm_north ? "N" : "S");
  out += fmt::format("convergence:      {:.6f} deg (UTM scale {:.8f})\n", g.convergence_deg, g.utm_scale);
  out += fmt::format("axes:             {}\n", g.axis_mapping);
  out += fmt::format("vertical datum:   {}\n", g.vertical_datum);
  out += fmt::format("datum note:       {}\n", g.datum_note);
  return out;
}

Json point_metrics_json(const PointMetrics& m, double seconds) {
  Json j;
  j["count"] = m.count;
  j["area_m2"] = m.area;
  j["spacing_m"] = m.spacing;
  j["min_distance_m"] = m.min_distance;
  j["rho"] = m.rho;
  j["mean_nn"] = m.mean_nn;
  j["nn_spread"] = m.nn_spread;
  j["close_pairs"] = m.close_pairs;
  j["edge_density_ratio"] = m.edge_density_ratio;
  j["corner_density_ratio"] = m.corner_density_ratio;
  j["anisotropy_db"] = m.spectrum.mean_anisotropy_db;
  j["anisotropy_off_grid_db"] = m.spectrum.mean_anisotropy_off_grid_db;
  j["anisotropy_noise_floor_db"] = m.spectrum.noise_floor_db;
  j["scatter_seconds"] = seconds;
  Json spectrum;
  spectrum["window_m"] = m.spectrum.window;
  spectrum["windows"] = m.spectrum.windows;
  spectrum["frequency_per_m"] = m.spectrum.frequency;
  spectrum["power"] = m.spectrum.power;
  spectrum["anisotropy_db"] = m.spectrum.anisotropy_db;
  j["spectrum"] = std::move(spectrum);
  return j;
}

std::string point_metrics_text(const PointMetrics& m, double packing_diameter) {
  std::string out;
  out += fmt::format("points:                {}\n", m.count);
  out += fmt::format("rho (d_min / spacing): {:.4f}  (d_min {:.4f} m, spacing {:.4f} m)\n", m.rho, m.min_distance,
                     m.spacing);
  out += fmt::format("mean NN / spacing:     {:.4f}\n", m.mean_nn);
  out += fmt::format("NN std / mean:         {:.4f}\n", m.nn_spread);
  out += fmt::format("pairs < {:.4f} m:      {}\n", packing_diameter, m.close_pairs);
  out += fmt::format("edge density ratio:    {:.3f}\n", m.edge_density_ratio);
  out += fmt::format("corner density ratio:  {:.3f}\n", m.corner_density_ratio);
  out +=
      fmt::format("anisotropy:            {:.2f} dB, {:.2f} dB off the tile grid (noise floor {:.2f} dB, {} windows)\n",
                  m.spectrum.mean_anisotropy_db, m.spectrum.mean_anisotropy_off_grid_db, m.spectrum.noise_floor_db,
                  m.spectrum.windows);
  return out;
}

std::string tileset_summary_text(const TileSet& set) {
  std::string out;
  out += fmt::format("name:    {}\n", printable(set.name));
  out += fmt::format("kind:    {}{}\n", set.kind == TileKind::edge ? "edge" : "corner",
                     set.kind == TileKind::edge && set.has_corners ? " (corners coded too)" : "");
  out += fmt::format("tiles:   {}\n", set.size());
  if (set.has_edges) out += fmt::format("colors:  {} N/S, {} E/W\n", set.horizontal_colors, set.vertical_colors);
  if (set.has_corners) out += fmt::format("corners: {} colors\n", set.corner_colors);
  return out;
}

std::string poisson_fill_text(const FilledTileSet& filled, const PoissonFillReport& report, int points_per_tile) {
  const double spacing = hexagonal_spacing(1.0, points_per_tile);
  return fmt::format(
      "{}: {} distinct points; rho over every configuration {:.4f} after darts, {:.4f} after {} relaxation "
      "rounds{}; radius_packing {:.5f}, radius_tight {:.5f} (tile sides)\n",
      printable(filled.set.name), report.class_points, report.dart_min_distance / spacing,
      report.final_min_distance / spacing, report.relax_rounds_run,
      report.stopped_before_lattice ? " (stopped before a lattice)" : "", filled.radius_packing, filled.radius_tight);
}

}  // namespace wangscape
