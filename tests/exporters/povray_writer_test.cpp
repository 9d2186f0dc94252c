// POV-Ray's numbers (issue 25): the fixed-point writer took |value| x 10^decimals in 63 bits and
// wrapped beyond, so a camera at east 1e30 m was written as the origin. Larger values are now
// written in full, as std::to_chars writes them.
#include "exporters/povray_writer.h"

#include <gtest/gtest.h>

#include <locale>
#include <sstream>

#include "core/error.h"
#include "scene/scene.h"
#include "scene/shading_light.h"
#include "scene/sun.h"

namespace wangscape {
namespace {

TEST(PovrayWriter, NumbersBeyondSixtyThreeBitsAreWrittenInFull) {
  Camera camera;
  camera.position = {1e30, 2.5, -3e16};  // east, north, up (POV-Ray: <x, up, north>)
  camera.target = {0, 0, 0};
  camera.fov_degrees = 60;
  const std::string text = povray_camera_and_sun(camera, Sun{});
  EXPECT_NE(text.find("location <1000000000000000019884624838656.000,-30000000000000000.000,2.500>"), std::string::npos)
      << text;
  EXPECT_NE(text.find("look_at <0.000,0.000,0.000>"), std::string::npos) << text;
}

// One look (issue 39): POV-Ray's sun is the one shading model's, times the scene's strength.
TEST(PovrayWriter, TheSunIsTheOneShadingModelsTimesItsStrength) {
  Camera camera;
  camera.position = {0, 0, 2};
  camera.target = {0, 10, 0};
  Sun sun;
  sun.strength = 0.5;
  const Vec3f color = with_sun(ShadingSettings{}, sun).sun_color;
  EXPECT_FLOAT_EQ(color[0], 0.5f * ShadingSettings{}.sun_color[0]);
  std::ostringstream expected;
  expected.imbue(std::locale::classic());
  expected.setf(std::ios::fixed);
  expected.precision(4);
  expected << "color rgb <" << color[0] << "," << color[1] << "," << color[2] << ">";
  const std::string text = povray_camera_and_sun(camera, sun);
  EXPECT_NE(text.find(expected.str()), std::string::npos) << expected.str() << " not in\n" << text;
}

// Models are named by what they are (issue 40): a species' grass was `Sunflower_12` before.
TEST(PovrayWriter, ModelsAreNamedByTheirSpecies) {
  std::vector<Mesh> models(6);
  models[0].name = "sunflower_0";
  models[1].name = "meadow_grass_3";
  models[2].name = "sunflower_0 proxy";
  models[3].name = "2nd tulip.v2";  // a user's file stem
  models[4].name = "";
  models[5].name = "sunflower_0";  // used twice
  EXPECT_EQ(povray_model_names(models), (std::vector<std::string>{"Sunflower_0", "Meadow_grass_3", "Sunflower_0_proxy",
                                                                  "Model_2nd_tulip_v2", "Model_", "Sunflower_0_v5"}));
  // The instances name them.
  std::ostringstream out;
  {
    PovrayInstanceWriter writer(out, povray_model_names(models));
    InstanceBatch batch;
    batch.push_back(1, 2, 3, 0, 1, 1, 0);
    writer.write(batch);
    batch.variant[0] = 6;  // past the models
    EXPECT_THROW(writer.write(batch), Error);
  }
  EXPECT_EQ(out.str().rfind("object{Meadow_grass_3 ", 0), 0u) << out.str();
}

}  // namespace
}  // namespace wangscape
