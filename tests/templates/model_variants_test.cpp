#include "templates/model_variants.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace wangscape {
namespace {

namespace fs = std::filesystem;

const fs::path kModels = fs::path(WANGSCAPE_SOURCE_DIR) / "tests" / "data" / "models";

// A fresh directory per test, removed afterwards.
class ModelVariants : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("wangscape_model_variants_" + std::to_string(::getpid()) + "_" + std::string(info->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name, std::ios::binary) << text;
    return dir_ / name;
  }
  // The message of the Error load_model_variants throws ("" if none).
  static std::string error_of(const std::vector<fs::path>& named, bool objects = false) {
    try {
      load_model_variants(named, objects, {});
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  }
  fs::path dir_;
};

constexpr const char* kTriangle = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";

void expect_contains(const std::string& text, const std::string& part) {
  EXPECT_NE(text.find(part), std::string::npos) << "'" << text << "' should contain '" << part << "'";
}

TEST_F(ModelVariants, AListOfFilesGivesOneVariantEachInOrder) {
  const auto variants = load_model_variants(
      {kModels / "tulips" / "tulip_3.obj", kModels / "tulip.obj", kModels / "leaf_card.gltf"}, false, {});
  ASSERT_EQ(variants.size(), 3u);
  EXPECT_EQ(variants[0].name, "tulip_3");
  EXPECT_EQ(variants[1].name, "tulip");
  EXPECT_EQ(variants[2].name, "leaf_card");
  EXPECT_EQ(variants[0].triangle_count(), 576u);
  EXPECT_EQ(variants[1].triangle_count(), 10u);
  EXPECT_EQ(variants[2].triangle_count(), 2u);
}

TEST_F(ModelVariants, AFolderGivesItsModelFilesSortedByName) {
  // The tulips' folder holds its MTL too, which is no model.
  const auto tulips = model_files_in(kModels / "tulips");
  ASSERT_EQ(tulips.size(), 4u);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(tulips[i].filename(), "tulip_" + std::to_string(i + 1) + ".obj");
  // Written out of order, with files that are no models and a subfolder named like one.
  write("c.obj", kTriangle);
  write("a.ply",
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 1\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  write("b.mtl", "newmtl x\nKd 1 0 0\n");
  write("notes.txt", "not a model\n");
  fs::create_directories(dir_ / "d.obj");
  const auto files = model_files_in(dir_);
  ASSERT_EQ(files.size(), 2u);
  EXPECT_EQ(files[0].filename(), "a.ply");
  EXPECT_EQ(files[1].filename(), "c.obj");
  const auto variants = load_model_variants({dir_, kModels / "tulip.obj"}, false, {});
  ASSERT_EQ(variants.size(), 3u);
  EXPECT_EQ(variants[2].name, "tulip");
  const auto four = load_model_variants({kModels / "tulips"}, false, {});
  ASSERT_EQ(four.size(), 4u);
  // Taller stems and larger heads from tulip_1 to tulip_4 (tests/data/models/make_own_models.py).
  for (int i = 1; i < 4; ++i) EXPECT_GT(measure_extent(four[i]).height, measure_extent(four[i - 1]).height);
}

TEST_F(ModelVariants, EachObjectOfAFileIsAVariantWhenAsked) {
  const fs::path bunch = kModels / "tulip_bunch.obj";
  const auto one = load_model_variants({bunch}, false, {});
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].triangle_count(), 4 * 576u);
  const auto objects = load_model_variants({bunch}, true, {});
  ASSERT_EQ(objects.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(objects[i].name, "tulip_" + std::to_string(i + 1));
    EXPECT_EQ(objects[i].triangle_count(), 576u);
    ASSERT_EQ(objects[i].materials.size(), 2u);  // its stem and head, colours from the MTL
    EXPECT_EQ(objects[i].materials[1].name, "head");
    // Laid 0.3 m apart in the file, each stands on the origin.
    const MeshExtent extent = measure_extent(objects[i]);
    EXPECT_NEAR(extent.min[0] + extent.max[0], 0, 1e-4);
    EXPECT_NEAR(extent.min[1] + extent.max[1], 0, 1e-4);
    EXPECT_NEAR(extent.min[2], 0, 1e-6);
    if (i > 0) {
      EXPECT_GT(extent.height, measure_extent(objects[i - 1]).height);
    }
  }
  // A PLY file is one object; a file of one object one variant.
  EXPECT_EQ(load_model_variants({kModels / "cube.ply", kModels / "tulip.obj"}, true, {}).size(), 2u);
}

TEST_F(ModelVariants, ErrorsNameTheFileOrFolder) {
  fs::create_directories(dir_ / "empty");
  write("empty/readme.txt", "no models here\n");
  expect_contains(error_of({dir_ / "empty"}), (dir_ / "empty").string() + ": the folder holds no model file");
  write("broken.glb", "this is not a binary glTF");
  expect_contains(error_of({kModels / "tulip.obj", dir_ / "broken.glb"}),
                  (dir_ / "broken.glb").string() + ": not a model Assimp reads");
  expect_contains(error_of({dir_ / "missing.obj"}), "missing.obj: no such model file");
  // 1001 objects in one file: more variants than are drawn.
  std::string many;
  for (int i = 0; i < 1001; ++i) many += "o leaf" + std::to_string(i) + "\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n";
  const fs::path crowd = write("crowd.obj", many);
  EXPECT_EQ(load_model_variants({crowd}, false, {}).size(), 1u);
  expect_contains(error_of({crowd}, true), crowd.string() + ": takes the model variants to 1001; at most 1000");
}

}  // namespace
}  // namespace wangscape
