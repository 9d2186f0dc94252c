// Poisson-disk tiles against their goals and peers (issue 3), in one run:
//  - figures: cohen8 with 20 points per tile over 64 x 64 tilings (mean of 8 fill seeds) and over
//    ~1 M points, darts alone and relaxed; the corner sets for the corner densities; a Bridson
//    sampler (30 candidates) and scipy.stats.qmc.PoissonDisk (bench/scipy_poisson.py, 100 k points)
//    as peers: points/s, rho, mean NN distance;
//  - Google Benchmark timings: scattering tiles over a plane in memory (points/s), filling and
//    relaxing the 8-tile set.
// Options besides Google Benchmark's: --scipy-points N (0 skips the scipy peer), --figures-only.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <numbers>
#include <random>
#include <string>

#include "generator/placement.h"
#include "generator/point_metrics.h"
#include "generator/poisson_tiles.h"

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
  std::printf("\n");
  std::fflush(stdout);
}

// Scattering from tiles over a plane in memory: the sink only counts.
void BM_ScatterPlane(benchmark::State& state) {
  PoissonFillOptions fill;
  const bool hashed = state.range(0) == 1;
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
  state.SetLabel(hashed ? "hash, complete-edge-2" : "scanline, cohen8");
}
BENCHMARK(BM_ScatterPlane)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond)->UseRealTime();

// Filling and relaxing the 8-tile set (goal: under 10 s).
void BM_FillRelaxCohen8(benchmark::State& state) {
  PoissonFillOptions options;
  options.relax_rounds = static_cast<int>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(fill_poisson_tiles(builtin_tileset("cohen8"), options));
}
BENCHMARK(BM_FillRelaxCohen8)->Arg(0)->Arg(100)->Unit(benchmark::kMillisecond);

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
