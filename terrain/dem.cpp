#include "terrain/dem.h"

#include <gdal.h>
#include <gdal_alg.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <limits>
#include <memory>

#include "core/memory_budget.h"
#include "terrain/gdal_support.h"

namespace wangscape {

namespace {

using gdal_support::DatasetPtr;

std::string quoted(const std::filesystem::path& path) {
  std::string text = "'";  // built by appending: GCC 12 warns falsely on "'" + s + "'"
  text += path.string();
  text += '\'';
  return text;
}

DatasetPtr open_raster(const std::filesystem::path& path, gdal_support::ErrorCapture& capture) {
  std::error_code ec;
  const bool gdal_virtual = path.string().starts_with("/vsi");  // GDAL's in-memory and archive files
  if (!gdal_virtual && !std::filesystem::exists(path, ec)) throw Error("DEM file " + quoted(path) + " does not exist");
  if (std::filesystem::is_directory(path, ec))
    throw Error("DEM file " + quoted(path) + " is a directory, expected a DEM file");
  // A pipe or a device would block GDAL forever or never end.
  if (!gdal_virtual && !std::filesystem::is_regular_file(path, ec))
    throw Error("DEM file " + quoted(path) + " is not a regular file (a pipe or a device), expected a DEM file");
  DatasetPtr dataset(
      GDALDataset::FromHandle(GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
  if (!dataset)
    throw Error("cannot read DEM " + quoted(path) +
                ": not a raster format GDAL recognizes (expected USGS ASCII DEM, GeoTIFF, SRTM .hgt or "
                "ESRI ASCII grid)" +
                capture.suffix());
  if (dataset->GetRasterCount() < 1) throw Error("DEM " + quoted(path) + " has no raster band");
  return dataset;
}

// Meters per unit of a band's "unit type" (USGS DEMs may store feet).
std::optional<double> meters_per_height_unit(const std::string& unit) {
  std::string u = unit;
  std::transform(u.begin(), u.end(), u.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (u.empty() || u == "m" || u == "metre" || u == "meter" || u == "meters" || u == "metres") return 1.0;
  if (u == "ft" || u == "foot" || u == "feet" || u == "international foot") return 0.3048;
  if (u == "us-ft" || u == "us survey foot" || u == "ftus") return 1200.0 / 3937.0;
  return std::nullopt;
}

}  // namespace

std::array<double, 2> DemRaster::sample_of(double x, double y) const {
  const double det = transform[1] * transform[5] - transform[2] * transform[4];
  const double dx = x - transform[0], dy = y - transform[3];
  const double col = (dx * transform[5] - dy * transform[2]) / det;
  const double row = (dy * transform[1] - dx * transform[4]) / det;
  return {col - 0.5, row - 0.5};
}

DemRaster read_dem(const std::filesystem::path& path) {
  gdal_support::ErrorCapture capture;
  DatasetPtr dataset = open_raster(path, capture);

  DemRaster dem;
  dem.path = path;
  dem.driver = dataset->GetDriver() != nullptr ? dataset->GetDriver()->GetDescription() : "";
  dem.width = dataset->GetRasterXSize();
  dem.height = dataset->GetRasterYSize();
  if (dem.width <= 0 || dem.height <= 0) throw Error("DEM " + quoted(path) + " has an empty raster");

  const OGRSpatialReference* crs = dataset->GetSpatialRef();
  if (crs == nullptr || crs->IsEmpty()) {
    std::string hint;
    if (dem.driver == "AAIGrid") {
      std::filesystem::path prj = path;
      prj.replace_extension(".prj");
      hint = ": an ESRI ASCII grid carries no CRS itself; expected its .prj file " + quoted(prj) +
             " (no CRS is assumed, to avoid placing the scene in the wrong place)";
    }
    throw Error("DEM " + quoted(path) + " has no coordinate reference system" + hint);
  }
  if (!crs->IsGeographic() && !crs->IsProjected())
    throw Error("DEM " + quoted(path) + " has a CRS that is neither geographic nor projected");
  {
    char* wkt = nullptr;
    const char* options[] = {"FORMAT=WKT2_2019", "MULTILINE=NO", nullptr};
    crs->exportToWkt(&wkt, options);
    dem.crs_wkt = wkt != nullptr ? wkt : "";
    CPLFree(wkt);
  }
  dem.crs_name = crs->GetName() != nullptr ? crs->GetName() : "";
  if (dem.crs_name.empty() || dem.crs_name == "unnamed") {  // USGS DEMs: describe it ourselves
    const char* datum = crs->GetAttrValue("GEOGCS");
    dem.crs_name = datum != nullptr ? datum : "unknown datum";
    int north = 0;
    const int zone = crs->IsProjected() ? crs->GetUTMZone(&north) : 0;
    if (zone > 0) {
      dem.crs_name += " / UTM zone " + std::to_string(zone) + (north ? "N" : "S");
    } else if (crs->IsProjected()) {
      const char* projection = crs->GetAttrValue("PROJECTION");
      dem.crs_name += " / ";
      dem.crs_name += projection != nullptr ? projection : "unnamed projection";
    }
  }
  dem.geographic = crs->IsGeographic() != 0;
  dem.linear_unit_m = dem.geographic ? 1.0 : crs->GetLinearUnits();

  if (dataset->GetGeoTransform(dem.transform.data()) != CE_None)
    throw Error("DEM " + quoted(path) + " has no georeferencing (no geotransform)");
  if (dem.transform[1] * dem.transform[5] - dem.transform[2] * dem.transform[4] == 0)
    throw Error("DEM " + quoted(path) + " has a degenerate geotransform (zero pixel size)");

  GDALRasterBand* band = dataset->GetRasterBand(1);
  const char* unit = band->GetUnitType();
  dem.height_unit_in_file = (unit != nullptr && *unit != '\0') ? std::string(unit) : std::string(1, 'm');
  const auto unit_m = meters_per_height_unit(dem.height_unit_in_file);
  if (!unit_m)
    throw Error("DEM " + quoted(path) + " stores heights in unit '" + dem.height_unit_in_file +
                "', expected meters or feet");

  // Heights are held as 4-byte floats, one per cell: first the memory this machine can give
  // (the estimate names the size), then a fixed cap on cells, so that a 1 KB header declaring
  // 1.7 GB of heights is refused on any machine (docs/limits.md).
  check_memory_estimate(path, "its " + std::to_string(dem.width) + " x " + std::to_string(dem.height) + " heights",
                        4.0 * dem.width * dem.height);
  constexpr std::uint64_t kMaxDemCells = std::uint64_t{1} << 28;
  const std::uint64_t cells = std::uint64_t(dem.width) * std::uint64_t(dem.height);
  if (cells > kMaxDemCells)
    throw Error("DEM " + quoted(path) + " declares " + std::to_string(dem.width) + " x " + std::to_string(dem.height) +
                " cells (" + std::to_string(cells * sizeof(float) >> 20) + " MiB of heights); at most " +
                std::to_string(kMaxDemCells) + " cells (1 GiB) are read");
  dem.heights.resize(std::size_t(cells));
  if (band->RasterIO(GF_Read, 0, 0, dem.width, dem.height, dem.heights.data(), dem.width, dem.height, GDT_Float32, 0, 0,
                     nullptr) != CE_None) {
    std::string why = "cannot read its heights";
    if (dem.driver == "USGSDEM")
      why = "the header declares " + std::to_string(dem.width) + " x " + std::to_string(dem.height) +
            " cells but its elevation profiles cannot be read (the file is truncated, or is a header with no "
            "profiles)";
    throw Error("DEM " + quoted(path) + ": " + why + capture.suffix());
  }

  int has_nodata = 0;
  const double nodata = band->GetNoDataValue(&has_nodata);
  const float nodata_f = static_cast<float>(nodata);
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float scale = static_cast<float>(*unit_m);
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (float& h : dem.heights) {
    if (std::isnan(h) || (has_nodata && h == nodata_f) || std::isinf(h)) {
      h = nan;
      ++dem.nodata_count;
      continue;
    }
    h *= scale;
    lo = std::min(lo, double(h));
    hi = std::max(hi, double(h));
  }
  if (dem.nodata_count == dem.heights.size())
    throw Error("DEM " + quoted(path) + " has no valid heights: every one of its " +
                std::to_string(dem.heights.size()) + " cells is no-data");
  dem.min_height = lo;
  dem.max_height = hi;
  return dem;
}

int gdal_checksum(const std::filesystem::path& path) {
  gdal_support::ErrorCapture capture;
  DatasetPtr dataset = open_raster(path, capture);
  GDALRasterBand* band = dataset->GetRasterBand(1);
  const int sum = GDALChecksumImage(GDALRasterBand::ToHandle(band), 0, 0, band->GetXSize(), band->GetYSize());
  if (sum < 0 || !capture.messages().empty())
    throw Error("cannot compute the checksum of DEM " + quoted(path) + capture.suffix());
  return sum;
}

}  // namespace wangscape
