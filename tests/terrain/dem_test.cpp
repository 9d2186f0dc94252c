// Reading DEMs through real GDAL: the shared DEMs' sizes, CRSs and heights, the edge
// cases (load with GDAL's own checksums, or fail naming the file), and broken input.
#include "terrain/dem.h"

#include <gtest/gtest.h>

#include <chrono>

#include <cmath>
#include <regex>

#include "core/memory_budget.h"
#include "terrain/terrain.h"
#include "terrain_test_support.h"

namespace wangscape {
namespace {

using test::boulder;
using test::saint_helens;
using test::test_dem;

// Loading must fail with a Error whose message names the file and says why.
void expect_failure(const std::filesystem::path& path, const std::string& reason) {
  testing::internal::CaptureStderr();
  try {
    (void)Terrain::load(path);
    ADD_FAILURE() << "loading " << path << " should fail";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
    EXPECT_NE(message.find(reason), std::string::npos) << message;
  }
  // GDAL's own error printer must stay quiet: everything goes into the message.
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
}

TEST(Dem, SainteHelensSizeCrsAndHeights) {
  const DemRaster dem = read_dem(saint_helens());
  EXPECT_EQ(dem.driver, "USGSDEM");
  EXPECT_EQ(dem.width, 327);
  EXPECT_EQ(dem.height, 468);
  EXPECT_FALSE(dem.geographic);
  EXPECT_NE(dem.crs_wkt.find("NAD27"), std::string::npos);
  EXPECT_NE(dem.crs_wkt.find("UTM zone 10N"), std::string::npos);
  EXPECT_DOUBLE_EQ(dem.spacing_x(), 30.0);
  EXPECT_DOUBLE_EQ(dem.spacing_y(), 30.0);
  EXPECT_DOUBLE_EQ(dem.min_height, 682.0);
  EXPECT_DOUBLE_EQ(dem.max_height, 2543.0);
  // "up to 468 rows": the quadrangle's corners outside the profiles are no-data.
  EXPECT_EQ(dem.nodata_count, 4151u);
  std::size_t nan = 0;
  for (float h : dem.heights) nan += std::isnan(h);
  EXPECT_EQ(nan, dem.nodata_count);
}

TEST(Dem, BoulderGeographicWgs84) {
  const DemRaster dem = read_dem(boulder());
  EXPECT_EQ(dem.driver, "AAIGrid");
  EXPECT_EQ(dem.width, 240);
  EXPECT_EQ(dem.height, 144);
  EXPECT_TRUE(dem.geographic);
  EXPECT_NE(dem.crs_wkt.find("WGS"), std::string::npos);
  EXPECT_NEAR(dem.spacing_x(), 3.0 / 3600, 1e-9);
  EXPECT_DOUBLE_EQ(dem.min_height, 1943.0);
  EXPECT_DOUBLE_EQ(dem.max_height, 3286.0);
  EXPECT_EQ(dem.nodata_count, 0u);
}

TEST(Dem, BoulderNodataZeroIsAMaskNotAHeight) {
  // Punch zeros (the grid's NODATA_value) into a copy: they must become no-data.
  const auto dir = test::scratch_dir("boulder_nodata");
  std::string text = test::read_text(boulder());
  const std::size_t header_end = text.find("NODATA_value");
  std::size_t at = text.find('\n', header_end) + 1;
  for (int k = 0; k < 3; ++k) {  // the first three values of the first row
    while (text[at] == ' ') ++at;
    const std::size_t end = text.find(' ', at);
    text.replace(at, end - at, "0");
    at += 1;
  }
  test::write_text(dir / "holes.asc", text);
  std::filesystem::copy_file(boulder().replace_extension(".prj"), dir / "holes.prj");
  const DemRaster dem = read_dem(dir / "holes.asc");
  EXPECT_EQ(dem.nodata_count, 3u);
  EXPECT_DOUBLE_EQ(dem.min_height, 1943.0);  // the zeros are not heights
  EXPECT_FALSE(dem.at(0, 0).has_value());
  EXPECT_FALSE(dem.at(2, 0).has_value());
  EXPECT_TRUE(dem.at(3, 0).has_value());
}

TEST(Dem, EdgeCaseChecksumsMatchGdalsOwnTests) {
  EXPECT_EQ(gdal_checksum(test_dem("edge-cases/39109h1_truncated.dem")), 39443);
  EXPECT_EQ(gdal_checksum(test_dem("edge-cases/39079G6_truncated.dem")), 61424);
  EXPECT_EQ(gdal_checksum(test_dem("edge-cases/114p01_0100_deme_truncated.dem")), 53864);
  EXPECT_THROW(gdal_checksum(test_dem("edge-cases/fema06-140cm_2995441b_truncated.dem")), Error);
}

// Loading `path` throws an Error holding each of `fragments`, well before the conversions it
// refuses would have finished (a loose bound for a loaded machine).
void expect_refused_before_the_conversions(const std::filesystem::path& path,
                                           std::initializer_list<std::string> fragments) {
  const auto start = std::chrono::steady_clock::now();
  try {
    Terrain::load(path);
    ADD_FAILURE() << path << " became a terrain";
  } catch (const Error& e) {
    for (const std::string& fragment : fragments)
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 3.0);
}

// Found by fuzz/dem_fuzz: 39079G6_truncated.dem with its row count raised to 147154 (a strip
// 4400 km long, 2 columns) read fine, and building its frame then took 6 s of CPU (minutes under
// ASan) for 294,000 cells: its cells spread over a box that needs 3.6 million georeference
// nodes. Work out of proportion to the data is refused, naming the DEM, before it starts.
TEST(Dem, AStripTooLongForOneFrameIsRefusedQuickly) {
  const auto path = test_dem("edge-cases/strip_4400km.dem");
  EXPECT_EQ(read_dem(path).height, 147154);
  expect_refused_before_the_conversions(path, {"strip_4400km.dem': its heights span", "georeference node per 2 cells"});
}

// Found by bench/fuzz_million.sh: 2 x 280,487 cells whose extent the scene frame bends to
// 31 x 4,116 km passed the earlier cap of 4 nodes per cell and took 6 s (2.2 million nodes).
TEST(Dem, AStripBentByTheFrameIsRefusedBeforeItsLattice) {
  expect_refused_before_the_conversions(test_dem("edge-cases/strip_bent_4116km.dem"),
                                        {"strip_bent_4116km.dem': its heights span 31 x 41"});
}

// The lattice is a buffer sized by the input: over the memory limit it is refused with its
// estimate before a node is converted.
TEST(Dem, ALatticeOverTheMemoryLimitIsRefusedWithItsEstimate) {
  // A strip two cells wide at latitude 80 (cells 5.8 m east by 33 m north; the lattice steps 8
  // of the narrower): 800 heights (3,200 bytes) under a lattice of 2 x 290 nodes (18,560 bytes), so a
  // limit between the two holds the heights and refuses the lattice.
  const auto dir = test::scratch_dir("lattice_memory");
  std::string grid = "ncols 2\nnrows 400\nxllcorner -105.3\nyllcorner 80.0\ncellsize 0.0003\n";
  for (int row = 0; row < 400; ++row) grid += std::to_string(1600 + row) + " " + std::to_string(1601 + row) + "\n";
  test::write_text(dir / "strip.asc", grid);
  std::filesystem::copy_file(boulder().replace_extension(".prj"), dir / "strip.prj");
  set_memory_limit_bytes_for_process(8000);
  try {
    Terrain::load(dir / "strip.asc");
    set_memory_limit_bytes_for_process(0);
    FAIL() << "a lattice over the limit was built";
  } catch (const Error& e) {
    set_memory_limit_bytes_for_process(0);
    EXPECT_NE(std::string(e.what()).find("strip.asc: its georeference lattice of 2 x 290 nodes would need"),
              std::string::npos)
        << e.what();
  }
  EXPECT_NO_THROW(Terrain::load(dir / "strip.asc"));
}

// Found by fuzz/dem_fuzz: a GeoTIFF in UTM 10N whose origin a flipped bit put 2.4e12 km east
// escaped as GeographicLib's own exception instead of an Error naming the DEM.
TEST(Dem, UtmCoordinatesOutsideTheZoneAreAnErrorNamingTheDem) {
  try {
    Terrain::load(test_dem("edge-cases/utm_easting_out_of_zone.tif"));
    FAIL() << "a DEM 2.4e12 km east became a terrain";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("utm_easting_out_of_zone.tif': coordinates do not transform to WGS 84"),
              std::string::npos)
        << e.what();
  }
}

// Found by fuzz/dem_fuzz: a 978-byte USGS header declaring 1 x 428515590 cells had 1.7 GB of
// heights allocated and zeroed before GDAL found no profiles. Refused before allocating.
TEST(Dem, AHeaderDeclaringMoreCellsThanTheLimitIsRefusedBeforeAllocating) {
  try {
    read_dem(test_dem("edge-cases/usgs_declares_428m_cells.dem"));
    FAIL() << "428 million cells accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("declares 1 x 428515590 cells (1634 MiB of heights); at most 268435456"),
              std::string::npos)
        << e.what();
  }
}

TEST(Dem, EdgeCaseTruncatedUtmDemsLoad) {
  const DemRaster a = read_dem(test_dem("edge-cases/39109h1_truncated.dem"));
  EXPECT_EQ(a.width, 2);
  EXPECT_EQ(a.height, 1411);
  EXPECT_DOUBLE_EQ(a.spacing_x(), 10.0);
  EXPECT_NEAR(a.min_height, 1687.4, 0.01);
  EXPECT_NEAR(a.max_height, 1716.99, 0.01);
  const DemRaster b = read_dem(test_dem("edge-cases/39079G6_truncated.dem"));
  EXPECT_EQ(b.width, 2);
  EXPECT_EQ(b.height, 470);
  EXPECT_NE(b.crs_wkt.find("WGS 72"), std::string::npos);
  EXPECT_DOUBLE_EQ(b.min_height, 325.0);
  EXPECT_DOUBLE_EQ(b.max_height, 385.0);
  // Both become terrains with heights where they have data.
  for (const char* name : {"edge-cases/39109h1_truncated.dem", "edge-cases/39079G6_truncated.dem"}) {
    const Terrain terrain = Terrain::load(test_dem(name));
    const Extent e = terrain.extent();
    int found = 0;
    for (int k = 0; k <= 200; ++k) {
      const auto h = terrain.height((e.min_x + e.max_x) / 2, e.min_y + e.height() * k / 200);
      if (h) {
        ++found;
        EXPECT_GE(*h, terrain.dem().min_height - 1e-3);
        EXPECT_LE(*h, terrain.dem().max_height + 1e-3);
      }
    }
    EXPECT_GT(found, 0) << name;
  }
}

TEST(Dem, EdgeCaseCdedAllNodataFailsCleanly) {
  expect_failure(test_dem("edge-cases/114p01_0100_deme_truncated.dem"), "no valid heights");
}

TEST(Dem, EdgeCaseFemaHeaderWithoutProfilesFailsCleanly) {
  expect_failure(test_dem("edge-cases/fema06-140cm_2995441b_truncated.dem"), "elevation profiles cannot be read");
}

TEST(Dem, TruncatedAndGarbageFilesFailCleanly) {
  const auto dir = test::scratch_dir("broken");
  const std::string whole = test::read_text(saint_helens());
  for (std::size_t size : {std::size_t(100), std::size_t(1500), std::size_t(3000), std::size_t(200000)}) {
    const auto path = dir / ("cut_" + std::to_string(size) + ".dem");
    test::write_text(path, whole.substr(0, size));
    testing::internal::CaptureStderr();
    try {
      const Terrain terrain = Terrain::load(path);
      ADD_FAILURE() << path << " loaded although truncated";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(path.string()), std::string::npos) << e.what();
    }
    EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  }
  std::string garbage(4096, '\0');
  for (std::size_t k = 0; k < garbage.size(); ++k) garbage[k] = char((k * 2654435761u) >> 13);
  test::write_text(dir / "garbage.dem", garbage);
  expect_failure(dir / "garbage.dem", "not a raster format GDAL recognizes");
  test::write_text(dir / "empty.asc", "");
  expect_failure(dir / "empty.asc", "not a raster format GDAL recognizes");
  expect_failure(dir / "missing.dem", "does not exist");
}

TEST(Dem, AsciiGridWithoutPrjFailsNamingThePrj) {
  const auto dir = test::scratch_dir("no_prj");
  std::filesystem::copy_file(boulder(), dir / "lonely.asc");
  expect_failure(dir / "lonely.asc", "lonely.prj");
}

TEST(Dem, GeoTiffInWgs84UtmLoads) {
  const auto dir = test::scratch_dir("geotiff");
  const auto path = dir / "ramp.tif";
  // 50 x 40 samples, 10 m, WGS 84 / UTM 13N, heights 1000 + col + 100 row, one no-data hole.
  test::write_raster(path, "GTiff", GDT_Float32, 50, 40, {480000, 10, 0, 4440000, 0, -10}, "EPSG:32613",
                     [](int col, int row) { return col == 7 && row == 9 ? -9999.0 : 1000.0 + col + 100.0 * row; });
  {
    GDALDataset* d = GDALDataset::FromHandle(GDALOpen(path.c_str(), GA_Update));
    d->GetRasterBand(1)->SetNoDataValue(-9999);
    GDALClose(d);
  }
  const Terrain terrain = Terrain::load(path);
  EXPECT_EQ(terrain.dem().driver, "GTiff");
  EXPECT_EQ(terrain.dem().nodata_count, 1u);
  EXPECT_DOUBLE_EQ(terrain.dem().min_height, 1000.0);
  EXPECT_DOUBLE_EQ(terrain.dem().max_height, 1000.0 + 49 + 3900);
  EXPECT_NE(terrain.crs().note().find("GeographicLib"), std::string::npos);
  EXPECT_NEAR(terrain.spacing_m()[0], 10.0 / terrain.frame().utm_scale(), 1e-3);
}

TEST(Dem, SrtmHgtLoads) {
  const auto dir = test::scratch_dir("hgt");
  const auto path = dir / "N40W106.hgt";
  const double step = 1.0 / 1200;
  test::write_raster(path, "SRTMHGT", GDT_Int16, 1201, 1201, {-106 - step / 2, step, 0, 41 + step / 2, 0, -step},
                     "EPSG:4326", [](int col, int row) { return (col + row) % 2000 == 0 ? -32768.0 : 1500.0 + row; });
  const Terrain terrain = Terrain::load(path);
  EXPECT_EQ(terrain.dem().driver, "SRTMHGT");
  EXPECT_EQ(terrain.dem().width, 1201);
  EXPECT_TRUE(terrain.dem().geographic);
  EXPECT_EQ(terrain.dem().nodata_count, 402u);  // col + row = 0 (1 cell) or 2000 (401 cells)
  EXPECT_NEAR(terrain.georeference().origin_lat_deg, 40.5, 1e-9);
  EXPECT_NEAR(terrain.georeference().origin_lon_deg, -105.5, 1e-9);
  EXPECT_NE(terrain.georeference().vertical_datum.find("EGM96"), std::string::npos);
}

}  // namespace
}  // namespace wangscape

namespace wangscape {
namespace {

TEST(Dem, OneDegreeGeographicUsgsDemLoads) {
  // A 1-degree USGS DEM (3 arc-second, geographic), written by GDAL's own USGSDEM driver.
  const auto dir = test::scratch_dir("one_degree");
  const double step = 3.0 / 3600;
  const auto value = [](int col, int row) { return 1000.0 + col + 2.0 * row; };
  test::write_raster(dir / "one_degree.dem", "USGSDEM", GDT_Int16, 1201, 1201,
                     {-106 - step / 2, step, 0, 41 + step / 2, 0, -step}, "EPSG:4326", value);
  const Terrain terrain = Terrain::load(dir / "one_degree.dem");
  const DemRaster& dem = terrain.dem();
  EXPECT_EQ(dem.driver, "USGSDEM");
  EXPECT_TRUE(dem.geographic);
  EXPECT_EQ(dem.width, 1201);
  EXPECT_EQ(dem.height, 1201);
  EXPECT_NEAR(dem.spacing_x(), step, 1e-9);
  EXPECT_DOUBLE_EQ(dem.min_height, 1000.0);
  EXPECT_DOUBLE_EQ(dem.max_height, 1000.0 + 1200 + 2400);
  EXPECT_NEAR(terrain.spacing_m()[0], 70.6, 0.5);  // 3" of longitude at 40.5 N
  EXPECT_NEAR(terrain.spacing_m()[1], 92.5, 0.5);  // 3" of latitude
  for (const auto& [col, row] : {std::pair{0, 0}, {600, 600}, {17, 1100}, {1200, 3}}) {
    ASSERT_TRUE(dem.at(col, row).has_value());
    EXPECT_DOUBLE_EQ(*dem.at(col, row), value(col, row));
  }
  double x = 600, y = 600;
  terrain.samples_to_enu(std::span(&x, 1), std::span(&y, 1));
  EXPECT_NEAR(x, 0.0, 1e-6);  // the center sample is the default origin
  EXPECT_NEAR(*terrain.height(x, y), value(600, 600), 1e-3);
}

}  // namespace
}  // namespace wangscape

namespace wangscape {
namespace {

TEST(Dem, HeightsInFeetBecomeMeters) {
  const auto dir = test::scratch_dir("feet");
  const auto path = dir / "feet.tif";
  test::write_raster(path, "GTiff", GDT_Float32, 10, 10, {500000, 30, 0, 4000000, 0, -30}, "EPSG:26913",
                     [](int col, int) { return 1000.0 + col; });
  {
    GDALDataset* d = GDALDataset::FromHandle(GDALOpen(path.c_str(), GA_Update));
    d->GetRasterBand(1)->SetUnitType("ft");
    GDALClose(d);
  }
  const DemRaster dem = read_dem(path);
  EXPECT_EQ(dem.height_unit_in_file, "ft");
  EXPECT_NEAR(dem.min_height, 1000 * 0.3048, 1e-3);
  EXPECT_NEAR(dem.max_height, 1009 * 0.3048, 1e-3);
}

}  // namespace
}  // namespace wangscape
