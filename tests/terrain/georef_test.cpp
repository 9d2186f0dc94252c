// Georeferencing: ENU round trips, UTM zone and convergence, datum handling, and the
// DEM -> ENU mapping checked against GDAL/PROJ doing the same conversion independently.
#include "terrain/georef.h"

#include <gtest/gtest.h>
#include <ogr_spatialref.h>
#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/UTMUPS.hpp>

#include <random>

#include "terrain/terrain.h"
#include "terrain_test_support.h"

namespace wangscape {
namespace {

double distance_m(LatLon a, LatLon b) {
  double s = 0;
  GeographicLib::Geodesic::WGS84().Inverse(a.lat, a.lon, b.lat, b.lon, s);
  return s;
}

TEST(Georef, EnuRoundTripWithinAMillimeter) {
  std::mt19937_64 rng(20260401);
  const LatLon origins[] = {{46.19, -122.19}, {40.15, -105.45}, {-33.9, 18.4}, {69.6, 18.9}, {0.1, 179.9}};
  for (const LatLon origin : origins) {
    const EnuFrame frame(origin);
    const auto at_origin = frame.to_enu(origin);
    EXPECT_NEAR(at_origin[0], 0.0, 1e-9);
    EXPECT_NEAR(at_origin[1], 0.0, 1e-9);
    std::uniform_real_distribution<double> offset(-0.25, 0.25);  // about +-28 km
    for (int k = 0; k < 2000; ++k) {
      LatLon p{origin.lat + offset(rng), origin.lon + offset(rng)};
      if (p.lon > 180) p.lon -= 360;
      const auto xy = frame.to_enu(p);
      const LatLon back = frame.to_lat_lon(xy[0], xy[1]);
      ASSERT_LT(distance_m(p, back), 1e-3) << p.lat << ", " << p.lon;
    }
  }
}

TEST(Georef, EnuAxesPointEastAndNorthInMeters) {
  const EnuFrame frame({46.19, -122.19});
  double lat = 0, lon = 0, azimuth = 0;
  // 1000 m due east and due north along geodesics from the origin.
  GeographicLib::Geodesic::WGS84().Direct(46.19, -122.19, 90.0, 1000.0, lat, lon, azimuth);
  auto east = frame.to_enu({lat, lon});
  EXPECT_NEAR(east[0], 1000.0, 0.01);
  EXPECT_NEAR(east[1], 0.0, 0.1);  // the parallel curves away from the east geodesic by ~mm
  GeographicLib::Geodesic::WGS84().Direct(46.19, -122.19, 0.0, 1000.0, lat, lon, azimuth);
  auto north = frame.to_enu({lat, lon});
  EXPECT_NEAR(north[0], 0.0, 1e-6);
  EXPECT_NEAR(north[1], 1000.0, 0.01);
}

TEST(Georef, UtmZoneAndConvergenceOfTheOrigin) {
  const EnuFrame frame({46.19, -122.19});
  EXPECT_EQ(frame.utm_zone(), 10);
  EXPECT_TRUE(frame.utm_north());
  // Convergence: the bearing of UTM grid north from true north. Walk 1 km up the grid and
  // measure the bearing of that step with a geodesic.
  int zone = 0;
  bool north = true;
  double x = 0, y = 0;
  GeographicLib::UTMUPS::Forward(46.19, -122.19, zone, north, x, y);
  double lat = 0, lon = 0, s = 0, azimuth = 0, azimuth2 = 0;
  GeographicLib::UTMUPS::Reverse(zone, north, x, y + 1000.0, lat, lon);
  GeographicLib::Geodesic::WGS84().Inverse(46.19, -122.19, lat, lon, s, azimuth, azimuth2);
  EXPECT_NEAR(frame.convergence_deg(), azimuth, 1e-3);
  EXPECT_GT(frame.convergence_deg(), 0.5);  // east of the central meridian (-123), north
  EXPECT_LT(frame.convergence_deg(), 0.7);
  EXPECT_EQ(EnuFrame({-33.9, 18.4}).utm_zone(), 34);
  EXPECT_FALSE(EnuFrame({-33.9, 18.4}).utm_north());
  EXPECT_THROW(EnuFrame({95, 0}), Error);
}

// PROJ (through OSR, straight from the file's CRS) and our path (OSR datum shift +
// GeographicLib frame) must agree on where the DEM's samples are.
void expect_samples_agree_with_gdal(const std::filesystem::path& path, double tolerance_m) {
  const Terrain terrain = Terrain::load(path);
  const DemRaster& dem = terrain.dem();
  OGRSpatialReference source, wgs84;
  source.importFromWkt(dem.crs_wkt.c_str());
  source.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  wgs84.SetWellKnownGeogCS("WGS84");
  wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  OGRCoordinateTransformation* ct = OGRCreateCoordinateTransformation(&source, &wgs84);
  ASSERT_NE(ct, nullptr);
  std::mt19937 rng(7);
  for (int k = 0; k < 200; ++k) {
    const double col = std::uniform_real_distribution<double>(0, dem.width - 1)(rng);
    const double row = std::uniform_real_distribution<double>(0, dem.height - 1)(rng);
    auto crs = dem.crs_of(col, row);
    ASSERT_TRUE(ct->Transform(1, &crs[0], &crs[1]));
    const LatLon expected{crs[1], crs[0]};
    double x = col, y = row;
    terrain.samples_to_enu(std::span(&x, 1), std::span(&y, 1));
    EXPECT_LT(distance_m(terrain.frame().to_lat_lon(x, y), expected), tolerance_m);
    // And back: ENU -> sample coordinates, exactly and through the lattice.
    double c = x, r = y;
    terrain.enu_to_samples(std::span(&c, 1), std::span(&r, 1));
    EXPECT_NEAR(c, col, 3e-5);  // PROJ's inverse Helmert is good to ~0.3 mm, not exact
    EXPECT_NEAR(r, row, 3e-5);
    double lc = 0, lr = 0;
    if (!terrain.extent().contains(x, y)) continue;  // the lattice covers the data's extent only
    ASSERT_TRUE(terrain.map_to_sample(x, y, lc, lr));
    EXPECT_NEAR(lc, col, 1e-4);  // 1e-4 of a 30 m sample = 3 mm
    EXPECT_NEAR(lr, row, 1e-4);
  }
  OGRCoordinateTransformation::DestroyCT(ct);
}

TEST(Georef, SainteHelensSamplesAgreeWithGdal) { expect_samples_agree_with_gdal(test::saint_helens(), 1e-3); }
TEST(Georef, BoulderSamplesAgreeWithGdal) { expect_samples_agree_with_gdal(test::boulder(), 1e-3); }

TEST(Georef, Wgs84UtmThroughGeographicLibAgreesWithProj) {
  const auto dir = test::scratch_dir("utm_agree");
  test::write_raster(dir / "flat.tif", "GTiff", GDT_Float32, 100, 100, {600000, 30, 0, 5000000, 0, -30}, "EPSG:32610",
                     [](int, int) { return 100.0; });
  expect_samples_agree_with_gdal(dir / "flat.tif", 1e-3);
}

TEST(Georef, DatumNotesStateTheResidual) {
  const Terrain helens = Terrain::load(test::saint_helens());
  const TerrainGeoreference g = helens.georeference();
  EXPECT_EQ(g.horizontal_datum, "NAD27");
  EXPECT_NE(g.datum_note.find("NAD27 -> WGS 84"), std::string::npos) << g.datum_note;
  EXPECT_NE(g.datum_note.find("accurate to about"), std::string::npos) << g.datum_note;
  EXPECT_GT(g.datum_accuracy_m, 0.0);  // NAD27 always needs a shift
  EXPECT_LE(g.datum_accuracy_m, 20.0);
  EXPECT_EQ(g.utm_zone, 10);
  // The default origin is the DEM's center: sample (163, 233.5) is at ENU (0, 0).
  double x = 163, y = 233.5;
  helens.samples_to_enu(std::span(&x, 1), std::span(&y, 1));
  EXPECT_NEAR(x, 0.0, 1e-6);
  EXPECT_NEAR(y, 0.0, 1e-6);
  // The NAD27 -> WGS 84 shift here is about 94 m (mostly west): the origin is not the
  // naive reading of the NAD27 coordinates.
  EXPECT_NEAR(g.origin_lon_deg, -122.18859, 1e-4);

  const TerrainGeoreference wgs72 = Terrain::load(test::test_dem("edge-cases/39079G6_truncated.dem")).georeference();
  EXPECT_NE(wgs72.datum_note.find("WGS 72"), std::string::npos) << wgs72.datum_note;
  EXPECT_LE(wgs72.datum_accuracy_m, 5.0);

  const TerrainGeoreference srtm = Terrain::load(test::boulder()).georeference();
  EXPECT_EQ(srtm.datum_accuracy_m, 0.0);
  EXPECT_NE(srtm.datum_note.find("no datum shift"), std::string::npos);
}

TEST(Georef, OriginCanBeGiven) {
  TerrainOptions options;
  options.origin = LatLon{46.2, -122.2};
  const Terrain terrain = Terrain::load(test::saint_helens(), options);
  EXPECT_DOUBLE_EQ(terrain.georeference().origin_lat_deg, 46.2);
  const auto p = terrain.frame().to_enu({46.2, -122.2});
  EXPECT_NEAR(p[0], 0, 1e-9);
  // Heights do not depend on the origin: the same ground point, two frames.
  const Terrain centered = Terrain::load(test::saint_helens());
  const auto q = centered.frame().to_enu({46.2, -122.2});
  ASSERT_TRUE(terrain.height(0, 0).has_value());
  EXPECT_NEAR(*terrain.height(0, 0), *centered.height(q[0], q[1]), 1e-3);
}

TEST(Georef, FieldsAreJsonFriendly) {
  const auto fields = georeference_fields(Terrain::load(test::saint_helens()).georeference());
  std::set<std::string> keys;
  for (const auto& f : fields) keys.insert(f.key);
  for (const char* key : {"source_crs_wkt", "origin_latitude_deg", "origin_longitude_deg", "units", "vertical_datum",
                          "axis_mapping", "utm_zone", "meridian_convergence_deg", "datum_transformation"})
    EXPECT_TRUE(keys.count(key)) << key;
  EXPECT_EQ(keys.size(), fields.size());  // no duplicate keys
}

}  // namespace
}  // namespace wangscape
