// The Embree reference renderer against the real Embree, on hand-made scenes whose pictures are
// known: a flat square of ground, boards (vertical quads) as flowers, a camera at eye height
// looking north. Suites are named reference_* so `ctest -R reference` runs them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>
#include <string>

#include "core/error.h"
#include "core/text_file.h"
#include "renders/trace/embree_reference.h"
#include "renders/trace/image_compare.h"

namespace wangscape {
namespace {

constexpr double kPi = std::numbers::pi;

// A vertical board in model space: the plane x = 0, y in [-half, half], z in [0, height], so its
// face looks along +x (east) before yaw; one bright material.
Mesh board(float half, float height) {
  Mesh mesh;
  mesh.name = "board";
  mesh.materials = {{"yellow", {0.9f, 0.7f, 0.1f}, 0.6f, 0.0f}};
  mesh.positions = {{0, -half, 0}, {0, half, 0}, {0, half, height}, {0, -half, height}};
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  mesh.triangle_material = {0, 0};
  return mesh;
}

// Ground: the square [-size, size]^2 at z = 0 as two triangles.
Mesh ground(float size) {
  Mesh mesh;
  mesh.name = "ground";
  mesh.positions = {{-size, -size, 0}, {size, -size, 0}, {size, size, 0}, {-size, size, 0}};
  mesh.triangles = {{0, 1, 2}, {0, 2, 3}};
  return mesh;
}

struct Flower {
  float x, y, z, yaw, scale;
};

// A scene of ground, one board model and these flowers; the camera at (0, -10, 1) looks north
// level with the ground, 60 degrees wide; sun in the south-west, 40 degrees up.
Scene test_scene(std::vector<Flower> flowers, bool with_ground = true) {
  Scene scene;
  scene.name = "test";
  if (with_ground) scene.terrain = ground(60);
  scene.models = {board(1.0f, 2.0f)};
  scene.instances = [flowers](const InstanceSink& sink) {
    InstanceBatch batch;
    for (const Flower& f : flowers) batch.push_back(f.x, f.y, f.z, f.yaw, f.scale, 0, 0);
    if (!batch.empty()) sink(batch);
  };
  scene.camera = Camera{{0, -10, 1}, {0, 0, 1}, 60};
  scene.sun = Sun{200, 40, 1};
  scene.render = RenderSettings{64, 48, 1, false, 0};
  return scene;
}

ReferenceOptions fast(int spp = 1) {
  ReferenceOptions o;
  o.samples_per_pixel = spp;
  o.shading.ao_rays = 2;
  return o;
}

double luminance(const ImageRgb8& img, int x, int y) {
  const Rgb8 c = img.at(x, y);
  return 0.299 * c.r + 0.587 * c.g + 0.114 * c.b;
}

// Variance of the luminance over rows [y0, y1).
double row_variance(const ImageRgb8& img, int y0, int y1) {
  double sum = 0, sum2 = 0;
  int n = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = 0; x < img.width; ++x) {
      const double l = luminance(img, x, y);
      sum += l, sum2 += l * l, ++n;
    }
  const double mean = sum / n;
  return sum2 / n - mean * mean;
}

TEST(reference_render, SameBytesTwiceAndOnOneOrTwoThreads) {
  const Scene scene = test_scene({{0, 0, 0, float(kPi / 2), 1}, {2, 3, 0, 0.3f, 0.8f}});
  ReferenceOptions o = fast(4);
  o.threads = 1;
  const ReferenceImage one = render_reference(scene, o);
  o.threads = 2;
  const ReferenceImage two = render_reference(scene, o);
  const ReferenceImage again = render_reference(scene, o);
  EXPECT_EQ(one.image.pixels, two.image.pixels);
  EXPECT_EQ(two.image.pixels, again.image.pixels);
  EXPECT_EQ(one.coverage, two.coverage);
  EXPECT_EQ(one.stats.instances, 2u);
  EXPECT_EQ(one.stats.primary_rays, 64u * 48u * 4u);
  EXPECT_GT(one.stats.secondary_rays, 0u);
  // Not one color: sky, ground, board and shadow.
  std::set<std::uint32_t> colors;
  for (std::size_t i = 0; i < one.image.pixels.size(); i += 3)
    colors.insert(std::uint32_t(one.image.pixels[i]) << 16 | std::uint32_t(one.image.pixels[i + 1]) << 8 |
                  one.image.pixels[i + 2]);
  EXPECT_GT(colors.size(), 20u);
  // Another seed moves the jitter: other bytes.
  o.seed = 1;
  EXPECT_NE(render_reference(scene, o).image.pixels, one.image.pixels);
}

TEST(reference_render, FlowersChangeThePixelsWhereTheyStandAndNotTheSky) {
  const Scene with = test_scene({{0, 0, 0, float(kPi / 2), 1}});
  const Scene without = test_scene({});
  const ReferenceImage a = render_reference(with, fast()), b = render_reference(without, fast());
  const int w = a.image.width, h = a.image.height;
  // The board (2 m wide, 2 m high, 10 m ahead) spans +-5.5 pixels around the centre.
  int changed_middle = 0;
  for (int y = h / 2 - 4; y < h / 2 + 4; ++y)
    for (int x = w / 2 - 4; x < w / 2 + 4; ++x) changed_middle += a.image.at(x, y) != b.image.at(x, y);
  EXPECT_EQ(changed_middle, 64);
  // The sky left and right of it and above it is the same in both.
  for (int y = 0; y < h / 2; ++y)
    for (int x = 0; x < w; ++x)
      if (std::abs(x - w / 2) > w / 4 || y < h / 8) {
        EXPECT_EQ(a.image.at(x, y), b.image.at(x, y)) << x << ", " << y;
        EXPECT_EQ(a.coverage[std::size_t(y * w + x)], 0.0f);
      }
  EXPECT_EQ(b.stats.instances, 0u);
}

// The covered columns of row y (depth within `near`..`far`): first and one past the last.
std::pair<int, int> covered_columns(const ReferenceImage& r, int y, float near, float far) {
  int first = -1, last = -1;
  for (int x = 0; x < r.image.width; ++x) {
    const float d = r.depth[std::size_t(y * r.image.width + x)];
    if (d >= near && d <= far) {
      if (first < 0) first = x;
      last = x;
    }
  }
  return {first, last + 1};
}

TEST(reference_render, AnInstanceLandsWhereTheCameraProjectionSays) {
  // One board facing the camera (yaw 90 degrees turns its +x face to the north... either side
  // shows: two-sided), 10 m ahead, 2 m wide, without ground so only the board has depth.
  const int w = 128, h = 96;
  ReferenceOptions o = fast();
  o.width = w;
  o.height = h;
  const ReferenceImage r = render_reference(test_scene({{0, 0, 0, float(kPi / 2), 1}}, false), o);
  // Half width in pixels: (1 m / 10 m) / tan(30 degrees) * w / 2.
  const double half = 0.1 / std::tan(kPi / 6) * w / 2;
  const auto [x0, x1] = covered_columns(r, h / 2 + 2, 9.5f, 10.5f);
  EXPECT_NEAR(x0, w / 2 - half, 1.0);
  EXPECT_NEAR(x1, w / 2 + half, 1.0);
  // The centre ray meets the board at 10 m.
  EXPECT_NEAR(r.depth[std::size_t((h / 2) * w + w / 2)], 10.0f, 0.01f);
  // Its top edge (2 m, 1 m above the eye) is (1 / 10) / tan(30) * w / 2 pixels above the centre.
  int top = -1;
  for (int y = 0; y < h && top < 0; ++y)
    if (std::isfinite(r.depth[std::size_t(y * w + w / 2)])) top = y;
  EXPECT_NEAR(top, h / 2.0 - half, 1.0);

  // Scale and translation: half the size, 2 m east, lifted 0.5 m.
  const ReferenceImage s = render_reference(test_scene({{2, 0, 0.5f, float(kPi / 2), 0.5f}}, false), o);
  const auto [s0, s1] = covered_columns(s, h / 2 + 2, 9.5f, 10.5f);
  const double centre = w / 2 + 0.2 / std::tan(kPi / 6) * w / 2;
  EXPECT_NEAR((s0 + s1) / 2.0, centre, 1.0);
  EXPECT_NEAR(s1 - s0, half, 1.5);

  // Yaw 0: the board is seen edge on, nearly invisible.
  const ReferenceImage edge = render_reference(test_scene({{0, 0, 0, 0, 1}}, false), o);
  int covered = 0;
  for (float c : edge.coverage) covered += c > 0;
  EXPECT_LE(covered, h);
}

// A baked ground: stripes 2 m wide, dark and light, running north-south (so the camera sees
// them across its view), over the ground's extent.
std::shared_ptr<GroundBake> striped_ground(float size) {
  auto bake = std::make_shared<GroundBake>();
  bake->extent = {-size, -size, size, size};
  const int pixels = 240;
  bake->image = ImageRgb8(pixels, pixels);
  for (int y = 0; y < pixels; ++y)
    for (int x = 0; x < pixels; ++x) {
      const bool light = (x * int(2 * size) / pixels / 2) % 2 == 0;
      bake->image.set(x, y, light ? Rgb8{230, 210, 120} : Rgb8{30, 60, 20});
    }
  return bake;
}

TEST(reference_render, TheBakedGroundShowsAndThePlainGroundDoesNot) {
  Scene plain = test_scene({});
  Scene textured = plain;
  textured.ground_texture = striped_ground(60);
  const ReferenceImage p = render_reference(plain, fast()), t = render_reference(textured, fast());
  const int h = p.image.height;
  // The ground fills the lower half: stripes give it a large variance (measured 7,080), the
  // plain flat ground none (measured 0: one color, every sky ray open).
  const double textured_variance = row_variance(t.image, h / 2 + 2, h),
               plain_variance = row_variance(p.image, h / 2 + 2, h);
  EXPECT_GT(textured_variance, 500.0);
  EXPECT_LT(plain_variance, 50.0);
  // Stripe k covers ENU x in [-60 + 2k, -58 + 2k), light for even k: [0, 2) is light, [-2, 0)
  // dark. The bottom row meets the ground ~2.3 m ahead; columns w/2 + 6 and w/2 - 7 see x = +-0.27 m.
  const int w = t.image.width;
  EXPECT_GT(luminance(t.image, w / 2 + 6, h - 1), luminance(t.image, w / 2 - 7, h - 1) + 50);
}

TEST(reference_render, MoreSamplesSoftenEdgesDeterministically) {
  const Scene scene = test_scene({{0, 0, 0, float(kPi / 2), 1}}, false);
  const ReferenceImage one = render_reference(scene, fast(1)), many = render_reference(scene, fast(16));
  int partial_one = 0, partial_many = 0;
  for (float c : one.coverage) partial_one += c > 0 && c < 1;
  for (float c : many.coverage) partial_many += c > 0 && c < 1;
  EXPECT_EQ(partial_one, 0);
  EXPECT_GT(partial_many, 10);  // the board's edges: coverage between 0 and 1 (measured 44)
  EXPECT_EQ(render_reference(scene, fast(16)).image.pixels, many.image.pixels);
  EXPECT_EQ(many.stats.samples_per_pixel, 16);
}

TEST(reference_render, TheSceneSizeAndSamplesAreTheDefaults) {
  Scene scene = test_scene({});
  scene.render.antialias_samples = 2;
  ReferenceOptions o;
  o.shading.ao_rays = 0;
  const ReferenceImage r = render_reference(scene, o);
  EXPECT_EQ(r.image.width, 64);
  EXPECT_EQ(r.image.height, 48);
  EXPECT_EQ(r.stats.samples_per_pixel, 4);
  EXPECT_EQ(r.coverage.size(), 64u * 48u);
}

TEST(reference_render, TheSkyIsTheGradientTheViewCanDraw) {
  const Scene scene = test_scene({}, false);
  ReferenceOptions o = fast();
  const ReferenceImage r = render_reference(scene, o);
  const CameraFrame f = reference_camera_frame(scene.camera, 64, 48);
  const ShadingSettings s = with_sun(o.shading, scene.sun);
  for (int y : {0, 10, 30, 47}) {
    const double nx = 2.0 * 20.5 / 64 - 1, ny = 1 - 2.0 * (y + 0.5) / 48;
    Vec3f d{};
    for (std::size_t c = 0; c < 3; ++c) d[c] = float(f.forward[c] + nx * f.right[c] + ny * f.up[c]);
    const auto expected = to_srgb8(sky_radiance(s, d));
    const Rgb8 got = r.image.at(20, y);
    EXPECT_NEAR(got.r, expected[0], 1);
    EXPECT_NEAR(got.b, expected[2], 1);
  }
  // Bluer overhead than at the horizon.
  EXPECT_LT(r.image.at(20, 0).r, r.image.at(20, 23).r);
}

// One look (issue 39): the sky overhead is blue, not the pale grey it was (zenith 0.7 x sky_color),
// and the horizon a pale haze; POV-Ray and Cycles draw this gradient (sky_gradient) too.
TEST(reference_render, TheSkyIsBlueOverheadAndPaleAtTheHorizon) {
  const ShadingSettings s;
  const Vec3f zenith = sky_radiance(s, {0, 0, 1}), horizon = sky_radiance(s, {1, 0, 0});
  EXPECT_GT(zenith[2], 2.5f * zenith[0]);
  EXPECT_GT(horizon[0], 0.6f);
  EXPECT_LT(horizon[2], 1.3f * horizon[0]);
  const SkyGradient g = sky_gradient(s);
  for (std::size_t c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(zenith[c], g.zenith[c] * s.exposure);
}

// The tiny scene of the CLI tests (tests/cli/tiny_scene.toml: flat ground, a field of real
// sunflowers seen from its edge), assembled as `wangscape build` does.
Scene tiny_scene() {
  std::string text = read_text_file(std::string(WANGSCAPE_SOURCE_DIR) + "/tests/cli/tiny_scene.toml", 1 << 20, "test");
  for (const char* key : {"@TERRAIN@", "@TILES@", "@MODELS@", "@IMAGE@", "@EXPORTS@", "@SUN@"}) {
    const std::size_t at = text.find(key);
    text.replace(at, std::string(key).size(), std::string(key) == "@SUN@" ? "azimuth = 200.0\nelevation = 40.0" : "");
  }
  return make_scene(parse_scene_config(text, "tiny_scene.toml", WANGSCAPE_SOURCE_DIR));
}

TEST(reference_render, TheTinySceneIsDeterministicAndItsFlowersShow) {
  const Scene field = tiny_scene();
  Scene bare = field;
  bare.instances = {};
  ReferenceOptions o = fast(2);
  o.width = 64;
  o.height = 48;
  const ReferenceImage a = render_reference(field, o), again = render_reference(field, o);
  const ReferenceImage b = render_reference(bare, o);
  EXPECT_EQ(a.image.pixels, again.image.pixels);
  EXPECT_GT(a.stats.instances, 100u);
  // The camera (2.2 m up, looking down at 1.2 m 16 m ahead) sees sky over the top rows: the
  // same with and without flowers; the field below differs in most pixels.
  int sky_differs = 0, sky_covered = 0, field_differs = 0;
  for (int y = 0; y < 48; ++y)
    for (int x = 0; x < 64; ++x) {
      const bool differs = a.image.at(x, y) != b.image.at(x, y);
      if (y < 8) sky_differs += differs, sky_covered += a.coverage[std::size_t(y * 64 + x)] > 0;
      if (y >= 30) field_differs += differs;
    }
  EXPECT_EQ(sky_differs, 0);
  EXPECT_EQ(sky_covered, 0);
  EXPECT_GT(field_differs, 18 * 64 / 2);
  EXPECT_GT(row_variance(a.image, 30, 48), row_variance(b.image, 30, 48));
}

TEST(reference_render, RefusesOutOfRangeInput) {
  const Scene scene = test_scene({});
  ReferenceOptions o = fast();
  o.samples_per_pixel = -1;
  EXPECT_THROW(render_reference(scene, o), Error);
  o.samples_per_pixel = kMaxReferenceSamples + 1;
  EXPECT_THROW(render_reference(scene, o), Error);
  o = fast();
  o.width = kMaxReferenceSide + 1;
  EXPECT_THROW(render_reference(scene, o), Error);
  o = fast();
  o.width = -4;
  EXPECT_THROW(render_reference(scene, o), Error);
  o = fast();
  o.threads = -1;
  EXPECT_THROW(render_reference(scene, o), Error);
  Camera down;
  down.position = {0, 0, 10};
  down.target = {0, 0, 0};
  EXPECT_THROW(reference_camera_frame(down, 10, 10), Error);
  Camera wide;
  wide.fov_degrees = 180;
  EXPECT_THROW(reference_camera_frame(wide, 10, 10), Error);
  Camera nan;
  nan.position[0] = std::nan("");
  EXPECT_THROW(reference_camera_frame(nan, 10, 10), Error);
}

}  // namespace
}  // namespace wangscape
