// Files a GIS opens, written through GDAL/OGR (terrain/ is the folder that links GDAL): a point
// layer of plants (OGR's GPKG or GeoJSON driver) and a one-band Float32 GeoTIFF (GTiff). No GDAL
// type appears here: the caller hands coordinates already in the file's CRS. Each file is written
// under a temporary name beside its target and renamed into place by commit(); nothing appears
// under the target's name otherwise (core/atomic_file.h). GDAL's messages never reach stderr: a
// failure is an Error naming the file, with GDAL's words appended. Not thread-safe (one writer, one
// thread at a time; a writer may move between threads between calls).
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "terrain/dem.h"

namespace wangscape {

enum class GisVectorFormat { geopackage, geojson };

// The coordinate reference system of a GIS file: a WKT (a DEM's, DemRaster::crs_wkt: x, y in its
// units), or empty for WGS 84 geographic (x = longitude, y = latitude, degrees). When GDAL
// recognises the WKT as an EPSG CRS (a UTM zone on WGS 84, NAD27 or NAD83), the files carry the
// EPSG code too, so GeoJSON (which names a CRS only by its code) keeps it.
struct GisCrs {
  std::string wkt;
  bool geographic = false;  // degrees (WGS 84, or a geographic DEM): coordinates kept to 1e-9 degrees
};

// One batch of plants, column by column, all of one length (checked).
struct PlantColumns {
  std::span<const double> x, y;               // in the layer's CRS
  std::span<const std::uint16_t> species;     // index into the layer's species names
  std::span<const std::uint16_t> variant;     // model variant
  std::span<const float> scale, yaw, height;  // factor; radians counter-clockwise from east; meters
  std::span<const float> rank;                // progressive order in [0, 1)
};

// The field names of every plant layer, in order (the names scripts and docs rely on).
inline constexpr std::array<const char*, 6> kPlantFields = {"species", "variant", "scale", "yaw", "height", "rank"};

// A layer "plants" of points with the fields kPlantFields: species (string), variant (integer),
// scale, yaw, height, rank (reals; each float written as the shortest decimal that reads back as
// it). GeoPackage features are written inside GDAL's transactions (one per million points), with
// SQLite's journal in memory (the file is a temporary until commit) and the spatial index built
// at the end.
class PlantLayerFile {
 public:
  // Creates the temporary file. Throws Error naming `path` when GDAL cannot create it.
  PlantLayerFile(const std::filesystem::path& path, GisVectorFormat format, const GisCrs& crs,
                 std::vector<std::string> species_names);
  ~PlantLayerFile();  // an uncommitted file is closed and removed
  PlantLayerFile(const PlantLayerFile&) = delete;
  PlantLayerFile& operator=(const PlantLayerFile&) = delete;

  void append(const PlantColumns& plants);  // throws Error naming the file
  // Closes the dataset (GeoPackage: commits, builds the spatial index) and renames it into place.
  void commit();
  std::uint64_t count() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// A north-up grid of Float32 values in a CRS: `transform` is GDAL's geotransform (the corner of
// pixel (0, 0) and the pixel steps), `values` row-major from row 0, width x height of them.
struct GisGrid {
  GisCrs crs;
  std::array<double, 6> transform{0, 1, 0, 0, 0, -1};
  int width = 0, height = 0;
  std::vector<float> values;
  std::string description;  // the band's description (what a value is, with its unit)
};

// The area of a cell of row `row` of the DEM's grid, square metres: for a projected CRS the
// cell's area in the CRS's own units (metres of the map projection, as gdalinfo's pixel size
// gives it); for a geographic one the area between the cell's meridians and parallels on the
// WGS 84 ellipsoid (GeographicLib's authalic latitude).
double dem_cell_area_m2(const DemRaster& dem, int row);

// Writes `grid` as a tiled, deflate-compressed GeoTIFF at `path` (temporary, then renamed). Throws
// Error naming the file.
void write_geotiff(const std::filesystem::path& path, const GisGrid& grid);

}  // namespace wangscape
