// The batch file and its expansion (renders/batch/batch_file.h): viewpoints from the ground, suns,
// input hashes, errors with file and line. The CLI runs are in tests/cli/batch.cmake.
#include "renders/batch/batch_file.h"
#include "scene/scene.h"
#include "scene/scene_ground.h"
#include "templates/mesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

namespace wangscape {
namespace {

// A flat 120 m ground, flowers on [-12, 12]^2 (as tests/cli/tiny_scene.toml).
const char* const kScene = R"(name = "t"
[terrain]
flat_size = 120.0
[tiles]
area = [-12.0, -12.0, 12.0, 12.0]
[camera]
position = [0.0, -16.0, 2.2]
target = [0.0, 0.0, 1.2]
)";

BatchConfig batch(const std::string& rest) {
  BatchConfig config = parse_batch_config("scene = \"default\"\n" + rest, "b.toml", ".");
  config.scene = parse_scene_config(kScene, "s.toml", ".");  // the tiny flat scene instead
  return config;
}

TEST(BatchFile, FlowerViewpointsStandInTheFieldAtHeadHeight) {
  const auto tasks = expand_batch(batch("[[viewpoints]]\nkind = \"flowers\"\ncount = 5\neye_height = 1.5\n"));
  ASSERT_EQ(tasks.size(), 5u);
  int at_head_height = 0;
  for (const auto& t : tasks) {
    EXPECT_LE(std::abs(t.camera.position[0]), 12.0 + 5.0);  // moved out of the plants by at most 5 m
    EXPECT_LE(std::abs(t.camera.position[1]), 12.0 + 5.0);
    EXPECT_GE(t.camera.position[2], 1.5);  // or lifted above them
    at_head_height += t.camera.position[2] == 1.5;
    EXPECT_GE(std::hypot(t.camera.target[0] - t.camera.position[0], t.camera.target[1] - t.camera.position[1]), 5.0);
  }
  EXPECT_GT(at_head_height, 0);
}

// A head-height eye stands clear of the plants (issue 40: a still taken from inside a sunflower had
// a leaf filling a corner): over 12 flower and 9 grid viewpoints of the tiny field, no plant's
// reach (its widest leaf, scaled) holds an eye below that plant's top.
TEST(BatchFile, HeadHeightEyesStandClearOfThePlants) {
  const BatchConfig config =
      batch("[[viewpoints]]\nkind = \"flowers\"\ncount = 12\n[[viewpoints]]\nkind = \"grid\"\ngrid = [3, 3]\n");
  const auto tasks = expand_batch(config);
  ASSERT_EQ(tasks.size(), 21u);
  const Scene scene = make_scene(config.scene);
  std::vector<MeshExtent> extents;
  for (const Mesh& model : scene.models) extents.push_back(measure_extent(model));
  int plants_near = 0;
  for (const auto& t : tasks) {
    const auto& eye = t.camera.position;
    scene.field->place_in(Extent{eye[0] - 3, eye[1] - 3, eye[0] + 3, eye[1] + 3}, [&](const InstanceBatch& b) {
      for (std::size_t i = 0; i < b.size(); ++i) {
        const MeshExtent& e = extents[b.variant[i]];
        const double distance = std::hypot(eye[0] - b.x[i], eye[1] - b.y[i]);
        plants_near += distance < 1.5;
        EXPECT_TRUE(eye[2] >= b.z[i] + e.height * b.scale[i] || distance >= e.radius * b.scale[i])
            << t.viewpoint << ": " << distance << " m from a plant of reach " << e.radius * b.scale[i];
      }
    });
  }
  EXPECT_GT(plants_near, 20);  // the field is dense around the eyes: the test can fail
}

TEST(BatchFile, ExpandsViewpointsTimesSunsTimesEnginesWithDistinctHashesAndOneScene) {
  const auto tasks =
      expand_batch(batch("engines = [\"povray\", \"blender\"]\n[[viewpoints]]\nkind = \"grid\"\ngrid = [2, 1]\n"
                         "[sun]\nangles = [[100.0, 20.0], [200.0, 40.0], [300.0, 60.0]]\n"));
  ASSERT_EQ(tasks.size(), 2u * 3u * 2u);
  std::set<std::string> hashes, scenes;
  for (const auto& t : tasks) hashes.insert(t.input_hash), scenes.insert(t.scene_key);
  EXPECT_EQ(hashes.size(), tasks.size());
  EXPECT_EQ(scenes.size(), 1u);  // camera, sun and engine never change the scene folder
  EXPECT_EQ(tasks[1].engine, RenderEngine::blender);
  EXPECT_DOUBLE_EQ(tasks[2].sun.azimuth, 200.0);
  const std::string grid = "[[viewpoints]]\nkind = \"grid\"\ngrid = [2, 1]\n";
  EXPECT_EQ(expand_batch(batch(grid))[0].input_hash, expand_batch(batch(grid))[0].input_hash);  // deterministic
}

// Summits see the field (issue 40): on the default scene's DEM the crater rim's highest summit
// gave a still of near ground and sky, its own shoulder hiding the field 6 km away. Every summit
// kept sees the field's centre (1 m above the ground there), checked every metre along the line.
TEST(BatchFile, SummitsSeeTheField) {
  const BatchConfig config =
      parse_batch_config("scene = \"default\"\n[[viewpoints]]\nkind = \"summits\"\ncount = 4\n", "b.toml", ".");
  const auto tasks = expand_batch(config);
  ASSERT_EQ(tasks.size(), 4u);
  const SceneGround ground =
      SceneGround::load(config.scene.terrain, config.scene.masks, config.scene.tiles.area_latlon);
  const Extent field = field_area(config.scene, ground);
  const double cx = (field.min_x + field.max_x) / 2, cy = (field.min_y + field.max_y) / 2;
  const std::array<double, 3> flowers{cx, cy, *ground.height(cx, cy) + 1.0};
  for (const auto& t : tasks) {
    const auto& eye = t.camera.position;
    const double length = std::hypot(flowers[0] - eye[0], flowers[1] - eye[1]);
    for (double d = 1; d < length; d += 1) {
      const double k = d / length;
      const auto h = ground.height(eye[0] + k * (flowers[0] - eye[0]), eye[1] + k * (flowers[1] - eye[1]));
      ASSERT_TRUE(!h || *h <= eye[2] + k * (flowers[2] - eye[2]) + 0.5) << t.viewpoint << " at " << d << " m";
    }
  }
}

TEST(BatchFile, PathLooksAlongThePath) {
  const auto tasks = expand_batch(batch("[[viewpoints]]\nkind = \"path\"\nenu = [[0.0, 0.0], [10.0, 0.0]]\n"));
  ASSERT_EQ(tasks.size(), 2u);
  for (const auto& t : tasks) EXPECT_GT(t.camera.target[0], t.camera.position[0]);  // eastwards, also the last
}

TEST(BatchFile, SunTimesFromToStepAndNight) {
  const auto tasks = expand_batch(
      batch("[sun]\nfrom = 2024-07-15T12:00:00+00:00\nto = 2024-07-15T14:00:00+00:00\nstep_minutes = 60\n"));
  ASSERT_EQ(tasks.size(), 2u * 3u);  // the default rule: 2 flower cameras
  EXPECT_EQ(tasks[1].sun.label, "2024-07-15T13:00:00Z");
  EXPECT_GT(tasks[0].sun.elevation, 0.0);
  EXPECT_THROW(expand_batch(batch("[sun]\ntimes = [2024-07-15T00:00:00+00:00]\n")), Error);  // night at 0, 0
}

TEST(BatchFile, ErrorsNameTheFileAndTheLine) {
  try {
    parse_batch_config("scene = \"default\"\n[[viewpoints]]\ncont = 3\n", "b.toml", ".");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "b.toml:3: unknown key 'viewpoints.cont'");
  }
  EXPECT_THROW(parse_batch_config("scene = \"default\"\nengines = [\"cycles\"]\n", "b.toml", "."), Error);
  BatchConfig missing = batch("");
  missing.dems = {"/no/such/dem.tif"};
  try {
    expand_batch(missing);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/no/such/dem.tif"), std::string::npos);
  }
}

TEST(BatchFile, TheExampleIsTwoViewpointsTimesTwoSuns) {
  const auto config = parse_batch_config(example_batch_text(), "<example batch>", ".");
  EXPECT_EQ(config.viewpoints.size(), 1u);
  EXPECT_EQ(config.viewpoints[0].count, 2);
  EXPECT_EQ(config.suns.size(), 2u);
}

}  // namespace
}  // namespace wangscape
