// POV-Ray's numbers (issue 25): the fixed-point writer took |value| x 10^decimals in 63 bits and
// wrapped beyond, so a camera at east 1e30 m was written as the origin. Larger values are now
// written in full, as std::to_chars writes them.
#include "exporters/povray_writer.h"

#include <gtest/gtest.h>

#include "scene/scene.h"
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

}  // namespace
}  // namespace wangscape
