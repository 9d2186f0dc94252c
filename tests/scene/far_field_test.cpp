// The far field's canopy look (scene/far_field.h): what a square of the field shows along the
// view at grazing angles: the petals' yellow apart from the rest, and the lower the ray, the more
// of the ground the canopy hides.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "scene/camera_view.h"
#include "scene/far_field.h"
#include "scene/scene.h"
#include "scene/scene_file.h"
#include "tests/scene/far_field_scene.h"

namespace wangscape {
namespace {

// A flat field seen from its southern edge looking north; heads facing `facing` degrees.
Scene field_facing(double facing) {
  testing::FarFieldScene scene;
  scene.facing = facing;
  return make_scene(parse_scene_config(testing::far_field_scene_text(scene), "test.toml", "."));
}

FieldTexture texture_of(const Scene& scene) {
  const SceneField& field = *scene.field;
  const auto first = scene.models.begin() + std::ptrdiff_t(field.proxy_offset);
  const std::vector<Mesh> proxies(first, first + std::ptrdiff_t(field.filled.variants));
  return FieldTexture(field, proxies, field.view->far_view_direction(), scene.sun);
}

TEST(FarFieldLook, ShowsThePetalsYellowAndTheRestGreen) {
  // Heads facing south (180) face the camera, which looks north; facing north (0) they turn away
  // and show the backs of their petals, darker (a test of the lit pixels, not of the shares:
  // tests/renders/far_field_render_test.cpp).
  for (const double facing : {180.0, 0.0}) {
    const FieldTexture texture = texture_of(field_facing(facing));
    for (const double sine : FieldTexture::kLookSines) {
      const CanopyLook look = texture.look(sine);
      EXPECT_GT(look.yellow.coverage, 0.01) << "facing " << facing << ", sine " << sine;
      EXPECT_LT(look.yellow.coverage, 0.5) << "facing " << facing << ", sine " << sine;
      EXPECT_GT(look.yellow.r, 3 * look.yellow.b);
      EXPECT_GT(look.yellow.r, look.rest.r);
      EXPECT_GT(look.rest.g, look.rest.r);
      const FieldSplat mean = look.mean();
      EXPECT_NEAR(mean.r, look.yellow.r * look.yellow.coverage + look.rest.r * look.rest.coverage, 1e-5);
    }
  }
}

TEST(FarFieldLook, TheLowerTheRayTheMoreOfTheGroundIsHidden) {
  const FieldTexture texture = texture_of(field_facing(180));
  double previous = 1.0;
  for (const double sine : FieldTexture::kLookSines) {
    const CanopyLook look = texture.look(sine);
    EXPECT_GT(look.coverage, 0.0);
    EXPECT_LE(look.coverage, previous + 1e-6) << "sine " << sine;
    previous = look.coverage;
  }
  EXPECT_GT(texture.look(0.05).coverage, 0.95);  // at 3 degrees nothing of the ground shows
  // Between the sines rendered the look is interpolated; outside them it is the nearest one.
  const CanopyLook low = texture.look(0.01), lowest = texture.look(0.05);
  EXPECT_EQ(low.coverage, lowest.coverage);
  const float between = texture.look(0.07).coverage;
  EXPECT_LE(between, lowest.coverage);
  EXPECT_GE(between, texture.look(0.1).coverage);
}

}  // namespace
}  // namespace wangscape
