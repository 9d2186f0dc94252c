// The ground look ([ground], scene/ground_look.h): the parser, the materials by height and slope,
// the texture detail, and the bake every exporter writes.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include "scene/ground_look.h"
#include "scene/scene_file.h"
#include "scene/scene_ground.h"

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

// Mean sRGB color of an image.
std::array<double, 3> mean_color(const ImageRgb8& image) {
  std::array<double, 3> sum{};
  for (std::size_t p = 0; p < image.pixels.size(); ++p) sum[p % 3] += image.pixels[p] / 255.0;
  for (double& v : sum) v /= static_cast<double>(image.pixels.size() / 3);
  return sum;
}

// Mean color of the look (texture only) over x in [x0, x1), and the mean absolute difference of
// each sample from the sample one texture tile east: zero if every tile there were the same.
struct RegionLook {
  std::array<double, 3> mean{};
  double tile_period_difference = 0;
};
RegionLook region_look(const GroundLook& look, double x0, double x1, double tile) {
  RegionLook region;
  int n = 0;
  for (double x = x0; x < x1; x += 0.37 * tile / 8)
    for (double y = 0; y < 6 * tile; y += 0.41 * tile / 8, ++n) {
      const GroundColor c = look.color_at(x, y, 0, 0), east = look.color_at(x + tile, y, 0, 0);
      region.mean[0] += c.r;
      region.mean[1] += c.g;
      region.mean[2] += c.b;
      region.tile_period_difference += std::abs(c.g - east.g);
    }
  for (double& v : region.mean) v /= n;
  region.tile_period_difference /= n;
  return region;
}

double distance(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

TEST(GroundLook, Exemplar2AboveSwitchesTheTextureAlongTheContour) {
  // A ramp: height = x meters. Below 0 m the texture must be the meadow's, above it the pumice's,
  // and each side must stay a stochastic tiling (not one tile repeated).
  const SceneConfig scene = parse(
      "[ground]\nlook = \"texture\"\nexemplar = \"meadow\"\nexemplar2 = \"pumice\"\n"
      "texture_scale = 8.0\nexemplar2_above = 0.0\n");
  const auto exemplars = load_ground_exemplars(scene);
  ASSERT_EQ(exemplars.size(), 2u);
  const GroundLook look(*scene.ground, exemplars, [](double x, double) { return std::optional<double>(x); });
  const double tile = 8.0;
  const RegionLook west = region_look(look, -12 * tile, -2 * tile, tile);
  const RegionLook east = region_look(look, 2 * tile, 12 * tile, tile);
  const auto meadow = mean_color(exemplars[0]), pumice = mean_color(exemplars[1]);
  EXPECT_LT(distance(west.mean, meadow), 0.25 * distance(meadow, pumice));
  EXPECT_LT(distance(east.mean, pumice), 0.25 * distance(meadow, pumice));
  EXPECT_GT(west.tile_period_difference, 0.02);
  EXPECT_GT(east.tile_period_difference, 0.02);

  // Control: with random marks both sides mix the two exemplars alike.
  const SceneConfig random =
      parse("[ground]\nlook = \"texture\"\nexemplar = \"meadow\"\nexemplar2 = \"pumice\"\ntexture_scale = 8.0\n");
  const GroundLook mixed(*random.ground, load_ground_exemplars(random));
  const RegionLook mixed_west = region_look(mixed, -12 * tile, -2 * tile, tile);
  const RegionLook mixed_east = region_look(mixed, 2 * tile, 12 * tile, tile);
  EXPECT_LT(distance(mixed_west.mean, mixed_east.mean), 0.25 * distance(meadow, pumice));
}

TEST(GroundLook, Exemplar2AboveNeedsASecondExemplar) {
  try {
    parse("[ground]\nexemplar2_above = 1200.0\n");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("test.toml:2: 'ground.exemplar2_above' needs an exemplar2"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace wangscape
