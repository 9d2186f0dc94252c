// PSNR, SSIM, holes and the difference image on made-up images whose figures are known
// analytically. Suites are named image_compare* so `ctest -R image_compare` runs them.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "core/error.h"
#include "renders/trace/image_compare.h"

namespace wangscape {
namespace {

// Random values in [lo, hi] per channel (seeded: the same image every run).
ImageRgb8 random_image(int w, int h, int lo, int hi, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> value(lo, hi);
  ImageRgb8 img(w, h);
  for (auto& p : img.pixels) p = std::uint8_t(value(rng));
  return img;
}

// A 3 x 3 box blur (edges clamped).
ImageRgb8 blurred(const ImageRgb8& in) {
  ImageRgb8 out(in.width, in.height);
  for (int y = 0; y < in.height; ++y)
    for (int x = 0; x < in.width; ++x)
      for (int c = 0; c < 3; ++c) {
        int sum = 0;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int sx = std::clamp(x + dx, 0, in.width - 1), sy = std::clamp(y + dy, 0, in.height - 1);
            sum += in.pixels[in.offset(sx, sy) + std::size_t(c)];
          }
        out.pixels[out.offset(x, y) + std::size_t(c)] = std::uint8_t((sum + 4) / 9);
      }
  return out;
}

TEST(image_compare, IdenticalImagesHaveInfinitePsnrAndSsimOne) {
  const ImageRgb8 a = random_image(40, 30, 0, 255, 1);
  EXPECT_TRUE(std::isinf(psnr_db(a, a)));
  EXPECT_GT(psnr_db(a, a), 0);
  EXPECT_NEAR(ssim(a, a), 1.0, 1e-12);
}

TEST(image_compare, PsnrOfKnownNoiseIsTheAnalyticValue) {
  const ImageRgb8 ref = random_image(64, 64, 20, 235, 2);
  // Every value off by exactly +-5: MSE 25, PSNR 10 log10(255^2 / 25) = 34.151 dB.
  ImageRgb8 shifted = ref;
  std::mt19937 rng(3);
  for (auto& p : shifted.pixels) p = std::uint8_t(p + ((rng() & 1) ? 5 : -5));
  EXPECT_NEAR(psnr_db(shifted, ref), 10 * std::log10(255.0 * 255.0 / 25.0), 1e-9);
  // Uniform integer noise in -8..8: expected MSE = 8 * 9 / 3 = 24, so 34.33 dB within 0.1 dB.
  ImageRgb8 noisy = random_image(256, 256, 20, 235, 4);
  const ImageRgb8 clean = noisy;
  std::uniform_int_distribution<int> noise(-8, 8);
  for (auto& p : noisy.pixels) p = std::uint8_t(p + noise(rng));
  EXPECT_NEAR(psnr_db(noisy, clean), 10 * std::log10(255.0 * 255.0 / 24.0), 0.1);
}

TEST(image_compare, SsimOfFlatImagesIsTheLuminanceTerm) {
  // Constant images a and b: no variance, so SSIM = (2ab + C1) / (a^2 + b^2 + C1), C1 = (0.01 * 255)^2.
  const ImageRgb8 a(20, 16, {100, 100, 100}), b(20, 16, {110, 110, 110});
  const double c1 = 2.55 * 2.55;
  EXPECT_NEAR(ssim(a, b), (2 * 100.0 * 110 + c1) / (100.0 * 100 + 110.0 * 110 + c1), 1e-9);
}

TEST(image_compare, SsimIsSymmetricAndBelowOneForABlurredCopy) {
  const ImageRgb8 a = random_image(48, 40, 0, 255, 5), b = blurred(a);
  const double ab = ssim(a, b), ba = ssim(b, a);
  EXPECT_DOUBLE_EQ(ab, ba);
  EXPECT_LT(ab, 0.9);
  EXPECT_GT(ab, 0.0);
  // A lighter blur of a smoother image stays closer.
  const ImageRgb8 smooth = blurred(blurred(a));
  EXPECT_GT(ssim(smooth, blurred(smooth)), ab);
}

TEST(image_compare, HolesAreCountedWhereOnlyTheReferenceHasGeometry) {
  CoverageMask candidate{4, 2, {1, 0, 0, 1, 1, 1, 0, 0}};
  CoverageMask reference{4, 2, {1, 1, 0, 0, 1, 1, 1, 1}};
  const HoleCount h = count_holes(candidate, reference);
  EXPECT_EQ(h.holes, 3u);  // pixels 1, 6, 7
  EXPECT_EQ(h.reference_covered, 6u);
  EXPECT_DOUBLE_EQ(h.share, 3.0 / 8.0);
  EXPECT_DOUBLE_EQ(h.share_of_covered, 0.5);
  const CoverageMask from_shares = coverage_mask({0.f, 0.49f, 0.5f, 1.f}, 2, 2);
  EXPECT_EQ(from_shares.covered, (std::vector<std::uint8_t>{0, 0, 1, 1}));
}

TEST(image_compare, DifferenceImageScalesAndMarksHoles) {
  ImageRgb8 a(2, 1, {100, 100, 100}), b(2, 1, {100, 100, 100});
  a.set(0, 0, {110, 90, 100});
  const ImageRgb8 d = difference_image(a, b, 4.0);
  EXPECT_EQ(d.at(0, 0), (Rgb8{120, 0, 0}));  // the largest channel's 10 x 4 = 40 of 255: a third up the red
  EXPECT_EQ(d.at(1, 0), (Rgb8{0, 0, 0}));
  // Up the ramp: red, then yellow, then white; a difference of colour is never magenta.
  for (int step = 0; step <= 255; ++step) {
    ImageRgb8 c(1, 1, {0, 0, 0});
    c.set(0, 0, {std::uint8_t(step), 0, std::uint8_t(step)});
    const Rgb8 heat = difference_image(c, ImageRgb8(1, 1, {0, 0, 0}), 1.0).at(0, 0);
    EXPECT_TRUE(heat.r >= heat.g && heat.g >= heat.b) << step;
  }
  EXPECT_EQ(difference_image(ImageRgb8(1, 1, {255, 0, 0}), ImageRgb8(1, 1, {0, 0, 0}), 1.0).at(0, 0),
            (Rgb8{255, 255, 255}));
  const CoverageMask cand{2, 1, {1, 0}}, ref{2, 1, {1, 1}};
  const ImageComparison all = compare_images(random_image(12, 12, 0, 255, 6), random_image(12, 12, 0, 255, 6));
  EXPECT_TRUE(std::isinf(all.psnr_db));
  EXPECT_EQ(all.holes.holes, 0u);
  EXPECT_EQ(difference_image(a, b, 4.0, &cand, &ref).at(1, 0), (Rgb8{255, 0, 255}));
}

TEST(image_compare, RefusesMismatchedOrTinyImages) {
  const ImageRgb8 a(20, 20), b(20, 19), tiny(8, 8);
  EXPECT_THROW(psnr_db(a, b), Error);
  EXPECT_THROW(ssim(a, b), Error);
  EXPECT_THROW(ssim(tiny, tiny), Error);
  EXPECT_THROW(count_holes(CoverageMask{2, 2, {1, 1, 1, 1}}, CoverageMask{2, 1, {1, 1}}), Error);
  EXPECT_THROW(coverage_mask({0.f, 1.f}, 3, 1), Error);
  EXPECT_THROW(difference_image(a, a, 0.0), Error);
}

TEST(image_compare, SideBySideKeepsBothImagesAndAWhiteGap) {
  const ImageRgb8 left(5, 3, Rgb8{10, 20, 30}), right(4, 6, Rgb8{200, 100, 50});
  const ImageRgb8 both = side_by_side(left, right, 2);
  ASSERT_EQ(both.width, 11);
  ASSERT_EQ(both.height, 6);
  EXPECT_EQ(both.at(4, 2).r, 10);
  EXPECT_EQ(both.at(4, 3).r, 255);  // below the shorter image
  EXPECT_EQ(both.at(5, 0).g, 255);  // the gap
  EXPECT_EQ(both.at(7, 5).g, 100);
  EXPECT_EQ(both.at(10, 0).b, 50);
}

}  // namespace
}  // namespace wangscape
