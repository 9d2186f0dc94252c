// The scene file: every key's default, every range refused with the file, line and key,
// unknown keys named, a tile-set JSON as [tiles] set, and errors found after parsing (a camera
// off the DEM) still naming the file and line.
#include "scene/scene_file.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <string>

#include "scene/scene.h"
#include "tests/scene/scene_file_support.h"

namespace wangscape {
namespace {

using scene_file_test::error_of;
using scene_file_test::parse;

TEST(SceneFile, EmptyFileGivesTheDocumentedDefaults) {
  const SceneConfig c = parse("");
  EXPECT_EQ(c.name, "wangscape");
  EXPECT_TRUE(c.terrain.dem.empty());
  EXPECT_FALSE(c.terrain.origin_latitude);
  EXPECT_FALSE(c.terrain.crop);
  EXPECT_EQ(c.terrain.flat_size, 200.0);
  EXPECT_EQ(c.tiles.set, "cohen8");
  EXPECT_EQ(c.tiles.tile_size, 4.0);
  EXPECT_EQ(c.tiles.points_per_tile, 20);
  EXPECT_EQ(c.tiles.relaxation_rounds, 8);
  EXPECT_EQ(c.tiles.seed, 1u);
  EXPECT_EQ(c.tiles.algorithm, TilingAlgorithm::scanline);
  EXPECT_FALSE(c.tiles.area);
  EXPECT_FALSE(c.masks.max_height);
  EXPECT_FALSE(c.masks.min_height);
  EXPECT_FALSE(c.masks.max_slope);
  EXPECT_TRUE(c.masks.mask.empty());
  EXPECT_TRUE(c.masks.fair_edges);
  EXPECT_EQ(c.models.variants, 11);
  EXPECT_EQ(c.models.triangle_budget, 6000u);
  EXPECT_EQ(c.models.seed, 1u);
  EXPECT_TRUE(c.models.mesh.empty());
  EXPECT_FALSE(c.models.mesh_y_up);
  EXPECT_EQ(c.models.scale, 1.0);
  EXPECT_EQ(c.models.scale_jitter, 0.1);
  EXPECT_FALSE(c.models.facing);
  EXPECT_EQ(c.models.facing_jitter, 30.0);
  EXPECT_FALSE(c.camera.position.enu || c.camera.position.enu_ground || c.camera.position.latitude);
  EXPECT_EQ(c.camera.position.height_above_ground, 2.0);
  EXPECT_FALSE(c.camera.heading);
  EXPECT_EQ(c.camera.pitch, 0.0);
  EXPECT_EQ(c.camera.fov, 50.0);
  EXPECT_EQ(c.sun.azimuth, 135.0);
  EXPECT_EQ(c.sun.elevation, 35.0);
  EXPECT_FALSE(c.sun.time_unix);
  EXPECT_EQ(c.sun.strength, 1.0);
  EXPECT_EQ(c.image.width, 640);
  EXPECT_EQ(c.image.height, 360);
  EXPECT_EQ(c.image.antialias, 3);
  EXPECT_EQ(c.image.threads, 0);
  EXPECT_FALSE(c.image.radiosity);
  EXPECT_TRUE(c.exports.povray);
  EXPECT_FALSE(c.exports.blender);
  EXPECT_FALSE(c.exports.gltf);
  EXPECT_FALSE(c.exports.ldi);
  EXPECT_EQ(c.ldi.head_height, 1.7);
  EXPECT_EQ(c.ldi.levels, 7);
  EXPECT_EQ(c.ldi.directions, 8);
  EXPECT_EQ(c.ldi.sky_rays, 8);
}

// One value outside the documented range per key: the error names the file, the line (2: the
// key follows its section header) and the key.
TEST(SceneFile, EveryRangeIsRefusedNamingFileLineAndKey) {
  const std::pair<const char*, const char*> cases[] = {
      {"terrain", "origin_latitude = 91.0\norigin_longitude = 0.0"},
      {"terrain", "origin_longitude = 400.0\norigin_latitude = 0.0"},
      {"terrain", "flat_size = 0.5"},
      {"terrain", "crop = [10.0, 0.0, 0.0, 10.0]"},
      {"tiles", "tile_size = 0.01"},
      {"tiles", "points_per_tile = 0"},
      {"tiles", "relaxation_rounds = 1001"},
      {"tiles", "seed = -1"},
      {"tiles", "algorithm = \"spiral\""},
      {"tiles", "area = [0.0, 0.0, 0.0, 0.0]"},
      {"masks", "max_slope = 91.0"},
      {"masks", "min_height = 10.0\nmax_height = 5.0"},
      {"models", "variants = 0"},
      {"models", "triangle_budget = 1"},
      {"models", "seed = -3"},
      {"models", "scale = 0.0"},
      {"models", "scale_jitter = 0.95"},
      {"models", "facing = 400.0"},
      {"models", "facing_jitter = 181.0"},
      {"models", "up_axis = \"x\""},
      {"camera", "pitch = 90.0"},
      {"camera", "heading = 500.0"},
      {"camera", "fov = 180.0"},
      {"camera", "position = [1.0, nan, 2.0]"},
      {"camera", "target = [1.0, 2.0, inf]"},
      {"camera", "position = [0.0, 0.0, 1e300]"},  // issue 25: built, and written as height 0
      {"camera", "position = [1e30, 0.0, 2.0]"},
      {"camera", "target = [0.0, -2e7]"},
      {"camera", "height_above_ground = 1e300"},
      {"sun", "elevation = 91.0"},
      {"sun", "azimuth = 1e300"},
      {"sun", "strength = 101.0"},
      {"image", "width = 0"},
      {"image", "height = 40000"},
      {"image", "antialias = 10"},
      {"image", "threads = -1"},
      {"camera_aware", "proxy_triangles = 7000"},  // above models.triangle_budget (6000)
      {"ldi", "head_height = 0.0"},
      {"ldi", "levels = 65"},
      {"ldi", "directions = 0"},
      {"ldi", "sky_rays = 2000"},
  };
  for (const auto& [section, line] : cases) {
    const std::string text = std::string("[") + section + "]\n" + line + "\n";
    const std::string key = std::string(line).substr(0, std::string(line).find(' '));
    const std::string error = error_of(text);
    EXPECT_NE(error.find("test.toml:2: '" + std::string(section) + "." + key + "'"), std::string::npos)
        << text << " -> " << error;
  }
}

TEST(SceneFile, WrongTypesAndNonFiniteNumbersAreRefused) {
  EXPECT_NE(error_of("[tiles]\ntile_size = \"big\"\n").find("test.toml:2: 'tiles.tile_size' must be a number"),
            std::string::npos);
  EXPECT_NE(error_of("[tiles]\ntile_size = nan\n").find("'tiles.tile_size' must be a finite number"),
            std::string::npos);
  EXPECT_NE(error_of("[exports]\npovray = 1\n").find("'exports.povray' must be true or false"), std::string::npos);
  EXPECT_NE(error_of("[camera]\nposition = [1.0]\n").find("'camera.position'"), std::string::npos);
  EXPECT_NE(error_of("terrain = 3\n").find("test.toml:1: 'terrain' must be a table"), std::string::npos);
}

TEST(SceneFile, UnknownKeysAreNamedWithTheirLine) {
  EXPECT_NE(error_of("[camera]\nfov = 50.0\n\nfvo = 40.0\n").find("test.toml:4: unknown key 'camera.fvo'"),
            std::string::npos);
  EXPECT_NE(error_of("[sky]\ncolor = 1\n").find("test.toml:1: unknown key 'sky'"), std::string::npos);
  EXPECT_NE(error_of("nmae = \"x\"\n").find("unknown key 'nmae'"), std::string::npos);
}

TEST(SceneFile, RelativePathsResolveAgainstTheSceneFolder) {
  const SceneConfig c = parse(
      "[terrain]\ndem = \"dem/a.dem\"\n[tiles]\nset = \"sets/mine.json\"\n[masks]\nmask = \"m.png\"\n"
      "[models]\nmesh = \"flower.obj\"\nup_axis = \"y\"\n");
  EXPECT_EQ(c.terrain.dem, std::filesystem::path("/base/dem/a.dem"));
  EXPECT_EQ(c.tiles.set, "/base/sets/mine.json");
  EXPECT_EQ(c.masks.mask, std::filesystem::path("/base/m.png"));
  EXPECT_EQ(c.models.mesh, std::vector<std::filesystem::path>{"/base/flower.obj"});
  EXPECT_TRUE(c.models.mesh_y_up);
  EXPECT_EQ(parse("[tiles]\nset = \"cohen12\"\n").tiles.set, "cohen12");  // built-in names stay names
}

TEST(SceneFile, SunTimeNeedsAnOffsetAndExcludesAngles) {
  EXPECT_EQ(*parse("[sun]\ntime = 1970-01-02T01:00:00+01:00\n").sun.time_unix, 86400);
  EXPECT_NE(error_of("[sun]\ntime = 2024-07-20T18:30:00\n").find("UTC offset"), std::string::npos);
  EXPECT_NE(error_of("[sun]\nazimuth = 10.0\ntime = 2024-07-20T18:30:00Z\n").find("cannot be given together"),
            std::string::npos);
}

TEST(SceneFile, KeyLinesNameErrorsFoundLater) {
  const SceneConfig c = parse("name = \"x\"\n[camera]\n\nposition = [1.0, 2.0]\n");
  EXPECT_EQ(c.key_lines.at("camera.position"), 4);
  EXPECT_STREQ(c.error_at("camera.position", "is off the ground").what(),
               "test.toml:4: 'camera.position' is off the ground");
  EXPECT_STREQ(c.error_at("camera.target", "is off the ground").what(), "test.toml: 'camera.target' is off the ground");
}

std::filesystem::path scratch(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("wangscape_scene_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir / name;
}

TEST(Scene, ATileSetJsonFileWorksAsTilesSet) {
  // A complete two-color set of four tiles, written by hand (the layout of docs/tileset-format.md).
  const auto json = scratch("two.json");
  std::ofstream(json) << R"({"name": "mine", "kind": "edge", "tiles": [)"
                      << R"({"n":0,"e":0,"s":0,"w":0}, {"n":0,"e":1,"s":0,"w":1},)"
                      << R"({"n":1,"e":0,"s":1,"w":0}, {"n":1,"e":1,"s":1,"w":1}]})";
  const SceneConfig c = parse_scene_config(
      "[terrain]\nflat_size = 40.0\n[tiles]\nset = \"two.json\"\npoints_per_tile = 4\narea = [-8.0, -8.0, 8.0, 8.0]\n"
      "[models]\nvariants = 1\ntriangle_budget = 400\n",
      "test.toml", json.parent_path());
  const Scene scene = make_scene(c);
  ASSERT_TRUE(scene.field);
  EXPECT_EQ(scene.field->filled.set.tiles.size(), 4u);
  std::uint64_t count = 0;
  scene.instances([&](const InstanceBatch& batch) { count += batch.size(); });
  EXPECT_GT(count, 0u);
}

TEST(Scene, AMissingTileSetFileNamesTheSceneLine) {
  const SceneConfig c = parse("[tiles]\n\nset = \"nowhere.json\"\n");
  try {
    make_scene(c);
    FAIL() << "expected Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("test.toml:3: 'tiles.set'"), std::string::npos) << e.what();
  }
}

TEST(Scene, ACameraOffTheGroundNamesTheSceneLine) {
  const SceneConfig c = parse("[terrain]\nflat_size = 40.0\n[camera]\nposition = [500.0, 0.0]\n");
  try {
    make_scene(c);
    FAIL() << "expected Error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("test.toml:4: 'camera.position'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("not over the ground"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace wangscape
