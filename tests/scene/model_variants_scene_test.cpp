// A user's models as several variants (issue 38, part 2) and their stand-ins (part 3), through
// the scene file: lists, folders and objects as variants in [models] mesh and [[species]] model,
// their errors naming file, line and key, and the camera-aware proxies they get.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "scene/scene.h"
#include "scene/scene_file.h"
#include "scene/species.h"
#include "tests/scene/scene_file_support.h"

namespace wangscape {
namespace {

namespace fs = std::filesystem;
using scene_file_test::error_of;
using scene_file_test::parse;

const fs::path kModels = fs::path(WANGSCAPE_SOURCE_DIR) / "tests" / "data" / "models";

void expect_contains(const std::string& text, const std::string& part) {
  EXPECT_NE(text.find(part), std::string::npos) << "'" << text << "' should contain '" << part << "'";
}

TEST(SceneFileModelLists, ListsAndObjectKeysAreRead) {
  const SceneConfig models = parse("[models]\nmesh = [\"a.obj\", \"dir/b.glb\"]\nmesh_objects = \"variants\"\n");
  EXPECT_EQ(models.models.mesh, (std::vector<fs::path>{"/base/a.obj", "/base/dir/b.glb"}));
  EXPECT_TRUE(models.models.mesh_objects_variants);
  const SceneConfig species = parse("[[species]]\nname = \"t\"\nmodel = [\"tulips/\", \"x.fbx\"]\nup_axis = \"y\"\n");
  ASSERT_EQ(species.species.size(), 1u);
  EXPECT_EQ(species.species[0].mesh, (std::vector<fs::path>{"/base/tulips/", "/base/x.fbx"}));
  EXPECT_TRUE(species.species[0].mesh_y_up);
  EXPECT_FALSE(species.species[0].mesh_objects_variants);
  EXPECT_TRUE(parse("[models]\nmesh = \"\"\n").models.mesh.empty());  // no mesh: the sunflowers
}

TEST(SceneFileModelLists, BadListsAreRefusedNamingFileLineAndKey) {
  const std::pair<const char*, const char*> cases[] = {
      {"[models]\nmesh = [\"a.obj\", \"b.obj\"]\nvariants = 3\n",
       "test.toml:3: 'models.variants' cannot be given with a list of models in models.mesh: the list gives the "
       "count (2)"},
      {"[models]\nmesh = []\n", "test.toml:2: 'models.mesh' must list model files or folders"},
      {"[models]\nmesh = [\"a.obj\", 3]\n", "test.toml:2: 'models.mesh' must list model files or folders"},
      {"[models]\nmesh_objects = \"variants\"\n", "test.toml:2: 'models.mesh_objects' needs models.mesh"},
      {"[models]\nmesh = \"a.obj\"\nmesh_objects = \"all\"\n", "test.toml:3: 'models.mesh_objects' must be \"one\""},
      {"[[species]]\nname = \"s\"\nmodel = [\"a.obj\"]\nvariants = 4\n",
       "test.toml:4: 'species.s.variants' cannot be given with a list of models"},
      {"[[species]]\nname = \"s\"\nmodel = \"a.obj\"\nvariants = 4\n",
       "test.toml:4: 'species.s.variants' must be 1 for a mesh file: its variants are the files of a list or a folder"},
      {"[[species]]\nname = \"s\"\nmodel = [\"a.obj\"]\ntriangle_budget = 400\n",
       "test.toml:4: 'species.s.triangle_budget' does not apply to a mesh file"},
      {"[[species]]\nname = \"s\"\nmesh_objects = \"variants\"\n",
       "test.toml:3: 'species.s.mesh_objects' needs a mesh file as the model"},
  };
  for (const auto& [text, expected] : cases) expect_contains(error_of(text), expected);
  std::string many = "[models]\nmesh = [";
  for (int i = 0; i < 1001; ++i) many += std::string(i ? ", " : "") + "\"m" + std::to_string(i) + ".obj\"";
  expect_contains(error_of(many + "]\n"), "test.toml:2: 'models.mesh' lists 1001 models; at most 1000");
}

// The tiny flat field of the tests, with `species` and camera-aware export (full models to 6 m,
// proxies to 30 m).
SceneConfig tiny_field(const std::string& species) {
  return parse_scene_config(
      "[terrain]\nflat_size = 60.0\n[tiles]\npoints_per_tile = 10\nrelaxation_rounds = 0\n[camera]\nposition = "
      "[0.0, -16.0, 2.2]\ntarget = [0.0, 0.0, 1.2]\n[camera_aware]\nenabled = true\nnear = 6.0\nfar = 30.0\n" +
          species,
      "test.toml", kModels);
}

// A folder of four tulips is a species of four variants: drawn per plant as a plant kind's are,
// each with a stand-in of at most proxy_triangles, named by species and variant.
TEST(SpeciesModels, AFolderIsASpeciesOfItsVariantsWithStandIns) {
  const Scene scene = make_scene(
      tiny_field("[[species]]\nname = \"tulip\"\nmodel = \"tulips\"\n[[species]]\nname = \"grass\"\nvariants = 2\n"
                 "triangle_budget = 100\n"));
  const std::size_t full = scene.field->proxy_offset;
  ASSERT_EQ(full, 6u);
  ASSERT_EQ(scene.models.size(), 12u);
  for (int v = 0; v < 4; ++v) {
    const std::string name = "tulip_" + std::to_string(v);
    EXPECT_EQ(scene.models[v].name, name);
    EXPECT_EQ(scene.models[v].triangle_count(), 576u);
    EXPECT_EQ(scene.models[full + v].name, name + " proxy");
    EXPECT_LE(scene.models[full + v].triangle_count(), 400u);
    EXPECT_EQ(scene.field->species_of_model(v), 0u);
    EXPECT_EQ(scene.field->species_of_model(full + v), 0u);
  }
  EXPECT_EQ(scene.models[4].name, "grass_0");
  EXPECT_EQ(scene.field->species_of_model(5), 1u);
  // The stand-ins' figures: the tulips' only (the grass proxies are procedural).
  ASSERT_EQ(scene.stand_ins.size(), 4u);
  for (int v = 0; v < 4; ++v) {
    const StandInFigures& s = scene.stand_ins[v];
    EXPECT_EQ(s.name, "tulip_" + std::to_string(v) + " proxy");
    EXPECT_EQ(s.triangles, scene.models[full + v].triangle_count());
    EXPECT_EQ(s.model_triangles, 576u);
    EXPECT_TRUE(std::isfinite(s.error));
    EXPECT_GE(s.error, 0.0);
    EXPECT_LT(s.error, 0.1);
  }
  // Every variant is drawn, full or as its stand-in.
  std::set<std::uint16_t> drawn;
  scene.instances([&](const InstanceBatch& batch) { drawn.insert(batch.variant.begin(), batch.variant.end()); });
  for (std::uint16_t v = 0; v < 4; ++v) EXPECT_TRUE(drawn.contains(v) || drawn.contains(std::uint16_t(full + v))) << v;
}

// mesh_objects = "variants": the bunch's four objects are four variants of [models].
TEST(SpeciesModels, ObjectsOfOneFileAreModelsVariants) {
  const Scene scene = make_scene(tiny_field("[models]\nmesh = \"tulip_bunch.obj\"\nmesh_objects = \"variants\"\n"));
  ASSERT_EQ(scene.field->proxy_offset, 4u);
  ASSERT_EQ(scene.models.size(), 8u);
  EXPECT_EQ(scene.field->filled.variants, 4);
  EXPECT_EQ(scene.models[0].name, "tulip_1_0");
  EXPECT_EQ(scene.models[7].name, "tulip_4_3 proxy");
  EXPECT_EQ(scene.stand_ins.size(), 4u);
}

TEST(SpeciesModels, LoadErrorsNameTheKeyAndTheFile) {
  const fs::path dir = fs::temp_directory_path() / ("wangscape_variants_scene_" + std::to_string(::getpid()));
  fs::create_directories(dir / "empty");
  std::ofstream(dir / "not_a_model.glb") << "text, not a model";
  const auto error = [&](const std::string& species) {
    try {
      make_scene(parse_scene_config(
          "[terrain]\nflat_size = 40.0\n[tiles]\narea = [-8.0, -8.0, 8.0, 8.0]\n[[species]]\nname = \"s\"\n" + species,
          "test.toml", dir));
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  expect_contains(error("model = \"empty\"\n"),
                  "test.toml:7: 'species.s.model' " + (dir / "empty").string() + ": the folder holds no model file");
  expect_contains(
      error("model = [\"" + (kModels / "tulip.obj").string() + "\", \"not_a_model.glb\"]\n"),
      "test.toml:7: 'species.s.model' " + (dir / "not_a_model.glb").string() + ": not a model Assimp reads");
  fs::remove_all(dir);
}

}  // namespace
}  // namespace wangscape
