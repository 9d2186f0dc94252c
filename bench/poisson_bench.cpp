// Poisson-disk tiles against their goals and peers (issue 3), in one run:
//  - figures: cohen8 with 20 points per tile over 64 x 64 tilings (mean of 8 fill seeds) and over
//    ~1 M points, darts alone and relaxed; the corner sets for the corner densities; a Bridson
//    sampler (30 candidates) and scipy.stats.qmc.PoissonDisk (bench/scipy_poisson.py, 100 k points)
//    as peers: points/s, rho, mean NN distance;
//  - several classes (issue 26): a meadow-like set of grass, flowers and a few boulders per class
//    (fill share, rho, edge / corner density), the progressive rank's thinning at d = 1, 0.5,
//    0.25, 0.125 against a random subset (rho, mean NN, low-frequency power, anisotropy), the
//    density of the thinned points across a tile (least / most band of 0.05 tile sides, cohen8
//    and corner-2, 64 fills) and across a density ramp;
//  - Google Benchmark timings: scattering tiles over a plane in memory (points/s; one class and
//    the three-class meadow), filling and relaxing the 8-tile set, filling the meadow set.
// Options besides Google Benchmark's: --scipy-points N (0 skips the scipy peer), --figures-only,
// --rank-map FILE.png (only the progressive rank's mean density over a tile, as a picture).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <random>
#include <string>

#include "exporters/image_io.h"
#include "generator/placement.h"
#include "generator/point_metrics.h"
#include "generator/poisson_tiles.h"
#include "generator/tiling.h"
#include "tests/generator/rank_density.h"

namespace wangscape {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// All points of a tiles_x x tiles_y scanline tiling (tile side 1).
void tiling_points(const FilledTileSet& filled, int tiles_x, int tiles_y, std::uint64_t seed, std::vector<float>& x,
                   std::vector<float>& y) {
  PlacementOptions options;
  options.tile_size = 1.0;
  options.seed = seed;
  x.clear();
  y.clear();
  place_instances(filled, FlatGround{{0, 0, double(tiles_x), double(tiles_y)}, 0}, options,
                  [&](const InstanceBatch& b) {
                    x.insert(x.end(), b.x.begin(), b.x.end());
                    y.insert(y.end(), b.y.begin(), b.y.end());
                  });
}

struct Row {
  double fill_seconds = 0, rho_configurations = 0;
  std::size_t violations = 0;
  double rho = 0, mean_nn = 0, spread = 0, edge = 0, corner = 0, aniso = 0, aniso_off_grid = 0, floor = 0;
};

Row measure_set(const std::string& set_name, int relax, int seeds, int tiles) {
  Row mean;
  for (int s = 1; s <= seeds; ++s) {
    PoissonFillOptions options;
    options.seed = static_cast<std::uint64_t>(s);
    options.relax_rounds = relax;
    const auto start = std::chrono::steady_clock::now();
    const FilledTileSet filled = fill_poisson_tiles(builtin_tileset(set_name), options);
    mean.fill_seconds += seconds_since(start) / seeds;
    mean.rho_configurations += 2 * filled.radius_packing / hexagonal_spacing(1.0, options.points_per_tile) / seeds;
    std::vector<float> x, y;
    tiling_points(filled, tiles, tiles, 100 + static_cast<std::uint64_t>(s), x, y);
    PointMetricsOptions mo;
    mo.area = {0, 0, double(tiles), double(tiles)};
    mo.packing_diameter = 2 * filled.radius_packing;
    const PointMetrics m = measure_points(x, y, mo);
    mean.violations += m.close_pairs;
    mean.rho += m.rho / seeds;
    mean.mean_nn += m.mean_nn / seeds;
    mean.spread += m.nn_spread / seeds;
    mean.edge += m.edge_density_ratio / seeds;
    mean.corner += m.corner_density_ratio / seeds;
    mean.aniso += m.spectrum.mean_anisotropy_db / seeds;
    mean.aniso_off_grid += m.spectrum.mean_anisotropy_off_grid_db / seeds;
    mean.floor = m.spectrum.noise_floor_db;
  }
  return mean;
}

void print_row(const char* label, const Row& r) {
  std::printf("%-34s %7.3f %6zu %6.3f %6.3f %6.3f %6.3f %6.3f %6.2f %6.2f (%5.1f) %7.3f\n", label, r.rho_configurations,
              r.violations, r.rho, r.mean_nn, r.spread, r.edge, r.corner, r.aniso, r.aniso_off_grid, r.floor,
              r.fill_seconds);
}

// Bridson (2007): active list, k candidates in the annulus [r, 2r], background grid of r / sqrt 2.
std::size_t bridson(double side, double r, int k, std::uint64_t seed, std::vector<float>& x, std::vector<float>& y) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double cell = r / std::sqrt(2.0);
  const int n = static_cast<int>(std::ceil(side / cell));
  std::vector<std::int32_t> grid(static_cast<std::size_t>(n) * n, -1);
  std::vector<double> px, py;
  std::vector<std::int32_t> active;
  auto add = [&](double ax, double ay) {
    const auto id = static_cast<std::int32_t>(px.size());
    px.push_back(ax);
    py.push_back(ay);
    active.push_back(id);
    grid[static_cast<std::size_t>(static_cast<int>(ay / cell)) * n + static_cast<int>(ax / cell)] = id;
  };
  add(unit(rng) * side, unit(rng) * side);
  while (!active.empty()) {
    const std::size_t pick = static_cast<std::size_t>(unit(rng) * active.size());
    const std::int32_t a = active[pick];
    bool found = false;
    for (int c = 0; c < k && !found; ++c) {
      const double angle = 2 * std::numbers::pi * unit(rng);
      const double radius = r * std::sqrt(1 + 3 * unit(rng));  // uniform by area in [r, 2r]
      const double cx = px[static_cast<std::size_t>(a)] + radius * std::cos(angle);
      const double cy = py[static_cast<std::size_t>(a)] + radius * std::sin(angle);
      if (cx < 0 || cy < 0 || cx >= side || cy >= side) continue;
      const int gx = static_cast<int>(cx / cell), gy = static_cast<int>(cy / cell);
      bool ok = true;
      for (int j = std::max(0, gy - 2); j <= std::min(n - 1, gy + 2) && ok; ++j)
        for (int i = std::max(0, gx - 2); i <= std::min(n - 1, gx + 2) && ok; ++i) {
          const std::int32_t q = grid[static_cast<std::size_t>(j) * n + i];
          if (q >= 0 && std::hypot(px[static_cast<std::size_t>(q)] - cx, py[static_cast<std::size_t>(q)] - cy) < r)
            ok = false;
        }
      if (ok) {
        add(cx, cy);
        found = true;
      }
    }
    if (!found) {
      active[pick] = active.back();
      active.pop_back();
    }
  }
  x.assign(px.begin(), px.end());
  y.assign(py.begin(), py.end());
  return px.size();
}

// Grass, flowers kept 0.05 tile sides off the boulders, a few boulders (packing radius 0.08).
PoissonFillOptions meadow_options(int points_per_tile, std::uint64_t seed = 1) {
  PoissonFillOptions options;
  options.points_per_tile = points_per_tile;
  options.seed = seed;
  options.classes = {PoissonClass{.share = 0.7, .variants = 4, .exclusion = {}},
                     PoissonClass{.share = 0.25, .variants = 3, .exclusion = {0.0, 0.0, 0.05}},
                     PoissonClass{.share = 0.05, .packing_radius = 0.08, .variants = 2, .exclusion = {}}};
  return options;
}

// The points of a 64 x 64 scanline tiling (tile side 1) that `keep(x, p)` keeps.
template <class Keep>
void kept_points(const FilledTileSet& filled, std::uint64_t seed, Keep keep, std::vector<float>& x,
                 std::vector<float>& y) {
  TilingOptions options;
  options.seed = seed;
  const Tiling tiling = make_tiling(filled.set, 64, 64, options);
  x.clear();
  y.clear();
  for (int j = 0; j < tiling.height; ++j)
    for (int i = 0; i < tiling.width; ++i)
      for (const TilePoint& p : filled.tiles[tiling.at(i, j)])
        if (keep(i + double(p.x), p)) {
          x.push_back(static_cast<float>(i + p.x));
          y.push_back(static_cast<float>(j + p.y));
        }
}

// Mean power below half the peak frequency (1 = white noise; blue noise is well below).
double low_frequency_power(const RadialSpectrum& s) {
  double sum = 0;
  int n = 0;
  for (std::size_t k = 0; k < s.frequency.size(); ++k)
    if (s.frequency[k] < 0.5 * s.peak_frequency) sum += s.power[k], ++n;
  return n ? sum / n : 0.0;
}

void print_class_figures() {
  std::printf("\n== Several classes (issue 26): cohen8, grass 0.7 / flowers 0.25 / boulders 0.05 of N per tile ==\n");
  std::printf(
      "per class over 64x64 scanline tilings, mean of 4 fill seeds: points per tile over the target, rho,\n"
      "edge / corner density (zones one own spacing wide, at most 0.3) over the interior's\n");
  std::printf("%-24s %8s %8s %7s %7s %7s\n", "N / class", "fill s", "share", "rho", "edge", "corner");
  for (const int n : {20, 40, 60}) {
    const char* names[] = {"grass", "flowers", "boulders"};
    std::array<std::array<double, 5>, 3> mean{};
    constexpr int kSeeds = 4;
    for (int s = 1; s <= kSeeds; ++s) {
      const PoissonFillOptions options = meadow_options(n, static_cast<std::uint64_t>(s));
      const auto start = std::chrono::steady_clock::now();
      const FilledTileSet filled = fill_poisson_tiles(builtin_tileset("cohen8"), options);
      const double secs = seconds_since(start);
      for (std::size_t c = 0; c < 3; ++c) {
        std::vector<float> x, y;
        kept_points(
            filled, 100 + static_cast<std::uint64_t>(s), [&](double, const TilePoint& p) { return p.species == c; }, x,
            y);
        PointMetricsOptions mo;
        mo.area = {0, 0, 64, 64};
        mo.packing_diameter = filled.classes[c].spacing;
        mo.zone_width = std::min(filled.classes[c].spacing, 0.3);
        mo.spectrum = false;
        const PointMetrics m = measure_points(x, y, mo);
        const double target = n * options.classes[c].share;
        const std::array<double, 5> row = {secs, x.size() / 4096.0 / target, m.rho, m.edge_density_ratio,
                                           m.corner_density_ratio};
        for (std::size_t k = 0; k < 5; ++k) mean[c][k] += row[k] / kSeeds;
        if (m.close_pairs)
          std::printf("  (%s seed %d: %zu pairs closer than the class spacing)\n", names[c], s, m.close_pairs);
      }
    }
    for (std::size_t c = 0; c < 3; ++c) {
      const std::string label = std::to_string(n) + " / " + names[c];
      std::printf("%-24s %8.3f %8.3f %7.3f %7.3f %7.3f\n", label.c_str(), mean[c][0], mean[c][1], mean[c][2],
                  mean[c][3], mean[c][4]);
    }
  }
}

void print_rank_figures() {
  std::printf("\n== Progressive rank (issue 26): cohen8, 60 points per tile, 64x64 scanline tiling, seed 1 ==\n");
  std::printf(
      "the points of rank < d against a random subset of the same share; low-f power: mean radial power\n"
      "below half the peak frequency (white noise 1); anisotropy off the tile grid (noise floor in ())\n");
  std::printf("%-8s %-7s %8s %7s %7s %8s %7s %7s %16s\n", "d", "subset", "share", "rho", "meanNN", "low-f", "edge",
              "corner", "aniso dB");
  PoissonFillOptions options;
  options.points_per_tile = 60;
  const FilledTileSet filled = fill_poisson_tiles(builtin_tileset("cohen8"), options);
  std::vector<float> x, y;
  kept_points(
      filled, 5, [](double, const TilePoint&) { return true; }, x, y);
  const double all = double(x.size());
  auto random_rank = [](const TilePoint& p) { return float(((p.id * 2654435761u) >> 8) & 0xffffu) / 65536.0f; };
  for (const double d : {1.0, 0.5, 0.25, 0.125})
    for (const bool random : {false, true}) {
      if (d == 1.0 && random) continue;
      kept_points(
          filled, 5, [&](double, const TilePoint& p) { return (random ? random_rank(p) : p.rank) < d; }, x, y);
      PointMetricsOptions mo;
      mo.area = {0, 0, 64, 64};
      mo.zone_width = 0.12;
      const PointMetrics m = measure_points(x, y, mo);
      std::printf("%-8.3f %-7s %8.3f %7.3f %7.3f %8.3f %7.3f %7.3f %8.2f (%5.1f)\n", d, random ? "random" : "rank",
                  x.size() / all, m.rho, m.mean_nn, low_frequency_power(m.spectrum), m.edge_density_ratio,
                  m.corner_density_ratio, m.spectrum.mean_anisotropy_off_grid_db, m.spectrum.noise_floor_db);
    }
  // No tile grid: the density of the kept points across a tile, in 20 bands of 0.05 tile sides
  // (x and y pooled, each tile counted once), summed over 64 fills, least and most band over the
  // mean band.
  std::printf("density across a tile, bands of 0.05 tile sides, 64 fills, 60 per tile: least / most band\n");
  for (const char* set_name : {"cohen8", "corner-2"}) {
    constexpr std::array<double, 3> densities = {0.5, 0.25, 0.125};
    PoissonFillOptions fill;
    fill.points_per_tile = 60;
    const auto profiles = testing::rank_density_across_tile(builtin_tileset(set_name), fill, densities, 64);
    std::printf("  %-9s", set_name);
    for (std::size_t k = 0; k < densities.size(); ++k) {
      const auto [least, most] = std::minmax_element(profiles[k].begin(), profiles[k].end());
      std::printf("  d %.3f: %.2f / %.2f", densities[k], *least, *most);
    }
    std::printf("\n");
  }
  // A ramp: d rises from 0.1 at x = 0 to 1 at x = 64; figures per band of 8 tiles.
  auto ramp = [](double at) { return 0.1 + 0.9 * at / 64.0; };
  kept_points(
      filled, 5, [&](double wx, const TilePoint& p) { return p.rank < ramp(wx); }, x, y);
  std::printf("ramp d = 0.1 .. 1 over x = 0 .. 64 tiles, per band of 8 tiles: kept / expected, rho, meanNN\n");
  for (int band = 0; band < 8; ++band) {
    std::vector<float> bx, by;
    double expected = 0;
    for (int i = band * 8; i < band * 8 + 8; ++i) expected += ramp(i + 0.5) * all / 64.0;
    for (std::size_t k = 0; k < x.size(); ++k)
      if (x[k] >= band * 8 && x[k] < band * 8 + 8) bx.push_back(x[k]), by.push_back(y[k]);
    PointMetricsOptions mo;
    mo.area = {double(band * 8), 0, double(band * 8 + 8), 64};
    mo.spectrum = false;
    const PointMetrics m = measure_points(bx, by, mo);
    std::printf("  x %2d..%2d  d %.2f..%.2f  %6.3f %7.3f %7.3f\n", band * 8, band * 8 + 8, ramp(band * 8),
                ramp(band * 8 + 8), bx.size() / expected, m.rho, m.mean_nn);
  }
}

void print_figures(int scipy_points) {
  std::printf("\n== Poisson-disk tiles (issue 3): cohen8, 20 points per tile ==\n");
  std::printf(
      "rho_cfg: over every neighbour configuration (exact); the rest measured over 64x64 scanline tilings,\n"
      "mean of 8 fill seeds (violations summed); edge/corner: density within one packing diameter of one\n"
      "edge / two edges over the interior's; anisotropy over 16 windows of 8x8 tiles, all frequencies and\n"
      "without the tile-grid spikes, noise floor of 16 independent windows in ().\n");
  std::printf("%-34s %7s %6s %6s %6s %6s %6s %6s %21s %7s\n", "set / phase", "rho_cfg", "viol", "rho", "meanNN",
              "NNsd/m", "edge", "corner", "aniso, off-grid dB", "fill s");
  print_row("cohen8 darts", measure_set("cohen8", 0, 8, 64));
  print_row("cohen8 darts + relax 100", measure_set("cohen8", 100, 8, 64));
  print_row("corner-2 darts", measure_set("corner-2", 0, 8, 64));
  print_row("corner-2 darts + relax 100", measure_set("corner-2", 100, 8, 64));
  print_row("cohen8-corners darts", measure_set("cohen8-corners", 0, 4, 64));
  print_row("cohen8-corners darts + relax 100", measure_set("cohen8-corners", 100, 4, 64));
  print_row("cohen8-corners-full darts + relax 100", measure_set("cohen8-corners-full", 100, 2, 64));

  std::printf("\n== ~1 M points (224 x 224 tiles of cohen8, seed 1) and peers ==\n");
  std::printf("%-34s %10s %12s %7s %7s %7s %6s\n", "method", "points", "points/s", "rho", "meanNN", "NNsd/m", "viol");
  for (int relax : {0, 100}) {
    PoissonFillOptions options;
    options.relax_rounds = relax;
    const FilledTileSet filled = fill_poisson_tiles(builtin_tileset("cohen8"), options);
    std::vector<float> x, y;
    const auto start = std::chrono::steady_clock::now();
    tiling_points(filled, 224, 224, 7, x, y);
    const double secs = seconds_since(start);
    PointMetricsOptions mo;
    mo.area = {0, 0, 224, 224};
    mo.packing_diameter = 2 * filled.radius_packing;
    mo.spectrum = false;
    const PointMetrics m = measure_points(x, y, mo);
    std::printf("%-34s %10zu %12.3g %7.3f %7.3f %7.3f %6zu\n",
                relax ? "Wang tiles, relaxed (incl. copy)" : "Wang tiles, darts (incl. copy)", m.count, m.count / secs,
                m.rho, m.mean_nn, m.nn_spread, m.close_pairs);
  }
  {
    std::vector<float> x, y;
    const double side = 1000.0, r = side * std::sqrt(0.7 / 1.0e6);
    const auto start = std::chrono::steady_clock::now();
    const std::size_t n = bridson(side, r, 30, 1, x, y);
    const double secs = seconds_since(start);
    PointMetricsOptions mo;
    mo.area = {0, 0, side, side};
    mo.packing_diameter = r;
    // Windows holding as many points as 8 x 8 tiles of 20: the reference anisotropy floor.
    mo.tile_size = std::sqrt(20.0 / (static_cast<double>(n) / (side * side)));
    const PointMetrics m = measure_points(x, y, mo);
    std::printf("%-34s %10zu %12.3g %7.3f %7.3f %7.3f %6zu\n", "Bridson, 30 candidates (C++)", n, n / secs, m.rho,
                m.mean_nn, m.nn_spread, m.close_pairs);
    std::printf("  (Bridson anisotropy over 16 windows of ~1280 points: %.2f dB, noise floor %.1f dB)\n",
                m.spectrum.mean_anisotropy_off_grid_db, m.spectrum.noise_floor_db);
  }
  if (scipy_points > 0) {
    const std::string command = std::string("/usr/bin/python3 ") + WANGSCAPE_SOURCE_DIR + "/bench/scipy_poisson.py " +
                                std::to_string(scipy_points);
    std::printf("running: %s\n", command.c_str());
    std::fflush(stdout);
    if (std::system(command.c_str()) != 0) std::printf("(scipy peer failed)\n");
  }
  print_class_figures();
  print_rank_figures();
  std::printf("\n");
  std::fflush(stdout);
}

// Scattering from tiles over a plane in memory: the sink only counts.
void BM_ScatterPlane(benchmark::State& state) {
  const bool hashed = state.range(0) == 1, meadow = state.range(0) == 2;
  const PoissonFillOptions fill = meadow ? meadow_options(20) : PoissonFillOptions{};
  const FilledTileSet filled = fill_poisson_tiles(builtin_tileset(hashed ? "complete-edge-2" : "cohen8"), fill);
  PlacementOptions options;
  options.tile_size = 4.0;
  options.algorithm = hashed ? TilingAlgorithm::hash : TilingAlgorithm::scanline;
  const FlatGround ground{{0, 0, 4000, 4000}, 0};  // 1000 x 1000 tiles, ~20 M points
  std::uint64_t points = 0;
  for (auto _ : state) {
    std::uint64_t n = 0;
    place_instances(filled, ground, options, [&](const InstanceBatch& b) { n += b.size(); });
    benchmark::DoNotOptimize(n);
    points += n;
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(points));
  state.SetLabel(hashed ? "hash, complete-edge-2" : meadow ? "scanline, cohen8, 3 classes" : "scanline, cohen8");
}
BENCHMARK(BM_ScatterPlane)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

// Filling cohen8 at N points per tile: one class (arg 1 = 0) or the meadow's three (arg 1 = 1).
void BM_FillClassesCohen8(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  PoissonFillOptions options = state.range(1) ? meadow_options(n) : PoissonFillOptions{};
  options.points_per_tile = n;
  for (auto _ : state) benchmark::DoNotOptimize(fill_poisson_tiles(builtin_tileset("cohen8"), options));
  state.SetLabel(state.range(1) ? "3 classes" : "1 class");
}
BENCHMARK(BM_FillClassesCohen8)->ArgsProduct({{20, 40, 60}, {0, 1}})->Unit(benchmark::kMillisecond);

// Filling and relaxing the 8-tile set (goal: under 10 s).
void BM_FillRelaxCohen8(benchmark::State& state) {
  PoissonFillOptions options;
  options.relax_rounds = static_cast<int>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(fill_poisson_tiles(builtin_tileset("cohen8"), options));
}
BENCHMARK(BM_FillRelaxCohen8)->Arg(0)->Arg(100)->Unit(benchmark::kMillisecond);

// The mean density of the points of rank < 0.25 (left) and < 0.125 (right) over one tile: every
// tile of cohen8 at 60 per tile, 800 fills, 32 x 32 bins of 7 pixels, north up; mid grey the
// mean, black half of it or less, white 1.5 times or more (docs/images/rank-density-across-tile.png).
void write_rank_density_map(const std::string& path) {
  constexpr int kBins = 32, kScale = 7, kGap = 12, kFills = 800;
  constexpr std::array<double, 2> densities = {0.25, 0.125};
  PoissonFillOptions fill;
  fill.points_per_tile = 60;
  const std::vector<std::vector<double>> count =
      testing::rank_counts_across_tile(builtin_tileset("cohen8"), fill, densities, kFills, kBins);
  const int side = kBins * kScale;
  ImageRgb8 image(2 * side + kGap, side, {255, 255, 255});
  for (std::size_t k = 0; k < densities.size(); ++k) {
    double mean = 0;
    for (const double c : count[k]) mean += c / (kBins * kBins);
    for (int y = 0; y < side; ++y)
      for (int x = 0; x < side; ++x) {
        const double ratio = count[k][std::size_t(((side - 1 - y) / kScale) * kBins + x / kScale)] / mean;
        const auto grey = static_cast<std::uint8_t>(std::lround(255 * std::clamp(ratio - 0.5, 0.0, 1.0)));
        image.set(int(k) * (side + kGap) + x, y, {grey, grey, grey});
      }
  }
  write_image(path, image);
  std::printf("wrote %s\n", path.c_str());
}

}  // namespace
}  // namespace wangscape

int main(int argc, char** argv) {
  int scipy_points = 100000;
  bool figures_only = false;
  std::vector<char*> rest;
  for (int i = 0; i < argc; ++i) {
    if (std::strcmp(argv[i], "--scipy-points") == 0 && i + 1 < argc) {
      scipy_points = std::atoi(argv[++i]);
    } else if (std::strcmp(argv[i], "--figures-only") == 0) {
      figures_only = true;
    } else if (std::strcmp(argv[i], "--rank-map") == 0 && i + 1 < argc) {
      wangscape::write_rank_density_map(argv[++i]);
      return 0;
    } else {
      rest.push_back(argv[i]);
    }
  }
  wangscape::print_figures(scipy_points);
  if (figures_only) return 0;
  int rest_count = static_cast<int>(rest.size());
  benchmark::Initialize(&rest_count, rest.data());
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
