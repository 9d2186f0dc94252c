// The ground look ([ground], scene/ground_look.h): the parser, the materials by height and slope,
// the texture detail, and the bake every exporter writes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "scene/ground.h"
#include "scene/ground_look.h"
#include "scene/scene_file.h"

namespace wangscape {
namespace {

SceneConfig parse(const std::string& text) { return parse_scene_config(text, "test.toml", WANGSCAPE_SOURCE_DIR); }

// Mean luminance (0..1) of the look over a 40 x 40 grid of points at one height and slope.
double mean_luminance(const GroundLook& look, double height, double slope) {
  double sum = 0;
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 40; ++j) {
      const GroundColor c = look.color_at(37.0 * i, 41.0 * j, height, slope);
      sum += 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
    }
  return sum / 1600;
}

TEST(GroundLook, ParsesTheSectionAndLeavesItOutWhenAbsent) {
  EXPECT_FALSE(parse("[terrain]\nflat_size = 50.0\n").ground);
  const SceneConfig config = parse("[ground]\nlook = \"materials\"\nnoise_scale = 12.5\nrock_slope = 40\n");
  ASSERT_TRUE(config.ground);
  EXPECT_EQ(config.ground->look, "materials");
  EXPECT_EQ(config.ground->noise_scale, 12.5);
  EXPECT_EQ(config.ground->rock_slope, 40.0);
  EXPECT_EQ(config.key_lines.at("ground.rock_slope"), 4);
}

TEST(GroundLook, RejectsBadValuesNamingKeyAndLine) {
  const auto message = [](const std::string& text) {
    try {
      parse(text);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(
      message("[ground]\nnoise_lattice = 12\n").find("test.toml:2: 'ground.noise_lattice' must be a power of two"),
      std::string::npos);
  EXPECT_NE(message("[ground]\ntexture_pixels = 15\n").find("'ground.texture_pixels' must be between 16"),
            std::string::npos);
  EXPECT_NE(message("[ground]\n\nbake_pixels = 0\n").find("test.toml:3: 'ground.bake_pixels'"), std::string::npos);
  EXPECT_NE(message("[ground]\nsnow = 1\n").find("unknown key 'ground.snow'"), std::string::npos);
}

TEST(GroundLook, MaterialsFollowHeightAndSlope) {
  GroundConfig config;
  config.look = "materials";
  const GroundLook look(config, {});
  const double meadow = mean_luminance(look, 500, 0), pumice = mean_luminance(look, 1900, 0);
  const double rock = mean_luminance(look, 1900, 60), snow = mean_luminance(look, 3000, 0);
  EXPECT_LT(meadow, pumice);
  EXPECT_LT(rock, pumice);
  EXPECT_LT(pumice, snow);
  // Meadow is green, not grey.
  const GroundColor c = look.color_at(10, 20, 500, 0);
  EXPECT_GT(c.g, c.b);
}

TEST(GroundLook, NotOneColorAndDeterministic) {
  const SceneConfig scene = parse("[ground]\nexemplar = \"meadow\"\nexemplar2 = \"pumice\"\ntexture_scale = 8.0\n");
  const GroundLook a(*scene.ground, load_ground_exemplars(scene)), b(*scene.ground, load_ground_exemplars(scene));
  ASSERT_NE(a.texture_tiles(), nullptr);
  float lo = 1, hi = 0;
  for (int i = 0; i < 500; ++i) {
    const double x = -1000 + 7.3 * i, y = 3.1 * i;
    const GroundColor ca = a.color_at(x, y, 800, 10), cb = b.color_at(x, y, 800, 10);
    EXPECT_EQ(ca.r, cb.r);
    EXPECT_EQ(ca.g, cb.g);
    EXPECT_EQ(ca.b, cb.b);
    lo = std::min(lo, ca.g);
    hi = std::max(hi, ca.g);
  }
  EXPECT_GT(hi - lo, 0.05f);
}

TEST(GroundLook, UnknownShippedExemplarNamesTheKey) {
  const SceneConfig scene = parse("[ground]\n\nexemplar = \"gravel\"\n");
  try {
    load_ground_exemplars(scene);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("test.toml:3: 'ground.exemplar' 'gravel' is no shipped exemplar"),
              std::string::npos)
        << e.what();
  }
}

TEST(GroundLook, BakeCoversTheGroundWithTheLongerSideGiven) {
  TerrainConfig terrain;
  terrain.flat_size = 100;
  const SceneGround ground = SceneGround::load(terrain);
  GroundConfig config;
  config.noise_scale = 10;
  config.texture_scale = 5;
  const SceneConfig scene = parse("[ground]\n");
  const GroundLook look(config, load_ground_exemplars(scene));
  const GroundBake bake = bake_ground(look, ground, 64);
  EXPECT_EQ(bake.image.width, 64);
  EXPECT_EQ(bake.image.height, 64);
  EXPECT_DOUBLE_EQ(bake.extent.width(), ground.extent().width());
  // The pixel at column 10, row 5 (north at the top) is the look at that pixel's centre.
  const double x = bake.extent.min_x + 10.5 * bake.extent.width() / 64;
  const double y = bake.extent.max_y - 5.5 * bake.extent.height() / 64;
  const GroundColor c = look.color_at(x, y, 0, 0);
  EXPECT_EQ(bake.image.at(10, 5).g, static_cast<std::uint8_t>(std::lround(std::clamp(c.g, 0.f, 1.f) * 255)));
  const auto [lo, hi] = std::minmax_element(bake.image.pixels.begin(), bake.image.pixels.end());
  EXPECT_GT(*hi - *lo, 20);
}

}  // namespace
}  // namespace wangscape
