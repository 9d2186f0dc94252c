#include "cli/terrain_ground.h"

#include <fmt/core.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>

namespace wangscape::cli {

namespace {
std::optional<double> parse_number(std::string_view text) {
  while (!text.empty() && text.front() == ' ') text.remove_prefix(1);
  while (!text.empty() && text.back() == ' ') text.remove_suffix(1);
  double value = 0;
  const auto result = std::from_chars(text.data(), text.data() + text.size(), value);
  if (result.ec != std::errc() || result.ptr != text.data() + text.size() || !std::isfinite(value)) return std::nullopt;
  return value;
}
}  // namespace

LatLon parse_lat_lon(const std::string& text) {
  const auto comma = text.find(',');
  const auto lat = comma == std::string::npos ? std::nullopt : parse_number(std::string_view(text).substr(0, comma));
  const auto lon = comma == std::string::npos ? std::nullopt : parse_number(std::string_view(text).substr(comma + 1));
  if (!lat || !lon || std::abs(*lat) > 90 || std::abs(*lon) > 180)
    throw std::invalid_argument("origin '" + text +
                                "' is not LAT,LON in WGS 84 degrees (latitude -90..90, longitude -180..180)");
  return {*lat, *lon};
}

CLI::Validator lat_lon_validator() {
  return CLI::Validator(
      [](std::string& text) {
        try {
          parse_lat_lon(text);
          return std::string();
        } catch (const std::exception& e) {
          return std::string(e.what());
        }
      },
      "LAT,LON");
}

CLI::Option* add_terrain_scatter_options(CLI::App& sub, TerrainScatterOptions& options) {
  CLI::Option* dem =
      sub.add_option("--dem", options.dem, "Scatter over this DEM (USGS DEM, GeoTIFF, SRTM .hgt, ESRI .asc)");
  sub.add_option("--max-height", options.max_height_m,
                 "With --dem: flowers only where the ground is at most this high (m)")
      ->needs(dem);
  sub.add_option("--max-slope", options.max_slope_deg, "With --dem: flowers only where the slope is at most this (deg)")
      ->check(CLI::Range(0.0, 90.0))
      ->needs(dem);
  sub.add_option("--mask", options.mask, "With --dem: painted mask image over the DEM's extent, white = flowers")
      ->needs(dem);
  sub.add_flag("--fair-edges", options.fair_edges,
               "With --dem: keep partial tiles, drop only flowers whose own ground fails (border follows the contour)")
      ->needs(dem);
  sub.add_option("--origin", options.origin, "With --dem: scene origin LAT,LON in WGS 84 degrees (default: DEM center)")
      ->check(lat_lon_validator())
      ->needs(dem);
  return dem;
}

TerrainScatter::TerrainScatter(const TerrainScatterOptions& options, double tile_size)
    : fair_edges_(options.fair_edges), tile_size_(tile_size) {
  TerrainOptions terrain_options;
  if (!options.origin.empty()) terrain_options.origin = parse_lat_lon(options.origin);
  terrain_ = std::make_unique<Terrain>(Terrain::load(options.dem, terrain_options));
  const Extent e = terrain_->extent();
  if (!(tile_size > 0) || tile_size > std::min(e.width(), e.height()))
    throw std::runtime_error(fmt::format(
        "--tile-size {:g} m does not fit DEM '{}' ({:.0f} x {:.0f} m): expected more than 0 and at most the "
        "terrain's smaller side",
        tile_size, options.dem, e.width(), e.height()));
  TerrainFilterOptions filter_options;
  if (!std::isnan(options.max_height_m)) filter_options.max_height_m = options.max_height_m;
  if (!std::isnan(options.max_slope_deg)) filter_options.max_slope_deg = options.max_slope_deg;
  if (!options.mask.empty()) filter_options.mask_image = options.mask;
  filter_ = std::make_unique<TerrainFilter>(*terrain_, filter_options);
  filter_->check_satisfiable();
}

PlacementStats TerrainScatter::place(const FilledTileSet& filled, const PlacementOptions& options,
                                     const std::function<void(const InstanceBatch&)>& sink) const {
  return place_instances(filled, TerrainGround{terrain_.get()}, options, sink,
                         TerrainTileFilter{filter_.get(), fair_edges_}, TerrainPointFilter{filter_.get(), fair_edges_});
}

std::string TerrainScatter::explain_empty() const {
  if (fair_edges_)
    return "no flower of the tiling stands on ground that passes the tests (height, slope, mask) of DEM '" +
           terrain_->dem().path.string() + "'";
  return fmt::format(
      "no {:g} m tile lies wholly on ground that passes the tests of DEM '{}'; smaller tiles or --fair-edges keep "
      "the partial ones",
      tile_size_, terrain_->dem().path.string());
}

}  // namespace wangscape::cli
