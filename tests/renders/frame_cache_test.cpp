// The view in motion (renders/view/frame_cache.h) on the tiny field of view_test_world.h: the
// cold frame is the renderer's, what a sideways step uncovers and a fast turn brings in match the
// exact image (the whole frame ray cast), the frames are the same bytes on 1 and 2 threads, a
// still camera converges past the exact one-sample image, holes never gather past a fifth of the
// frame, the cache fits 64 bytes a pixel and a warm frame allocates nothing.
// Suites are named ldi_view_cache so `ctest -R ldi` runs them.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstdlib>
#include <vector>

#include "renders/trace/embree_reference.h"
#include "renders/trace/image_compare.h"
#include "renders/view/frame_cache.h"
#include "renders/view/frame_cache_impl.h"
#include "renders/view/view_frames.h"
#include "renders/view/view_projection.h"
#include "renders/view/view_samples.h"
#include "tests/renders/counted_allocations.h"
#include "tests/renders/view_test_world.h"

namespace wangscape {
namespace {

using namespace view_test;

constexpr int kWidth = 160, kHeight = 120;

// Inside the field at head height, a flower's stem and leaves within a metre.
Camera in_the_field(double east = 0.3, double yaw_degrees = 0) {
  const double a = yaw_degrees * 3.141592653589793 / 180;
  return looking(east, -7.2, 1.3, east + 3.2 * std::sin(a), -7.2 + 3.2 * std::cos(a), 1.0, 60);
}

// The exact image of a camera: every pixel ray cast, as --engine embree draws it.
ImageRgb8 exact_frame(const Camera& camera) {
  LdiRenderer exact(field(), kWidth, kHeight);
  exact.set_engine(ViewEngine::embree);
  exact.render(camera);
  return exact.image();
}

// `image` as the cache shows a frame whose samples all lie at their pixels' centres: each pixel the
// mean of its 3 x 3 weighted by the reconstruction's tent (frame_cache_impl.h). The cache's frames
// are compared with the exact image seen so, not with its bare samples.
ImageRgb8 reconstructed(const ImageRgb8& image) {
  const view_detail::Luts& lut = view_detail::luts();
  ImageRgb8 out = image;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      float sum[3] = {0, 0, 0}, weights = 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = x + dx, ny = y + dy;
          if (nx < 0 || ny < 0 || nx >= image.width || ny >= image.height) continue;
          const float weight = frame_cache_detail::tent_weight(float(dx)) * frame_cache_detail::tent_weight(float(dy));
          const std::uint8_t* in = image.pixels.data() + image.offset(nx, ny);
          for (int c = 0; c < 3; ++c) sum[c] += weight * lut.to_linear[in[c]];
          weights += weight;
        }
      std::uint8_t* to = out.pixels.data() + out.offset(x, y);
      for (int c = 0; c < 3; ++c) to[c] = lut.encode(sum[c] / weights);
    }
  return out;
}

// Of the pixels `where` selects, the share whose colour differs from `reference` by more than
// `tolerance` (the mean of the three channels' absolute differences, 8-bit).
double share_off(const ImageRgb8& image, const ImageRgb8& reference, const std::vector<bool>& where, int tolerance) {
  int off = 0, n = 0;
  for (std::size_t p = 0; p < where.size(); ++p) {
    if (!where[p]) continue;
    int d = 0;
    for (std::size_t c = 0; c < 3; ++c) d += std::abs(int(image.pixels[3 * p + c]) - int(reference.pixels[3 * p + c]));
    off += d > 3 * tolerance;
    ++n;
  }
  return n ? double(off) / n : 0;
}

// A budget that traces a quarter of the frame's pixels at most (the default would trace them all
// at this size): what the cache keeps must then be right by itself.
FrameBudget quarter_budget() {
  FrameBudget budget;
  budget.pixel_ns = 1e-3;
  budget.sample_ns = 1e9 / budget.fps / (0.25 * kWidth * kHeight);
  return budget;
}

TEST(ldi_view_cache, TheColdFrameIsTheRenderersFrame) {
  LdiRenderer renderer(field(), kWidth, kHeight), alone(field(), kWidth, kHeight);
  renderer.set_near_field(6);
  alone.set_near_field(6);
  FrameCache cache(renderer);
  const CachedFrameStats& stats = cache.render(in_the_field());
  EXPECT_TRUE(stats.cold);
  EXPECT_EQ(stats.fresh_share(), 1.0);
  alone.render(in_the_field());
  EXPECT_EQ(cache.image().pixels, alone.image().pixels);
  // A jump (here: another field of view) is cold again.
  Camera wider = in_the_field(0.3, 10);
  cache.render(wider);
  wider.fov_degrees = 70;
  EXPECT_TRUE(cache.render(wider).cold);
}

TEST(ldi_view_cache, FromAfarTheWholeFrameIsDrawnWhileMoving) {
  // 20 m up and 30 m off the field: no near field, the LDIs alone are the cheaper source.
  LdiRenderer renderer(field(), kWidth, kHeight), alone(field(), kWidth, kHeight);
  renderer.apply(ViewSettings{});
  alone.apply(ViewSettings{});
  FrameCache cache(renderer);
  cache.render(looking(0, -30, 20, 0, 0, 0));
  const CachedFrameStats& moving = cache.render(looking(0.1, -30, 20, 0, 0, 0));
  EXPECT_TRUE(moving.cold);
  alone.render(looking(0.1, -30, 20, 0, 0, 0));
  EXPECT_EQ(cache.image().pixels, alone.image().pixels);
  // Still, it converges from the cache instead.
  EXPECT_FALSE(cache.render(looking(0.1, -30, 20, 0, 0, 0)).cold);
}

TEST(ldi_view_cache, WhatASideStepUncoversIsTheExactImage) {
  LdiRenderer renderer(field(), kWidth, kHeight);
  renderer.apply(ViewSettings{});  // the view's defaults: the near field, the engine by the frame
  FrameCache cache(renderer, quarter_budget());
  cache.render(in_the_field(0.3));
  std::vector<float> first(std::size_t(kWidth * kHeight));
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) first[std::size_t(y * kWidth + x)] = cache.depth_at(x, y);
  // Ten steps of 4 cm to the east (1.4 m/s at 35 frames/s): the near stems slide across the frame.
  double fresh = 0;
  for (int k = 1; k <= 10; ++k) {
    const CachedFrameStats& stats = cache.render(in_the_field(0.3 + 0.04 * k));
    EXPECT_FALSE(stats.cold) << k;
    fresh += stats.fresh_share();
  }
  EXPECT_LT(fresh / 10, 0.3);  // most of each frame was reused
  const Camera last = in_the_field(0.7);
  LdiRenderer exact(field(), kWidth, kHeight);
  exact.set_engine(ViewEngine::embree);
  exact.render(last);
  // The uncovered pixels: within 1.5 m in the first frame, beyond twice as far in the exact last.
  std::vector<bool> uncovered(first.size()), all(first.size(), true);
  int count = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const std::size_t p = std::size_t(y * kWidth + x);
      uncovered[p] = first[p] < 1.5f && exact.depth_at(x, y) > 2 * first[p];
      count += uncovered[p];
    }
  ASSERT_GT(count, 200) << "the step uncovers too little to test";
  // Measured against the exact image as the cache reconstructs it: 0.144 of the uncovered pixels
  // and 0.075 of all differ by more than 24 levels; with 1/256 of the pixels traced a frame, 0.291
  // and 0.185. (Against the bare exact image, before the reconstruction: 0.11 of all; the kept
  // samples lie off the pixel centres it samples.)
  EXPECT_LT(share_off(cache.image(), reconstructed(exact.image()), uncovered, 24), 0.25);
  EXPECT_LT(share_off(cache.image(), reconstructed(exact.image()), all, 24), 0.15);
}

// A budget that traces a twentieth of the frame's pixels at most.
FrameBudget twentieth_budget() {
  FrameBudget budget = quarter_budget();
  budget.sample_ns *= 5;
  return budget;
}

TEST(ldi_view_cache, WhatComesInAtTheEdgeASideStepMovesTowardIsDrawn) {
  LdiRenderer renderer(field(), kWidth, kHeight);
  renderer.apply(ViewSettings{});  // the view's defaults: the near field, the engine by the frame
  FrameCache cache(renderer, twentieth_budget());
  const Camera first = in_the_field(0.3);
  cache.render(first);
  // Twelve steps of 4 cm to the east (the camera looks north: the picture slides left).
  std::uint64_t probes = 0;
  for (int k = 1; k <= 12; ++k) probes += cache.render(in_the_field(0.3 + 0.04 * k)).probes;
  const Camera last = in_the_field(0.3 + 0.04 * 12);
  LdiRenderer exact(field(), kWidth, kHeight);
  exact.set_engine(ViewEngine::embree);
  exact.render(last);
  // The pixels whose surface (within 3 m) the first camera could not see: it lay beyond the
  // right edge of the first frame.
  const ViewProjection from = ViewProjection::of(first, kWidth, kHeight),
                       to = ViewProjection::of(last, kWidth, kHeight);
  std::vector<bool> came_in(std::size_t(kWidth * kHeight));
  int count = 0;
  for (int y = 0; y < kHeight; ++y)
    for (int x = 0; x < kWidth; ++x) {
      const double depth = exact.depth_at(x, y);
      if (exact.sky_at(x, y) || !(depth < 3)) continue;
      const Vector3d d = to.ray_through(x + 0.5, y + 0.5);
      const Vector3d seen = to.eye + (depth / dot(d, to.forward)) * d - from.eye;
      const double first_x = from.cx + from.focal * dot(seen, from.right) / dot(seen, from.forward);
      came_in[std::size_t(y * kWidth + x)] = first_x > kWidth + 1;
      count += came_in[std::size_t(y * kWidth + x)];
    }
  ASSERT_GT(count, 100) << "too little comes into view to test";
  EXPECT_GT(probes, std::uint64_t(0));
  // Measured: 0.118 of them differ by more than 24 levels (0.114 against the bare exact image,
  // before the reconstruction; a probe in each 4 x 4 pixels, 0.085 in each 2 x 2 then); 0.246
  // without the probes at the edge (the background's samples reprojected over what came in,
  // traced only by the refresh).
  EXPECT_LT(share_off(cache.image(), reconstructed(exact.image()), came_in, 24), 0.15) << count << " pixels came in";
}

TEST(ldi_view_cache, NoGhostAfterAFastTurn) {
  LdiRenderer renderer(field(), kWidth, kHeight);
  renderer.apply(ViewSettings{});  // the view's defaults: the near field, the engine by the frame
  FrameCache cache(renderer);
  cache.render(in_the_field(0.3, 0));
  // 24 degrees in one frame (1,440 degrees a second at 60 frames/s), below a jump.
  const CachedFrameStats& stats = cache.render(in_the_field(0.3, 24));
  EXPECT_FALSE(stats.cold);
  EXPECT_GT(stats.holes, std::uint64_t(kWidth * kHeight / 10));  // the side it turned to
  const ImageRgb8 exact = reconstructed(exact_frame(in_the_field(0.3, 24)));
  // Measured: 0.050 of the pixels differ by more than 24 levels (0.08 against the bare exact image,
  // before the reconstruction; with a quarter of the pixels traced 0.16, a twentieth 0.23, 1/256
  // 0.28 then).
  EXPECT_LT(share_off(cache.image(), exact, std::vector<bool>(kWidth * kHeight, true), 24), 0.12);
}

TEST(ldi_view_cache, HolesNeverGatherPastAFifthWhenThePassesOutrunTheFrame) {
  LdiRenderer renderer(field(), kWidth, kHeight);
  renderer.apply(ViewSettings{});  // the view's defaults: the near field, the engine by the frame
  FrameBudget outrun;              // the passes alone take longer than a frame: the floor, 1/256
  outrun.pixel_ns = 2e9 / outrun.fps / (kWidth * kHeight);
  FrameCache cache(renderer, outrun);
  cache.render(in_the_field(0.3));
  // A walk north at 1.4 m/s and 60 frames/s, turning 30 degrees a second.
  for (int k = 1; k <= 60; ++k) {
    const double north = -7.2 + 0.023 * k, a = 0.5 * k * 3.141592653589793 / 180;
    const CachedFrameStats& stats =
        cache.render(looking(0.3, north, 1.3, 0.3 + 3.2 * std::sin(a), north + 3.2 * std::cos(a), 1.0, 60));
    ASSERT_FALSE(stats.cold) << "frame " << k << ": the holes gathered until the frame went cold";
    // The holes left: a fifth of the pixels, and those the traced surfaces hid (the frame's last
    // test) beyond it: at most 0.202 measured. Before the cap they grew until frame 47 went cold.
    EXPECT_LE(stats.filled, std::uint64_t(0.22 * kWidth * kHeight)) << "frame " << k;
  }
}

// The frames of a short walk that ends still, on `threads` threads.
std::vector<std::uint8_t> walk_frames(int threads) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
  LdiRenderer renderer(field(), kWidth, kHeight);
  renderer.apply(ViewSettings{});  // the view's defaults: the near field, the engine by the frame
  FrameCache cache(renderer, quarter_budget());
  std::vector<std::uint8_t> bytes;
  for (int k = 0; k < 16; ++k) {
    cache.render(in_the_field(0.3 + 0.03 * std::min(k, 10), 2.0 * std::min(k, 10)));
    bytes.insert(bytes.end(), cache.image().pixels.begin(), cache.image().pixels.end());
  }
  return bytes;
}

TEST(ldi_view_cache, SameBytesOnOneAndTwoThreads) { EXPECT_EQ(walk_frames(1), walk_frames(2)); }

TEST(ldi_view_cache, AStillCameraConvergesPastTheExactOneSampleImage) {
  const Camera camera = in_the_field(0.3);
  ReferenceOptions options;
  options.camera = camera;
  options.width = kWidth;
  options.height = kHeight;
  options.shading = field()->shading();
  options.samples_per_pixel = 64;
  const ImageRgb8 truth = render_reference(field()->scene(), options).image;
  options.samples_per_pixel = 1;
  const double exact = compare_images(render_reference(field()->scene(), options).image, truth).psnr_db;

  LdiRenderer renderer(field(), kWidth, kHeight);
  renderer.apply(ViewSettings{});                // the view's defaults: the near field, the engine by the frame
  FrameCache cache(renderer, quarter_budget());  // a quarter of the pixels a frame
  cache.render(camera);
  std::vector<double> psnr;
  for (int k = 1; k <= 32; ++k) {
    const CachedFrameStats& stats = cache.render(camera);
    EXPECT_TRUE(stats.still);
    if (k % 4 == 0) psnr.push_back(compare_images(cache.image(), truth).psnr_db);
  }
  for (std::size_t i = 1; i < psnr.size(); ++i) EXPECT_GT(psnr[i], psnr[i - 1] - 0.05) << "checkpoint " << i;
  EXPECT_GT(psnr.back(), psnr.front() + 2);
  EXPECT_GT(psnr[1], exact) << "after 8 still frames: " << psnr[1] << " dB, the exact one-sample image " << exact;
}

TEST(ldi_view_cache, AWarmFrameAllocatesNothing) {
  LdiRenderer renderer(field(), kWidth, kHeight);
  renderer.apply(ViewSettings{});  // the view's defaults: the near field, the engine by the frame
  FrameCache cache(renderer, quarter_budget());
  cache.render(in_the_field(0.3));
  cache.render(in_the_field(0.31));  // (the first warm frame may build what warm frames share)
  // Before: two a frame (a message's std::string built for a check that passed).
  const long allocations = test::count_allocations([&] {
    for (int k = 2; k <= 12; ++k) cache.render(in_the_field(0.3 + 0.01 * std::min(k, 8), 0.5 * std::min(k, 8)));
  });
  EXPECT_EQ(allocations, 0) << "allocations in 11 warm frames (moving, then still)";
}

TEST(ldi_view_cache, TheCacheFitsSixtyFourBytesAPixel) {
  LdiRenderer renderer(field(), kWidth, kHeight);
  renderer.apply(ViewSettings{});  // the view's defaults: the near field, the engine by the frame
  FrameCache cache(renderer);
  cache.render(in_the_field());
  EXPECT_LE(cache.bytes_per_pixel(), 64.0);
}

}  // namespace
}  // namespace wangscape
