// The Blender export: array files match the scene byte for byte, the manifest describes
// them, instances are streamed, and inconsistent scenes are refused with a clear error.
#include "exporters/blender_export.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <vector>

#include "core/atomic_file.h"
#include "exporters/export_support.h"
#include "tests/blender/test_scene.h"

namespace wangscape {
namespace {

std::filesystem::path scratch(const std::string& name) {
  const auto path =
      std::filesystem::temp_directory_path() / ("wangscape_blender_export_" + std::to_string(::getpid()) + "_" + name);
  std::filesystem::remove_all(path);
  return path;
}

template <typename T>
std::vector<T> read_array(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(bytes.size() % sizeof(T), 0u) << path;
  std::vector<T> values(bytes.size() / sizeof(T));
  std::memcpy(values.data(), bytes.data(), values.size() * sizeof(T));
  return values;
}

nlohmann::json read_json(const std::filesystem::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

TEST(BlenderExport, ArraysRoundTripAndManifestDescribesThem) {
  const auto folder = scratch("roundtrip");
  const Scene scene = testing::make_test_scene(10007, 16, 30.0f, 1000);
  const BlenderExportSummary summary = export_blender(scene, folder);
  EXPECT_EQ(summary.instance_count, 10007u);
  const auto manifest = read_json(summary.manifest);
  EXPECT_EQ(manifest["format"]["name"], "wangscape-blender");
  EXPECT_EQ(manifest["format"]["version"], 1);
  EXPECT_EQ(manifest["counts"]["instances"], 10007);
  EXPECT_EQ(manifest["counts"]["models"], 3);
  EXPECT_EQ(manifest["counts"]["terrain_vertices"], 17 * 17);
  // stem, leaf, petal, disk shared across variants + soil.
  EXPECT_EQ(manifest["materials"].size(), 5u);
  for (const auto& file : manifest["files"]) EXPECT_TRUE(std::filesystem::exists(folder / file.get<std::string>()));
  EXPECT_TRUE(std::filesystem::exists(folder / "wangscape_import.zip"));

  const auto positions = read_array<float>(folder / manifest["terrain"]["positions"]["file"].get<std::string>());
  ASSERT_EQ(positions.size(), scene.terrain.positions.size() * 3);
  for (std::size_t i = 0; i < scene.terrain.positions.size(); ++i) {
    for (int c = 0; c < 3; ++c) ASSERT_EQ(positions[3 * i + c], scene.terrain.positions[i][c]);
  }
  for (std::size_t m = 0; m < scene.models.size(); ++m) {
    const auto& entry = manifest["models"][m];
    const auto indices = read_array<std::uint32_t>(folder / entry["indices"]["file"].get<std::string>());
    const auto slots = read_array<std::uint16_t>(folder / entry["material_indices"]["file"].get<std::string>());
    ASSERT_EQ(indices.size(), scene.models[m].triangles.size() * 3);
    ASSERT_EQ(slots, scene.models[m].triangle_material);
    EXPECT_EQ(entry["material_slots"].size(), scene.models[m].materials.size());
    for (std::size_t s = 0; s < scene.models[m].materials.size(); ++s) {
      EXPECT_EQ(manifest["materials"][entry["material_slots"][s].get<std::size_t>()]["name"],
                scene.models[m].materials[s].name);
    }
  }

  // Instances: the same values, in stream order, and bounds/per-variant counts that agree.
  const auto x = read_array<float>(folder / "instances_x.f32");
  const auto yaw = read_array<float>(folder / "instances_yaw.f32");
  const auto variant = read_array<std::uint16_t>(folder / "instances_variant.u16");
  ASSERT_EQ(x.size(), 10007u);
  ASSERT_EQ(variant.size(), 10007u);
  std::vector<float> expected_x, expected_yaw;
  std::vector<std::uint16_t> expected_variant;
  scene.instances([&](const InstanceBatch& batch) {
    expected_x.insert(expected_x.end(), batch.x.begin(), batch.x.end());
    expected_yaw.insert(expected_yaw.end(), batch.yaw.begin(), batch.yaw.end());
    expected_variant.insert(expected_variant.end(), batch.variant.begin(), batch.variant.end());
  });
  EXPECT_EQ(x, expected_x);
  EXPECT_EQ(yaw, expected_yaw);
  EXPECT_EQ(variant, expected_variant);
  std::uint64_t total = 0;
  for (const auto& n : manifest["instances"]["per_variant"]) total += n.get<std::uint64_t>();
  EXPECT_EQ(total, 10007u);
  EXPECT_EQ(manifest["instances"]["bounds"]["min"][0].get<float>(), *std::min_element(x.begin(), x.end()));
  EXPECT_EQ(manifest["instances"]["bounds"]["max"][0].get<float>(), *std::max_element(x.begin(), x.end()));

  EXPECT_EQ(manifest["blendergis"]["SRID"], "EPSG:32632");
  EXPECT_DOUBLE_EQ(manifest["blendergis"]["crs x"].get<double>(), 500000.5);
  EXPECT_DOUBLE_EQ(manifest["blendergis"]["latitude"].get<double>(), 46.0436);
  EXPECT_EQ(manifest["georeference"]["units"], "meters");
  std::filesystem::remove_all(folder);
}

TEST(BlenderExport, SameSceneSameBytes) {
  const auto a = scratch("same_a"), b = scratch("same_b");
  export_blender(testing::make_test_scene(3000, 8, 20.0f, 700), a);
  export_blender(testing::make_test_scene(3000, 8, 20.0f, 333), b);  // batching must not matter
  for (const auto& entry : std::filesystem::directory_iterator(a)) {
    const auto name = entry.path().filename();
    EXPECT_EQ(read_array<char>(a / name), read_array<char>(b / name)) << name;
  }
  std::filesystem::remove_all(a);
  std::filesystem::remove_all(b);
}

TEST(BlenderExport, StreamFailingMidwayLeavesNoManifestNorArrays) {
  const auto folder = scratch("midway");
  Scene scene = testing::make_test_scene(10000, 4, 10.0f, 1000);
  scene.instances = testing::failing_at_batch(scene.instances, 3);
  try {
    export_blender(scene, folder);
    FAIL() << "expected Error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("on purpose"), std::string::npos) << error.what();
  }
  EXPECT_FALSE(std::filesystem::exists(folder / "manifest.json"));
  EXPECT_FALSE(std::filesystem::exists(folder / "instances_x.f32"));  // no partial outputs
  std::filesystem::remove_all(folder);
}

TEST(BlenderExport, VariantOutsideModelsIsRefused) {
  Scene scene = testing::make_test_scene(10, 4, 10.0f);
  scene.models.resize(2);  // instances use variants 0..2
  EXPECT_THROW(export_blender(scene, scratch("variant")), Error);
}

TEST(BlenderExport, BlenderGisKeysFromGeoreference) {
  const auto keys = blendergis_properties({{"EPSG", "2056"}, {"origin_x", "2600000"}, {"crs_y", "not a number"}});
  ASSERT_EQ(keys.size(), 2u);
  EXPECT_EQ(keys[0], (std::pair<std::string, std::string>{"SRID", "EPSG:2056"}));
  EXPECT_EQ(keys[1], (std::pair<std::string, std::string>{"crs x", "2600000"}));
}

TEST(BlenderExport, BlenderGisKeysFromUtmZoneOfTheOrigin) {
  // The keys terrain/georef.h writes: Mount St. Helens, UTM zone 10 north.
  const auto keys = blendergis_properties({{"origin_latitude_deg", "46.2"},
                                           {"origin_longitude_deg", "-122.19"},
                                           {"utm_zone", "10"},
                                           {"utm_hemisphere", "north"}});
  ASSERT_EQ(keys.size(), 5u);
  EXPECT_EQ(keys[0], (std::pair<std::string, std::string>{"SRID", "EPSG:32610"}));
  EXPECT_EQ(keys[1].first, "latitude");
  EXPECT_EQ(keys[2].first, "longitude");
  EXPECT_EQ(keys[3].first, "crs x");
  EXPECT_EQ(keys[4].first, "crs y");
  // Zone 10's central meridian is -123: 0.81 deg x 111.3 km x cos(46.2 deg) = 62.4 km east of 500 km.
  EXPECT_NEAR(std::stod(keys[3].second), 562'400.0, 300.0);
  EXPECT_NEAR(std::stod(keys[4].second), 5'116'700.0, 1'000.0);
}

}  // namespace
}  // namespace wangscape
