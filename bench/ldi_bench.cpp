// The LDI build on the default scene's tile set: cohen8 filled with 20 points per tile (seed 7,
// 4 relaxation rounds), the 11 default sunflower variants at the default scene's budget of 5,000
// triangles each, 4 m tiles, 7 levels x 8 directions.
//  - BM_LdiSamplerRays/W: multi-hit primary rays per second of the sampler alone (no shading, no
//    ground), W = 1 for rtcIntersect1, 4 / 8 / 16 for packets over runs of a row; level 1 of one tile.
//  - BM_LdiBuildCohen8: the whole build (8 tiles x 7 levels x 8 directions, shaded with sun shadows
//    and 8 sky rays, ground where it shows through) written to a pack; counters give the pack size.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>

#include "folder/ldi_pack.h"
#include "generator/poisson_tiles.h"
#include "renders/ldi/ldi_build.h"
#include "templates/sunflower.h"

namespace {

using namespace wangscape;

struct DefaultSet {
  FilledTileSet filled;
  std::vector<Mesh> models;
};

const DefaultSet& default_set() {
  static const DefaultSet set = [] {
    PoissonFillOptions fill;
    fill.points_per_tile = 20;
    fill.seed = 7;
    fill.relax_rounds = 4;
    fill.variants = 11;
    DefaultSet s{fill_poisson_tiles(builtin_tileset("cohen8"), fill), {}};
    for (auto& model : make_sunflower_variants({11, 3, 5000})) s.models.push_back(std::move(model.mesh));
    return s;
  }();
  return set;
}

void BM_LdiSamplerRays(benchmark::State& state) {
  const DefaultSet& s = default_set();
  LdiBuildOptions o;
  o.view.levels = 1;
  o.ground = LdiGround::none;
  o.shading.shadows = false;
  o.shading.ao_rays = 0;
  o.packet_width = int(state.range(0));
  o.instancing = state.range(1) != 0;
  LdiBuildReport report;
  std::uint64_t rays = 0, hits = 0;
  double seconds = 0, cpu = 0;
  for (auto _ : state) {
    build_tile_ldis(s.filled, s.models, o, 0, &report);
    rays += report.primary_rays;
    hits += report.hits;
    seconds += report.sampling_seconds;
    cpu += report.sampling_cpu_seconds;
  }
  // Rays over the time spent tracing them (the scene builds of each iteration left out): per
  // second of wall clock, and per CPU second (what one core does, whatever else runs).
  state.counters["rays_per_s"] = double(rays) / seconds;
  state.counters["rays_per_cpu_s"] = double(rays) / cpu;
  state.counters["rays"] = double(rays) / double(state.iterations());
  state.counters["hits_per_ray"] = double(hits) / double(std::max<std::uint64_t>(rays, 1));
}
BENCHMARK(BM_LdiSamplerRays)
    ->ArgsProduct({{1, 4, 8, 16}, {1, 0}})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);

// Where the bytes of one tile's LDIs go (tile 0, all levels and directions, default options).
void BM_LdiTileBreakdown(benchmark::State& state) {
  const DefaultSet& s = default_set();
  LdiBuildOptions o;
  o.instancing = state.range(0) != 0;
  o.packet_width = int(state.range(1));
  std::vector<LdiImage> ldis;
  LdiBuildReport report;
  for (auto _ : state) ldis = build_tile_ldis(s.filled, s.models, o, 0, &report);
  state.counters["sampling_s"] = report.sampling_seconds;
  state.counters["sampling_cpu_s"] = report.sampling_cpu_seconds;
  state.counters["scenes_s"] = report.seconds - report.sampling_seconds;
  double spans = 0, pixels = 0, depth_pixels = 0, nonempty = 0, rows = 0, all_pixels = 0;
  for (const LdiImage& ldi : ldis) {
    spans += double(ldi.spans.size());
    pixels += double(ldi.counts.size());
    depth_pixels += double(ldi.depth_pixels.size());
    rows += double(ldi.row_spans.size());
    all_pixels += double(ldi.frame.width) * ldi.frame.height;
    for (std::uint8_t c : ldi.counts) nonempty += c > 0;
  }
  state.counters["spans_MB"] = spans * sizeof(LdiSpan) / 1e6;
  state.counters["counts_MB"] = pixels / 1e6;
  state.counters["rows_MB"] = rows * 4 / 1e6;
  state.counters["depth_pixels_MB"] = depth_pixels * sizeof(DepthPixel) / 1e6;
  state.counters["in_span_share"] = pixels / all_pixels;
  state.counters["nonempty_share"] = nonempty / all_pixels;
  state.counters["layers_per_nonempty_pixel"] = depth_pixels / nonempty;
}
BENCHMARK(BM_LdiTileBreakdown)
    ->Args({1, 1})
    ->Args({0, 1})
    ->Args({0, 16})
    ->Iterations(1)
    ->Unit(benchmark::kSecond)
    ->UseRealTime();

void BM_LdiBuildCohen8(benchmark::State& state) {
  const DefaultSet& s = default_set();
  LdiBuildOptions o;
  o.packet_width = int(state.range(0));
  // WANGSCAPE_LDI_BENCH_PACK=FILE keeps the pack there (for `ldi info`, a sheet); else a temporary.
  const char* keep = std::getenv("WANGSCAPE_LDI_BENCH_PACK");
  const auto path =
      keep ? std::filesystem::path(keep)
           : std::filesystem::temp_directory_path() / ("wangscape_ldi_bench_" + std::to_string(::getpid()) + ".ldi");
  LdiBuildReport report;
  for (auto _ : state) report = build_ldi_pack(s.filled, s.models, o, path);
  const LdiPack pack(path);
  const LdiPackStats stats = ldi_pack_stats(pack);
  state.counters["pack_MB"] = double(pack.file_bytes()) / 1e6;
  state.counters["depth_pixels_M"] = double(stats.depth_pixels) / 1e6;
  state.counters["pixels_M"] = double(stats.pixels) / 1e6;
  state.counters["top_level_MB"] = double(stats.bytes_per_level[0]) / 1e6;
  state.counters["rays_per_s"] = double(report.primary_rays + report.secondary_rays) / report.sampling_seconds;
  state.counters["rays_per_cpu_s"] = double(report.primary_rays + report.secondary_rays) / report.sampling_cpu_seconds;
  state.counters["build_s"] = report.seconds;
  state.counters["primary_M"] = double(report.primary_rays) / 1e6;
  state.counters["secondary_M"] = double(report.secondary_rays) / 1e6;
  state.counters["prism_top_m"] = double(pack.info().prism_top);
  state.counters["hits_M"] = double(report.hits) / 1e6;
  state.counters["duplicate_hits"] = double(report.duplicate_hits);
  state.counters["outside_hits"] = double(report.outside_hits);
  state.counters["merged_hits"] = double(report.merged_hits);
  state.counters["dropped_hits"] = double(report.dropped_hits);
  std::string resolutions;
  for (auto r : pack.info().resolutions) resolutions += std::to_string(r) + " ";
  state.SetLabel("resolutions " + resolutions);
  if (!keep) std::filesystem::remove(path);
}
BENCHMARK(BM_LdiBuildCohen8)->Arg(16)->Iterations(1)->Unit(benchmark::kSecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
