#include "generator/point_metrics.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>

#include "generator/poisson_tiles.h"

namespace wangscape {

namespace {

// Points bucketed in square cells (counting sort), for neighbour queries.
class PointGrid {
 public:
  PointGrid(std::span<const float> x, std::span<const float> y, const Extent& area, double cell)
      : x_(x), y_(y), area_(area), cell_(cell) {
    nx_ = std::max(1, static_cast<int>(std::ceil(area.width() / cell)));
    ny_ = std::max(1, static_cast<int>(std::ceil(area.height() / cell)));
    start_.assign(static_cast<std::size_t>(nx_) * ny_ + 1, 0);
    std::vector<std::uint32_t> cell_of(x.size());
    for (std::size_t p = 0; p < x.size(); ++p) {
      cell_of[p] = static_cast<std::uint32_t>(index(cx(x[p]), cy(y[p])));
      ++start_[cell_of[p] + 1];
    }
    for (std::size_t k = 1; k < start_.size(); ++k) start_[k] += start_[k - 1];
    order_.resize(x.size());
    std::vector<std::size_t> fill(start_.begin(), start_.end() - 1);
    for (std::size_t p = 0; p < x.size(); ++p) order_[fill[cell_of[p]]++] = static_cast<std::uint32_t>(p);
  }

  int cx(double px) const { return std::clamp(static_cast<int>((px - area_.min_x) / cell_), 0, nx_ - 1); }
  int cy(double py) const { return std::clamp(static_cast<int>((py - area_.min_y) / cell_), 0, ny_ - 1); }
  std::size_t index(int i, int j) const { return static_cast<std::size_t>(j) * nx_ + i; }

  // Calls f(q) for every point q in cells at Chebyshev ring r around cell (i, j).
  template <class F>
  void ring(int i, int j, int r, F&& f) const {
    for (int cj = j - r; cj <= j + r; ++cj) {
      if (cj < 0 || cj >= ny_) continue;
      const bool edge_row = cj == j - r || cj == j + r;
      for (int ci = i - r; ci <= i + r; ci += (edge_row || r == 0) ? 1 : 2 * r) {
        if (ci < 0 || ci >= nx_) continue;
        const std::size_t c = index(ci, cj);
        for (std::size_t k = start_[c]; k < start_[c + 1]; ++k) f(order_[k]);
      }
    }
  }

  double cell() const { return cell_; }
  int max_ring() const { return std::max(nx_, ny_); }

 private:
  std::span<const float> x_, y_;
  Extent area_;
  double cell_;
  int nx_ = 1, ny_ = 1;
  std::vector<std::size_t> start_;
  std::vector<std::uint32_t> order_;
};

double grid_cell(const Extent& area, std::size_t n) {
  return std::max(hexagonal_spacing(std::max(area.width() * area.height(), 1e-30), std::max<double>(n, 1)), 1e-9);
}

struct NnPartial {
  double min = std::numeric_limits<double>::infinity();
  double sum = 0, sum2 = 0;
  std::size_t counted = 0;
};

}  // namespace

NeighbourStats nearest_neighbour_stats(std::span<const float> x, std::span<const float> y, const Extent& area) {
  NeighbourStats stats;
  if (x.size() < 2) return stats;
  const PointGrid grid(x, y, area, grid_cell(area, x.size()));
  // Fixed grain + deterministic reduce: the same sums on any thread count.
  const NnPartial total = tbb::parallel_deterministic_reduce(
      tbb::blocked_range<std::size_t>(0, x.size(), 4096), NnPartial{},
      [&](const tbb::blocked_range<std::size_t>& range, NnPartial part) {
        for (std::size_t p = range.begin(); p != range.end(); ++p) {
          const double px = x[p], py = y[p];
          const int i = grid.cx(px), j = grid.cy(py);
          double best2 = std::numeric_limits<double>::infinity();
          for (int r = 0; r <= grid.max_ring(); ++r) {
            grid.ring(i, j, r, [&](std::uint32_t q) {
              if (q == p) return;
              const double dx = x[q] - px, dy = y[q] - py;
              best2 = std::min(best2, dx * dx + dy * dy);
            });
            const double safe = r * grid.cell();
            if (best2 <= safe * safe) break;
          }
          const double best = std::sqrt(best2);
          part.min = std::min(part.min, best);
          const double border = std::min({px - area.min_x, area.max_x - px, py - area.min_y, area.max_y - py});
          if (best <= border) {
            part.sum += best;
            part.sum2 += best * best;
            ++part.counted;
          }
        }
        return part;
      },
      [](NnPartial a, const NnPartial& b) {
        a.min = std::min(a.min, b.min);
        a.sum += b.sum;
        a.sum2 += b.sum2;
        a.counted += b.counted;
        return a;
      });
  stats.min_distance = total.min;
  stats.counted = total.counted;
  if (total.counted > 0) {
    stats.mean = total.sum / total.counted;
    stats.std = std::sqrt(std::max(0.0, total.sum2 / total.counted - stats.mean * stats.mean));
    stats.spread = stats.mean > 0 ? stats.std / stats.mean : 0;
  }
  return stats;
}

std::size_t count_close_pairs(std::span<const float> x, std::span<const float> y, const Extent& area, double diameter) {
  if (x.size() < 2 || diameter <= 0) return 0;
  const PointGrid grid(x, y, area, std::max(diameter, grid_cell(area, x.size())));
  // Coordinates are floats: a pair exactly at the diameter may round either way by a few ulps.
  const double magnitude =
      std::max({std::abs(area.min_x), std::abs(area.max_x), std::abs(area.min_y), std::abs(area.max_y)});
  const double tolerance = magnitude * 0x1.0p-21;
  const double d2 = (diameter - tolerance) * (diameter - tolerance);
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, x.size()), std::size_t{0},
      [&](const tbb::blocked_range<std::size_t>& range, std::size_t count) {
        for (std::size_t p = range.begin(); p != range.end(); ++p) {
          const int i = grid.cx(x[p]), j = grid.cy(y[p]);
          for (int r = 0; r <= 1; ++r)
            grid.ring(i, j, r, [&](std::uint32_t q) {
              if (q <= p) return;
              const double dx = double(x[q]) - x[p], dy = double(y[q]) - y[p];
              if (dx * dx + dy * dy < d2) ++count;
            });
        }
        return count;
      },
      std::plus<>());
}

RadialSpectrum radial_power_spectrum(std::span<const float> x, std::span<const float> y, const Extent& area,
                                     double window, int max_windows, double grid_period) {
  RadialSpectrum s;
  s.window = window;
  const int wx = static_cast<int>(std::floor(area.width() / window + 1e-9));
  const int wy = static_cast<int>(std::floor(area.height() / window + 1e-9));
  s.windows = std::min(wx * wy, std::max(max_windows, 0));
  if (s.windows == 0 || x.empty()) return s;
  s.peak_frequency = 1.0 / grid_cell(area, x.size());
  const int kmax = std::clamp(static_cast<int>(std::ceil(3.5 * s.peak_frequency * window)), 4, 400);
  const int ny = 2 * kmax + 1, nxh = kmax + 1;  // kx in [0, kmax], ky in [-kmax, kmax]

  // Bucket points by window (row-major from the south-west corner).
  std::vector<std::vector<std::uint32_t>> members(static_cast<std::size_t>(s.windows));
  for (std::size_t p = 0; p < x.size(); ++p) {
    const int i = static_cast<int>(std::floor((x[p] - area.min_x) / window));
    const int j = static_cast<int>(std::floor((y[p] - area.min_y) / window));
    if (i < 0 || j < 0 || i >= wx || j >= wy) continue;
    const int w = j * wx + i;
    if (w < s.windows) members[static_cast<std::size_t>(w)].push_back(static_cast<std::uint32_t>(p));
  }
  std::vector<std::vector<double>> periodograms(static_cast<std::size_t>(s.windows));
  tbb::parallel_for(0, s.windows, [&](int w) {
    const double ox = area.min_x + (w % wx) * window, oy = area.min_y + (w / wx) * window;
    const auto& pts = members[static_cast<std::size_t>(w)];
    std::vector<std::complex<double>> sum(static_cast<std::size_t>(nxh) * ny);
    std::vector<std::complex<double>> ex(static_cast<std::size_t>(nxh)), ey(static_cast<std::size_t>(ny));
    for (std::uint32_t p : pts) {
      const double u = (x[p] - ox) / window, v = (y[p] - oy) / window;
      for (int k = 0; k < nxh; ++k) ex[static_cast<std::size_t>(k)] = std::polar(1.0, -2.0 * std::numbers::pi * k * u);
      for (int k = -kmax; k <= kmax; ++k)
        ey[static_cast<std::size_t>(k + kmax)] = std::polar(1.0, -2.0 * std::numbers::pi * k * v);
      for (int a = 0; a < nxh; ++a) {
        std::complex<double>* row = &sum[static_cast<std::size_t>(a) * ny];
        const std::complex<double> e = ex[static_cast<std::size_t>(a)];
        for (int b = 0; b < ny; ++b) row[b] += e * ey[static_cast<std::size_t>(b)];
      }
    }
    auto& pg = periodograms[static_cast<std::size_t>(w)];
    pg.resize(sum.size());
    const double n = std::max<double>(pts.size(), 1);
    for (std::size_t k = 0; k < sum.size(); ++k) pg[k] = std::norm(sum[k]) / n;
  });
  std::vector<double> mean(static_cast<std::size_t>(nxh) * ny, 0.0);
  for (const auto& pg : periodograms)
    for (std::size_t k = 0; k < mean.size(); ++k) mean[k] += pg[k] / s.windows;

  // Annulus sums, all frequencies and (set 1) without the tile-grid frequencies.
  const int grid = grid_period > 0 ? static_cast<int>(std::lround(window / grid_period)) : 0;
  struct Bins {
    std::vector<double> sum, sum2;
    std::vector<int> count;
  };
  std::array<Bins, 2> bins;
  for (Bins& b : bins) {
    b.sum.assign(static_cast<std::size_t>(kmax) + 1, 0.0);
    b.sum2.assign(b.sum.size(), 0.0);
    b.count.assign(b.sum.size(), 0);
  }
  for (int a = 0; a < nxh; ++a)
    for (int b = -kmax; b <= kmax; ++b) {
      if (a == 0 && b <= 0) continue;  // DC, and the mirror half of the kx = 0 column
      const int r = static_cast<int>(std::lround(std::hypot(a, b)));
      if (r < 1 || r > kmax) continue;
      const double pw = mean[static_cast<std::size_t>(a) * ny + static_cast<std::size_t>(b + kmax)];
      const bool on_grid = grid > 0 && a % grid == 0 && b % grid == 0;
      for (int set = 0; set < 2; ++set) {
        if (set == 1 && on_grid) continue;
        Bins& bin = bins[static_cast<std::size_t>(set)];
        bin.sum[static_cast<std::size_t>(r)] += pw;
        bin.sum2[static_cast<std::size_t>(r)] += pw * pw;
        ++bin.count[static_cast<std::size_t>(r)];
      }
    }
  auto anisotropy = [](const Bins& b, std::size_t r, double& mean_power) {
    mean_power = b.sum[r] / b.count[r];
    const double var = std::max(0.0, b.sum2[r] / b.count[r] - mean_power * mean_power);
    return mean_power > 0 && var > 0 ? 10.0 * std::log10(var / (mean_power * mean_power)) : -100.0;
  };
  double aniso_sum = 0, off_grid_sum = 0;
  int aniso_bins = 0;
  for (int r = 1; r <= kmax; ++r) {
    const auto ru = static_cast<std::size_t>(r);
    if (bins[0].count[ru] == 0) continue;
    double m = 0, m_off = 0;
    const double f = r / window;
    s.frequency.push_back(f);
    s.anisotropy_db.push_back(anisotropy(bins[0], ru, m));
    s.power.push_back(m);
    const double off = bins[1].count[ru] > 0 ? anisotropy(bins[1], ru, m_off) : s.anisotropy_db.back();
    if (f >= 0.5 * s.peak_frequency && f <= 3.0 * s.peak_frequency) {
      aniso_sum += s.anisotropy_db.back();
      off_grid_sum += off;
      ++aniso_bins;
    }
  }
  s.mean_anisotropy_db = aniso_bins > 0 ? aniso_sum / aniso_bins : 0.0;
  s.mean_anisotropy_off_grid_db = aniso_bins > 0 ? off_grid_sum / aniso_bins : 0.0;
  s.noise_floor_db = -10.0 * std::log10(static_cast<double>(s.windows));

  s.image_size = ny;
  s.image.assign(static_cast<std::size_t>(ny) * ny, 0.0f);
  for (int row = 0; row < ny; ++row)
    for (int col = 0; col < ny; ++col) {
      int kx = col - kmax, ky = kmax - row;
      if (kx < 0) kx = -kx, ky = -ky;  // P(-k) = P(k) for real point sets
      s.image[static_cast<std::size_t>(row) * ny + col] =
          static_cast<float>(mean[static_cast<std::size_t>(kx) * ny + static_cast<std::size_t>(ky + kmax)]);
    }
  return s;
}

PointMetrics measure_points(std::span<const float> x, std::span<const float> y, const PointMetricsOptions& options) {
  PointMetrics m;
  const Extent& area = options.area;
  m.count = x.size();
  m.area = area.width() * area.height();
  if (m.count < 2 || m.area <= 0) return m;
  m.spacing = hexagonal_spacing(m.area, static_cast<double>(m.count));
  const NeighbourStats nn = nearest_neighbour_stats(x, y, area);
  m.min_distance = nn.min_distance;
  m.rho = nn.min_distance / m.spacing;
  m.mean_nn = nn.mean / m.spacing;
  m.nn_spread = nn.spread;
  m.close_pairs = count_close_pairs(x, y, area, options.packing_diameter);

  // Edge and corner zones of the complete tiles inside the area.
  const double s = options.tile_size;
  const double zone = (options.zone_width > 0 ? options.zone_width : options.packing_diameter) / s;
  if (zone > 0 && zone < 0.5) {
    std::array<std::size_t, 3> counts{};  // interior, edge, corner
    for (std::size_t p = 0; p < x.size(); ++p) {
      const double ti = std::floor(x[p] / s), tj = std::floor(y[p] / s);
      if (ti * s < area.min_x || (ti + 1) * s > area.max_x || tj * s < area.min_y || (tj + 1) * s > area.max_y)
        continue;
      const double u = x[p] / s - ti, v = y[p] / s - tj;
      const int near = static_cast<int>(u < zone || u >= 1 - zone) + static_cast<int>(v < zone || v >= 1 - zone);
      ++counts[static_cast<std::size_t>(near)];
    }
    const double interior_area = (1 - 2 * zone) * (1 - 2 * zone), edge_area = 4 * zone * (1 - 2 * zone),
                 corner_area = 4 * zone * zone;
    const double interior_density = counts[0] / interior_area;
    if (interior_density > 0) {
      m.edge_density_ratio = counts[1] / edge_area / interior_density;
      m.corner_density_ratio = counts[2] / corner_area / interior_density;
    }
  }
  if (options.spectrum)
    m.spectrum = radial_power_spectrum(x, y, area, options.spectrum_window_tiles * options.tile_size,
                                       options.spectrum_windows, options.tile_size);
  return m;
}

ImageRgb8 draw_spectrum_plot(const RadialSpectrum& spectrum, int height) {
  const int side = std::max(height, 32);
  ImageRgb8 image(3 * side, side, {255, 255, 255});
  if (spectrum.image_size == 0 || spectrum.power.empty()) return image;
  // Periodogram, log10 power mapped from -2..1 to black..white.
  for (int py = 0; py < side; ++py)
    for (int px = 0; px < side; ++px) {
      const int row = py * spectrum.image_size / side, col = px * spectrum.image_size / side;
      const double p = spectrum.image[static_cast<std::size_t>(row) * spectrum.image_size + col];
      const double v = std::clamp((std::log10(std::max(p, 1e-3)) + 2.0) / 3.0, 0.0, 1.0);
      const auto g = static_cast<std::uint8_t>(255 * v);
      image.set(px, py, {g, g, g});
    }
  // Radial curves: x = frequency (0..max), power on 0..2, anisotropy on -20..+10 dB.
  const int x0 = side + side / 8, width = 2 * side - side / 4;
  const double f_max = spectrum.frequency.back();
  auto to_x = [&](double f) { return x0 + static_cast<int>(width * f / f_max); };
  auto power_y = [&](double p) { return static_cast<int>((side - 1) * (1.0 - std::clamp(p / 2.0, 0.0, 1.0))); };
  auto aniso_y = [&](double db) {
    return static_cast<int>((side - 1) * (1.0 - std::clamp((db + 20.0) / 30.0, 0.0, 1.0)));
  };
  auto plot = [&](auto value_y, auto value_at, Rgb8 color, bool dashed) {
    for (std::size_t k = 1; k < spectrum.frequency.size(); ++k) {
      const int xa = to_x(spectrum.frequency[k - 1]), xb = to_x(spectrum.frequency[k]);
      const int ya = value_y(value_at(k - 1)), yb = value_y(value_at(k));
      const int steps = std::max({1, std::abs(xb - xa), std::abs(yb - ya)});
      for (int s = 0; s <= steps; ++s) {
        if (dashed && (xa + s * (xb - xa) / steps) / 4 % 2) continue;
        image.fill_rect(xa + s * (xb - xa) / steps, ya + s * (yb - ya) / steps, 2, 2, color);
      }
    }
  };
  image.fill_rect(x0, 0, 1, side, {0, 0, 0});
  image.fill_rect(x0, power_y(1.0), width, 1, {150, 150, 150});
  for (int m = 1; m <= 3; ++m) image.fill_rect(to_x(m * spectrum.peak_frequency), 0, 1, side, {220, 220, 220});
  plot(
      aniso_y, [&](std::size_t) { return spectrum.noise_floor_db; }, {230, 120, 120}, true);
  plot(
      aniso_y, [&](std::size_t k) { return spectrum.anisotropy_db[k]; }, {200, 30, 30}, false);
  plot(
      power_y, [&](std::size_t k) { return spectrum.power[k]; }, {30, 60, 200}, false);
  return image;
}

}  // namespace wangscape
