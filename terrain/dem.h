// Reading digital elevation models through GDAL: USGS ASCII DEM (7.5' UTM and 1-degree
// geographic), GeoTIFF, SRTM .hgt, ESRI ASCII grid (.asc + .prj). The raster is kept in
// the file's own CRS and grid; terrain/terrain.h maps it into the scene's ENU frame.
#pragma once

#include "core/error.h"

#include <array>
#include <cmath>
#include <cstddef>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace wangscape {

// A DEM as stored in its file: a raster of heights in the file's horizontal CRS.
// Sample (col, row) stands at the center of GDAL pixel (col, row), whatever the file's
// AREA_OR_POINT says (GDAL already folds that into the geotransform).
struct DemRaster {
  std::filesystem::path path;
  std::string driver;   // GDAL driver short name, e.g. "USGSDEM", "GTiff", "AAIGrid", "SRTMHGT"
  std::string crs_wkt;  // horizontal CRS, WKT2
  std::string crs_name;
  bool geographic = false;          // CRS axes in degrees (else projected, linear units)
  double linear_unit_m = 1.0;       // meters per CRS unit (projected CRSs)
  int width = 0, height = 0;        // columns, rows
  std::array<double, 6> transform;  // GDAL geotransform: CRS x/y of pixel corners
  std::vector<float> heights;       // row-major, row 0 first; meters; NaN = no data
  std::size_t nodata_count = 0;
  double min_height = 0, max_height = 0;  // meters, over cells with data
  std::string height_unit_in_file;        // "m" unless the file said otherwise (feet are converted)

  std::size_t cell_count() const { return heights.size(); }
  std::size_t index(int col, int row) const { return std::size_t(row) * std::size_t(width) + std::size_t(col); }
  // Height in meters of sample (col, row); nullopt outside the raster or where there is no data.
  std::optional<double> at(int col, int row) const {
    if (col < 0 || row < 0 || col >= width || row >= height) return std::nullopt;
    const float h = heights[index(col, row)];
    return std::isnan(h) ? std::nullopt : std::optional<double>(h);
  }
  // CRS coordinates of sample (col, row) (its pixel center).
  std::array<double, 2> crs_of(double col, double row) const {
    return {transform[0] + (col + 0.5) * transform[1] + (row + 0.5) * transform[2],
            transform[3] + (col + 0.5) * transform[4] + (row + 0.5) * transform[5]};
  }
  // Fractional sample coordinates (col, row) of a CRS point; inverse of crs_of.
  std::array<double, 2> sample_of(double x, double y) const;
  // Grid spacing in CRS units along columns and rows (positive).
  double spacing_x() const { return std::hypot(transform[1], transform[4]); }
  double spacing_y() const { return std::hypot(transform[2], transform[5]); }
};

// Reads the first band of a DEM. No-data cells (the band's no-data value, and any NaN)
// become NaN in `heights`, never a height. Vertical units in feet are converted to meters.
// Throws Error naming the file when GDAL cannot open or read it, when it has no
// CRS (an ESRI .asc grid needs its .prj beside it), no georeferencing, a rotated grid,
// or no valid heights at all. GDAL's own messages never reach stderr; they end up in the
// error's text.
DemRaster read_dem(const std::filesystem::path& path);

// GDAL's checksum of band 1 (GDALChecksumImage over the whole band), as `gdalinfo
// -checksum` prints it. Throws Error if GDAL cannot read the pixels.
int gdal_checksum(const std::filesystem::path& path);

}  // namespace wangscape
