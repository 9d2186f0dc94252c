// Georeferencing: the DEM's CRS <-> WGS 84 (GDAL/OSR does datum shifts; GeographicLib
// does UTM and the local frame), and the scene's local east-north-up frame in meters.
//
// The scene frame: x east, y north (meters, the WGS 84 ellipsoid point projected onto the
// plane tangent at the origin, GeographicLib::LocalCartesian), z up = orthometric height
// (meters above the DEM's vertical datum, as stored in the file). The Earth's curvature is
// not folded into z (about 8 m of drop 10 km from the origin): the scene is a height
// field over the tangent plane, which is what renderers and DCC tools expect.
#pragma once

#include <GeographicLib/LocalCartesian.hpp>

#include <array>
#include <memory>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include "terrain/dem.h"

namespace wangscape {

// A point on the WGS 84 ellipsoid, degrees.
struct LatLon {
  double lat = 0, lon = 0;
};

// The local east-north-up frame around an origin. Thread-safe (const, no caches).
class EnuFrame {
 public:
  explicit EnuFrame(LatLon origin);  // WGS 84 degrees; throws Error if out of range

  LatLon origin() const { return origin_; }
  // ENU x, y (meters) of a WGS 84 point on the ellipsoid.
  std::array<double, 2> to_enu(LatLon p) const;
  // The WGS 84 point whose ENU x, y (meters) are given; inverse of to_enu to well under
  // a millimeter (a few Newton steps on the tangent-plane height).
  LatLon to_lat_lon(double x, double y) const;

  int utm_zone() const { return utm_zone_; }     // standard UTM zone of the origin (0 = UPS)
  bool utm_north() const { return utm_north_; }  // northern hemisphere
  double convergence_deg() const {
    return gamma_;
  }                                                // meridian convergence at the origin, degrees
                                                   // (bearing of UTM grid north, clockwise from true north)
  double utm_scale() const { return utm_scale_; }  // UTM point scale factor at the origin

 private:
  LatLon origin_;
  GeographicLib::LocalCartesian local_;
  int utm_zone_ = 0;
  bool utm_north_ = true;
  double gamma_ = 0, utm_scale_ = 1;
};

// Converts between a DEM's CRS and WGS 84 geographic coordinates. WGS 84 geographic is the
// identity, WGS 84 / UTM goes through GeographicLib::UTMUPS, anything else (other datums:
// NAD27, WGS 72, NAD83, other projections) through GDAL/OSR, which applies the datum shift
// PROJ can do with the grids installed. Thread-safe (the OSR transform is locked).
class CrsToWgs84 {
 public:
  explicit CrsToWgs84(const DemRaster& dem);
  ~CrsToWgs84();
  CrsToWgs84(CrsToWgs84&&) noexcept;
  CrsToWgs84& operator=(CrsToWgs84&&) noexcept;

  // In place: CRS x, y -> WGS 84 lon, lat (degrees). Throws Error on failure.
  void to_wgs84(std::span<double> x_to_lon, std::span<double> y_to_lat) const;
  // In place: WGS 84 lon, lat (degrees) -> CRS x, y.
  void from_wgs84(std::span<double> lon_to_x, std::span<double> lat_to_y) const;

  const std::string& datum() const;  // the DEM CRS's geodetic datum, e.g. "NAD27"
  // How the datum is brought to WGS 84 and how good that is, one sentence. The first
  // call (of note or accuracy_m) asks PROJ, which takes a few tenths of a second.
  const std::string& note() const;
  // Accuracy of the datum transformation, meters: 0 = exact (WGS 84 already),
  // NaN = unknown (PROJ found only a ballpark transformation).
  double accuracy_m() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// What exporters put in manifests so a scene can be put back on the Earth.
struct TerrainGeoreference {
  std::string crs_wkt;           // the DEM's horizontal CRS, WKT2
  std::string crs_name;          // e.g. "NAD27 / UTM zone 10N" (as GDAL names it)
  std::string horizontal_datum;  // datum of the DEM CRS, e.g. "NAD27"
  std::string frame = "local east-north-up (GeographicLib LocalCartesian on WGS 84)";
  double origin_lat_deg = 0, origin_lon_deg = 0;  // WGS 84, where x = y = 0
  double origin_height_m = 0;                     // orthometric height at z = 0
  std::string units = "metre";
  std::string vertical_datum;
  std::string axis_mapping = "x = east, y = north, z = up (orthometric height)";
  int utm_zone = 0;  // of the origin (0 = UPS)
  bool utm_north = true;
  double convergence_deg = 0;   // meridian convergence at the origin
  double utm_scale = 1;         // UTM point scale at the origin
  std::string datum_note;       // how the datum reached WGS 84, and the residual
  double datum_accuracy_m = 0;  // meters; 0 = exact, NaN = unknown
};

// One key of a georeference, as a JSON-friendly value.
struct GeoreferenceField {
  std::string key;
  std::variant<std::string, double, long long, bool> value;
};

// The georeference as ordered key/value pairs (exporters write them as JSON).
// Non-finite numbers (an unknown accuracy) come out as the string "unknown".
std::vector<GeoreferenceField> georeference_fields(const TerrainGeoreference& g);

}  // namespace wangscape
