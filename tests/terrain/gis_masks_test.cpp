// The masks from georeferenced files (terrain/mask.h: GroundMask::raster, polygons, lat_lon_box)
// through real GDAL and OGR over the St. Helens DEM (NAD27 / UTM 10N): a polygon keeps its inside or
// its outside to the metre, grows and shrinks by its buffer; a raster in WGS 84 allows where its
// pixels are non-zero; a lat/lon box is exact at its edges; bad files are refused naming the file.
#include <gtest/gtest.h>

#include <random>
#include <string>

#include "core/error.h"
#include "core/number_text.h"
#include "terrain/mask.h"
#include "terrain_test_support.h"

namespace wangscape {
namespace {

const Terrain& helens() {
  static const Terrain terrain = Terrain::load(test::saint_helens());
  return terrain;
}

// The ENU point of a point in the DEM's CRS.
std::array<double, 2> enu_of(double x, double y) {
  const auto sample = helens().dem().sample_of(x, y);
  std::array<double, 1> col{sample[0]}, row{sample[1]};
  helens().samples_to_enu(col, row);
  return {col[0], row[0]};
}

// The pumice plain 5.5 km north of the DEM's centre, in the DEM's CRS.
std::array<double, 2> plain() {
  const auto& t = helens().dem().transform;
  return {t[0] + helens().dem().width * t[1] / 2, t[3] + helens().dem().height * t[5] / 2 + 5500};
}

// A 200 m square around plain() as GeoJSON in NAD27 / UTM 10N (EPSG:26710, the DEM's CRS).
std::filesystem::path square(const std::filesystem::path& dir) {
  const auto [cx, cy] = plain();
  std::string ring;
  for (const auto& [dx, dy] : {std::pair{-100, -100}, {100, -100}, {100, 100}, {-100, 100}, {-100, -100}}) {
    // Appended piecewise: GCC 12 warns falsely on a chain of + here.
    if (!ring.empty()) ring += ',';
    ring += '[';
    ring += fixed_text(cx + dx, 3);
    ring += ',';
    ring += fixed_text(cy + dy, 3);
    ring += ']';
  }
  const auto path = dir / "square.geojson";
  test::write_text(
      path, R"({"type":"FeatureCollection","crs":{"type":"name","properties":{"name":"urn:ogc:def:crs:EPSG::26710"}},)"
            R"("features":[{"type":"Feature","properties":{},"geometry":{"type":"Polygon","coordinates":[[)" +
                ring + "]]}}]}");
  return path;
}

bool allows_at(const GroundMask& mask, double dx, double dy) {
  const auto [cx, cy] = plain();
  const auto p = enu_of(cx + dx, cy + dy);
  return mask.allows(p[0], p[1]);
}

TEST(GisMasks, PolygonsKeepTheirInsideOrOutsideToTheMetre) {
  const auto path = square(test::scratch_dir("gis_masks_square"));
  const GroundMask inside = GroundMask::polygons(path, helens(), PolygonSide::inside, 0);
  const GroundMask outside = GroundMask::polygons(path, helens(), PolygonSide::outside, 0);
  EXPECT_EQ(inside.file(), path);
  for (const auto& [dx, dy, in] : {std::tuple{0.0, 0.0, true},
                                   {99.0, 0.0, true},
                                   {101.0, 0.0, false},
                                   {0.0, -99.5, true},
                                   {0.0, -100.5, false},
                                   {150.0, 150.0, false}}) {
    EXPECT_EQ(allows_at(inside, dx, dy), in) << dx << ", " << dy;
    EXPECT_EQ(allows_at(outside, dx, dy), !in) << dx << ", " << dy;
  }
  // Tiles: wholly inside, across the edge, wholly outside.
  const auto [cx, cy] = plain();
  const auto centre = enu_of(cx, cy), edge = enu_of(cx + 100, cy), away = enu_of(cx + 300, cy);
  const auto tile = [](const std::array<double, 2>& p) { return Extent{p[0] - 2, p[1] - 2, p[0] + 2, p[1] + 2}; };
  EXPECT_TRUE(inside.allows_all(tile(centre)));
  EXPECT_FALSE(inside.allows_all(tile(edge)));
  EXPECT_TRUE(inside.allows_any(tile(edge)));
  EXPECT_FALSE(inside.allows_any(tile(away)));
  EXPECT_TRUE(outside.allows_all(tile(away)));
  // An estimate of the square's 44 cells of 900 m2: its boundary band (3 cells wide) counts half.
  EXPECT_GT(inside.allowed_count(), 30.0);
  EXPECT_LT(inside.allowed_count(), 65.0);
}

TEST(GisMasks, ABufferGrowsOrShrinksThePolygonsInMetres) {
  const auto path = square(test::scratch_dir("gis_masks_buffer"));
  const GroundMask grown = GroundMask::polygons(path, helens(), PolygonSide::inside, 20);
  const GroundMask shrunk = GroundMask::polygons(path, helens(), PolygonSide::inside, -20);
  EXPECT_TRUE(allows_at(grown, 119, 0));
  EXPECT_FALSE(allows_at(grown, 121, 0));
  EXPECT_TRUE(allows_at(shrunk, 79, 0));
  EXPECT_FALSE(allows_at(shrunk, 81, 0));
  // The corner is rounded: 20 m along the diagonal from it is outside, 10 m inside.
  EXPECT_FALSE(allows_at(grown, 100 + 15, 100 + 15));
  EXPECT_TRUE(allows_at(grown, 100 + 7, 100 + 7));
}

TEST(GisMasks, ALatLonBoxIsExactAtItsEdges) {
  const Terrain& terrain = helens();
  const auto [cx, cy] = plain();
  const auto centre = enu_of(cx, cy);
  const LatLon c = terrain.frame().to_lat_lon(centre[0], centre[1]);
  const std::array<double, 4> box{c.lat - 0.002, c.lon - 0.003, c.lat + 0.002, c.lon + 0.003};
  const GroundMask mask = GroundMask::lat_lon_box(box, terrain);
  EXPECT_TRUE(mask.file().empty());
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> lat(box[0] - 0.001, box[2] + 0.001), lon(box[1] - 0.001, box[3] + 0.001);
  int in = 0;
  for (int k = 0; k < 20000; ++k) {
    const auto p = terrain.frame().to_enu({lat(rng), lon(rng)});
    // The box as the GIS export writes a point: its stored float coordinates in WGS 84.
    const LatLon q = terrain.frame().to_lat_lon(double(float(p[0])), double(float(p[1])));
    const bool inside = q.lat >= box[0] && q.lat <= box[2] && q.lon >= box[1] && q.lon <= box[3];
    ASSERT_EQ(mask.allows(p[0], p[1]), inside) << q.lat << ", " << q.lon;
    in += inside;
  }
  EXPECT_GT(in, 5000);
}

TEST(GisMasks, ARasterInWgs84AllowsWhereItsPixelsAreNonZero) {
  const auto dir = test::scratch_dir("gis_masks_raster");
  const Terrain& terrain = helens();
  const auto [cx, cy] = plain();
  const auto centre = enu_of(cx, cy);
  const LatLon c = terrain.frame().to_lat_lon(centre[0], centre[1]);
  // 0.01 degrees around the plain, 0.0002-degree pixels: 1 west of the centre's meridian, 0 east.
  const std::array<double, 6> transform{c.lon - 0.01, 0.0002, 0, c.lat + 0.01, 0, -0.0002};
  test::write_raster(dir / "west.tif", "GTiff", GDT_Byte, 100, 100, transform, "EPSG:4326",
                     [](int col, int) { return col < 50 ? 1.0 : 0.0; });
  const GroundMask mask = GroundMask::raster(dir / "west.tif", terrain);
  // Pixels of 15-20 m: the 30 m DEM cells are cut in two.
  EXPECT_EQ(mask.width(), 2 * terrain.dem().width);
  for (const double dlon : {-0.009, -0.002, -0.0005, 0.0005, 0.002, 0.009}) {
    const auto p = terrain.frame().to_enu({c.lat, c.lon + dlon});
    EXPECT_EQ(mask.allows(p[0], p[1]), dlon < 0) << dlon;
  }
  // Beyond the raster: no flowers.
  const auto far = terrain.frame().to_enu({c.lat + 0.02, c.lon - 0.005});
  EXPECT_FALSE(mask.allows(far[0], far[1]));
}

// The message of the Error `make` throws.
template <class Make>
std::string refusal(const Make& make) {
  try {
    make();
  } catch (const Error& e) {
    return e.what();
  }
  return "(nothing thrown)";
}

TEST(GisMasks, BadFilesAreRefusedNamingTheFileAndWhatWasExpected) {
  const auto dir = test::scratch_dir("gis_masks_bad");
  const Terrain& terrain = helens();
  testing::internal::CaptureStderr();
  auto message = refusal([&] { GroundMask::raster(dir / "missing.tif", terrain); });
  EXPECT_NE(message.find("missing.tif: does not exist (expected a georeferenced raster"), std::string::npos) << message;
  test::write_raster(dir / "plain.tif", "GTiff", GDT_Byte, 8, 8, {}, nullptr, [](int, int) { return 1.0; });
  message = refusal([&] { GroundMask::raster(dir / "plain.tif", terrain); });
  EXPECT_NE(message.find("plain.tif: has no georeference"), std::string::npos) << message;
  test::write_text(dir / "text.tif", "not a raster");
  message = refusal([&] { GroundMask::raster(dir / "text.tif", terrain); });
  EXPECT_NE(message.find("text.tif: is not a raster GDAL reads"), std::string::npos) << message;

  test::write_text(dir / "points.geojson",
                   R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{},)"
                   R"("geometry":{"type":"Point","coordinates":[-122.19,46.25]}}]})");
  message = refusal([&] { GroundMask::polygons(dir / "points.geojson", terrain, PolygonSide::inside, 0); });
  EXPECT_NE(message.find("points.geojson: layer 'points' holds a Point"), std::string::npos) << message;
  EXPECT_NE(message.find("expected polygons"), std::string::npos) << message;
  test::write_text(dir / "empty.geojson", R"({"type":"FeatureCollection","features":[]})");
  message = refusal([&] { GroundMask::polygons(dir / "empty.geojson", terrain, PolygonSide::inside, 0); });
  EXPECT_NE(message.find("holds no polygon"), std::string::npos) << message;
  message = refusal([&] { GroundMask::polygons(dir / "missing.gpkg", terrain, PolygonSide::inside, 0); });
  EXPECT_NE(message.find("missing.gpkg: does not exist (expected a layer of polygons"), std::string::npos) << message;
  // GDAL said nothing on stderr: its words are in the messages.
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
}

}  // namespace
}  // namespace wangscape
