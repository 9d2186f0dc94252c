// The georeferenced masks (terrain/mask.h): a raster warped by GDAL onto the DEM's grid, an OGR
// polygon layer reprojected into the DEM's CRS and burnt onto that grid, a WGS 84 latitude/longitude
// rectangle the same way. The grid's pixels a polygon's boundary touches are decided per point.
#include <cpl_string.h>
#include <gdal_alg.h>
#include <gdal_priv.h>
#include <gdalwarper.h>
#include <ogr_geometry.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "core/error.h"
#include "core/memory_budget.h"
#include "core/number_text.h"
#include "terrain/gdal_support.h"
#include "terrain/mask.h"

namespace wangscape {

namespace {

using gdal_support::DatasetPtr;
using gdal_support::TransformPtr;

// A raster mask's grid is the DEM's, each cell cut into at most this many pixels a side.
constexpr int kMaxRefine = 16;
// GDAL's default for a buffer's round corners (segments per quarter circle).
constexpr int kBufferQuadrantSegments = 30;
// A lat/lon rectangle's edges are cut every this many degrees before they are reprojected: a
// parallel then strays from the straight pieces by well under a millimetre, far inside the one
// pixel the boundary band is widened by.
constexpr double kLatLonStepDeg = 1e-3;

void require_file(const std::filesystem::path& file, const std::string& expected) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) throw Error(file, "", "does not exist (expected " + expected + ")");
}

OGRSpatialReference dem_srs(const DemRaster& dem) {
  OGRSpatialReference srs;
  srs.importFromWkt(dem.crs_wkt.c_str());
  srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  return srs;
}

// Reprojects `g` in place from `from` to `to`. The geometry keeps no reference to either CRS (they
// may live on the stack): it is plain coordinates afterwards.
void reproject(OGRGeometry& g, const OGRSpatialReference& from, const OGRSpatialReference& to,
               const std::filesystem::path& file, const std::string& what, const gdal_support::ErrorCapture& capture) {
  const TransformPtr transform(OGRCreateCoordinateTransformation(&from, &to));
  const bool done = transform && g.transform(transform.get()) == OGRERR_NONE;
  g.assignSpatialReference(nullptr);
  if (!done) throw Error(file, "", what + " cannot be reprojected into the DEM's CRS" + capture.suffix());
}

// The DEM's grid, each cell cut `refine` times a side, as an in-memory one-band GDAL raster in the
// DEM's CRS.
DatasetPtr dem_grid(const DemRaster& dem, int refine, GDALDataType type, const std::filesystem::path& file,
                    const gdal_support::ErrorCapture& capture) {
  GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
  DatasetPtr grid(mem ? mem->Create("", dem.width * refine, dem.height * refine, 1, type, nullptr) : nullptr);
  if (!grid) throw Error(file, "", "cannot make the DEM's grid in memory" + capture.suffix());
  std::array<double, 6> t = dem.transform;
  for (const int k : {1, 2, 4, 5}) t[std::size_t(k)] /= refine;
  grid->SetGeoTransform(t.data());
  grid->SetProjection(dem.crs_wkt.c_str());
  return grid;
}

template <class T>
std::vector<T> read_band(GDALDataset& grid, GDALDataType type, const std::filesystem::path& file,
                         const gdal_support::ErrorCapture& capture) {
  const int w = grid.GetRasterXSize(), h = grid.GetRasterYSize();
  std::vector<T> values(std::size_t(w) * std::size_t(h));
  if (grid.GetRasterBand(1)->RasterIO(GF_Read, 0, 0, w, h, values.data(), w, h, type, 0, 0, nullptr) != CE_None)
    throw Error(file, "", "cannot read the mask's grid back" + capture.suffix());
  return values;
}

// Polygons on the DEM's grid (one pixel a cell): kAllowed where a pixel's centre is inside, and a
// band of boundary pixels (those the rings touch, widened by one pixel) to be decided per point.
// The states are 0 refused, 1 allowed, 2 boundary (GroundMask's).
std::vector<std::uint8_t> burn_polygons(OGRGeometry& polygons, const DemRaster& dem, const std::filesystem::path& file,
                                        const gdal_support::ErrorCapture& capture) {
  check_memory_estimate(file, "the mask's grid of " + std::to_string(dem.width) + " x " + std::to_string(dem.height),
                        2.0 * dem.width * dem.height);
  const DatasetPtr grid = dem_grid(dem, 1, GDT_Byte, file, capture);
  int band = 1;
  OGRGeometryH inside = OGRGeometry::ToHandle(&polygons);
  double one = 1;
  if (GDALRasterizeGeometries(GDALDataset::ToHandle(grid.get()), 1, &band, 1, &inside, nullptr, nullptr, &one, nullptr,
                              nullptr, nullptr) != CE_None)
    throw Error(file, "", "cannot burn its polygons onto the DEM's grid" + capture.suffix());
  std::unique_ptr<OGRGeometry> rings(polygons.Boundary());
  if (!rings) throw Error(file, "", "cannot take its polygons' boundaries" + capture.suffix());
  OGRGeometryH boundary = OGRGeometry::ToHandle(rings.get());
  double two = 2;
  char** touched = CSLSetNameValue(nullptr, "ALL_TOUCHED", "TRUE");
  const CPLErr burnt = GDALRasterizeGeometries(GDALDataset::ToHandle(grid.get()), 1, &band, 1, &boundary, nullptr,
                                               nullptr, &two, touched, nullptr, nullptr);
  CSLDestroy(touched);
  if (burnt != CE_None) throw Error(file, "", "cannot burn its polygons onto the DEM's grid" + capture.suffix());
  const auto burnt_pixels = read_band<std::uint8_t>(*grid, GDT_Byte, file, capture);
  // Widened by a pixel: a pixel the rasterizer missed by rounding, or that a reprojected edge
  // crosses between its vertices, is still decided per point.
  std::vector<std::uint8_t> pixels = burnt_pixels;
  const int w = dem.width, h = dem.height;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (burnt_pixels[std::size_t(y) * std::size_t(w) + std::size_t(x)] != 2) continue;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = x + dx, ny = y + dy;
          if (nx >= 0 && ny >= 0 && nx < w && ny < h) pixels[std::size_t(ny) * std::size_t(w) + std::size_t(nx)] = 2;
        }
    }
  return pixels;
}

// Even-odd point-in-polygon over every ring of a valid (multi)polygon, in the DEM's CRS. The
// segments are bucketed by the DEM row their y-range meets, so a point looks only at the segments
// of its own row.
class RingTest {
 public:
  RingTest(const OGRGeometry& polygons, const DemRaster& dem) : dem_(dem) {
    rows_.resize(std::size_t(dem.height));
    std::vector<const OGRPolygon*> parts;
    const auto type = wkbFlatten(polygons.getGeometryType());
    if (type == wkbPolygon) {
      parts.push_back(polygons.toPolygon());
    } else if (type == wkbMultiPolygon) {
      for (const OGRPolygon* p : *polygons.toMultiPolygon()) parts.push_back(p);
    }
    for (const OGRPolygon* polygon : parts)
      for (const OGRLinearRing* ring : *polygon) {
        const int n = ring->getNumPoints();
        for (int k = 0; k + 1 < n; ++k) add({ring->getX(k), ring->getY(k), ring->getX(k + 1), ring->getY(k + 1)});
      }
  }

  // Whether the DEM-CRS point (x, y) is inside.
  bool inside(double x, double y) const {
    const long long row = row_of(y);
    if (row < 0 || row >= dem_.height) return false;
    bool in = false;
    for (const std::uint32_t s : rows_[std::size_t(row)]) {
      const auto& [x0, y0, x1, y1] = segments_[s];
      if ((y0 > y) != (y1 > y) && x < x0 + (y - y0) / (y1 - y0) * (x1 - x0)) in = !in;
    }
    return in;
  }

 private:
  long long row_of(double y) const {
    return static_cast<long long>(std::floor((y - dem_.transform[3]) / dem_.transform[5]));
  }
  void add(const std::array<double, 4>& s) {
    const auto index = std::uint32_t(segments_.size());
    segments_.push_back(s);
    const long long a = row_of(s[1]), b = row_of(s[3]);
    const long long first = std::max<long long>(std::min(a, b), 0),
                    last = std::min<long long>(std::max(a, b), dem_.height - 1);
    for (long long r = first; r <= last; ++r) rows_[std::size_t(r)].push_back(index);
  }

  const DemRaster& dem_;
  std::vector<std::array<double, 4>> segments_;
  std::vector<std::vector<std::uint32_t>> rows_;
};

}  // namespace

GroundMask GroundMask::raster(const std::filesystem::path& file, const Terrain& terrain) {
  const std::string expected = "a georeferenced raster GDAL reads, e.g. a GeoTIFF";
  require_file(file, expected);
  gdal_support::ErrorCapture capture;
  DatasetPtr source(
      GDALDataset::FromHandle(GDALOpenEx(file.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
  if (!source || source->GetRasterCount() < 1)
    throw Error(file, "", "is not a raster GDAL reads (expected " + expected + ")" + capture.suffix());
  double transform[6];
  if (source->GetGeoTransform(transform) != CE_None || source->GetSpatialRef() == nullptr)
    throw Error(file, "",
                "has no georeference (expected a raster with a coordinate reference system and a geotransform, "
                "e.g. a GeoTIFF; a painted image stretched over the DEM is 'masks.mask')");
  const DemRaster& dem = terrain.dem();

  // Refined until a pixel is no larger than the file's, as GDAL suggests its size in the DEM's CRS.
  int refine = 1;
  {
    char** to_dem = CSLSetNameValue(nullptr, "DST_SRS", dem.crs_wkt.c_str());
    void* probe = GDALCreateGenImgProjTransformer2(GDALDataset::ToHandle(source.get()), nullptr, to_dem);
    CSLDestroy(to_dem);
    if (probe == nullptr)
      throw Error(file, "", "cannot be transformed into the DEM's coordinate reference system" + capture.suffix());
    double suggested[6];
    int columns = 0, rows = 0;
    const CPLErr suggested_ok = GDALSuggestedWarpOutput(GDALDataset::ToHandle(source.get()), GDALGenImgProjTransform,
                                                        probe, suggested, &columns, &rows);
    GDALDestroyGenImgProjTransformer(probe);
    const double cell = std::min(dem.spacing_x(), dem.spacing_y());
    if (suggested_ok == CE_None && suggested[1] > 0)
      refine = std::clamp(int(std::ceil(cell / suggested[1] - 1e-6)), 1, kMaxRefine);
    // A float a pixel while warping, then a byte: at most a quarter of the memory budget.
    while (refine > 1 && 5.0 * dem.width * dem.height * refine * refine > double(memory_limit_bytes()) / 4) --refine;
  }
  check_memory_estimate(file,
                        "the raster mask warped onto the DEM's grid of " + std::to_string(dem.width * refine) + " x " +
                            std::to_string(dem.height * refine) + " pixels",
                        5.0 * dem.width * dem.height * refine * refine);

  const DatasetPtr grid = dem_grid(dem, refine, GDT_Float32, file, capture);
  void* transformer =
      GDALCreateGenImgProjTransformer2(GDALDataset::ToHandle(source.get()), GDALDataset::ToHandle(grid.get()), nullptr);
  if (transformer == nullptr)
    throw Error(file, "", "cannot be transformed into the DEM's coordinate reference system" + capture.suffix());
  // Nearest neighbour (a mask is categories, not a quantity) with the exact transformation: the
  // same pixels as `gdalwarp -r near -et 0` onto the same grid.
  GDALWarpOptions* options = GDALCreateWarpOptions();
  options->hSrcDS = GDALDataset::ToHandle(source.get());
  options->hDstDS = GDALDataset::ToHandle(grid.get());
  options->nBandCount = 1;
  options->panSrcBands = static_cast<int*>(CPLMalloc(sizeof(int)));
  options->panDstBands = static_cast<int*>(CPLMalloc(sizeof(int)));
  options->panSrcBands[0] = options->panDstBands[0] = 1;
  options->eResampleAlg = GRA_NearestNeighbour;
  options->pfnTransformer = GDALGenImgProjTransform;
  options->pTransformerArg = transformer;
  options->papszWarpOptions = CSLSetNameValue(options->papszWarpOptions, "INIT_DEST", "0");
  int has_nodata = 0;
  const double nodata = source->GetRasterBand(1)->GetNoDataValue(&has_nodata);
  if (has_nodata) {
    options->padfSrcNoDataReal = static_cast<double*>(CPLMalloc(sizeof(double)));
    options->padfSrcNoDataReal[0] = nodata;
  }
  GDALWarpOperation warp;
  CPLErr warped = warp.Initialize(options);
  if (warped == CE_None) warped = warp.ChunkAndWarpImage(0, 0, grid->GetRasterXSize(), grid->GetRasterYSize());
  GDALDestroyGenImgProjTransformer(transformer);
  options->pTransformerArg = nullptr;
  GDALDestroyWarpOptions(options);
  if (warped != CE_None) throw Error(file, "", "cannot be warped onto the DEM's grid" + capture.suffix());

  const auto values = read_band<float>(*grid, GDT_Float32, file, capture);
  GroundMask mask;
  mask.file_ = file;
  mask.terrain_ = &terrain;
  mask.refine_ = refine;
  mask.width_ = grid->GetRasterXSize();
  mask.height_ = grid->GetRasterYSize();
  mask.pixels_.resize(values.size());
  for (std::size_t k = 0; k < values.size(); ++k)
    mask.pixels_[k] = values[k] != 0 && !std::isnan(values[k]) ? kAllowed : kRefused;
  return mask;
}

GroundMask GroundMask::polygons(const std::filesystem::path& file, const Terrain& terrain, PolygonSide keep,
                                double buffer_m) {
  const std::string expected = "a layer of polygons OGR reads: GeoPackage, Shapefile, GeoJSON";
  require_file(file, expected);
  if (!std::isfinite(buffer_m)) throw Error(file, "", "its buffer is not a finite number of metres");
  gdal_support::ErrorCapture capture;
  DatasetPtr source(
      GDALDataset::FromHandle(GDALOpenEx(file.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
  if (!source || source->GetLayerCount() < 1)
    throw Error(file, "", "is not a vector file OGR reads (expected " + expected + ")" + capture.suffix());
  OGRLayer* layer = source->GetLayer(0);
  const std::string name = layer->GetName();
  const OGRSpatialReference* layer_srs = layer->GetSpatialRef();
  if (layer_srs == nullptr)
    throw Error(file, "",
                "layer '" + name + "' has no coordinate reference system (expected " + expected + ", in a CRS)");

  OGRMultiPolygon all;
  layer->ResetReading();
  for (std::unique_ptr<OGRFeature> feature(layer->GetNextFeature()); feature; feature.reset(layer->GetNextFeature())) {
    const OGRGeometry* geometry = feature->GetGeometryRef();
    if (geometry == nullptr || geometry->IsEmpty()) continue;
    const auto type = wkbFlatten(geometry->getGeometryType());
    if (type == wkbPolygon) {
      all.addGeometry(geometry);
    } else if (type == wkbMultiPolygon) {
      for (const OGRPolygon* p : *geometry->toMultiPolygon()) all.addGeometry(p);
    } else {
      throw Error(file, "",
                  "layer '" + name + "' holds a " + OGRGeometryTypeToName(geometry->getGeometryType()) + " (feature " +
                      std::to_string(feature->GetFID()) + "): expected polygons or multipolygons");
    }
  }
  if (all.IsEmpty()) throw Error(file, "", "layer '" + name + "' holds no polygon (expected " + expected + ")");

  // Into the DEM's CRS; a buffer in metres is drawn there when it is projected, else around the
  // scene's origin in an azimuthal equidistant projection, whose distances from there are true.
  OGRSpatialReference source_srs(*layer_srs);
  source_srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  const OGRSpatialReference target = dem_srs(terrain.dem());
  all.assignSpatialReference(nullptr);
  std::unique_ptr<OGRGeometry> shape;
  const std::string what = "layer '" + name + "'";
  if (buffer_m != 0 && terrain.dem().geographic) {
    OGRSpatialReference local;
    local.SetWellKnownGeogCS("WGS84");
    local.SetAE(terrain.frame().origin().lat, terrain.frame().origin().lon, 0, 0);
    local.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    reproject(all, source_srs, local, file, what, capture);
    shape.reset(all.Buffer(buffer_m, kBufferQuadrantSegments));
    if (shape) reproject(*shape, local, target, file, what, capture);
  } else {
    reproject(all, source_srs, target, file, what, capture);
    // UnionCascaded: overlapping polygons become one, so the even-odd test holds for them.
    shape.reset(buffer_m != 0 ? all.Buffer(buffer_m / terrain.dem().linear_unit_m, kBufferQuadrantSegments)
                              : all.UnionCascaded());
  }
  if (!shape) throw Error(file, "", "cannot buffer or merge the polygons of layer '" + name + "'" + capture.suffix());

  GroundMask mask;
  mask.file_ = file;
  mask.terrain_ = &terrain;
  mask.width_ = terrain.dem().width;
  mask.height_ = terrain.dem().height;
  mask.pixels_ = burn_polygons(*shape, terrain.dem(), file, capture);
  const bool outside = keep == PolygonSide::outside;
  if (outside)
    for (std::uint8_t& p : mask.pixels_) p = p == kBoundary ? kBoundary : p == kAllowed ? kRefused : kAllowed;
  auto rings = std::make_shared<RingTest>(*shape, terrain.dem());
  const Terrain* t = &terrain;
  // The point in the DEM's CRS as the GIS export writes it (exporters/gis_writer.cpp).
  mask.exact_ = std::make_shared<const std::function<bool(double, double)>>([t, rings, outside](double x, double y) {
    double col = 0, row = 0;
    if (!t->map_to_sample(x, y, col, row)) return false;
    const auto p = t->dem().crs_of(col, row);
    return rings->inside(p[0], p[1]) != outside;
  });
  return mask;
}

GroundMask GroundMask::lat_lon_box(const std::array<double, 4>& box, const Terrain& terrain) {
  gdal_support::ErrorCapture capture;
  const double lat0 = box[0], lon0 = box[1], lat1 = box[2], lon1 = box[3];
  OGRLinearRing ring;
  const auto edge = [&](double a_lat, double a_lon, double b_lat, double b_lon) {
    const int steps =
        std::max(1, int(std::ceil(std::max(std::abs(b_lat - a_lat), std::abs(b_lon - a_lon)) / kLatLonStepDeg)));
    for (int k = 0; k < steps; ++k) {
      const double t = double(k) / steps;
      ring.addPoint(a_lon + t * (b_lon - a_lon), a_lat + t * (b_lat - a_lat));
    }
  };
  edge(lat0, lon0, lat0, lon1);
  edge(lat0, lon1, lat1, lon1);
  edge(lat1, lon1, lat1, lon0);
  edge(lat1, lon0, lat0, lon0);
  ring.closeRings();
  OGRPolygon polygon;
  polygon.addRing(&ring);
  OGRSpatialReference wgs84;
  wgs84.importFromEPSG(4326);
  wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  reproject(polygon, wgs84, dem_srs(terrain.dem()), terrain.dem().path, "the latitude/longitude area", capture);

  GroundMask mask;
  mask.terrain_ = &terrain;
  mask.width_ = terrain.dem().width;
  mask.height_ = terrain.dem().height;
  mask.pixels_ = burn_polygons(polygon, terrain.dem(), terrain.dem().path, capture);
  const Terrain* t = &terrain;
  // The point's WGS 84 latitude and longitude as the GIS export writes them (--crs wgs84).
  mask.exact_ = std::make_shared<const std::function<bool(double, double)>>([t, box](double x, double y) {
    const LatLon p = t->frame().to_lat_lon(x, y);
    return p.lat >= box[0] && p.lat <= box[2] && p.lon >= box[1] && p.lon <= box[3];
  });
  return mask;
}

}  // namespace wangscape
