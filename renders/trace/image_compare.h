// Measuring a rendered frame against a reference (the LDI view against the Embree reference,
// `wangscape view DIR --compare`): PSNR, SSIM, the share of hole pixels and a difference image.
//
// Interface kept stable for the LDI viewer (branch ldi-view). All functions are pure, take
// images of equal size (else they throw Error naming both sizes) and are thread-safe.
//   - PSNR: of the 8-bit sRGB values (what the PNGs hold), the mean squared error over R, G and B
//     of every pixel, peak 255: 10 log10(255^2 / MSE) dB; +infinity for identical images.
//   - SSIM: Wang, Bovik, Sheikh, Simoncelli 2004, on luma Y = 0.299 R + 0.587 G + 0.114 B of the
//     8-bit sRGB values (0..255), an 11 x 11 Gaussian window with sigma 1.5 (normalised),
//     K1 = 0.01, K2 = 0.03, L = 255, averaged over every window position that lies wholly inside
//     the image (no padding), as the authors' reference implementation does. 1 for identical
//     images; images must be at least 11 x 11 pixels.
//   - Holes: pixels where the candidate shows sky but the reference has geometry, as a share of
//     all pixels (and their count); masks are one byte per pixel, row-major, non-zero = geometry.
#pragma once

#include <cstdint>
#include <vector>

#include "generator/image.h"

namespace wangscape {

inline constexpr int kSsimWindow = 11;  // pixels: the side of SSIM's Gaussian window

// One byte per pixel (row-major, top row first): non-zero where the frame has geometry.
struct CoverageMask {
  int width = 0, height = 0;
  std::vector<std::uint8_t> covered;
};

// The mask of per-pixel coverage shares (0..1, e.g. ReferenceImage::coverage): covered where a
// pixel's share is at least `threshold`. Throws Error when coverage.size() != width * height.
CoverageMask coverage_mask(const std::vector<float>& coverage, int width, int height, float threshold = 0.5f);

double psnr_db(const ImageRgb8& candidate, const ImageRgb8& reference);  // +inf when identical
double ssim(const ImageRgb8& candidate, const ImageRgb8& reference);     // -1..1, 1 when identical

struct HoleCount {
  std::uint64_t holes = 0;              // candidate sky, reference geometry
  std::uint64_t reference_covered = 0;  // reference geometry
  double share = 0;                     // holes / all pixels (0 for an empty image)
  double share_of_covered = 0;          // holes / reference_covered (0 when nothing is covered)
};
HoleCount count_holes(const CoverageMask& candidate, const CoverageMask& reference);

// A heat map of the difference: per pixel the largest |candidate - reference| of its channels
// times `gain` (255: the top of the ramp), from black where they agree through red and yellow to
// white. Holes (when both masks are given) are painted magenta, which the ramp never shows.
ImageRgb8 difference_image(const ImageRgb8& candidate, const ImageRgb8& reference, double gain = 4.0,
                           const CoverageMask* candidate_mask = nullptr, const CoverageMask* reference_mask = nullptr);

struct ImageComparison {
  double psnr_db = 0;  // +inf when identical
  double ssim = 0;
  HoleCount holes;  // zeros unless both masks were given
  ImageRgb8 difference;
};

// Everything above in one call (masks optional: without both, no hole count and no magenta).
ImageComparison compare_images(const ImageRgb8& candidate, const ImageRgb8& reference,
                               const CoverageMask* candidate_mask = nullptr,
                               const CoverageMask* reference_mask = nullptr, double difference_gain = 4.0);

// `left` and `right` side by side, `gap` white pixels apart (the taller one's height; the other
// on white): the picture of a comparison that users share.
ImageRgb8 side_by_side(const ImageRgb8& left, const ImageRgb8& right, int gap = 4);

}  // namespace wangscape
