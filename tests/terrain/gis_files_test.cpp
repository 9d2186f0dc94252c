// The GIS files through real GDAL (terrain/gis_files.h): a plant layer read back by OGR with its
// fields, CRS and shortest numbers; nothing left by an uncommitted writer; the GeoTIFF's grid;
// the cell areas of a projected and a geographic DEM; failures named, GDAL silent on stderr.
#include "terrain/gis_files.h"

#include <gtest/gtest.h>
#include <ogrsf_frmts.h>

#include <cmath>
#include <numbers>

#include "core/error.h"
#include "terrain/dem.h"
#include "terrain_test_support.h"

namespace wangscape {
namespace {

using test::boulder;
using test::saint_helens;
using test::scratch_dir;

struct Plants {
  std::vector<double> x{562000.5, 562010.25, 562020.125};
  std::vector<double> y{5116000.5, 5116001.5, 5116002.5};
  std::vector<std::uint16_t> species{0, 1, 0};
  std::vector<std::uint16_t> variant{0, 3, 2};
  std::vector<float> scale{0.9876543f, 1.0f, 1.125f};
  std::vector<float> yaw{0.5f, 6.25f, 3.0f};
  std::vector<float> height{700.25f, 701.0f, 702.5f};
  std::vector<float> rank{0.1f, 0.5f, 0.99f};
  PlantColumns columns() const { return {x, y, species, variant, scale, yaw, height, rank}; }
};

GisCrs helens_crs() { return GisCrs{read_dem(saint_helens()).crs_wkt, false}; }

TEST(PlantLayerFile, GeoPackageReadsBackWithFieldsCrsAndShortestNumbers) {
  const auto dir = scratch_dir("gis_gpkg");
  const auto path = dir / "plants.gpkg";
  testing::internal::CaptureStderr();
  {
    PlantLayerFile file(path, GisVectorFormat::geopackage, helens_crs(), {"grass", "sunflower"});
    file.append(Plants{}.columns());
    file.append(Plants{}.columns());
    EXPECT_EQ(file.count(), 6u);
    EXPECT_FALSE(std::filesystem::exists(path));  // a temporary until commit
    file.commit();
  }
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
  ASSERT_EQ(std::vector<std::filesystem::path>(std::filesystem::directory_iterator(dir), {}),
            std::vector<std::filesystem::path>{path});
  auto* dataset = static_cast<GDALDataset*>(GDALOpenEx(path.c_str(), GDAL_OF_VECTOR, nullptr, nullptr, nullptr));
  ASSERT_NE(dataset, nullptr);
  OGRLayer* layer = dataset->GetLayerByName("plants");
  ASSERT_NE(layer, nullptr);
  EXPECT_EQ(layer->GetFeatureCount(), 6);
  ASSERT_NE(layer->GetSpatialRef(), nullptr);
  EXPECT_EQ(std::string(layer->GetSpatialRef()->GetAuthorityCode(nullptr)), "26710");  // NAD27 / UTM 10N
  OGRFeatureDefn* defn = layer->GetLayerDefn();
  ASSERT_EQ(defn->GetFieldCount(), int(kPlantFields.size()));
  for (std::size_t i = 0; i < kPlantFields.size(); ++i)
    EXPECT_STREQ(defn->GetFieldDefn(int(i))->GetNameRef(), kPlantFields[i]);
  layer->ResetReading();
  OGRFeature::DestroyFeature(layer->GetNextFeature());  // the second one
  OGRFeature* second = layer->GetNextFeature();
  ASSERT_NE(second, nullptr);
  EXPECT_STREQ(second->GetFieldAsString("species"), "sunflower");
  EXPECT_EQ(second->GetFieldAsInteger("variant"), 3);
  EXPECT_EQ(second->GetFieldAsDouble("yaw"), 6.25);
  const auto* point = second->GetGeometryRef()->toPoint();
  EXPECT_EQ(point->getX(), 562010.25);
  EXPECT_EQ(point->getY(), 5116001.5);
  OGRFeature::DestroyFeature(second);
  OGRFeature* first = layer->GetFeature(1);
  ASSERT_NE(first, nullptr);
  EXPECT_EQ(first->GetFieldAsDouble("scale"), 0.9876543);  // the float's shortest text, not 0.98765432834...
  EXPECT_EQ(first->GetFieldAsDouble("rank"), 0.1);
  OGRFeature::DestroyFeature(first);
  GDALClose(dataset);
}

TEST(PlantLayerFile, GeoJsonInWgs84) {
  const auto dir = scratch_dir("gis_geojson");
  const auto path = dir / "plants.geojson";
  Plants p;
  p.x = {-122.19, -122.18, -122.17};
  p.y = {46.2, 46.21, 46.22};
  PlantLayerFile file(path, GisVectorFormat::geojson, GisCrs{"", true}, {"a", "b"});
  file.append(p.columns());
  file.commit();
  const std::string text = test::read_text(path);
  EXPECT_NE(text.find("\"species\": \"b\""), std::string::npos) << text;
  EXPECT_NE(text.find("\"scale\": 0.9876543,"), std::string::npos) << text;
  EXPECT_NE(text.find("[ -122.18, 46.21 ]"), std::string::npos) << text;
}

TEST(PlantLayerFile, UncommittedLeavesNothing) {
  const auto dir = scratch_dir("gis_uncommitted");
  {
    PlantLayerFile file(dir / "plants.gpkg", GisVectorFormat::geopackage, helens_crs(), {"a", "b"});
    file.append(Plants{}.columns());
  }
  EXPECT_TRUE(std::filesystem::is_empty(dir));
}

TEST(PlantLayerFile, FailuresNameTheFile) {
  const auto dir = scratch_dir("gis_failures");
  testing::internal::CaptureStderr();
  try {
    PlantLayerFile file(dir / "no" / "such" / "plants.gpkg", GisVectorFormat::geopackage, helens_crs(), {"a"});
    ADD_FAILURE() << "a file in a missing folder was created";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("plants.gpkg"), std::string::npos) << e.what();
  }
  PlantLayerFile file(dir / "plants.gpkg", GisVectorFormat::geopackage, helens_crs(), {"a"});  // one species
  EXPECT_THROW(file.append(Plants{}.columns()), Error);                                        // species 1 has no name
  EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
}

TEST(GeoTiff, GridCrsAndValues) {
  const auto dir = scratch_dir("gis_geotiff");
  GisGrid grid;
  grid.crs = helens_crs();
  grid.transform = {560000, 30, 0, 5120000, 0, -30};
  grid.width = 3;
  grid.height = 2;
  grid.values = {0, 0.5f, 1, 2, 0, 0.25f};
  grid.description = "plants per square metre";
  write_geotiff(dir / "cover.tif", grid);
  auto* dataset = static_cast<GDALDataset*>(GDALOpen((dir / "cover.tif").c_str(), GA_ReadOnly));
  ASSERT_NE(dataset, nullptr);
  std::array<double, 6> t{};
  dataset->GetGeoTransform(t.data());
  EXPECT_EQ(t, grid.transform);
  EXPECT_EQ(std::string(dataset->GetSpatialRef()->GetAuthorityCode(nullptr)), "26710");
  std::vector<float> values(6);
  ASSERT_EQ(dataset->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, 3, 2, values.data(), 3, 2, GDT_Float32, 0, 0, nullptr),
            CE_None);
  EXPECT_EQ(values, grid.values);
  EXPECT_STREQ(dataset->GetRasterBand(1)->GetDescription(), "plants per square metre");
  GDALClose(dataset);
  grid.values.pop_back();
  EXPECT_THROW(write_geotiff(dir / "short.tif", grid), Error);
  EXPECT_FALSE(std::filesystem::exists(dir / "short.tif"));
}

TEST(DemCellArea, ProjectedIsThePixelGeographicIsOnTheEllipsoid) {
  EXPECT_DOUBLE_EQ(dem_cell_area_m2(read_dem(saint_helens()), 0), 900.0);  // 30 m cells
  const DemRaster b = read_dem(boulder());
  // 3 arc-seconds near 40.1 N: about 92.6 m of latitude by 92.6 cos(40.1) = 70.9 m of longitude.
  const double lat = b.transform[3] + 0.5 * b.transform[5];
  const double approx =
      std::pow(6371008.8 * std::numbers::pi / 180 * b.transform[1], 2) * std::cos(lat * std::numbers::pi / 180);
  EXPECT_NEAR(dem_cell_area_m2(b, 0), approx, 0.01 * approx);
  // Cells shrink towards the pole.
  EXPECT_GT(dem_cell_area_m2(b, b.height - 1), dem_cell_area_m2(b, 0));
}

}  // namespace
}  // namespace wangscape
