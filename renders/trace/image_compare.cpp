#include "renders/trace/image_compare.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include "core/error.h"

namespace wangscape {

namespace {

std::string size_text(int w, int h) { return std::to_string(w) + " x " + std::to_string(h); }

void check_same_size(int w1, int h1, int w2, int h2, const char* what) {
  if (w1 != w2 || h1 != h2)
    throw Error(std::string("image compare: the candidate ") + what + " is " + size_text(w1, h1) +
                " pixels, the reference's " + size_text(w2, h2));
}

void check_images(const ImageRgb8& a, const ImageRgb8& b) {
  check_same_size(a.width, a.height, b.width, b.height, "image");
  if (a.pixels.size() != std::size_t(a.width) * std::size_t(a.height) * 3 || a.pixels.size() != b.pixels.size())
    throw Error("image compare: an image's pixels do not match its size " + size_text(a.width, a.height));
}

void check_mask(const CoverageMask& m) {
  if (m.covered.size() != std::size_t(m.width) * std::size_t(m.height))
    throw Error("image compare: a coverage mask of " + std::to_string(m.covered.size()) + " bytes for " +
                size_text(m.width, m.height) + " pixels");
}

std::vector<double> luma(const ImageRgb8& image) {
  std::vector<double> y(std::size_t(image.width) * std::size_t(image.height));
  for (std::size_t i = 0; i < y.size(); ++i)
    y[i] = 0.299 * image.pixels[3 * i] + 0.587 * image.pixels[3 * i + 1] + 0.114 * image.pixels[3 * i + 2];
  return y;
}

// The normalised 1-D Gaussian of SSIM's window (the 2-D window is its outer product).
std::array<double, kSsimWindow> gaussian_window() {
  constexpr double sigma = 1.5;
  std::array<double, kSsimWindow> w{};
  double sum = 0;
  for (int i = 0; i < kSsimWindow; ++i) {
    const double x = i - (kSsimWindow - 1) / 2.0;
    w[std::size_t(i)] = std::exp(-x * x / (2 * sigma * sigma));
    sum += w[std::size_t(i)];
  }
  for (double& v : w) v /= sum;
  return w;
}

// The separable Gaussian filter of `in` (w x h), "valid" part only: (w - 10) x (h - 10).
std::vector<double> filter_valid(const std::vector<double>& in, int w, int h,
                                 const std::array<double, kSsimWindow>& g) {
  const int ow = w - kSsimWindow + 1, oh = h - kSsimWindow + 1;
  std::vector<double> rows(std::size_t(ow) * std::size_t(h)), out(std::size_t(ow) * std::size_t(oh));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < ow; ++x) {
      double s = 0;
      for (int k = 0; k < kSsimWindow; ++k)
        s += g[std::size_t(k)] * in[std::size_t(y) * std::size_t(w) + std::size_t(x + k)];
      rows[std::size_t(y) * std::size_t(ow) + std::size_t(x)] = s;
    }
  for (int y = 0; y < oh; ++y)
    for (int x = 0; x < ow; ++x) {
      double s = 0;
      for (int k = 0; k < kSsimWindow; ++k)
        s += g[std::size_t(k)] * rows[std::size_t(y + k) * std::size_t(ow) + std::size_t(x)];
      out[std::size_t(y) * std::size_t(ow) + std::size_t(x)] = s;
    }
  return out;
}

}  // namespace

CoverageMask coverage_mask(const std::vector<float>& coverage, int width, int height, float threshold) {
  if (width < 0 || height < 0 || coverage.size() != std::size_t(width) * std::size_t(height))
    throw Error("image compare: " + std::to_string(coverage.size()) + " coverage values for " +
                size_text(width, height) + " pixels");
  CoverageMask m{width, height, std::vector<std::uint8_t>(coverage.size())};
  for (std::size_t i = 0; i < coverage.size(); ++i) m.covered[i] = coverage[i] >= threshold ? 1 : 0;
  return m;
}

double psnr_db(const ImageRgb8& candidate, const ImageRgb8& reference) {
  check_images(candidate, reference);
  if (candidate.pixels.empty()) throw Error("image compare: the images are empty");
  double sum = 0;
  for (std::size_t i = 0; i < candidate.pixels.size(); ++i) {
    const double d = double(candidate.pixels[i]) - double(reference.pixels[i]);
    sum += d * d;
  }
  const double mse = sum / double(candidate.pixels.size());
  if (mse == 0) return std::numeric_limits<double>::infinity();
  return 10.0 * std::log10(255.0 * 255.0 / mse);
}

double ssim(const ImageRgb8& candidate, const ImageRgb8& reference) {
  check_images(candidate, reference);
  const int w = candidate.width, h = candidate.height;
  if (w < kSsimWindow || h < kSsimWindow)
    throw Error("image compare: SSIM needs images of at least " + std::to_string(kSsimWindow) + " x " +
                std::to_string(kSsimWindow) + " pixels, not " + size_text(w, h));
  const auto g = gaussian_window();
  const std::vector<double> x = luma(candidate), y = luma(reference);
  std::vector<double> xx(x.size()), yy(x.size()), xy(x.size());
  for (std::size_t i = 0; i < x.size(); ++i) xx[i] = x[i] * x[i], yy[i] = y[i] * y[i], xy[i] = x[i] * y[i];
  const auto mx = filter_valid(x, w, h, g), my = filter_valid(y, w, h, g);
  const auto sxx = filter_valid(xx, w, h, g), syy = filter_valid(yy, w, h, g), sxy = filter_valid(xy, w, h, g);
  constexpr double L = 255, c1 = (0.01 * L) * (0.01 * L), c2 = (0.03 * L) * (0.03 * L);
  double total = 0;
  for (std::size_t i = 0; i < mx.size(); ++i) {
    const double vx = sxx[i] - mx[i] * mx[i], vy = syy[i] - my[i] * my[i], cov = sxy[i] - mx[i] * my[i];
    total += ((2 * mx[i] * my[i] + c1) * (2 * cov + c2)) / ((mx[i] * mx[i] + my[i] * my[i] + c1) * (vx + vy + c2));
  }
  return total / double(mx.size());
}

HoleCount count_holes(const CoverageMask& candidate, const CoverageMask& reference) {
  check_mask(candidate);
  check_mask(reference);
  check_same_size(candidate.width, candidate.height, reference.width, reference.height, "mask");
  HoleCount out;
  for (std::size_t i = 0; i < candidate.covered.size(); ++i) {
    if (reference.covered[i] == 0) continue;
    ++out.reference_covered;
    if (candidate.covered[i] == 0) ++out.holes;
  }
  const std::size_t pixels = candidate.covered.size();
  out.share = pixels ? double(out.holes) / double(pixels) : 0.0;
  out.share_of_covered = out.reference_covered ? double(out.holes) / double(out.reference_covered) : 0.0;
  return out;
}

ImageRgb8 difference_image(const ImageRgb8& candidate, const ImageRgb8& reference, double gain,
                           const CoverageMask* candidate_mask, const CoverageMask* reference_mask) {
  check_images(candidate, reference);
  if (!(gain > 0) || !std::isfinite(gain))
    throw Error("image compare: difference gain " + std::to_string(gain) + "; expected a finite number > 0");
  const bool holes = candidate_mask && reference_mask;
  if (holes) {
    check_mask(*candidate_mask);
    check_mask(*reference_mask);
    check_same_size(candidate_mask->width, candidate_mask->height, candidate.width, candidate.height, "mask");
    check_same_size(reference_mask->width, reference_mask->height, reference.width, reference.height, "mask");
  }
  ImageRgb8 out(candidate.width, candidate.height);
  for (std::size_t p = 0; p < out.pixels.size() / 3; ++p) {
    double largest = 0;
    for (std::size_t c = 0; c < 3; ++c)
      largest = std::max(largest, std::abs(double(candidate.pixels[3 * p + c]) - double(reference.pixels[3 * p + c])));
    // The hot ramp, black to red to yellow to white: never magenta, which is the holes' alone.
    const double heat = std::min(1.0, largest * gain / 255.0);
    for (std::size_t c = 0; c < 3; ++c)
      out.pixels[3 * p + c] = std::uint8_t(std::round(255.0 * std::clamp(3.0 * heat - double(c), 0.0, 1.0)));
  }
  if (holes)
    for (std::size_t p = 0; p < candidate_mask->covered.size(); ++p)
      if (reference_mask->covered[p] != 0 && candidate_mask->covered[p] == 0) {
        out.pixels[3 * p] = 255;
        out.pixels[3 * p + 1] = 0;
        out.pixels[3 * p + 2] = 255;
      }
  return out;
}

ImageComparison compare_images(const ImageRgb8& candidate, const ImageRgb8& reference,
                               const CoverageMask* candidate_mask, const CoverageMask* reference_mask,
                               double difference_gain) {
  ImageComparison out;
  out.psnr_db = psnr_db(candidate, reference);
  out.ssim = ssim(candidate, reference);
  if (candidate_mask && reference_mask) out.holes = count_holes(*candidate_mask, *reference_mask);
  out.difference = difference_image(candidate, reference, difference_gain, candidate_mask, reference_mask);
  return out;
}

ImageRgb8 side_by_side(const ImageRgb8& left, const ImageRgb8& right, int gap) {
  ImageRgb8 out(left.width + gap + right.width, std::max(left.height, right.height), Rgb8{255, 255, 255});
  const auto paste = [&out](const ImageRgb8& image, int x0) {
    for (int y = 0; y < image.height; ++y)
      std::copy_n(image.pixels.begin() + std::ptrdiff_t(image.offset(0, y)), std::size_t(image.width) * 3,
                  out.pixels.begin() + std::ptrdiff_t(out.offset(x0, y)));
  };
  paste(left, 0);
  paste(right, left.width + gap);
  return out;
}

}  // namespace wangscape
