#include "terrain/georef.h"

#include <cpl_conv.h>
#include <cpl_string.h>
#include <ogr_spatialref.h>
#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/UTMUPS.hpp>

#include <charconv>
#include <cmath>
#include <filesystem>
#include <limits>
#include <mutex>

#include "core/number_text.h"
#include "terrain/gdal_support.h"

namespace wangscape {

namespace {

using gdal_support::TransformPtr;

OGRSpatialReference wgs84_geographic() {
  OGRSpatialReference wgs84;
  wgs84.SetWellKnownGeogCS("WGS84");
  wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);  // lon, lat
  return wgs84;
}

TransformPtr make_transform(const OGRSpatialReference& from, const OGRSpatialReference& to,
                            const OGRCoordinateTransformationOptions& options) {
  return TransformPtr(OGRCreateCoordinateTransformation(&from, &to, options));
}

// Whether PROJ can find a NADCON grid for NAD27 (Debian's proj-data does not ship them).
bool nad27_grid_installed() {
  char** paths = OSRGetPROJSearchPaths();
  bool found = false;
  for (char** p = paths; p != nullptr && *p != nullptr && !found; ++p) {
    for (const char* name : {"us_noaa_conus.tif", "conus", "us_noaa_nadcon5_nad27_nad83_1986_conus.tif"}) {
      std::error_code ec;
      if (std::filesystem::exists(std::filesystem::path(*p) / name, ec)) found = true;
    }
  }
  CSLDestroy(paths);
  return found;
}

}  // namespace

// ---------------------------------------------------------------------------------------
// EnuFrame

EnuFrame::EnuFrame(LatLon origin) : origin_(origin) {
  if (!(std::abs(origin.lat) <= 90.0) || !(std::abs(origin.lon) <= 180.0))
    throw Error("origin latitude/longitude " + fixed_text(origin.lat, 6) + ", " + fixed_text(origin.lon, 6) +
                " is out of range (expected latitude in [-90, 90], longitude in [-180, 180] degrees)");
  local_.Reset(origin.lat, origin.lon, 0.0);
  double x = 0, y = 0;
  GeographicLib::UTMUPS::Forward(origin.lat, origin.lon, utm_zone_, utm_north_, x, y, gamma_, utm_scale_);
}

std::array<double, 2> EnuFrame::to_enu(LatLon p) const {
  double x = 0, y = 0, z = 0;
  local_.Forward(p.lat, p.lon, 0.0, x, y, z);
  return {x, y};
}

LatLon EnuFrame::to_lat_lon(double x, double y) const {
  // Find the ellipsoid point (h = 0) whose tangent-plane x, y are given: start on the
  // plane, then slide along the local up axis by the height found. Moving by dz changes
  // the height by dz (1 - O(d^2/R^2)), so each step gains about 12 digits at 10 km.
  double z = 0, lat = 0, lon = 0, h = 0;
  for (int step = 0; step < 8; ++step) {
    local_.Reverse(x, y, z, lat, lon, h);
    if (std::abs(h) < 1e-7) break;
    z -= h;
  }
  return {lat, lon};
}

// ---------------------------------------------------------------------------------------
// CrsToWgs84

struct CrsToWgs84::Impl {
  enum class Kind { identity, utm, osr } kind = Kind::osr;
  int zone = 0;
  bool north = true;
  TransformPtr forward, inverse;
  std::mutex mutex;  // OGRCoordinateTransformation objects are not thread-safe
  std::string datum, path;
  std::string source_wkt;
  std::array<double, 2> center_crs{0, 0};  // DEM center in its CRS
  std::array<double, 4> area{};            // west, south, east, north of the DEM, degrees

  // The datum diagnosis costs PROJ a few operation searches (~0.1 s each), so it is made
  // on first use only.
  std::once_flag diagnosed;
  std::string note;
  double accuracy = 0;
  void diagnose();
};

CrsToWgs84::CrsToWgs84(const DemRaster& dem) : impl_(std::make_unique<Impl>()) {
  gdal_support::ErrorCapture capture;
  impl_->path = dem.path.string();
  impl_->source_wkt = dem.crs_wkt;
  impl_->center_crs = dem.crs_of((dem.width - 1) / 2.0, (dem.height - 1) / 2.0);
  OGRSpatialReference source;
  if (source.importFromWkt(dem.crs_wkt.c_str()) != OGRERR_NONE)
    throw Error("DEM '" + impl_->path + "': cannot parse its CRS" + capture.suffix());
  source.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  const OGRSpatialReference wgs84 = wgs84_geographic();
  const char* geogcs = source.GetAttrValue("GEOGCS");
  const char* datum = source.GetAttrValue("DATUM");
  impl_->datum = geogcs != nullptr ? geogcs : (datum != nullptr ? datum : "unknown datum");
  const bool same_datum = source.IsSameGeogCS(&wgs84) != 0;

  int north = 0;
  const int zone = source.IsProjected() ? source.GetUTMZone(&north) : 0;
  if (same_datum && source.IsGeographic()) {
    impl_->kind = Impl::Kind::identity;
    impl_->note = "WGS 84 geographic already: no datum shift";
    std::call_once(impl_->diagnosed, [] {});
    return;
  }
  if (same_datum && zone > 0 && std::abs(source.GetLinearUnits() - 1.0) < 1e-12) {
    impl_->kind = Impl::Kind::utm;
    impl_->zone = zone;
    impl_->north = north != 0;
    impl_->note = "WGS 84 / UTM zone " + std::to_string(zone) + (north ? "N" : "S") +
                  " already: inverted with GeographicLib UTMUPS, no datum shift";
    std::call_once(impl_->diagnosed, [] {});
    return;
  }

  // Anything else goes through PROJ (via OSR), which picks the best operation it can run
  // for each point.
  impl_->forward = make_transform(source, wgs84, OGRCoordinateTransformationOptions());
  if (impl_->forward) impl_->inverse.reset(impl_->forward->GetInverse());
  if (!impl_->forward || !impl_->inverse)
    throw Error("DEM '" + impl_->path + "': GDAL cannot transform its CRS to WGS 84" + capture.suffix());
  std::array<double, 5> lons, lats;
  for (int k = 0; k < 5; ++k) {
    const double col = k == 4 ? (dem.width - 1) / 2.0 : (k & 1 ? dem.width - 1 : 0);
    const double row = k == 4 ? (dem.height - 1) / 2.0 : (k & 2 ? dem.height - 1 : 0);
    const auto p = dem.crs_of(col, row);
    lons[k] = p[0];
    lats[k] = p[1];
  }
  if (!impl_->forward->Transform(5, lons.data(), lats.data()))
    throw Error("DEM '" + impl_->path + "': its corners do not transform to WGS 84" + capture.suffix());
  impl_->area = {180, 90, -180, -90};
  for (int k = 0; k < 5; ++k) {
    impl_->area[0] = std::min(impl_->area[0], lons[k]);
    impl_->area[1] = std::min(impl_->area[1], lats[k]);
    impl_->area[2] = std::max(impl_->area[2], lons[k]);
    impl_->area[3] = std::max(impl_->area[3], lats[k]);
  }
  if (same_datum) {
    impl_->note = "WGS 84 already: projection inverted by GDAL/PROJ, no datum shift";
    std::call_once(impl_->diagnosed, [] {});
  }
}

void CrsToWgs84::Impl::diagnose() {
  gdal_support::ErrorCapture capture;  // keep PROJ's complaints about failed probes quiet
  OGRSpatialReference source;
  source.importFromWkt(source_wkt.c_str());
  source.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  const OGRSpatialReference wgs84 = wgs84_geographic();

  // The most accurate operation PROJ can run here: probe decreasing accuracy bounds
  // (a successful probe is cheap, a failed one is not, so go from loose to tight).
  accuracy = std::numeric_limits<double>::quiet_NaN();
  for (double bound : {100.0, 20.0, 10.0, 5.0, 2.0, 1.0, 0.1}) {
    OGRCoordinateTransformationOptions probe;
    probe.SetAreaOfInterest(area[0], area[1], area[2], area[3]);
    probe.SetDesiredAccuracy(bound);
    probe.SetBallparkAllowed(false);
    if (!make_transform(source, wgs84, probe)) break;
    accuracy = bound;
  }

  // How far the shift moves the DEM center: compare with the same coordinates read in
  // the DEM's own datum.
  OGRSpatialReference own_geographic;
  own_geographic.CopyGeogCSFrom(&source);
  own_geographic.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  TransformPtr unshifted = make_transform(source, own_geographic, OGRCoordinateTransformationOptions());
  std::string shift;
  double lon = center_crs[0], lat = center_crs[1], own_lon = lon, own_lat = lat;
  if (unshifted && unshifted->Transform(1, &own_lon, &own_lat) && forward->Transform(1, &lon, &lat)) {
    double meters = 0;
    GeographicLib::Geodesic::WGS84().Inverse(own_lat, own_lon, lat, lon, meters);
    shift = " (the shift moves the DEM center by " + fixed_text(meters, 1) + " m)";
  }
  const std::string how = datum + " -> WGS 84 by GDAL/PROJ" + shift;
  if (std::isnan(accuracy)) {
    note = how +
           ": PROJ knows no transformation for this datum here and used a ballpark one; "
           "the horizontal error is unknown and may exceed 100 m";
    return;
  }
  note = how + ": the best transformation PROJ can run with the installed grids is accurate to about " +
         fixed_text(accuracy, accuracy < 1 ? 1 : 0) + " m";
  const bool nad27 = datum.find("27") != std::string::npos;
  if (nad27 && accuracy > 1 && !nad27_grid_installed())
    note +=
        " (the NADCON grids, e.g. us_noaa_conus.tif, are not in Debian's proj-data, so PROJ falls back to a "
        "Helmert shift: expect a horizontal residual up to that figure)";
}

CrsToWgs84::~CrsToWgs84() = default;
CrsToWgs84::CrsToWgs84(CrsToWgs84&&) noexcept = default;
CrsToWgs84& CrsToWgs84::operator=(CrsToWgs84&&) noexcept = default;

void CrsToWgs84::to_wgs84(std::span<double> x_to_lon, std::span<double> y_to_lat) const {
  switch (impl_->kind) {
    case Impl::Kind::identity:
      return;
    case Impl::Kind::utm:
      for (std::size_t k = 0; k < x_to_lon.size(); ++k) {
        double lat = 0, lon = 0;
        try {  // GeographicLib throws for coordinates outside the zone (a corrupt header's corner)
          GeographicLib::UTMUPS::Reverse(impl_->zone, impl_->north, x_to_lon[k], y_to_lat[k], lat, lon);
        } catch (const GeographicLib::GeographicErr& e) {
          throw Error("DEM '" + impl_->path + "': coordinates do not transform to WGS 84 (" + e.what() + ")");
        }
        x_to_lon[k] = lon;
        y_to_lat[k] = lat;
      }
      return;
    case Impl::Kind::osr: {
      std::lock_guard lock(impl_->mutex);
      gdal_support::ErrorCapture capture;
      if (!impl_->forward->Transform(int(x_to_lon.size()), x_to_lon.data(), y_to_lat.data()))
        throw Error("DEM '" + impl_->path + "': coordinates do not transform to WGS 84" + capture.suffix());
      return;
    }
  }
}

void CrsToWgs84::from_wgs84(std::span<double> lon_to_x, std::span<double> lat_to_y) const {
  switch (impl_->kind) {
    case Impl::Kind::identity:
      return;
    case Impl::Kind::utm:
      for (std::size_t k = 0; k < lon_to_x.size(); ++k) {
        int zone = 0;
        bool north = true;
        double x = 0, y = 0;
        try {
          GeographicLib::UTMUPS::Forward(lat_to_y[k], lon_to_x[k], zone, north, x, y, impl_->zone);
        } catch (const GeographicLib::GeographicErr&) {  // as for a PROJ transform: this point has no ground
          lon_to_x[k] = lat_to_y[k] = std::numeric_limits<double>::quiet_NaN();
          continue;
        }
        // The DEM's hemisphere decides the false northing, not the point's.
        if (north != impl_->north) y += impl_->north ? -1e7 : 1e7;
        lon_to_x[k] = x;
        lat_to_y[k] = y;
      }
      return;
    case Impl::Kind::osr: {
      std::lock_guard lock(impl_->mutex);
      gdal_support::ErrorCapture capture;
      // Points far outside the DEM may fail individually; they are marked NaN (no ground).
      std::vector<int> ok(lon_to_x.size(), 0);
      impl_->inverse->Transform(int(lon_to_x.size()), lon_to_x.data(), lat_to_y.data(), nullptr, ok.data());
      for (std::size_t k = 0; k < ok.size(); ++k)
        if (!ok[k]) lon_to_x[k] = lat_to_y[k] = std::numeric_limits<double>::quiet_NaN();
      return;
    }
  }
}

const std::string& CrsToWgs84::datum() const { return impl_->datum; }
const std::string& CrsToWgs84::note() const {
  std::call_once(impl_->diagnosed, [this] { impl_->diagnose(); });
  return impl_->note;
}

double CrsToWgs84::accuracy_m() const {
  std::call_once(impl_->diagnosed, [this] { impl_->diagnose(); });
  return impl_->accuracy;
}

// ---------------------------------------------------------------------------------------
// TerrainGeoreference

std::vector<GeoreferenceField> georeference_fields(const TerrainGeoreference& g) {
  auto number = [](double v) -> decltype(GeoreferenceField::value) {
    if (std::isfinite(v)) return v;
    return std::string("unknown");
  };
  return {
      {"frame", g.frame},
      {"axis_mapping", g.axis_mapping},
      {"units", g.units},
      {"origin_latitude_deg", number(g.origin_lat_deg)},
      {"origin_longitude_deg", number(g.origin_lon_deg)},
      {"origin_height_m", number(g.origin_height_m)},
      {"origin_datum", std::string("WGS 84")},
      {"vertical_datum", g.vertical_datum},
      {"utm_zone", static_cast<long long>(g.utm_zone)},
      {"utm_hemisphere", std::string(g.utm_north ? "north" : "south")},
      {"meridian_convergence_deg", number(g.convergence_deg)},
      {"utm_scale_factor", number(g.utm_scale)},
      {"source_crs_name", g.crs_name},
      {"source_horizontal_datum", g.horizontal_datum},
      {"datum_transformation", g.datum_note},
      {"datum_accuracy_m", number(g.datum_accuracy_m)},
      {"source_crs_wkt", g.crs_wkt},
  };
}

}  // namespace wangscape
