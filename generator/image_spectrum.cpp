#include "generator/image_spectrum.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <complex>
#include <numbers>
#include <string>

#include "core/error.h"

namespace wangscape {

namespace {

using Complex = std::complex<double>;

// In-place radix-2 FFT of `n` values `stride` apart (n a power of two).
void fft(Complex* data, std::size_t n, std::size_t stride) {
  for (std::size_t i = 1, j = 0; i < n; ++i) {
    std::size_t bit = n >> 1;
    for (; j & bit; bit >>= 1) j ^= bit;
    j ^= bit;
    if (i < j) std::swap(data[i * stride], data[j * stride]);
  }
  for (std::size_t length = 2; length <= n; length <<= 1) {
    const double angle = -2 * std::numbers::pi / static_cast<double>(length);
    const Complex step(std::cos(angle), std::sin(angle));
    for (std::size_t start = 0; start < n; start += length) {
      Complex w(1, 0);
      for (std::size_t k = 0; k < length / 2; ++k, w *= step) {
        Complex& a = data[(start + k) * stride];
        Complex& b = data[(start + k + length / 2) * stride];
        const Complex t = w * b;
        b = a - t;
        a += t;
      }
    }
  }
}

}  // namespace

GrayImage to_gray(const ImageRgb8& image) {
  GrayImage gray{image.width, image.height, std::vector<float>(image.pixels.size() / 3)};
  for (std::size_t p = 0; p < gray.values.size(); ++p)
    gray.values[p] = 0.299f * image.pixels[3 * p] + 0.587f * image.pixels[3 * p + 1] + 0.114f * image.pixels[3 * p + 2];
  return gray;
}

GrayImage to_gray(const ImageGray16& image) {
  return {image.width, image.height, std::vector<float>(image.pixels.begin(), image.pixels.end())};
}

double axis_energy_ratio(const GrayImage& image, const AxisEnergyOptions& options) {
  if (image.width < 16 || image.height < 16)
    throw Error("axis energy ratio: image of " + std::to_string(image.width) + " x " + std::to_string(image.height) +
                " pixels; expected at least 16 x 16");
  const std::size_t n = std::bit_floor(static_cast<std::size_t>(std::min(image.width, image.height)));
  // A radial Hann window: a separable one leaks the strong low frequencies along the axes (its
  // transform is a cross), which alone reads as axis energy; a radial one leaks alike in every direction.
  std::vector<double> window(n * n);
  const double centre = static_cast<double>(n) / 2;
  for (std::size_t y = 0; y < n; ++y)
    for (std::size_t x = 0; x < n; ++x) {
      const double r =
          std::hypot(static_cast<double>(x) + 0.5 - centre, static_cast<double>(y) + 0.5 - centre) / centre;
      window[y * n + x] = r < 1 ? 0.5 + 0.5 * std::cos(std::numbers::pi * r) : 0;
    }
  // Welch: the power summed over every whole n x n square of the image.
  std::vector<double> power(n * n, 0);
  std::vector<Complex> data(n * n);
  for (std::size_t y0 = 0; y0 + n <= static_cast<std::size_t>(image.height); y0 += n)
    for (std::size_t x0 = 0; x0 + n <= static_cast<std::size_t>(image.width); x0 += n) {
      const auto value = [&](std::size_t x, std::size_t y) {
        return static_cast<double>(image.at(static_cast<int>(x0 + x), static_cast<int>(y0 + y)));
      };
      double mean = 0;
      for (std::size_t y = 0; y < n; ++y)
        for (std::size_t x = 0; x < n; ++x) mean += value(x, y);
      mean /= static_cast<double>(n * n);
      for (std::size_t y = 0; y < n; ++y)
        for (std::size_t x = 0; x < n; ++x) data[y * n + x] = (value(x, y) - mean) * window[y * n + x];
      for (std::size_t y = 0; y < n; ++y) fft(&data[y * n], n, 1);
      for (std::size_t x = 0; x < n; ++x) fft(&data[x], n, n);
      for (std::size_t k = 0; k < data.size(); ++k) power[k] += std::norm(data[k]);
    }

  const double wedge = options.wedge_degrees * std::numbers::pi / 180;
  double axes = 0, diagonals = 0;
  const auto half = static_cast<std::ptrdiff_t>(n / 2);
  for (std::ptrdiff_t ky = -half + 1; ky < half; ++ky)
    for (std::ptrdiff_t kx = 0; kx < half; ++kx) {  // half plane: the spectrum of a real image is symmetric
      if (kx == 0 && ky <= 0) continue;
      const double fx = static_cast<double>(kx) / static_cast<double>(n),
                   fy = static_cast<double>(ky) / static_cast<double>(n);
      const double radius = std::hypot(fx, fy);
      if (radius < options.lowest || radius > options.highest) continue;
      // Angle folded into [0, 90) degrees: 0 on an axis, 45 on a diagonal.
      const double angle = std::fmod(std::atan2(fy, fx) + 2 * std::numbers::pi, std::numbers::pi / 2);
      const double from_axis = std::min(angle, std::numbers::pi / 2 - angle);
      const std::size_t row =
          static_cast<std::size_t>((ky + static_cast<std::ptrdiff_t>(n)) % static_cast<std::ptrdiff_t>(n));
      const double p = power[row * n + static_cast<std::size_t>(kx)];
      if (from_axis <= wedge)
        axes += p;
      else if (std::abs(from_axis - std::numbers::pi / 4) <= wedge)
        diagonals += p;
    }
  return diagonals > 0 ? axes / diagonals : 0;
}

double shifted_correlation(const GrayImage& image, int dx, int dy) {
  const int x0 = std::max(0, -dx), x1 = std::min(image.width, image.width - dx);
  const int y0 = std::max(0, -dy), y1 = std::min(image.height, image.height - dy);
  if (x1 <= x0 || y1 <= y0) return 0;
  double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const double a = image.at(x, y), b = image.at(x + dx, y + dy);
      sa += a, sb += b, saa += a * a, sbb += b * b, sab += a * b;
    }
  const double count = static_cast<double>(x1 - x0) * static_cast<double>(y1 - y0);
  const double cov = sab / count - sa / count * sb / count;
  const double va = saa / count - sa / count * sa / count, vb = sbb / count - sb / count * sb / count;
  return va > 0 && vb > 0 ? cov / std::sqrt(va * vb) : 0;
}

namespace {
constexpr std::array<std::array<int, 2>, 4> kTileDirections = {{{1, 0}, {0, 1}, {1, 1}, {1, -1}}};
}  // namespace

double tile_repetition(const GrayImage& image, int period) {
  double worst = 0;
  for (const auto& [dx, dy] : kTileDirections)
    worst = std::max(worst, shifted_correlation(image, dx * period, dy * period));
  return worst;
}

double tile_period_peak(const GrayImage& image, int period) {
  const int shorter = period * 7 / 8, longer = (period * 9 + 7) / 8;
  double worst = 0;
  for (const auto& [dx, dy] : kTileDirections) {
    const double around = 0.5 * (shifted_correlation(image, dx * shorter, dy * shorter) +
                                 shifted_correlation(image, dx * longer, dy * longer));
    worst = std::max(worst, shifted_correlation(image, dx * period, dy * period) - around);
  }
  return worst;
}

}  // namespace wangscape
