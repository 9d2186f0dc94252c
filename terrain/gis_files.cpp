#include "terrain/gis_files.h"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_string.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>
#include <GeographicLib/Ellipsoid.hpp>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <optional>

#include "core/atomic_file.h"
#include "core/error.h"
#include "terrain/gdal_support.h"

namespace wangscape {

namespace {

// GeoPackage features per transaction: SQLite writes a transaction's pages once, at its commit.
constexpr std::uint64_t kFeaturesPerTransaction = 1u << 20;

// The double that prints as the shortest text of `value`: 0.9876543f is stored as 0.9876543, not
// 0.98765432834625244, so a GIS shows the digits the float holds.
double shortest_double(float value) {
  char text[32];
  const auto end = std::to_chars(text, text + sizeof text, value).ptr;
  double out = value;
  std::from_chars(text, end, out);
  return out;
}

// The CRS as OGR wants it, x = east (or longitude) first; with an EPSG code where GDAL recognises
// one (AutoIdentifyEPSG leaves the definition as it is).
OGRSpatialReference spatial_reference(const GisCrs& crs, const std::filesystem::path& path,
                                      const gdal_support::ErrorCapture& capture) {
  OGRSpatialReference srs;
  const OGRErr err = crs.wkt.empty() ? srs.importFromEPSG(4326) : srs.importFromWkt(crs.wkt.c_str());
  if (err != OGRERR_NONE) throw Error(path, "", "cannot make its coordinate reference system" + capture.suffix());
  srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  if (!crs.wkt.empty()) srs.AutoIdentifyEPSG();
  return srs;
}

GDALDriver* driver(const char* name, const std::filesystem::path& path) {
  gdal_support::ensure_registered();
  GDALDriver* d = GetGDALDriverManager()->GetDriverByName(name);
  if (d == nullptr) throw Error(path, "", std::string("GDAL has no ") + name + " driver");
  return d;
}

// Sets a GDAL configuration option on this thread while alive (read when a file is opened).
class ThreadOption {
 public:
  ThreadOption(const char* key, const char* value) : key_(key) {
    if (const char* old = CPLGetThreadLocalConfigOption(key, nullptr)) old_ = old;
    CPLSetThreadLocalConfigOption(key, value);
  }
  ~ThreadOption() { CPLSetThreadLocalConfigOption(key_, old_ ? old_->c_str() : nullptr); }
  ThreadOption(const ThreadOption&) = delete;
  ThreadOption& operator=(const ThreadOption&) = delete;

 private:
  const char* key_;
  std::optional<std::string> old_;
};

// Closes a dataset; true when GDAL reported no failure while flushing it.
bool close_dataset(GDALDataset*& dataset) {
  if (dataset == nullptr) return true;
  CPLErrorReset();
  GDALClose(GDALDataset::ToHandle(dataset));
  dataset = nullptr;
  return CPLGetLastErrorType() < CE_Failure;
}

}  // namespace

// ---------------------------------------------------------------------------------------
// PlantLayerFile

struct PlantLayerFile::Impl {
  std::filesystem::path path;
  AtomicPath temp;
  GisVectorFormat format;
  std::vector<std::string> species;
  GDALDataset* dataset = nullptr;
  OGRLayer* layer = nullptr;
  std::unique_ptr<OGRFeature> feature;
  OGRPoint* point = nullptr;  // owned by `feature`
  std::array<int, kPlantFields.size()> field{};
  bool in_transaction = false;
  std::uint64_t count = 0, since_commit = 0;

  Impl(const std::filesystem::path& p, GisVectorFormat f) : path(p), temp(p), format(f) {}
  ~Impl() {
    if (dataset != nullptr) {
      gdal_support::ErrorCapture quiet;  // a failed file is removed: nothing to report
      feature.reset();
      close_dataset(dataset);
    }
  }

  Error error(const std::string& what, const gdal_support::ErrorCapture& capture) const {
    return Error(path, "", what + capture.suffix());
  }
  void commit_transaction(const gdal_support::ErrorCapture& capture) {
    if (!in_transaction) return;
    in_transaction = false;
    if (dataset->CommitTransaction() != OGRERR_NONE) throw error("cannot write its points", capture);
  }
  void start_transaction(const gdal_support::ErrorCapture& capture) {
    if (format != GisVectorFormat::geopackage) return;  // GeoJSON is written as a stream
    if (dataset->StartTransaction() != OGRERR_NONE) throw error("cannot start a transaction", capture);
    in_transaction = true;
    since_commit = 0;
  }
};

PlantLayerFile::PlantLayerFile(const std::filesystem::path& path, GisVectorFormat format, const GisCrs& crs,
                               std::vector<std::string> species_names)
    : impl_(std::make_unique<Impl>(path, format)) {
  Impl& m = *impl_;
  m.species = std::move(species_names);
  const bool gpkg = format == GisVectorFormat::geopackage;
  GDALDriver* d = driver(gpkg ? "GPKG" : "GeoJSON", path);
  gdal_support::ErrorCapture capture;
  OGRSpatialReference srs = spatial_reference(crs, path, capture);
  {
    // The file is a temporary until commit renames it (flushed to disk first): SQLite's journal
    // and its flushes would only slow the writing of a file that is discarded on failure.
    const ThreadOption journal("OGR_SQLITE_JOURNAL", "MEMORY");
    const ThreadOption synchronous("OGR_SQLITE_SYNCHRONOUS", "OFF");
    m.dataset = d->Create(m.temp.temp_path().c_str(), 0, 0, 0, GDT_Unknown, nullptr);
  }
  if (m.dataset == nullptr) throw m.error("cannot be created", capture);
  char** options = nullptr;
  if (gpkg) {
    options = CSLSetNameValue(options, "SPATIAL_INDEX", "YES");
    options = CSLSetNameValue(options, "FID", "fid");
  } else {
    // Millimetres in meters, or about 0.1 mm in degrees; the fields' floats need 9 digits.
    options = CSLSetNameValue(options, "COORDINATE_PRECISION", crs.geographic ? "9" : "3");
    options = CSLSetNameValue(options, "SIGNIFICANT_FIGURES", "9");
  }
  m.layer = m.dataset->CreateLayer("plants", &srs, wkbPoint, options);
  CSLDestroy(options);
  if (m.layer == nullptr) throw m.error("cannot create its point layer", capture);
  const OGRFieldType types[kPlantFields.size()] = {OFTString, OFTInteger, OFTReal, OFTReal, OFTReal, OFTReal};
  for (std::size_t i = 0; i < kPlantFields.size(); ++i) {
    OGRFieldDefn definition(kPlantFields[i], types[i]);
    if (m.layer->CreateField(&definition) != OGRERR_NONE)
      throw m.error(std::string("cannot create the field '") + kPlantFields[i] + "'", capture);
  }
  OGRFeatureDefn* defn = m.layer->GetLayerDefn();
  for (std::size_t i = 0; i < kPlantFields.size(); ++i) m.field[i] = defn->GetFieldIndex(kPlantFields[i]);
  m.feature.reset(OGRFeature::CreateFeature(defn));
  m.point = new OGRPoint(0, 0);
  m.feature->SetGeometryDirectly(m.point);
  m.start_transaction(capture);
}

PlantLayerFile::~PlantLayerFile() = default;

std::uint64_t PlantLayerFile::count() const { return impl_->count; }

void PlantLayerFile::append(const PlantColumns& p) {
  Impl& m = *impl_;
  if (m.dataset == nullptr) throw Error(m.path, "", "is already closed");
  const std::size_t n = p.x.size();
  if (p.y.size() != n || p.species.size() != n || p.variant.size() != n || p.scale.size() != n || p.yaw.size() != n ||
      p.height.size() != n || p.rank.size() != n)
    throw Error(m.path, "", "a batch of plants has columns of different lengths");
  gdal_support::ErrorCapture capture;
  OGRFeature& f = *m.feature;
  for (std::size_t k = 0; k < n; ++k) {
    if (p.species[k] >= m.species.size())
      throw Error(m.path, "",
                  "a plant's species " + std::to_string(p.species[k]) + " has no name (" +
                      std::to_string(m.species.size()) + " species)");
    f.SetFID(OGRNullFID);
    m.point->setX(p.x[k]);
    m.point->setY(p.y[k]);
    f.SetField(m.field[0], m.species[p.species[k]].c_str());
    f.SetField(m.field[1], int(p.variant[k]));
    f.SetField(m.field[2], shortest_double(p.scale[k]));
    f.SetField(m.field[3], shortest_double(p.yaw[k]));
    f.SetField(m.field[4], shortest_double(p.height[k]));
    f.SetField(m.field[5], shortest_double(p.rank[k]));
    if (m.layer->CreateFeature(&f) != OGRERR_NONE) throw m.error("cannot write a point", capture);
    ++m.count;
    if (m.in_transaction && ++m.since_commit >= kFeaturesPerTransaction) {
      m.commit_transaction(capture);
      m.start_transaction(capture);
    }
  }
}

void PlantLayerFile::commit() {
  Impl& m = *impl_;
  if (m.dataset == nullptr) throw Error(m.path, "", "is already closed");
  gdal_support::ErrorCapture capture;
  m.commit_transaction(capture);
  m.feature.reset();
  if (!close_dataset(m.dataset)) throw m.error("cannot be completed", capture);
  m.temp.commit();
}

// ---------------------------------------------------------------------------------------
// GeoTIFF

double dem_cell_area_m2(const DemRaster& dem, int row) {
  const auto& t = dem.transform;
  if (!dem.geographic) return std::abs(t[1] * t[5] - t[2] * t[4]) * dem.linear_unit_m * dem.linear_unit_m;
  // A north-up grid in degrees (DEMs are refused rotated): the band between the row's parallels.
  const GeographicLib::Ellipsoid& wgs84 = GeographicLib::Ellipsoid::WGS84();
  const double lat_a = std::clamp(t[3] + row * t[5], -90.0, 90.0),
               lat_b = std::clamp(t[3] + (row + 1) * t[5], -90.0, 90.0);
  const double degree = std::acos(-1.0) / 180.0;
  const double xi_a = wgs84.AuthalicLatitude(lat_a) * degree, xi_b = wgs84.AuthalicLatitude(lat_b) * degree;
  const double r2 = wgs84.Area() / (4 * std::acos(-1.0));  // the authalic radius, squared
  return std::abs(t[1] * degree) * r2 * std::abs(std::sin(xi_a) - std::sin(xi_b));
}

void write_geotiff(const std::filesystem::path& path, const GisGrid& grid) {
  if (grid.width <= 0 || grid.height <= 0 || grid.values.size() != std::size_t(grid.width) * std::size_t(grid.height))
    throw Error(path, "",
                "a grid of " + std::to_string(grid.width) + " x " + std::to_string(grid.height) +
                    " cells needs as many values (it has " + std::to_string(grid.values.size()) + ")");
  GDALDriver* d = driver("GTiff", path);
  gdal_support::ErrorCapture capture;
  const OGRSpatialReference srs = spatial_reference(grid.crs, path, capture);
  AtomicPath temp(path);
  char** options = nullptr;
  options = CSLSetNameValue(options, "TILED", "YES");
  options = CSLSetNameValue(options, "COMPRESS", "DEFLATE");
  options = CSLSetNameValue(options, "PREDICTOR", "3");  // floating point
  GDALDataset* dataset = d->Create(temp.temp_path().c_str(), grid.width, grid.height, 1, GDT_Float32, options);
  CSLDestroy(options);
  if (dataset == nullptr) throw Error(path, "", "cannot be created" + capture.suffix());
  std::array<double, 6> transform = grid.transform;
  bool ok = dataset->SetGeoTransform(transform.data()) == CE_None && dataset->SetSpatialRef(&srs) == CE_None;
  GDALRasterBand* band = ok ? dataset->GetRasterBand(1) : nullptr;
  if (band != nullptr) {
    band->SetDescription(grid.description.c_str());
    ok = band->RasterIO(GF_Write, 0, 0, grid.width, grid.height, const_cast<float*>(grid.values.data()), grid.width,
                        grid.height, GDT_Float32, 0, 0, nullptr) == CE_None;
  }
  ok = close_dataset(dataset) && ok && band != nullptr;
  if (!ok) throw Error(path, "", "cannot be written" + capture.suffix());
  temp.commit();
}

}  // namespace wangscape
