// glTF export: the .glb is well formed, accessor min/max equal the float32 data exactly,
// instances reach EXT_mesh_gpu_instancing (used, not required) in glTF's y-up frame, and the
// Khronos glTF validator (tools/validate_gltf.mjs) reports 0 errors for every file written.
#include "exporters/gltf_writer.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <vector>

#include "core/atomic_file.h"
#include "scene/wind.h"
#include "tests/blender/test_scene.h"

namespace wangscape {
namespace {

const std::filesystem::path& scratch_dir() {
  // Removed when the test program exits.
  static const struct Dir {
    std::filesystem::path path =
        std::filesystem::temp_directory_path() / ("wangscape_gltf_tests_" + std::to_string(::getpid()));
    Dir() { std::filesystem::create_directories(path); }
    ~Dir() {
      std::error_code ec;
      std::filesystem::remove_all(path, ec);
    }
  } dir;
  return dir.path;
}

std::filesystem::path scratch(const std::string& name) { return scratch_dir() / name; }

struct Glb {
  nlohmann::json json;
  std::string bin;
};

std::uint32_t u32(const std::string& bytes, std::size_t offset) {
  std::uint32_t value;
  std::memcpy(&value, bytes.data() + offset, 4);
  return value;
}

Glb read_glb(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(bytes.substr(0, 4), "glTF");
  EXPECT_EQ(u32(bytes, 4), 2u);
  EXPECT_EQ(u32(bytes, 8), bytes.size());
  const std::uint32_t json_size = u32(bytes, 12);
  EXPECT_EQ(bytes.substr(16, 4), "JSON");
  EXPECT_EQ(json_size % 4, 0u);
  Glb glb{nlohmann::json::parse(bytes.substr(20, json_size)), {}};
  if (20 + json_size < bytes.size()) {
    const std::uint32_t bin_size = u32(bytes, 20 + json_size);
    EXPECT_EQ(bytes.substr(24 + json_size, 3), "BIN");
    glb.bin = bytes.substr(28 + json_size, bin_size);
  }
  return glb;
}

// The float values of accessor `index` (tightly packed float accessors only).
std::vector<float> accessor_floats(const Glb& glb, std::size_t index, int& components) {
  const auto& accessor = glb.json["accessors"][index];
  const auto& view = glb.json["bufferViews"][accessor["bufferView"].get<std::size_t>()];
  EXPECT_EQ(accessor["componentType"], 5126);
  const std::string type = accessor["type"];
  components = type == "SCALAR" ? 1 : type == "VEC3" ? 3 : 4;
  std::vector<float> values(accessor["count"].get<std::size_t>() * components);
  std::memcpy(values.data(), glb.bin.data() + view["byteOffset"].get<std::size_t>(), values.size() * sizeof(float));
  return values;
}

void expect_validator_accepts(const std::filesystem::path& glb) {
  const std::string tools = std::string(WANGSCAPE_SOURCE_DIR) + "/tools";
  ASSERT_TRUE(std::filesystem::exists(tools + "/node_modules/gltf-validator"))
      << "run scripts/install-deps.sh (npm install in tools/) for the Khronos glTF validator";
  const std::string report = glb.string() + ".report";
  const std::string command = "node '" + tools + "/validate_gltf.mjs' '" + glb.string() + "' > '" + report + "' 2>&1";
  const int status = std::system(command.c_str());
  std::ifstream in(report);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(status, 0) << text;
  EXPECT_NE(text.find(": 0 errors"), std::string::npos) << text;
  std::filesystem::remove(report);
}

TEST(GltfWriter, InstancedSceneIsValidWithExactBounds) {
  const auto path = scratch("instanced.glb");
  const Scene scene = testing::make_test_scene(5003, 16, 30.0f, 777);
  const GltfSummary summary = write_gltf(scene, path);
  EXPECT_EQ(summary.instance_count, 5003u);
  EXPECT_EQ(summary.bytes, std::filesystem::file_size(path));
  const Glb glb = read_glb(path);
  EXPECT_EQ(glb.json["extensionsUsed"], nlohmann::json::array({"EXT_mesh_gpu_instancing"}));
  EXPECT_FALSE(glb.json.contains("extensionsRequired"));
  EXPECT_EQ(glb.json["scenes"][0]["extras"]["georeference"]["srid"], "EPSG:32632");
  EXPECT_EQ(glb.json["scenes"][0]["extras"]["instance_count"], 5003);

  // Every accessor that declares min/max declares exactly the float32 extremes of its data.
  int bounded = 0;
  for (std::size_t a = 0; a < glb.json["accessors"].size(); ++a) {
    const auto& accessor = glb.json["accessors"][a];
    if (!accessor.contains("min")) continue;
    int components = 0;
    const auto values = accessor_floats(glb, a, components);
    for (int c = 0; c < components; ++c) {
      float low = INFINITY, high = -INFINITY;
      for (std::size_t i = c; i < values.size(); i += components) {
        low = std::min(low, values[i]);
        high = std::max(high, values[i]);
      }
      EXPECT_EQ(accessor["min"][c].get<double>(), double(low)) << "accessor " << a;
      EXPECT_EQ(accessor["max"][c].get<double>(), double(high)) << "accessor " << a;
    }
    ++bounded;
  }
  EXPECT_GE(bounded, 4 + 3);  // terrain + 3 model POSITIONs, 3 TRANSLATIONs

  // Instances: per variant node, TRANSLATION in y-up, unit yaw quaternions, uniform scale.
  std::vector<std::array<float, 3>> first_enu(3);
  std::vector<bool> seen(3, false);
  scene.instances([&](const InstanceBatch& batch) {
    for (std::size_t i = 0; i < batch.size(); ++i) {
      if (!seen[batch.variant[i]]) first_enu[batch.variant[i]] = {batch.x[i], batch.y[i], batch.z[i]};
      seen[batch.variant[i]] = true;
    }
  });
  std::uint64_t total = 0;
  int variant = 0;
  for (const auto& node : glb.json["nodes"]) {
    if (!node.contains("extensions")) continue;
    const auto& attributes = node["extensions"]["EXT_mesh_gpu_instancing"]["attributes"];
    int components = 0;
    const auto t = accessor_floats(glb, attributes["TRANSLATION"], components);
    const auto r = accessor_floats(glb, attributes["ROTATION"], components);
    ASSERT_EQ(components, 4);
    const auto s = accessor_floats(glb, attributes["SCALE"], components);
    total += t.size() / 3;
    EXPECT_EQ(t[0], first_enu[variant][0]);
    EXPECT_EQ(t[1], first_enu[variant][2]);   // up
    EXPECT_EQ(t[2], -first_enu[variant][1]);  // -north
    for (std::size_t i = 0; i < r.size(); i += 4) {
      EXPECT_EQ(r[i], 0.0f);
      EXPECT_EQ(r[i + 2], 0.0f);
      EXPECT_NEAR(r[i + 1] * r[i + 1] + r[i + 3] * r[i + 3], 1.0f, 1e-6f);
    }
    for (std::size_t i = 0; i < s.size(); i += 3) EXPECT_TRUE(s[i] == s[i + 1] && s[i] == s[i + 2]);
    ++variant;
  }
  EXPECT_EQ(variant, 3);
  EXPECT_EQ(total, 5003u);
  // No temporaries left beside the output.
  for (const auto& entry : std::filesystem::directory_iterator(path.parent_path())) {
    EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos) << entry.path();
  }
  expect_validator_accepts(path);
}

TEST(GltfWriter, SameSceneSameBytesWhateverTheBatching) {
  const auto a = scratch("batch_a.glb"), b = scratch("batch_b.glb");
  write_gltf(testing::make_test_scene(2000, 8, 20.0f, 100), a);
  write_gltf(testing::make_test_scene(2000, 8, 20.0f, 1999), b);
  std::ifstream ia(a, std::ios::binary), ib(b, std::ios::binary);
  EXPECT_TRUE(std::equal(std::istreambuf_iterator<char>(ia), std::istreambuf_iterator<char>(),
                         std::istreambuf_iterator<char>(ib), std::istreambuf_iterator<char>()));
}

TEST(GltfWriter, NodePerInstanceIsValid) {
  const auto path = scratch("nodes.glb");
  GltfOptions options;
  options.instancing = GltfInstancing::node_per_instance;
  write_gltf(testing::make_test_scene(400, 8, 20.0f), path, options);
  const Glb glb = read_glb(path);
  EXPECT_FALSE(glb.json.contains("extensionsUsed"));
  std::size_t flowers = 0;
  for (const auto& node : glb.json["nodes"]) flowers += node.contains("mesh") && node.contains("scale");
  EXPECT_EQ(flowers, 400u);
  expect_validator_accepts(path);
}

// With wind, each flower leans as at time 0 (scene/wind.h), the rotation composed as quaternions:
// a second spelling of lean_rotation's axes and their order, so the two must turn a flower's top
// (glTF +y) to the same place. In glTF's frame x is east, y up and z south.
TEST(GltfWriter, WindyFlowersLeanAsTheWindFieldSays) {
  Scene scene = testing::make_test_scene(300, 8, 20.0f);
  WindConfig config;
  config.direction = 60;
  config.strength = 30;  // strong, so that the two axes' order shows (it moves the top by ~0.03)
  config.gust_scale = 6;
  scene.wind = wind_field(config);
  const auto path = scratch("windy.glb");
  GltfOptions options;
  options.instancing = GltfInstancing::node_per_instance;
  write_gltf(scene, path, options);
  const Glb glb = read_glb(path);
  std::size_t flowers = 0;
  double largest_lean = 0;
  for (const auto& node : glb.json["nodes"]) {
    if (!node.contains("mesh") || !node.contains("scale") || !node.contains("rotation")) continue;
    ++flowers;
    const double east = node["translation"][0], north = -node["translation"][2].get<double>();
    const double x = node["rotation"][0], y = node["rotation"][1], z = node["rotation"][2], w = node["rotation"][3];
    // The quaternion's image of +y: the second column of its matrix.
    const double top[3] = {2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x)};
    const auto r = lean_rotation(scene.wind->lean(east, north, 0));
    const double expected[3] = {r[2], r[8], -r[5]};  // R * (0, 0, 1) over ENU, into glTF's frame
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(top[c], expected[c], 2e-6) << "flower at " << east << ", " << north;
    largest_lean = std::max(largest_lean, std::acos(std::clamp(expected[1], -1.0, 1.0)));
  }
  EXPECT_EQ(flowers, 300u);
  EXPECT_GT(largest_lean, 0.2);  // radians: the wind really leans them
}

TEST(GltfWriter, SceneWithoutTerrainOrInstancesIsValid) {
  Scene scene = testing::make_test_scene(0, 4, 10.0f);
  scene.terrain = Mesh{};
  const auto path = scratch("models_only.glb");
  write_gltf(scene, path);
  const Glb glb = read_glb(path);
  EXPECT_EQ(glb.json["meshes"].size(), 3u);
  expect_validator_accepts(path);
}

TEST(GltfWriter, MalformedMeshIsRefusedWithoutOutput) {
  Scene scene = testing::make_test_scene(10, 4, 10.0f);
  scene.models[1].triangles.push_back({0, 1, 100000});
  const auto path = scratch("broken.glb");
  std::filesystem::remove(path);
  EXPECT_THROW(write_gltf(scene, path), Error);
  EXPECT_FALSE(std::filesystem::exists(path));
}

}  // namespace
}  // namespace wangscape
