// The field painted beyond camera-aware `far` against the field itself: the same flat field
// rendered by the Embree reference twice, once painted beyond `far` and once with proxies to its
// end. Over the pixels that see the ground beyond `far`, the painted band must carry the mean
// color and the specks of yellow the flowers show from the camera (issue 23, item 4).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "core/color.h"
#include "renders/trace/embree_reference.h"
#include "scene/scene.h"
#include "scene/scene_file.h"
#include "tests/scene/far_field_scene.h"

namespace wangscape {
namespace {

// A flat 700 m field seen from 20 m above its southern part (so that the ground beyond `far` shows
// over the near flowers), the heads turned towards the camera.
Scene scene_of(double far) {
  testing::FarFieldScene scene;
  scene.flat_size = 700;
  scene.facing = 170;
  scene.camera = "[0.0, -300.0, 20.0]";
  scene.target = "[0.0, 0.0, 0.0]";
  scene.far = far;
  scene.width = 192;
  scene.height = 108;
  return make_scene(parse_scene_config(testing::far_field_scene_text(scene), "test.toml", "."));
}

ReferenceImage render(const Scene& scene) {
  ReferenceOptions options;
  options.samples_per_pixel = 4;
  options.threads = 2;
  options.shading.ao_rays = 0;  // the open sky, as POV-Ray's ambient light and the far field's look
  return render_reference(scene, options);
}

struct BandStats {
  double r = 0, g = 0, b = 0;  // mean sRGB, 0..1
  double yellow = 0;           // share of sunflower-yellow pixels
  int pixels = 0;
};

// Over the pixels whose nearest hit in `band_of` lies between `from` and `to` meters.
BandStats band_stats(const ReferenceImage& image, const ReferenceImage& band_of, double from, double to) {
  BandStats s;
  for (std::size_t p = 0; p < band_of.depth.size(); ++p) {
    if (!(band_of.depth[p] > from && band_of.depth[p] < to)) continue;
    const double r = image.image.pixels[3 * p] / 255.0, g = image.image.pixels[3 * p + 1] / 255.0,
                 b = image.image.pixels[3 * p + 2] / 255.0;
    s.r += r, s.g += g, s.b += b;
    // Sunflower yellow (sRGB), as tests/renders/povray_render_test.cpp counts it.
    s.yellow += r > 0.45 && g > 0.28 && b < 0.5 * g && r > 1.2 * b + 0.25;
    ++s.pixels;
  }
  if (s.pixels) s.r /= s.pixels, s.g /= s.pixels, s.b /= s.pixels, s.yellow /= s.pixels;
  return s;
}

TEST(FarField, ThePaintedBandShowsWhatTheFlowersThereShow) {
  constexpr double kFar = 60;
  const Scene painted = scene_of(kFar);
  const Scene flowers = scene_of(2000);  // proxies to the field's end, nothing painted
  const ReferenceImage a = render(painted);
  const ReferenceImage b = render(flowers);
  // The ground beyond far (the fade over its last tenth left out), short of the field's end.
  const BandStats paint = band_stats(a, a, kFar * 1.05, 600);
  const BandStats truth = band_stats(b, a, kFar * 1.05, 600);
  ASSERT_GT(paint.pixels, 400);
  // The figures behind the tolerances below, on every run.
  std::printf(
      "far band (%d pixels): painted sRGB (%.3f, %.3f, %.3f), yellow %.3f; flowers (%.3f, %.3f, %.3f), yellow %.3f\n",
      paint.pixels, paint.r, paint.g, paint.b, paint.yellow, truth.r, truth.g, truth.b, truth.yellow);
  EXPECT_GT(truth.yellow, 0.03) << "the reference shows no heads: the scene is wrong";
  // Tolerances from measurement (see the commit): the means within 0.04, the yellow share within
  // half of the reference's.
  EXPECT_NEAR(paint.r, truth.r, 0.04);
  EXPECT_NEAR(paint.g, truth.g, 0.04);
  EXPECT_NEAR(paint.b, truth.b, 0.04);
  EXPECT_NEAR(paint.yellow, truth.yellow, 0.5 * truth.yellow);
}

}  // namespace
}  // namespace wangscape
