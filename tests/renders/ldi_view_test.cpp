// The real-time LDI view against a real pack of a tiny flat field (built here by Embree, coarse
// levels): deterministic frames on 1 and 2 threads, every placed tile drawn or culled, frustum
// culling, no holes in a close view, levels by distance, back-to-front order and the z-buffer
// letting the near tile hide the far one. Suites are named ldi_view so `ctest -R ldi` runs them.
#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <numbers>
#include <string>

#include "core/error.h"
#include "core/vecmath.h"
#include "renders/ldi/ldi_scene.h"
#include "renders/trace/scene_tracer.h"
#include "renders/trace/traced_shading.h"
#include "renders/view/vector_path.h"
#include "renders/view/view_frames.h"
#include "scene/scene.h"
#include "scene/scene_file.h"
#include "tests/renders/view_test_world.h"

namespace wangscape {
namespace {

namespace fs = std::filesystem;
using namespace view_test;

// The mean level of the drawn tiles (the far field counted as the last).
double mean_drawn_level(const ViewFrameStats& stats) {
  double sum = 0, n = 0;
  for (std::size_t k = 0; k < stats.levels.size(); ++k) {
    sum += double(k) * double(stats.levels[k]);
    n += double(stats.levels[k]);
  }
  return sum / n;
}

// A frame of only the tiles `mask` keeps: its depths (row-major) and its pixels.
std::pair<std::vector<float>, std::vector<std::uint8_t>> masked_frame(LdiRenderer& renderer, const Camera& camera,
                                                                      std::vector<std::uint8_t> mask) {
  renderer.set_tile_mask(std::move(mask));
  renderer.render(camera);
  const int w = renderer.width(), h = renderer.height();
  std::vector<float> depth(std::size_t(w * h));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) depth[std::size_t(y * w + x)] = renderer.depth_at(x, y);
  return {depth, renderer.image().pixels};
}

TEST(ldi_view, PlacesEveryTileOfTheArea) {
  // 24 m x 24 m of 4 m tiles on a flat plane without masks: 6 x 6 tiles, each with flowers.
  EXPECT_EQ(field()->tiles().size(), 36u);
}

TEST(ldi_view, DrawnAndCulledAddUpToThePlacedTiles) {
  LdiRenderer renderer(field(), 96, 64);
  for (const Camera& camera : {looking(0, -16, 2, 0, 0, 1), looking(3, 1, 1.7, 10, 5, 1),
                               looking(-30, -30, 20, 0, 0, 0), looking(0, 0, 1.7, 0, -10, 0.5)}) {
    const ViewFrameStats& stats = renderer.render(camera);
    EXPECT_EQ(stats.tiles_drawn + stats.tiles_culled, 36u);
    std::uint64_t by_level = 0;
    for (std::uint64_t n : stats.levels) by_level += n;
    EXPECT_EQ(by_level, stats.tiles_drawn);
  }
}

TEST(ldi_view, LookingAwayFromTheFieldDrawsNoTile) {
  LdiRenderer renderer(field(), 96, 64);
  const ViewFrameStats& stats = renderer.render(looking(0, -20, 1.7, 0, -40, 1.7));
  EXPECT_EQ(stats.tiles_drawn, 0u);
  EXPECT_EQ(stats.tiles_culled, 36u);
  EXPECT_EQ(stats.depth_pixels, 0u);
  // Turned round, the same eye sees tiles.
  EXPECT_GT(renderer.render(looking(0, -20, 1.7, 0, 0, 1.7)).tiles_drawn, 0u);
}

TEST(ldi_view, SameBytesOnOneAndTwoThreadsAndTwice) {
  const Camera camera = looking(-2, -9, 1.7, 4, 6, 0.8);
  std::vector<std::uint8_t> one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    LdiRenderer renderer(field(), 120, 80);
    renderer.render(camera);
    one = renderer.image().pixels;
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    LdiRenderer renderer(field(), 120, 80);
    renderer.render(camera);
    two = renderer.image().pixels;
    renderer.render(looking(5, 5, 3, 0, 0, 0));
    renderer.render(camera);
    EXPECT_EQ(renderer.image().pixels, two);
  }
  EXPECT_EQ(one, two);
}

// The warp's projection runs in the widest vector lanes the CPU has; every narrower path makes
// the same bytes (issue 22), with level, direction and elevation dithers and the far steps in
// the frame (the second camera, from above): the same colors and, to the last bit, the same
// depths (the projection's camera depth, which a contracted a * b + c changes where the colors
// rarely do: compiled with contraction, the colors still agreed).
TEST(ldi_view, SameBytesOnEveryVectorPath) {
  static const auto above = tiny_world("[-40.0, -8.0, 40.0, 120.0]", "above", "300.0");
  const std::pair<std::shared_ptr<const ViewWorld>, Camera> views[] = {{field(), looking(-2, -9, 1.7, 4, 6, 0.8)},
                                                                       {above, looking(0, -10, 20, 0, 40, 1.0, 60)}};
  const VectorPath widest = widest_vector_path();
  std::printf("this CPU's widest vector path: %s\n", std::string(to_string(widest)).c_str());
  for (const auto& [world, camera] : views) {
    std::vector<std::uint8_t> reference;
    std::vector<std::uint32_t> reference_depths;
    for (int p = int(widest); p >= int(VectorPath::baseline); --p) {
      set_vector_path(VectorPath(p));
      LdiRenderer renderer(world, 160, 90);
      renderer.set_engine(ViewEngine::ldi);
      EXPECT_GT(renderer.render(camera).depth_pixels, 10000u);
      std::vector<std::uint32_t> depths;
      for (int y = 0; y < renderer.height(); ++y)
        for (int x = 0; x < renderer.width(); ++x)
          depths.push_back(std::bit_cast<std::uint32_t>(renderer.depth_at(x, y)));
      if (reference.empty()) {
        reference = renderer.image().pixels;
        reference_depths = depths;
      } else {
        EXPECT_EQ(renderer.image().pixels, reference) << to_string(VectorPath(p)) << " against " << to_string(widest);
        EXPECT_EQ(depths, reference_depths) << to_string(VectorPath(p)) << " against " << to_string(widest);
      }
    }
  }
  set_vector_path(widest);
  EXPECT_EQ(vector_path(), widest);
  if (widest != VectorPath::avx512) {
    EXPECT_THROW(set_vector_path(VectorPath::avx512), Error);
  }
}

TEST(ldi_view, NoHolesInACloseView) {
  // Standing in the field looking across it. A hole is a pixel where the ground shows through a
  // surface: the terrain's own depth there, its left and right neighbours flower samples of about
  // the same depth (within 2 %). Measured with splats 1.5 x the projected depth-pixel size:
  // flowers cover 51.6 % of the frame, 64 holes (0.32 % of the flower pixels, mostly real gaps
  // between stems); with 0.6 x they cover 24 %.
  const int w = 240, h = 160;
  LdiRenderer renderer(field(), w, h);
  const Camera camera = looking(0, -6, 1.7, 0, 4, 0.6, 60);
  const auto ground = masked_frame(renderer, camera, std::vector<std::uint8_t>(field()->tiles().size(), 0)).first;
  const auto all = masked_frame(renderer, camera, {}).first;
  int flowers = 0, holes = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 1; x + 1 < w; ++x) {
      const std::size_t p = std::size_t(y * w + x);
      auto flower = [&](std::size_t q) { return all[q] < ground[q]; };
      flowers += flower(p);
      if (!flower(p) && flower(p - 1) && flower(p + 1) && std::abs(all[p - 1] - all[p + 1]) < 0.02f * all[p - 1])
        ++holes;
    }
  EXPECT_GT(flowers, w * h * 45 / 100);
  EXPECT_LT(holes, flowers / 100) << holes << " holes among " << flowers << " flower pixels";
}

TEST(ldi_view, LevelsCoarsenWithDistance) {
  LdiRenderer renderer(field(), 160, 90);
  auto mean_level = [&](const Camera& camera) { return mean_drawn_level(renderer.render(camera)); };
  const double near = mean_level(looking(0, -14, 1.7, 0, 0, 0.5));
  const double middle = mean_level(looking(0, -22, 1.7, 0, 0, 0.5));
  const double far = mean_level(looking(0, -120, 1.7, 0, 0, 0.5));
  EXPECT_LT(near, middle);
  EXPECT_LT(middle, far);
  // From 120 m every tile is beyond the last level: the far field's one-layer LDIs, far fewer
  // depth pixels than at 22 m; from 5 km, beyond their last step: only the directional colors.
  const std::uint64_t middle_pixels = renderer.render(looking(0, -22, 1.7, 0, 0, 0.5)).depth_pixels;
  const ViewFrameStats& stats = renderer.render(looking(0, -120, 1.7, 0, 0, 0.5));
  EXPECT_EQ(stats.levels.back(), stats.tiles_drawn);
  EXPECT_GT(stats.depth_pixels, 0u);
  EXPECT_LT(stats.depth_pixels * 10, middle_pixels);
  const ViewFrameStats& beyond = renderer.render(looking(0, -5000, 1.7, 0, 0, 0.5));
  EXPECT_EQ(beyond.levels.back(), beyond.tiles_drawn);
  EXPECT_EQ(beyond.depth_pixels, 0u);
}

TEST(ldi_view, LessDetailDrawsCoarserLevelsAndFewerDepthPixels) {
  LdiRenderer renderer(field(), 160, 90);
  const Camera camera = looking(0, -14, 1.7, 0, 0, 0.5);
  const ViewFrameStats full = renderer.render(camera);
  renderer.set_detail(0.5);
  const ViewFrameStats half = renderer.render(camera);
  EXPECT_EQ(half.tiles_drawn, full.tiles_drawn);
  EXPECT_LT(half.depth_pixels * 2, full.depth_pixels) << half.depth_pixels << " vs " << full.depth_pixels;
  EXPECT_GT(mean_drawn_level(half), mean_drawn_level(full));
  EXPECT_THROW(renderer.set_detail(0), Error);
  EXPECT_THROW(renderer.set_detail(std::numeric_limits<double>::quiet_NaN()), Error);
}

TEST(ldi_view, TilesAreDrawnBackToFront) {
  LdiRenderer renderer(field(), 96, 64);
  renderer.render(looking(1, -3, 1.7, 2, 8, 0.5));
  const auto& order = renderer.draw_order();
  ASSERT_GT(order.size(), 3u);
  for (std::size_t k = 1; k < order.size(); ++k)
    EXPECT_GE(renderer.tile_distance(order[k - 1]), renderer.tile_distance(order[k]));
}

TEST(ldi_view, TheNearTileHidesTheFarOne) {
  // Two tiles in a row, the eye low in front of them looking along the row.
  const auto world = tiny_world("[0.0, 0.0, 8.0, 4.0]", "row");
  ASSERT_EQ(world->tiles().size(), 2u);
  const std::size_t near_tile = world->tiles().x0[0] < world->tiles().x0[1] ? 0 : 1;
  const int w = 120, h = 80;
  LdiRenderer renderer(world, w, h);
  const Camera camera = looking(-2.5, 2, 0.9, 8, 2, 0.9, 70);
  auto frame = [&](std::vector<std::uint8_t> mask) { return masked_frame(renderer, camera, std::move(mask)); };
  std::vector<std::uint8_t> only_near(2, 0), only_far(2, 0);
  only_near[near_tile] = 1;
  only_far[1 - near_tile] = 1;
  const auto [near_depth, near_rgb] = frame(only_near);
  const auto [far_depth, far_rgb] = frame(only_far);
  const auto [ground_depth, ground_rgb] = frame({0, 0});  // the terrain alone
  const auto [both_depth, both_rgb] = frame({});
  ASSERT_EQ(renderer.draw_order().size(), 2u);
  EXPECT_EQ(renderer.draw_order()[0], 1 - near_tile);  // the far one first
  int hidden = 0;
  for (std::size_t p = 0; p < near_depth.size(); ++p) {
    EXPECT_EQ(both_depth[p], std::min(near_depth[p], far_depth[p]));
    const bool near_wins = near_depth[p] < far_depth[p];
    for (std::size_t c = 0; c < 3; ++c)
      EXPECT_EQ(both_rgb[3 * p + c], near_wins ? near_rgb[3 * p + c] : far_rgb[3 * p + c]);
    // A far-tile flower behind a near-tile flower: hidden.
    hidden += near_depth[p] < far_depth[p] && far_depth[p] < ground_depth[p];
  }
  // Splats cover the pixel centres of their square: 98 such pixels measured (1 % of the frame).
  EXPECT_GT(hidden, w * h / 150);
}

}  // namespace
}  // namespace wangscape

namespace wangscape {
namespace {

// The near field: the tiles around the eye ray traced from their real flowers.
TEST(ldi_view_near, SameBytesOnOneAndTwoThreadsAndAfterMovingAway) {
  const Camera camera = looking(0.5, -5, 1.5, 0, 3, 0.9);
  std::vector<std::uint8_t> one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    LdiRenderer renderer(field(), 120, 80);
    renderer.set_near_field(6);
    EXPECT_GT(renderer.render(camera).near_tiles, 0u);
    one = renderer.image().pixels;
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    LdiRenderer renderer(field(), 120, 80);
    renderer.set_near_field(6);
    renderer.render(camera);
    two = renderer.image().pixels;
    renderer.render(looking(8, 8, 3, 0, 0, 0));  // another window of near flowers
    renderer.render(camera);
    EXPECT_EQ(renderer.image().pixels, two);
  }
  EXPECT_EQ(one, two);
}

TEST(ldi_view_near, NearTilesAreNotWarpedAndTheFrameIsCloserToTheTruth) {
  // A close-up, 1.2 m from the flowers: the LDIs' splats against the real geometry. The truth is
  // the reference at 16 samples per pixel, the pack's light.
  const Camera camera = looking(0.3, -7.2, 1.3, 0.3, -4, 1.0, 60);
  LdiRenderer ldis(field(), 160, 120), near(field(), 160, 120);
  near.set_near_field(6);
  const ViewFrameStats& a = ldis.render(camera);
  const std::uint64_t warped_without = a.depth_pixels;
  const ViewFrameStats& b = near.render(camera);
  EXPECT_GT(b.near_tiles, 0u);
  EXPECT_GT(b.near_rays, 0u);
  EXPECT_LT(b.depth_pixels, warped_without);
  const ViewComparison with_ldis = compare_with_reference(*field(), ldis, camera, 16);
  const ViewComparison with_near = compare_with_reference(*field(), near, camera, 16);
  // The rest of the gap is this pack's coarse LDIs (3 levels, 128 pixels) beyond 6 m.
  EXPECT_GT(with_near.comparison.psnr_db, with_ldis.comparison.psnr_db + 2)
      << with_near.comparison.psnr_db << " dB against " << with_ldis.comparison.psnr_db;
  EXPECT_GT(with_near.comparison.ssim, with_ldis.comparison.ssim + 0.1);
  // Issue 22's goal: within 1 dB and 0.03 of SSIM of the exact one-sample image. Measured: 0.53 dB
  // and 0.002 with the flowers' baked sky share; 1.43 dB and 0.127 under the open sky with the
  // rasterized ground speckled over the near field's.
  EXPECT_LT(with_near.exact.psnr_db - with_near.comparison.psnr_db, 1.0)
      << with_near.comparison.psnr_db << " dB against exact " << with_near.exact.psnr_db;
  EXPECT_LT(with_near.exact.ssim - with_near.comparison.ssim, 0.03)
      << with_near.comparison.ssim << " against exact " << with_near.exact.ssim;
  EXPECT_LT(with_near.comparison.holes.holes, with_ldis.comparison.holes.holes);
}

// The flowers' sky share is estimated among the flowers of one fixed place, not wherever the
// view happened to start: the same frame either way.
TEST(ldi_view_near, AFrameDoesNotDependOnWhereTheViewStarted) {
  // A field three near-field windows long (at 2 m, a window is about 25 m across).
  const auto world = tiny_world("[-36.0, -12.0, 36.0, 12.0]", "long", "90.0");
  const Camera camera = looking(-28, -2, 1.5, -20, 3, 0.9);
  LdiRenderer direct(world, 120, 80), elsewhere_first(world, 120, 80);
  direct.set_near_field(2);
  elsewhere_first.set_near_field(2);
  direct.render(camera);
  elsewhere_first.render(looking(28, 2, 1.5, 20, -3, 0.9));
  elsewhere_first.render(camera);
  EXPECT_EQ(direct.image().pixels, elsewhere_first.image().pixels);
}

TEST(ldi_view_near, ADistanceOutOfRangeIsRefused) {
  LdiRenderer renderer(field(), 16, 16);
  EXPECT_THROW(renderer.set_near_field(-1), Error);
  EXPECT_THROW(renderer.set_near_field(kMaxNearField + 1), Error);
  EXPECT_THROW(renderer.set_near_field(std::nan("")), Error);
}

// --engine embree: the whole frame ray cast, the anchor the LDI frame is measured against. It is
// the exact geometry at one sample per pixel without sky rays: as close to the truth as the
// reference's own one-sample image (whose few sky rays are noise), the same on 1 and 2 threads.
TEST(ldi_view_ray_cast, IsTheExactOneSampleFrameOnAnyThreadCount) {
  const Camera camera = looking(0.3, -7.2, 1.3, 0.3, -4, 1.0, 60);
  std::vector<std::uint8_t> one;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    LdiRenderer renderer(field(), 96, 64);
    renderer.set_engine(ViewEngine::embree);
    renderer.render(camera);
    one = renderer.image().pixels;
  }
  LdiRenderer renderer(field(), 96, 64);
  renderer.set_engine(ViewEngine::embree);
  const ViewFrameStats& stats = renderer.render(camera);
  EXPECT_EQ(renderer.image().pixels, one);
  EXPECT_EQ(stats.depth_pixels, 0u);
  EXPECT_GE(stats.near_rays, 96u * 64u);  // every pixel's primary ray, and the hits' shadow rays
  const ViewComparison v = compare_with_reference(*field(), renderer, camera, 16);
  EXPECT_GT(v.comparison.psnr_db, v.exact.psnr_db - 0.5) << v.comparison.psnr_db << " against " << v.exact.psnr_db;
  EXPECT_GT(v.comparison.ssim, v.exact.ssim - 0.02);
  EXPECT_LE(v.comparison.holes.holes, v.exact.holes.holes + 8) << v.exact.holes.holes;
}

// ViewEngine::automatic: rays where the eye stands in the field (the near field stops most rays),
// LDIs from outside it; each frame byte for byte the one of the engine it chose.
TEST(ldi_view_automatic, RaysInTheFieldLdisFromOutside) {
  const Camera inside = looking(0.3, -7.2, 1.3, 0.3, -4, 1.0, 60);
  const Camera outside = looking(0, -16, 2.2, 0, 0, 1.2, 60);
  const auto frame = [](ViewEngine engine, const Camera& camera, bool* ray_cast) {
    LdiRenderer renderer(field(), 96, 64);
    renderer.set_near_field(6);
    renderer.set_engine(engine);
    const ViewFrameStats& stats = renderer.render(camera);
    if (ray_cast) *ray_cast = stats.ray_cast;
    return renderer.image().pixels;
  };
  bool chose_rays = false;
  EXPECT_EQ(frame(ViewEngine::automatic, inside, &chose_rays), frame(ViewEngine::embree, inside, nullptr));
  EXPECT_TRUE(chose_rays);
  EXPECT_EQ(frame(ViewEngine::automatic, outside, &chose_rays), frame(ViewEngine::ldi, outside, nullptr));
  EXPECT_FALSE(chose_rays);
}

// --spp N: N frames at sub-pixel offsets averaged; the first sample is the one-sample frame, and
// the average is closer to the truth than one sample (edges anti-aliased).
TEST(ldi_view_samples, JitteredFramesAreAveragedAndCloserToTheTruth) {
  const Camera camera = looking(0.3, -7.2, 1.3, 0.3, -4, 1.0, 60);
  for (const ViewEngine engine : {ViewEngine::ldi, ViewEngine::embree}) {
    LdiRenderer one(field(), 96, 64), four(field(), 96, 64);
    one.set_engine(engine);
    four.set_engine(engine);
    four.set_samples(1);
    const std::uint64_t one_sample_pixels = one.render(camera).depth_pixels;
    EXPECT_EQ(four.render(camera).depth_pixels, one_sample_pixels);
    EXPECT_EQ(four.image().pixels, one.image().pixels);
    four.set_samples(4);
    EXPECT_EQ(four.render(camera).depth_pixels, 4 * one_sample_pixels);
    EXPECT_NE(four.image().pixels, one.image().pixels);
    const ViewComparison a = compare_with_reference(*field(), one, camera, 16);
    const ViewComparison b = compare_with_reference(*field(), four, camera, 16);
    EXPECT_GT(b.comparison.psnr_db, a.comparison.psnr_db + 0.5) << int(engine);
  }
  LdiRenderer renderer(field(), 8, 8);
  EXPECT_THROW(renderer.set_samples(0), Error);
  EXPECT_THROW(renderer.set_samples(kMaxViewSamples + 1), Error);
}

// Seen from above (issue 22): tiles whose view is steeper than the pack's LDIs are drawn from the
// world's steep sets, sampled on the first such frame: the same bytes on 1 and 2 threads and from
// a renderer made after them, the far steps drawn, and the frame near the exact one-sample ray
// cast against the truth.
TEST(ldi_view_above, TwentyMetersUpDrawsTheSteepSetsTheSameOnAnyThreadCount) {
  static const auto world = tiny_world("[-40.0, -8.0, 40.0, 120.0]", "above", "300.0");
  const Camera camera = looking(0, -10, 20, 0, 40, 1.0, 60);
  std::vector<std::uint8_t> one;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    LdiRenderer renderer(world, 160, 90);
    renderer.set_engine(ViewEngine::ldi);
    const ViewFrameStats& stats = renderer.render(camera);
    EXPECT_GT(stats.levels.back(), 100u);                 // mostly the far steps
    EXPECT_GT(stats.steep_tiles, stats.tiles_drawn / 2);  // seen from above
    one = renderer.image().pixels;
  }
  LdiRenderer renderer(world, 160, 90);
  renderer.set_engine(ViewEngine::ldi);
  renderer.render(camera);
  EXPECT_EQ(renderer.image().pixels, one);
  const ViewComparison v = compare_with_reference(*world, renderer, camera, 16);
  EXPECT_GT(v.comparison.psnr_db, v.exact.psnr_db - 1.0) << v.comparison.psnr_db << " against " << v.exact.psnr_db;
  // Issue 22's goal, on this small flat field: 0.283 against 0.298 measured (0.288 with the steep
  // sets at the coarsest level's resolution, which lost 0.026 on the default scene's 25 m camera;
  // 0.292 with three steep sets instead of five: there five gained 0.012).
  std::printf("20 m up: SSIM %.4f (exact %.4f), PSNR %.2f dB (exact %.2f)\n", v.comparison.ssim, v.exact.ssim,
              v.comparison.psnr_db, v.exact.psnr_db);
  EXPECT_GT(v.comparison.ssim, v.exact.ssim - 0.03) << v.comparison.ssim << " against " << v.exact.ssim;
  EXPECT_EQ(v.comparison.holes.holes, 0u);
}

// The steep sets from the folder's steep pack (issue 40: the first frame from above took 6.4 s
// sampling them): the same bytes as sampled by the view, and a steep pack of another field refused.
TEST(ldi_view_above, TheSteepPackDrawsTheBytesTheViewWouldSample) {
  const std::string scene = tiny_scene("[-40.0, -8.0, 40.0, 120.0]", "300.0");
  const auto packed = world_of(scene, "above_packed", false, true);
  const auto sampled = std::make_shared<const ViewWorld>(
      make_scene(parse_scene_config(scene, "sampled.toml", fs::temp_directory_path())),
      FolderFiles(scratch("above_packed")).pack(), packed->shading());
  EXPECT_FALSE(sampled->steep_from_pack());
  EXPECT_TRUE(packed->steep_from_pack());
  const Camera camera = looking(0, -10, 20, 0, 40, 1.0, 60);
  std::vector<std::uint8_t> frames[2];
  for (int k = 0; k < 2; ++k) {
    LdiRenderer renderer(k ? packed : sampled, 160, 90);
    renderer.set_engine(ViewEngine::ldi);
    const ViewFrameStats& stats = renderer.render(camera);
    EXPECT_GT(stats.steep_tiles, stats.tiles_drawn / 2);
    frames[k] = renderer.image().pixels;
  }
  EXPECT_EQ(frames[0], frames[1]);
  // With three levels the steep sets take the finest level's resolution, six times: more than
  // twice the tiles' pack, so the build leaves them to the view.
  {
    LdiBuildOptions three;
    three.view.levels = 3;
    three.view.directions = 4;
    three.view.image_width = 128;
    three.shading.ao_rays = 0;
    const fs::path folder = scratch("three_levels");
    fs::create_directories(folder);
    const FolderFiles files(folder);
    build_scene_ldi_packs(make_scene(parse_scene_config(scene, "three.toml", fs::temp_directory_path())), files, three);
    EXPECT_TRUE(fs::exists(files.pack()));
    EXPECT_FALSE(fs::exists(files.steep_pack()));
  }
  // Another field's steep pack (5 m tiles) beside this pack: refused, naming the steep pack.
  std::string other_scene = tiny_scene("[-12.0, -12.0, 12.0, 12.0]");
  other_scene.replace(other_scene.find("tile_size = 4.0"), 15, "tile_size = 5.0");
  world_of(other_scene, "other_packed", false, true);
  Scene again = make_scene(parse_scene_config(scene, "again.toml", fs::temp_directory_path()));
  try {
    ViewWorld world(std::move(again), FolderFiles(scratch("above_packed")).pack(), {}, nullptr,
                    {FolderFiles(scratch("other_packed")).steep_pack(), {}, {}});
    ADD_FAILURE() << "a steep pack of another field was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("other_packed/steep.ldi"), std::string::npos) << e.what();
  }
}

// Straight down, the finer levels are drawn from the steep sets too: the pack's LDIs, sampled a
// few degrees below the horizon, showed the plants' sides, spread from above into sparse leaves
// over bare ground (the default scene 30 m up at 640 x 360: SSIM 0.267 against the truth, 0.391
// from the steep sets).
TEST(ldi_view_above, StraightDownTheFinerLevelsAreDrawnFromTheSteepSets) {
  // (The scene file's pack, 7 levels: the tiny world's 3 are all stood in for already.)
  static const auto world = tiny_world("[-12.0, -12.0, 12.0, 12.0]", "above_full_pack", "60.0", true);
  const LdiPackInfo& info = world->pack().info();
  LdiRenderer renderer(world, 320, 180);
  renderer.set_engine(ViewEngine::ldi);
  const Camera camera = looking(0, 0, 13, 0, 0.2, 0, 60);
  const ViewFrameStats& stats = renderer.render(camera);
  EXPECT_EQ(stats.steep_tiles, stats.tiles_drawn);
  int finer = 0;
  for (const std::uint32_t t : renderer.draw_order()) {
    const auto [level, steep_set] = renderer.tile_choice(t);
    finer += level + kSteepLevels < info.levels && steep_set > 0;
  }
  EXPECT_GT(finer, 0);
  const ViewComparison v = compare_with_reference(*world, renderer, camera, 16);
  std::printf("13 m up, straight down: SSIM %.4f (exact %.4f), PSNR %.2f dB (exact %.2f)\n", v.comparison.ssim,
              v.exact.ssim, v.comparison.psnr_db, v.exact.psnr_db);
  EXPECT_GT(v.comparison.ssim,
            0.6);  // 0.693 measured; 0.354 with the ground unshaded by the plants, 0.316 from the pack
}

// The ground light under a tile's plants (renders/ldi/ground_light.h) is baked in the tile's 3 x 3
// context, texel (i, j) east and north from its south-west corner: where the field's own plants
// (the reference tracer's scene, every tile as placed) shadow a point of the ground from the sun,
// the texel there is in shade. The tile's real neighbours may differ from its context near its
// edges, so most texels agree, not all (and more than if all were lit); the same texels read
// transposed (or with north down) agree by chance only.
TEST(ldi_view_above, TheGroundLightIsTheShadeThePlantsCastOnTheField) {
  const ViewWorld& world = *field();
  const TileGroundLight& light = world.ground_light();
  ASSERT_FALSE(light.empty());
  ASSERT_EQ(light.tiles(), world.pack().info().tiles);
  const SceneTracer tracer(world.scene(), {0, 0, 0});
  const std::uint32_t n = light.resolution();
  const double s = world.tile_size();
  double agree = 0, transposed = 0, flipped = 0, shaded = 0, count = 0;
  const ViewWorld::Tiles& tiles = world.tiles();
  for (std::size_t t = 0; t < tiles.tile.size(); ++t)
    for (std::uint32_t j = 1; j < n; j += 3)
      for (std::uint32_t i = 2; i < n; i += 3) {
        SurfaceSample ground;
        const double x = tiles.x0[t] + (i + 0.5) * s / n, y = tiles.y0[t] + (j + 0.5) * s / n;
        ground.position = {float(x), float(y), float(world.ground_height(x, y, 0))};
        ground.normal = {0, 0, 1};
        int rays = 0;
        const bool lit = shadowed_sun_share(tracer.scene(), world.sun_shading(), ground, &rays) > 0;
        // Texels a shadow's edge crosses (their four points disagree) tell nothing of a point.
        const std::uint8_t texel = light.at(tiles.tile[t], 0, i, j).sun;
        if (texel != 0 && texel != 255) continue;
        const auto in_sun = [&](std::uint32_t a, std::uint32_t b) {
          return light.at(tiles.tile[t], 0, a, b).sun > 127;
        };
        agree += lit == in_sun(i, j);
        transposed += lit == in_sun(j, i);
        flipped += lit == in_sun(i, n - 1 - j);
        shaded += !lit;
        ++count;
      }
  std::printf("ground light: %.0f texels, %.3f in shade; agreeing %.3f, transposed %.3f, north down %.3f\n", count,
              shaded / count, agree / count, transposed / count, flipped / count);
  EXPECT_GT(shaded / count, 0.1);
  EXPECT_GT(agree / count, 0.93);
  EXPECT_GT(agree / count, 1 - shaded / count + 0.05);
  EXPECT_LT(transposed / count, agree / count - 0.1);
  EXPECT_LT(flipped / count, agree / count - 0.1);
}

// Seen from above the lowest steep set, a far step's block (the average of 2^(k+1) x 2^(k+1) of
// its steep set's depth pixels) is drawn no larger than a pixel: two pixels averaged the
// heads into the leaves (the default scene's 25 m camera, SSIM 0.418 against the exact image's
// 0.454; issue 22). Blocks of up to 1.7 pixels before.
TEST(ldi_view_above, FarStepBlocksFromAboveAreNoLargerThanAPixel) {
  static const auto world = tiny_world("[-40.0, -8.0, 40.0, 120.0]", "above", "300.0");
  const LdiPackInfo& info = world->pack().info();
  LdiRenderer renderer(world, 160, 90);
  renderer.set_engine(ViewEngine::ldi);
  const double fov = 60;
  renderer.render(looking(0, -10, 20, 0, 40, 1.0, fov));
  const double focal = 80 / std::tan(fov / 2 * std::numbers::pi / 180);
  const double steep_pixel = world->tile_size() / double(world->steep_resolution());  // meters per depth pixel
  int far_steps = 0;
  double largest = 0;
  for (const std::uint32_t t : renderer.draw_order()) {
    const auto [level, steep_set] = renderer.tile_choice(t);
    if (level < info.levels || steep_set < 2) continue;  // a level, or seen lower than the lowest steep set
    ++far_steps;
    const double block = steep_pixel * double(2u << (level - info.levels));
    largest = std::max(largest, block * focal / renderer.tile_distance(t));
  }
  EXPECT_GT(far_steps, 100);
  EXPECT_LE(largest, 1.0 + 1e-6) << "pixels";
}

// The far steps keep each block with its cover's probability. By an ordered dither, the same
// thresholds at the same pixels of every tile, the kept blocks of two tiles agreed far beyond
// chance, a pattern repeating with the tiles: seen from 10-25 m up, rows along the tile grid that
// converged on the vanishing point. Hashed per tile and direction, they agree by chance only.
TEST(ldi_view_above, FarStepsOfTwoTilesKeepIndependentBlocks) {
  const ViewWorld& world = *field();
  double sum = 0, pairs = 0;
  for (std::uint32_t direction = 0; direction < world.pack().info().directions; ++direction)
    for (std::uint32_t step = 0; step < std::min(world.far_steps(), 2u); ++step)
      for (std::uint32_t a = 0; a + 1 < world.pack().info().tiles; ++a) {
        const LdiView p = world.far_ldi(a, direction, step), q = world.far_ldi(a + 1, direction, step);
        ASSERT_EQ(p.frame->width, q.frame->width);
        // The phi coefficient of the two kept masks over the pixels both frames have.
        double n[2][2] = {{0, 0}, {0, 0}};
        for (std::uint32_t y = 0; y < std::min(p.frame->height, q.frame->height); ++y)
          for (std::uint32_t x = 0; x < p.frame->width; ++x)
            n[p.pixel(int(x), int(y)).empty() ? 0 : 1][q.pixel(int(x), int(y)).empty() ? 0 : 1] += 1;
        const double rows0 = n[0][0] + n[0][1], rows1 = n[1][0] + n[1][1];
        const double cols0 = n[0][0] + n[1][0], cols1 = n[0][1] + n[1][1];
        const double denominator = std::sqrt(rows0 * rows1 * cols0 * cols1);
        if (denominator > 0) {
          sum += (n[1][1] * n[0][0] - n[1][0] * n[0][1]) / denominator;
          pairs += 1;
        }
      }
  ASSERT_GT(pairs, 10);
  // Measured: 0.46 with the ordered dither, 0.12 hashed.
  EXPECT_LT(sum / pairs, 0.2) << "mean phi of the kept masks of neighbouring tiles";
}

// Whether pixel i (0-based) of a frame shows a sunflower petal (saturated yellow; grass, even
// straw, is greener).
bool shows_petal(const ImageRgb8& image, std::size_t i) {
  const int r = image.pixels[3 * i], g = image.pixels[3 * i + 1], b = image.pixels[3 * i + 2];
  return r >= g && g > 100 && b * 2 < g;
}

// The pixels of a frame that show sunflower petals.
int yellow_pixels(const ImageRgb8& image) {
  int n = 0;
  for (std::size_t i = 0; i < image.pixels.size() / 3; ++i) n += shows_petal(image, i);
  return n;
}

// [[species]]: the LDIs hold every plant of a tile, and the view leaves out, per placed tile, the
// plants its species' rules and density leave out of the field (the depth pixels' plant byte).
TEST(ldi_view_species, PlantsTheRulesLeaveOutAreNotDrawn) {
  const auto world = [](const std::string& sunflower_rule, const std::string& name) {
    return world_of(
        "name = \"species view test\"\n[terrain]\nflat_size = 60.0\n[tiles]\nset = \"cohen8\"\n"
        "tile_size = 4.0\npoints_per_tile = 12\nseed = 5\narea = [-12.0, -12.0, 12.0, 12.0]\n"
        "[sun]\nazimuth = 200.0\nelevation = 40.0\n"
        "[[species]]\nname = \"grass\"\nmodel = \"grass\"\nvariants = 2\ntriangle_budget = 200\nshare = 2.0\n"
        "[[species]]\nname = \"sunflower\"\nmodel = \"sunflower\"\nvariants = 2\ntriangle_budget = 400\n" +
            sunflower_rule,
        name);
  };
  const Camera camera = looking(0, -15, 1.7, 0, 0, 0.8, 60);
  LdiRenderer everywhere(world("", "species_everywhere"), 160, 120);
  LdiRenderer nowhere(world("max_height = -1.0\n", "species_nowhere"), 160, 120);
  LdiRenderer half(world("density_by_height = [[0.0, 0.5], [1.0, 0.5]]\n", "species_half"), 160, 120);
  everywhere.render(camera);
  nowhere.render(camera);
  half.render(camera);
  const int all = yellow_pixels(everywhere.image()), none = yellow_pixels(nowhere.image()),
            some = yellow_pixels(half.image());
  EXPECT_GT(all, 100);
  EXPECT_EQ(none, 0) << "of " << all;
  std::printf("sunflower pixels: everywhere %d, nowhere %d, at half density %d\n", all, none, some);
  EXPECT_GT(some, all / 5) << "of " << all;
  EXPECT_LT(some, all * 4 / 5) << "of " << all;
}

// A species' rules followed within a tile, not at its centre: on a slope (about 0.55) a height
// rule's boundary crosses tiles. Each sunflower head pixel the view draws is taken back to the
// world by its depth, and the ground under it compared with the rule: even the real field's heads
// overhang it by a head's offset from its stem times the slope (about 0.2 m). Measured over seeds
// 1-7, the worst overshoot: 0.06-0.34 m (4 x 4 cells of rules per tile), -0.08-0.77 m (the rules
// at each tile's centre).
TEST(ldi_view_species, RulesFollowTheGroundWithinATile) {
  const double top = 1797.0;  // the rule: no sunflower on ground higher than this
  const std::string dem = (data_root() / "data/SainteHelens.dem").string();
  const int width = 320, height = 240;
  const double fov = 60;
  const double focal = width / 2.0 / std::tan(fov * std::numbers::pi / 360);
  double worst = -1e9;
  int heads = 0;
  for (int seed = 1; seed <= 7; ++seed) {
    const auto world = world_of(
        "name = \"species rule test\"\n[terrain]\ndem = \"" + dem +
            "\"\ncrop = [-2040.0, 1960.0, -1960.0, 2040.0]\n[tiles]\nset = \"cohen8\"\ntile_size = 4.0\n"
            "points_per_tile = 24\nseed = " +
            std::to_string(seed) +
            "\narea = [-2016.0, 1984.0, -1984.0, 2016.0]\n[sun]\nazimuth = 200.0\nelevation = 40.0\n"
            "[[species]]\nname = \"grass\"\nmodel = \"grass\"\nvariants = 2\ntriangle_budget = 200\nshare = 2.0\n"
            "[[species]]\nname = \"sunflower\"\nmodel = \"sunflower\"\nvariants = 2\ntriangle_budget = 400\n"
            "max_height = " +
            std::to_string(top) + "\n",
        "species_rule_slope_" + std::to_string(seed));
    const Camera camera = looking(-2000, 1990, top + 14, -2000, 2000, top, fov);
    LdiRenderer renderer(world, width, height);
    renderer.set_near_field(0);  // LDIs everywhere
    renderer.render(camera);
    const ImageRgb8& image = renderer.image();
    const auto basis = camera_basis(camera.position, camera.target);  // as the renderer's
    ASSERT_TRUE(basis);
    const SceneGround& ground = world->scene().field->ground;
    double seed_worst = -1e9;
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        if (!shows_petal(image, std::size_t(y) * width + std::size_t(x)) || renderer.sky_at(x, y)) continue;
        // The pixel centre's ray, as far as the depth drawn there.
        const double depth = renderer.depth_at(x, y), right = (x + 0.5 - width / 2.0) / focal,
                     up = -(y + 0.5 - height / 2.0) / focal;
        double p[3];
        for (int c = 0; c < 3; ++c)
          p[c] = camera.position[c] + depth * (basis->forward[c] + right * basis->right[c] + up * basis->up[c]);
        const auto h = ground.height(p[0], p[1]);
        if (!h) continue;
        ++heads;
        seed_worst = std::max(seed_worst, *h - top);
      }
    std::printf("seed %d: the worst head stands over ground %.2f m above the rule's height\n", seed, seed_worst);
    worst = std::max(worst, seed_worst);
  }
  ASSERT_GT(heads, 1000);
  EXPECT_LT(worst, 0.5) << "meters of height beyond the rule's boundary";
}

}  // namespace
}  // namespace wangscape
